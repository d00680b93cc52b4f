"""IRIS GL colour calls: the current colour (RGBmode and cmode) and the colour map.

RGBmode calls (cpack, RGBcolor, c3f/c4f, c3i/c4i, c3s/c4s) set ``ctx.colour`` as RGBA
floats in [0, 1]; cmode calls (color, colorf) set ``ctx.colour_index`` and put the
index bytes into ``ctx.colour`` so the kernels write the index word itself (see
:mod:`vgxsim.state.colormap`).  The manual makes the wrong mode an error: "It is an
error to call cpack while the current framebuffer is in color map mode" (cpack(3G),
the same sentence in RGBcolor, wmpack, RGBwritemask) and "It is an error to call
color or colorf while the current framebuffer is in RGB mode" (color(3G)); here
those raise :class:`GLUsageError`.

Out-of-range components saturate, as CPython's ``gl`` binding documents for c3f
("larger values saturate") and IGL does for every colour call.

lmcolor(3G): "Because lmcolor is effective only when lighting is active, the
standard color subroutines are used to change the current color when lighting is
off."  With lighting on, LMC_COLOR colour commands set the current colour (the
vertex is then coloured, not lit); LMC_EMISSION..LMC_AD ones change the bound
material in the hardware (``Context.shade_vertices`` applies them) and leave the
vertex lit; LMC_NULL ones are ignored.
"""

from __future__ import annotations

import math

from vgxsim import GL
from vgxsim.state import colormap

from ._core import (
    _NO,
    GLUsageError,
    GLValueError,
    as_float,
    as_int,
    current,
    describe,
    flat_numbers,
    given,
    gl_function,
    record_or_refuse,
    session,
)

__all__ = [
    "cpack", "RGBcolor", "c3f", "c4f", "c3i", "c4i", "c3s", "c4s", "gRGBcolor",
    "gRGBmask", "color", "colorf", "getcolor", "writemask", "getwritemask", "mapcolor",
    "getmcolor", "multimap", "onemap", "getcmmode", "setmap", "getmap",
]


# -- helpers -----------------------------------------------------------------------
def _need_rgb(ctx, name: str, args: tuple) -> None:
    if not ctx.config.rgb:
        raise GLUsageError(f"{describe(name, args)}: it is an error to call {name} while "
                           "the framebuffer is in colour map mode (cpack(3G)); use color()")


def _need_cmode(ctx, name: str, args: tuple) -> None:
    if ctx.config.rgb:
        raise GLUsageError(f"{describe(name, args)}: it is an error to call {name} while "
                           "the framebuffer is in RGB mode (color(3G)); use cpack()/c3f()")


def _byte(v: float) -> int:
    """A [0, 1] component as the 8-bit value the kernels write (numeric model s.4)."""
    return min(255, max(0, math.floor(v * 255.0 + 0.5)))


def packed_colour(ctx) -> int:
    """The current colour as a colour-plane word: 0xAABBGGRR, or the index in cmode."""
    if not ctx.config.rgb:
        return ctx.colour_index
    r, g, b, a = (_byte(c) for c in ctx.colour)
    return r | (g << 8) | (b << 16) | (a << 24)


def _set_rgba(ctx, rgba: tuple[float, float, float, float]) -> None:
    """Route an RGB colour command through lmcolor(3G) (see the module docstring)."""
    if not ctx.lighting_active():
        ctx.colour = rgba
        ctx.last_sent = "colour"
        return
    mode = ctx.lmcolor_mode
    if mode == _LMC_NULL:
        return
    ctx.colour = rgba
    if mode != _LMC_COLOR:
        ctx.lmcolor_set = True  # a material property now, the vertex stays lit
    else:
        ctx.last_sent = "colour"


_LMC_NULL, _LMC_COLOR = int(GL.LMC_NULL), int(GL.LMC_COLOR)


def _floats(name: str, args: tuple, n: int) -> tuple[float, ...]:
    vals = flat_numbers(name, args, n)
    for i, v in enumerate(vals):
        if not math.isfinite(v):
            raise GLValueError(f"{describe(name, args)}: element {i} is {v!r}, not a finite "
                               "number")
    return tuple(min(1.0, max(0.0, v)) for v in vals)


