"""IRIS GL calls: raster text -- cmov, charstr, strwidth, font and its metrics.

``cmov(x, y, z)`` transforms a point through the current matrix and viewport to
window coordinates; the result, snapped to the nearest pixel (ties upward, as
vertices snap with subpixel off, docs/numeric_model.md s. 2), is the current
character position ``Context.cpos`` (ints, row 0 at the bottom) with its depth
``Context.cpos_z``.  "If the transformed point is outside the viewport, the character
position is undefined" (cmov(3G)): here it is marked invalid
(``Context.cpos_valid``) and ``charstr`` draws nothing until the next ``cmov``.
cmov "does not affect the current graphics position".

``charstr(s)`` draws the string in the current raster font (``font(n)``; font 0 is
the built-in bitmap font of :mod:`vgxsim.font`, 8x13 cells, baseline 3 rows above
the bottom; others come from ``defrasterfont`` and the font manager, see
:mod:`vgxsim.gl._fm`) in the current colour, the first character's baseline
starting at the character position, which then advances by each character's width
(charstr(3G)).  Glyphs are bitmaps: the matrix does not
scale or rotate them.

**Choice**: each lit glyph pixel is queued as a *fragment* with the current raster
state (``CommandBatch.add_fragments``), exactly like the pixels of a point or a line,
so the raster rectangle, alpha test, stencil test, z test (at ``cpos_z``), blending,
logicop and write masks all apply -- the AIX GL reference says "strings drawn by the
charstr subroutine are subject to clipping and z-buffering" and are "fine clipped" to
the screen mask.  Text is never lit.  Characters the font does not define (outside
32..126) are ignored and have zero width ("the system ignores characters that are not
defined in the current raster font", charstr(3G)), so ``strwidth`` agrees with what
``charstr`` advances.
"""

from __future__ import annotations

import math
from math import floor

import numpy as np

from ._core import (
    _NO,
    INT_MAX,
    INT_MIN,
    GLTypeError,
    GLValueError,
    as_int,
    current,
    describe,
    given,
    gl_function,
    record_or_refuse,
    session,
)
from ._draw import coords
from ._fm import raster_font

__all__ = [
    "cmov", "cmovi", "cmovs", "cmov2", "cmov2i", "cmov2s", "charstr", "strwidth",
    "getheight", "getdescender", "font", "getfont", "getcpos",
]

def _current_font(ctx):
    """The window's current raster font (font 0 if its font was deleted since)."""
    return raster_font(ctx.font) or raster_font(0)


def character_position(ctx, xyzw) -> tuple[bool, int, int, int]:
    """Window position of an object-space point: (valid, x, y, z).

    Parameters
    ----------
    ctx : Context
    xyzw : sequence of 4 float
        Object coordinates.

    Returns
    -------
    tuple
        Whether the point is inside the view volume (cmov(3G): otherwise the
        character position is undefined), the snapped pixel x and y, and the depth
        as a z-buffer value (lsetdepth range).
    """
    x0, y0, z0, w0 = (float(c) for c in xyzw)
    return _position(ctx, x0, y0, z0, w0)


def _position(ctx, x0: float, y0: float, z0: float, w0: float) -> tuple:
    """:func:`character_position` of four floats.  The point times the mvp is
    spelled out in the order of :func:`vgxsim.geometry.transform.apply`
    (``((x*m0 + y*m1) + z*m2) + w*m3`` per column, IEEE doubles, no fused
    multiply-add: the same bits), on the mvp's entries as Python floats
    (MatrixState.mvp_flat), without a numpy array per call."""
    m = ctx.matrices.mvp_flat()
    x = ((x0 * m[0] + y0 * m[4]) + z0 * m[8]) + w0 * m[12]
    y = ((x0 * m[1] + y0 * m[5]) + z0 * m[9]) + w0 * m[13]
    z = ((x0 * m[2] + y0 * m[6]) + z0 * m[10]) + w0 * m[14]
    w = ((x0 * m[3] + y0 * m[7]) + z0 * m[11]) + w0 * m[15]
    if not (w > 0 and -w <= x <= w and -w <= y <= w and -w <= z <= w):
        return False, 0, 0, 0
    l, r, b, t = ctx.raster.viewport
    xw = (l - 0.5) + (x / w + 1.0) * (r - l + 1) / 2.0
    yw = (b - 0.5) + (y / w + 1.0) * (t - b + 1) / 2.0
    near, far = ctx.depth_range
    zw = near + (z / w + 1.0) * (far - near) / 2.0
    lo, hi = min(near, far), max(near, far)
    zi = min(max(math.floor(zw + 0.5), math.floor(lo + 0.5)), math.floor(hi + 0.5))
    return True, math.floor(xw + 0.5), math.floor(yw + 0.5), int(zi)