def _ints(name: str, args: tuple, n: int) -> tuple[float, ...]:
    vals = flat_numbers(name, args, n, integer=True)
    return tuple(min(255, max(0, v)) / 255.0 for v in vals)


# -- RGBmode -------------------------------------------------------------------------
_BYTE = tuple(v / 255.0 for v in range(256))  # a colour byte as a [0, 1] float


def _cpack_rgba(args: tuple) -> tuple[float, float, float, float]:
    w = args[0]
    if type(w) is not int:
        w = as_int("cpack", args, "abgr", w, wrap=True)
    w &= 0xFFFFFFFF  # C unsigned long
    return (_BYTE[w & 0xFF], _BYTE[(w >> 8) & 0xFF], _BYTE[(w >> 16) & 0xFF],
            _BYTE[w >> 24])


def _rgbcolor_rgba(args: tuple) -> tuple[float, float, float, float]:
    rgb = [min(255, max(0, as_int("RGBcolor", args, n, v))) / 255.0
           for n, v in zip("rgb", args, strict=True)]
    return (rgb[0], rgb[1], rgb[2], 1.0)


def _float_rgba(name: str, n: int):
    if n == 3:
        def rgba(args: tuple) -> tuple:
            if len(args) == 3:
                r, g, b = args
                if (type(r) is float and type(g) is float and type(b) is float
                        and 0.0 <= r <= 1.0 and 0.0 <= g <= 1.0 and 0.0 <= b <= 1.0):
                    return (r, g, b, 1.0)  # fast path: in range already
            return _floats(name, args, 3) + (1.0,)
        return rgba
    return lambda args: _floats(name, args, 4)


def _int_rgba(name: str, n: int):
    if n == 3:
        return lambda args: _ints(name, args, 3) + (1.0,)
    return lambda args: _ints(name, args, 4)


def _colour_call(name: str, rgba_of, doc: str):
    """An RGB colour call from the function giving its RGBA (also what display objects
    record)."""

    def general(*args, **kwargs) -> None:
        if kwargs or session.recording is not None:
            return record_or_refuse(body, args, kwargs)
        ctx = current(name, args)
        if not ctx.config.rgb:
            _need_rgb(ctx, name, args)
        _set_rgba(ctx, rgba_of(args))

    def body(*args, **kwargs) -> None:
        ctx = session.imm
        if ctx is None or kwargs:
            return general(*args, **kwargs)
        if not ctx.config.rgb:
            _need_rgb(ctx, name, args)
        _set_rgba(ctx, rgba_of(args))

    body.__name__ = body.__qualname__ = name
    body.__doc__ = doc
    call = gl_function(binds=(0, math.inf, ()))(body)
    call.stream_rgba = rgba_of
    call.general = general
    return call


def _c3f_call(doc: str):
    """c3f: :func:`_colour_call` with its valid path inlined (three floats already in
    [0, 1], separately or as one tuple or list, into an RGB window)."""
    rgba_of = _float_rgba("c3f", 3)
    slow = _colour_call("c3f", rgba_of, doc)
    general = slow.general

    def c3f(r=_NO, g=_NO, b=_NO, /, *more, **kw) -> None:
        ctx = session.imm
        p = None
        if b is _NO and g is _NO and (type(r) is tuple or type(r) is list) and len(r) == 3:
            p = r
            r, g, b = p
        if (ctx is None or kw or more
                or type(r) is not float or type(g) is not float or type(b) is not float
                or not (0.0 <= r <= 1.0 and 0.0 <= g <= 1.0 and 0.0 <= b <= 1.0)
                or not ctx.config.rgb):
            return general(*((p,) if p is not None else given((r, g, b), more)), **kw)
        bound = ctx.bound
        if bound["material"] != 0 and bound["lmodel"] != 0:  # Context.lighting_active
            _set_rgba(ctx, (r, g, b, 1.0))  # lmcolor(3G) decides
            return
        ctx.colour = (r, g, b, 1.0)
        ctx.last_sent = "colour"

    c3f.__doc__ = doc
    call = gl_function(binds=(0, math.inf, ()))(c3f)
    call.stream_rgba = rgba_of
    return call


c3f = _c3f_call("""Current colour from 3 floats in [0, 1]: ``c3f((r, g, b))`` or
    ``c3f(r, g, b)``; alpha 1.0, values outside [0, 1] saturate.""")
def _c4f_call(doc: str):
    """c4f: :func:`_colour_call` with its valid path inlined, as :func:`_c3f_call`
    (four floats already in [0, 1], separately or as one tuple or list)."""
    rgba_of = _float_rgba("c4f", 4)
    slow = _colour_call("c4f", rgba_of, doc)
    general = slow.general

    def c4f(r=_NO, g=_NO, b=_NO, a=_NO, /, *more, **kw) -> None:
        ctx = session.imm
        p = None
        if (a is _NO and b is _NO and g is _NO and (type(r) is tuple or type(r) is list)
                and len(r) == 4):
            p = r
            r, g, b, a = p
        if (ctx is None or kw or more
                or type(r) is not float or type(g) is not float or type(b) is not float
                or type(a) is not float
                or not (0.0 <= r <= 1.0 and 0.0 <= g <= 1.0 and 0.0 <= b <= 1.0
                        and 0.0 <= a <= 1.0)
                or not ctx.config.rgb):
            return general(*((p,) if p is not None else given((r, g, b, a), more)), **kw)
        bound = ctx.bound
        if bound["material"] != 0 and bound["lmodel"] != 0:  # Context.lighting_active
            _set_rgba(ctx, (r, g, b, a))  # lmcolor(3G) decides
            return
        ctx.colour = (r, g, b, a)
        ctx.last_sent = "colour"

    c4f.__doc__ = doc
    call = gl_function(binds=(0, math.inf, ()))(c4f)
    call.stream_rgba = rgba_of
    return call


c4f = _c4f_call("Current colour from 4 floats in [0, 1] (r, g, b, a); values saturate.")
c3i = _colour_call("c3i", _int_rgba("c3i", 3),
                   "Current colour from 3 ints 0..255 (alpha 255); values saturate.")
c4i = _colour_call("c4i", _int_rgba("c4i", 4),
                   "Current colour from 4 ints 0..255 (r, g, b, a); values saturate.")
c3s = _colour_call("c3s", _int_rgba("c3s", 3),
                   "As :func:`c3i` (the C form takes shorts).")
c4s = _colour_call("c4s", _int_rgba("c4s", 4),
                   "As :func:`c4i` (the C form takes shorts).")


def _general_cpack(*args, **kwargs) -> None:
    if kwargs or session.recording is not None or len(args) != 1:
        return record_or_refuse(cpack, args, kwargs)
    ctx = current("cpack", args)
    if not ctx.config.rgb:
        _need_rgb(ctx, "cpack", args)
    _set_rgba(ctx, _cpack_rgba(args))


@gl_function(binds=(1, 1, ("int",)))
def cpack(abgr=_NO, /, *more, **kw) -> None:
    """cpack(abgr): set the current colour from one packed word 0xAABBGGRR (cpack(3G)).

    Red is the low byte; alpha comes from the high byte, so ``cpack(0xFF)`` is red
    with alpha 0.
    """
    ctx = session.imm
    if ctx is None or kw or more or type(abgr) is not int or not ctx.config.rgb:
        return _general_cpack(*given((abgr,), more), **kw)
    packed = session.packed  # (interned colours, see _Session.reset)
    rgba = packed.get(abgr)
    if rgba is None:
        if len(packed) >= 4096:
            packed.clear()
        rgba = packed[abgr] = _cpack_rgba((abgr,))
    bound = ctx.bound
    if bound["material"] != 0 and bound["lmodel"] != 0:  # Context.lighting_active
        _set_rgba(ctx, rgba)  # lmcolor(3G) decides
        return
    ctx.colour = rgba
    ctx.last_sent = "colour"