def _window_map(ctx) -> tuple:
    """What cmov's valid path reads of the window's transform, made once per change
    (the mvp, the viewport tuple and the depth-range tuple are replaced, never
    mutated, on change, and the map holds them, so their identity is its key):
    ``(mvp, viewport, depth_range, m0 .. m15, l - 0.5, float(r - l + 1), b - 0.5,
    float(t - b + 1), float(near), float(far - near), zlo, zhi)``, the mvp's entries
    as :meth:`MatrixState.mvp_flat` gives them and the terms of :func:`_position`'s
    viewport and depth mapping that do not depend on the point, each the value
    Python's int-float arithmetic there converts to (``zlo``, ``zhi``: the depth
    clamp, ``floor(min/max(near, far) + 0.5)``)."""
    mats = ctx.matrices
    mvp = mats.mvp()
    vp = ctx.raster.viewport
    dr = ctx.depth_range
    l, r, b, t = vp
    near, far = dr
    ctx.cpos_map = memo = (
        (mvp, vp, dr) + tuple(mats.mvp_flat())
        + (l - 0.5, float(r - l + 1), b - 0.5, float(t - b + 1), float(near),
           float(far - near), math.floor(min(near, far) + 0.5),
           math.floor(max(near, far) + 0.5)))
    return memo


def _set_cpos(ctx, x: float, y: float, z: float) -> None:
    valid, px, py, pz = _position(ctx, x, y, z, 1.0)
    ctx.cpos_valid = valid
    if valid:
        ctx.cpos = (px, py)
        ctx.cpos_z = pz


def _make_cmov(dim: int, suffix: str):
    name = f"cmov{'2' if dim == 2 else ''}{suffix}"
    integer = suffix in ("i", "s")

    def body(*args) -> None:
        vals = coords(name, args, dim, integer)
        ctx = current(name, args)
        _set_cpos(ctx, vals[0], vals[1], vals[2] if dim == 3 else 0.0)

    def general(*args, **kwargs) -> None:
        if kwargs or session.recording is not None:
            return record_or_refuse(call, args, kwargs)
        body(*args)

    # Valid path (FAST_CALLS): dim finite floats (cmov, cmov2) or ints of 32 bits
    # (the i/s forms, as float(v)); anything else (one tuple too) takes the general
    # path, which validates and raises as before.
    def call(x=_NO, y=_NO, z=_NO, /, *more, **kw) -> None:
        ctx = session.imm
        if ctx is None or kw or more or (z is _NO) != (dim == 2):
            return general(*given((x, y, z), more), **kw)
        if dim == 2:
            z = 0.0
        if integer:
            if not (type(x) is int and type(y) is int and (dim == 2 or type(z) is int)
                    and INT_MIN <= x <= INT_MAX and INT_MIN <= y <= INT_MAX
                    and (dim == 2 or INT_MIN <= z <= INT_MAX)):
                return general(*given((x, y, z) if dim == 3 else (x, y), more))
            x, y, z = float(x), float(y), float(z)
        elif not (type(x) is float and type(y) is float and type(z) is float
                  and x - x == 0.0 and y - y == 0.0 and z - z == 0.0):
            return general(*given((x, y, z) if dim == 3 else (x, y), more))
        # _set_cpos(ctx, x, y, z) inlined on the window map (cmov2's cost was the
        # calls and the per-point int-float conversions): the same operations in
        # the same order (the point's w is 1.0, and 1.0 * m is m exactly).
        memo = ctx.cpos_map
        mvp = ctx.matrices._mvp
        if (memo is None or mvp is not memo[0] or ctx.raster.viewport is not memo[1]
                or ctx.depth_range is not memo[2]):
            memo = _window_map(ctx)
        (_, _, _, m0, m1, m2, m3, m4, m5, m6, m7, m8, m9, m10, m11, m12, m13, m14, m15,
         xo, xs, yo, ys, zo, zs, zlo, zhi) = memo
        cw = ((x * m3 + y * m7) + z * m11) + m15
        cx = ((x * m0 + y * m4) + z * m8) + m12
        cy = ((x * m1 + y * m5) + z * m9) + m13
        cz = ((x * m2 + y * m6) + z * m10) + m14
        if not (cw > 0 and -cw <= cx <= cw and -cw <= cy <= cw and -cw <= cz <= cw):
            ctx.cpos_valid = False
            return
        ctx.cpos_valid = True
        ctx.cpos = (floor(xo + (cx / cw + 1.0) * xs / 2.0 + 0.5),
                    floor(yo + (cy / cw + 1.0) * ys / 2.0 + 0.5))
        zi = floor(zo + (cz / cw + 1.0) * zs / 2.0 + 0.5)
        ctx.cpos_z = zlo if zi < zlo else zhi if zi > zhi else zi

    call.__name__ = call.__qualname__ = name
    call.__doc__ = (f"{name}(...): set the current character position to this "
                    f"{'2-D ' if dim == 2 else ''}point transformed to window "
                    f"coordinates (cmov(3G)).")
    return gl_function(record=True, binds=(0, math.inf, ()))(call)