cpack.stream_rgba = _cpack_rgba


def _general_RGBcolor(*args, **kwargs) -> None:
    if kwargs or session.recording is not None or len(args) != 3:
        return record_or_refuse(RGBcolor, args, kwargs)
    ctx = current("RGBcolor", args)
    _need_rgb(ctx, "RGBcolor", args)
    _set_rgba(ctx, _rgbcolor_rgba(args))


@gl_function(binds=(3, 3, ("int", "int", "int")))
def RGBcolor(r=_NO, g=_NO, b=_NO, /, *more, **kw) -> None:
    """Set the current colour from 0..255 components (RGBcolor(3G)); alpha 255.

    Alpha is set to 255 (as IGL does; the manual page says nothing about alpha).
    """
    ctx = session.imm
    # Valid path (FAST_CALLS): three ints 0..255 into an RGB window (_BYTE[v] is the
    # general path's v / 255.0); anything else, saturated values included, goes to
    # the general path.
    if (ctx is None or kw or more or type(r) is not int or type(g) is not int
            or type(b) is not int or not (0 <= r <= 255 and 0 <= g <= 255 and 0 <= b <= 255)
            or not ctx.config.rgb):
        return _general_RGBcolor(*given((r, g, b), more), **kw)
    rgba = (_BYTE[r], _BYTE[g], _BYTE[b], 1.0)
    bound = ctx.bound
    if bound["material"] != 0 and bound["lmodel"] != 0:  # Context.lighting_active
        _set_rgba(ctx, rgba)  # lmcolor(3G) decides
        return
    ctx.colour = rgba
    ctx.last_sent = "colour"


RGBcolor.stream_rgba = _rgbcolor_rgba


@gl_function(record=False)
def gRGBcolor() -> tuple[int, int, int]:
    """The current RGB colour as 0..255 ints (gRGBcolor(3G))."""
    ctx = current("gRGBcolor")
    _need_rgb(ctx, "gRGBcolor", ())
    r, g, b, _a = (_byte(c) for c in ctx.colour)
    return (r, g, b)


@gl_function(record=False)
def gRGBmask() -> tuple[int, int, int]:
    """The red, green and blue bytes of the colour write mask (gRGBmask(3G))."""
    ctx = current("gRGBmask")
    _need_rgb(ctx, "gRGBmask", ())
    w = ctx.raster.wmpack & 0xFFFFFFFF
    return (w & 0xFF, (w >> 8) & 0xFF, (w >> 16) & 0xFF)


# -- cmode -------------------------------------------------------------------------
def _set_index(ctx, name: str, args: tuple, index: int) -> None:
    if index < 0:
        raise GLValueError(f"{describe(name, args)}: colour index {index} is negative "
                           "(color(3G): indices below zero are undefined)")
    # color(3G): "Color indices larger than 2**n-1 are clamped to 2**n-1".
    index = min(index, colormap.map_size(ctx.multimap) - 1)
    ctx.colour_index = index
    ctx.colour = colormap.index_rgba(index)
    ctx.last_sent = "colour"


@gl_function()
def color(c: int) -> None:
    """Set the current colour index (color(3G)); cmode only.

    Indices above the map size (4096, or 256 with multimap) clamp to the last entry.
    """
    args = (c,)
    ctx = current("color", args)
    _need_cmode(ctx, "color", args)
    _set_index(ctx, "color", args, as_int("color", args, "c", c))


@gl_function()
def colorf(c: float) -> None:
    """Set the current colour index from a float, rounded to the nearest integer
    (color(3G)); fractional indices are not iterated (GD_CIFRACT 0)."""
    args = (c,)
    ctx = current("colorf", args)
    _need_cmode(ctx, "colorf", args)
    v = as_float("colorf", args, "c", c)
    if not math.isfinite(v):
        raise GLValueError(f"{describe('colorf', args)}: c must be a finite number")
    _set_index(ctx, "colorf", args, math.floor(v + 0.5))


@gl_function(record=False)
def getcolor() -> int:
    """The current colour index (getcolor(3G))."""
    return current("getcolor").colour_index


@gl_function()
def writemask(wtm: int) -> None:
    """Colour-index write mask, one bit per plane (writemask(3G)); cmode only.

    Bits above the 12 colour-index planes are ignored.
    """
    args = (wtm,)
    ctx = current("writemask", args)
    _need_cmode(ctx, "writemask", args)
    ctx.raster.set(wmpack=as_int("writemask", args, "wtm", wtm) & (colormap.MAP_SIZE - 1))


@gl_function(record=False)
def getwritemask() -> int:
    """The colour write mask: the index planes in cmode, the packed word in RGBmode."""
    ctx = current("getwritemask")
    w = ctx.raster.wmpack & 0xFFFFFFFF
    return w if ctx.config.rgb else w & (colormap.MAP_SIZE - 1)


def _map_index(ctx, name: str, args: tuple, i) -> int:
    index = as_int(name, args, "i", i)
    size = colormap.map_size(ctx.multimap)
    if not 0 <= index < size:
        raise GLValueError(f"{describe(name, args)}: index {index} is outside the colour "
                           f"map 0..{size - 1}")
    return colormap.map_base(ctx.multimap, ctx.curmap) + index


@gl_function()
def mapcolor(i: int, r: int, g: int, b: int) -> None:
    """Set colour-map entry ``i`` of the current map to (r, g, b), each 0..255
    (mapcolor(3G)).  Pixels already drawn with ``i`` change too: the map is read at
    display time.  Works in both modes, as in IGL."""
    args = (i, r, g, b)
    ctx = current("mapcolor", args)
    entry = _map_index(ctx, "mapcolor", args, i)
    rgb = []
    for n, v in zip("rgb", (r, g, b), strict=True):
        iv = as_int("mapcolor", args, n, v)
        if not 0 <= iv <= 255:
            raise GLValueError(f"{describe('mapcolor', args)}: {n} {iv} is outside 0..255")
        rgb.append(iv)
    ctx.colormap[entry] = rgb


@gl_function(record=False)
def getmcolor(i: int) -> tuple[int, int, int]:
    """Entry ``i`` of the current colour map as (r, g, b) (getmcolor(3G))."""
    args = (i,)
    ctx = current("getmcolor", args)
    entry = _map_index(ctx, "getmcolor", args, i)
    r, g, b = (int(v) for v in ctx.colormap[entry])
    return (r, g, b)


@gl_function(record=False)
def multimap() -> None:
    """Organise the colour map as 16 maps of 256 entries (multimap(3G)).

    Takes effect at once here (IRIS applies it at the next gconfig; the emulator has
    no map hardware to reconfigure).  Map ``n`` is table entries n*256..n*256+255.
    """
    ctx = current("multimap")
    ctx.multimap = True
    ctx.colour_index = min(ctx.colour_index, colormap.MULTIMAP_SIZE - 1)


@gl_function(record=False)
def onemap() -> None:
    """Organise the colour map as one map of 4096 entries (onemap(3G), the default)."""
    current("onemap").multimap = False


@gl_function(record=False)
def getcmmode() -> int:
    """1 (TRUE) in onemap mode, 0 in multimap mode (getcmmode(3G))."""
    return 0 if current("getcmmode").multimap else 1


@gl_function(record=False)
def setmap(mapnum: int) -> None:
    """Select the small map (0..15) that multimap mode displays and mapcolor edits
    (setmap(3G)).  Stored in onemap mode too, where it has no effect until
    multimap()."""
    args = (mapnum,)
    ctx = current("setmap", args)
    n = as_int("setmap", args, "mapnum", mapnum)
    if not 0 <= n < colormap.NMAPS:
        raise GLValueError(f"{describe('setmap', args)}: mapnum {n} is outside "
                           f"0..{colormap.NMAPS - 1} (getgdesc(GD_NMMAPS) is 16)")
    ctx.curmap = n


@gl_function(record=False)
def getmap() -> int:
    """The current small map in multimap mode, 0 in onemap mode (getmap(3G))."""
    ctx = current("getmap")
    return ctx.curmap if ctx.multimap else 0