cmov, cmovi, cmovs = (_make_cmov(3, s) for s in ("", "i", "s"))
cmov2, cmov2i, cmov2s = (_make_cmov(2, s) for s in ("", "i", "s"))


def _string(name: str, args: tuple) -> str:
    if len(args) != 1:
        raise GLTypeError(f"{describe(name, args)}: expected 1 argument, got {len(args)}")
    s = args[0]
    if isinstance(s, bytes):
        return s.decode("latin-1")
    if not isinstance(s, str):
        raise GLTypeError(f"{describe(name, args)}: the string must be a str, not "
                          f"{type(s).__name__}")
    return s


def _packed(colour) -> int:
    """RGBA floats -> 0xAABBGGRR with the vertex-colour rounding (numeric model s. 4)."""
    word = 0
    for i, c in enumerate(colour):
        word |= min(255, max(0, math.floor(float(c) * 255.0 + 0.5))) << (8 * i)
    return word


@gl_function(record=True)
def charstr(*args) -> None:
    """charstr(s): draw ``s`` at the current character position in the current colour
    and advance the position (charstr(3G)); see the module docstring."""
    text = _string("charstr", args)
    ctx = current("charstr", args)
    f = _current_font(ctx)
    s = f.defined(text)
    if not s or not ctx.cpos_valid:
        return
    x0, y0 = ctx.cpos
    dx, dy, advance = f.pixels(s)  # offsets from the character position
    if dx.size and ctx.select_hook is None:  # pick/select mode draws nothing
        xy = np.stack([x0 + dx, y0 + dy], axis=1).astype(np.int64)
        z = np.full(dx.size, ctx.cpos_z, dtype=np.int64)
        rgba = np.full(dx.size, _packed(ctx.colour), dtype=np.int64)
        ctx.batch.add_fragments(xy, z, rgba, ctx.raster.snapshot())
    ctx.cpos = (x0 + advance, y0)


@gl_function(record=False)
def strwidth(*args) -> int:
    """strwidth(s) -> int: the width of ``s`` in pixels in the current font (what
    charstr advances the character position by)."""
    s = _string("strwidth", args)
    return _current_font(current("strwidth", args)).string_width(s)


@gl_function(record=False)
def getheight(*args) -> int:
    """getheight() -> int: the height of the current raster font (13 for font 0)."""
    return _current_font(current("getheight", args)).height


@gl_function(record=False)
def getdescender(*args) -> int:
    """getdescender() -> int: the longest descender of the current raster font, in
    rows below the baseline (3 for font 0)."""
    return _current_font(current("getdescender", args)).descender


@gl_function(record=True)
def font(*args) -> None:
    """font(n): select raster font ``n`` (0, the built-in font, or one defined by
    defrasterfont or the font manager); an undefined number is a GLValueError."""
    if len(args) != 1:
        raise GLTypeError(f"{describe('font', args)}: expected 1 argument, got {len(args)}")
    n = as_int("font", args, "fntnum", args[0])
    if raster_font(n) is None:
        raise GLValueError(f"{describe('font', args)}: font {n} is not defined (font 0 is "
                           f"the built-in font; define others with defrasterfont)")
    current("font", args).font = n


@gl_function(record=False)
def getfont(*args) -> int:
    """getfont() -> int: the current raster font number."""
    return int(current("getfont", args).font)


@gl_function(record=False)
def getcpos(*args) -> tuple[int, int]:
    """getcpos() -> (x, y): the current character position in window pixels."""
    x, y = current("getcpos", args).cpos[:2]
    return int(x), int(y)
