"""IRIS GL pixel calls: lrectread, lrectwrite, rectread, rectwrite, rectzoom, readRGB,
writeRGB, readpixels, writepixels, rectcopy, readdisplay, packrect/unpackrect, and
:func:`read_pixels` for library users.

Zoom.  ``rectzoom(xfactor, yfactor)`` (rectzoom(3G)) scales what ``lrectwrite`` and
``rectwrite`` write: destination pixel ``(x1 + X, y1 + Y)`` takes source pixel
``(floor(X / xfactor), floor(Y / yfactor))``, so an integer factor replicates each
pixel into an xfactor x yfactor block (**choice** for fractional factors: the
manual says only that pixels are scaled; this is nearest-pixel sampling).
``rectcopy`` is not zoomed.

Colour-index rows and rectangles.  ``rectwrite``/``rectread`` are the 16-bit
(Colorindex) forms of lrectwrite/lrectread, colour-map mode only; ``writepixels(n,
colors)``/``readpixels(n)`` and ``writeRGB(n, r, g, b)`` (with readRGB) write and read
a row from the current character position, which then moves past it (writepixels(3G)).

Pixel words.  Colour pixels are packed 0xAABBGGRR (red in the low byte, lrectwrite(3G));
in colour-map mode the word holds the colour index.  CPython's binding returned
``lrectread`` as a string of native C longs (cpython_gl_module.md s.1.6); vgxsim
returns ``bytes`` of 4-byte **little-endian** words, bottom row first, left to right,
so ``bytes[0]`` is the red byte of the lower-left pixel.  ``np.frombuffer(s, '<u4')``
turns it back into words.

Reads see everything drawn so far (the command batch is flushed first) from the
buffer ``readsource`` selects.  Writes (``lrectwrite``, ``rectcopy``) land in order
with the drawing before them: through the software batch they are copied into the
planes after a flush (``PLANE_COPY``), otherwise queued in the batch as fragments.

Rectangles and the window.  IRIS GL leaves pixels outside the window undefined
(lrectread(3G), rectcopy(3G)); vgxsim reads them as 0 and never writes them.  The
work of every call is clipped to the window first, so it costs what the window
holds, never what the rectangle asks for: ``rectcopy`` of a 2**31-pixel rectangle
in a 64x48 window copies at most 64x48 pixels.  A call that *returns* a rectangle
(``lrectread``, ``readdisplay``) still returns every pixel asked for, as the binding
promises, so its rectangle may be at most ``MAX_WINDOW_SIZE`` (16384) pixels a side
(the largest window; a larger one raises GLValueError instead of a 2**62-byte
allocation).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from vgxsim import GL
from vgxsim.batch import CommandBatch

from ._core import (
    GLTypeError,
    GLUsageError,
    GLValueError,
    as_array,
    as_int,
    current,
    describe,
    gl_function,
    session,
    window_of,
)
from ._window import MAX_WINDOW_SIZE

__all__ = [
    "lrectread", "lrectwrite", "readRGB", "rectcopy", "readdisplay", "packrect",
    "unpackrect", "read_pixels", "rectzoom", "rectwrite", "rectread", "writepixels",
    "readpixels", "writeRGB",
]


def _corners(name: str, args: tuple, ordered: bool = True) -> tuple[int, int, int, int]:
    """(x1, y1, x2, y2) as ints; ``ordered`` requires x1 <= x2 and y1 <= y2."""
    names = ("x1", "y1", "x2", "y2")
    v = [as_int(name, args, n, a) for n, a in zip(names, args[:4], strict=True)]
    x1, y1, x2, y2 = v
    if ordered and (x2 < x1 or y2 < y1):
        raise GLValueError(f"{describe(name, args)}: the rectangle is empty (x2 < x1 or "
                           "y2 < y1); lrectread/lrectwrite take the lower-left corner first")
    if not ordered:
        x1, x2 = min(x1, x2), max(x1, x2)
        y1, y2 = min(y1, y2), max(y1, y2)
    return x1, y1, x2, y2


def _source(ctx, name: str, args: tuple, allow_z: bool = True) -> np.ndarray:
    """The plane ``readsource`` selects, as uint32 words (z as two's-complement words)."""
    src = int(ctx.readsource)
    if src == GL.SRC_ZBUFFER:
        if not allow_z:
            raise GLUsageError(f"{describe(name, args)}: readsource(SRC_ZBUFFER) is set; "
                               f"{name} reads colour (use readsource(SRC_AUTO))")
        ctx.flush()
        if ctx.fb.z is None:
            raise GLUsageError(f"{describe(name, args)}: readsource(SRC_ZBUFFER) but the "
                               "window has no z-buffer (zbsize(0) was configured)")
        return ctx.fb.z.view(np.uint32)
    layer = _LAYER_SOURCES.get(src)
    if layer is not None:
        return ctx.layer_buffer(layer)
    which = {int(GL.SRC_FRONT): "front", int(GL.SRC_BACK): "back"}.get(src, "auto")
    return ctx.colour_buffer(which)


#: readdisplay hints that leave a framebuffer out of the picture.
_IGNORE_HINTS = ((int(GL.RD_IGNORE_PUP), "popup"), (int(GL.RD_IGNORE_OVERLAY), "overlay"),
                 (int(GL.RD_IGNORE_UNDERLAY), "underlay"))

#: readsource tokens of the extra framebuffers (vgxsim.pipeline.layers names).
_LAYER_SOURCES = {int(GL.SRC_PUP): "popup", int(GL.SRC_OVER): "overlay",
                  int(GL.SRC_UNDER): "underlay"}


def _returned_size(name: str, args: tuple, x1: int, y1: int, x2: int, y2: int
                   ) -> tuple[int, int]:
    """(width, height) of a rectangle a call returns; each side at most
    MAX_WINDOW_SIZE (see the module docstring)."""
    w, h = x2 - x1 + 1, y2 - y1 + 1
    if w > MAX_WINDOW_SIZE or h > MAX_WINDOW_SIZE:
        raise GLValueError(f"{describe(name, args)}: a {w}x{h} rectangle is larger than "
                           f"the largest window ({MAX_WINDOW_SIZE}x{MAX_WINDOW_SIZE}); "
                           "read the part of the window you need")
    return w, h


def _clip(lo: int, hi: int, size: int) -> tuple[int, int]:
    """The part of the inclusive range lo..hi inside 0..size-1 (empty when lo > hi)."""
    return max(lo, 0), min(hi, size - 1)


def _region(plane: np.ndarray, x1: int, y1: int, x2: int, y2: int) -> np.ndarray:
    """plane[y1..y2, x1..x2] with zeros where the rectangle leaves the window (pixels
    outside a window are undefined on IRIS; zero is the documented choice here)."""
    h, w = plane.shape[:2]
    out = np.zeros((y2 - y1 + 1, x2 - x1 + 1) + plane.shape[2:], dtype=plane.dtype)
    xa, xb = max(x1, 0), min(x2, w - 1)
    ya, yb = max(y1, 0), min(y2, h - 1)
    if xa <= xb and ya <= yb:
        out[ya - y1:yb - y1 + 1, xa - x1:xb - x1 + 1] = plane[ya:yb + 1, xa:xb + 1]
    return out


@gl_function(record=False)
def lrectread(x1: int, y1: int, x2: int, y2: int) -> bytes:
    """Read a rectangle of pixels, inclusive bounds (lrectread(3G)).

    Returns
    -------
    bytes
        ``(x2-x1+1) * (y2-y1+1)`` little-endian 32-bit words, bottom row first:
        packed 0xAABBGGRR colours (colour indices in cmode), or signed z values when
        ``readsource(SRC_ZBUFFER)`` is set.  Pixels outside the window read as 0.
    """
    args = (x1, y1, x2, y2)
    r = _corners("lrectread", args)
    _returned_size("lrectread", args, *r)
    ctx = current("lrectread", args)
    words = _region(_source(ctx, "lrectread", args), *r)
    return np.ascontiguousarray(words, dtype="<u4").tobytes()


def _words(name: str, args: tuple, data, n: int) -> np.ndarray:
    """The pixel array of lrectwrite: bytes of >= n little-endian words (uint32), or
    n ints (int64, 0 .. 2**32 - 1)."""
    if isinstance(data, (bytes, bytearray, memoryview)):
        raw = bytes(data)
        if len(raw) < 4 * n:
            raise GLValueError(f"{describe(name, args)}: data has {len(raw)} bytes, the "
                               f"rectangle needs {n} pixels = {4 * n} bytes")
        # CPython's binding did not check the size (so pixmode(PM_SIZE) kept working);
        # extra bytes are ignored here, too few are an error.
        # A read-only view (no copy of a full window's 5 MB): every use indexes or
        # copies it.
        return np.frombuffer(raw, dtype="<u4", count=n)
    if isinstance(data, np.ndarray) or (isinstance(data, Sequence) and not isinstance(
            data, str)):
        arr = as_array(name, args, "data", data)
        if arr.dtype.kind not in "iub":
            raise GLTypeError(f"{describe(name, args)}: pixel values must be integers, not "
                              f"{arr.dtype}")
        arr = arr.reshape(-1)
        if arr.size != n:
            raise GLValueError(f"{describe(name, args)}: {arr.size} pixel values for a "
                               f"rectangle of {n} pixels")
        # unsigned long words: negative Python ints wrap as a C cast would
        return arr.astype(np.int64) & 0xFFFFFFFF
    raise GLTypeError(f"{describe(name, args)}: data must be bytes (as lrectread returns) "
                      f"or a sequence of ints, not {type(data).__name__}")


#: Fast path switch: a rectangle written through the software batch is copied into
#: the planes directly instead of being queued as one fragment per pixel.  Off, every
#: write takes the fragment path; the planes are the same (tests/gl/test_readback.py).
PLANE_COPY = True


def _write_pixels(ctx, x0: int, y0: int, words: np.ndarray, valid: np.ndarray) -> None:
    """Queue pixel writes with lower-left corner (x0, y0): words (h, w) packed.

    Pixel writes skip every test and blending (the clear state: no z, stencil or alpha
    test) but go through the viewport, the screen mask (scrmask(3G): "pixel write and
    pixel copy commands" are masked) and the colour write mask, to the draw buffers.
    """
    rs = ctx.raster.clear_state()
    batch = ctx.batch
    if PLANE_COPY and type(batch) is CommandBatch and valid.all():
        _copy_into_planes(batch, rs, x0, y0, words)
        return
    ys, xs = np.nonzero(valid)
    if ys.size == 0:
        return
    xy = np.stack([xs.astype(np.int64) + x0, ys.astype(np.int64) + y0], axis=1)
    x_lo, x_hi, y_lo, y_hi = rs.scissor
    inside = (xy[:, 0] >= x_lo) & (xy[:, 0] <= x_hi) & (xy[:, 1] >= y_lo) & (xy[:, 1] <= y_hi)
    if not inside.any():
        return
    xy = np.ascontiguousarray(xy[inside])
    rgba = np.ascontiguousarray(words[ys, xs][inside].astype(np.int64) & 0xFFFFFFFF)
    batch.add_fragments(xy, np.zeros(xy.shape[0], np.int64), rgba, rs)


def _copy_into_planes(batch: CommandBatch, rs, x0: int, y0: int, words: np.ndarray) -> None:
    """What the fragment path does with a rectangle, as array copies.

    The clear state ``rs`` has no z, stencil or alpha test, blendfunction(BF_ONE,
    BF_ZERO) and logicop LO_SRC, so each fragment the kernels would write stores
    ``(old & ~wmpack) | (word & wmpack)`` in each draw buffer, inside the raster
    rectangle (viewport and screen mask); a single-buffered window draws its one
    buffer for either.  The batch is flushed first so that the write lands after
    everything queued before it, as a queued fragment run would.
    """
    fb = batch.fb
    h, w = words.shape
    x_lo, x_hi, y_lo, y_hi = rs.scissor
    xa, xb = max(x0, x_lo), min(x0 + w - 1, x_hi)
    ya, yb = max(y0, y_lo), min(y0 + h - 1, y_hi)
    wm = rs.wmpack & 0xFFFFFFFF
    planes = []
    if fb.back is None:
        if rs.draw_front or rs.draw_back:
            planes.append(fb.front)
    else:
        planes += [fb.back] if rs.draw_back else []
        planes += [fb.front] if rs.draw_front else []
    if xa > xb or ya > yb or wm == 0 or not planes:
        return
    batch.flush()
    src = words[ya - y0:yb - y0 + 1, xa - x0:xb - x0 + 1]
    if src.dtype != np.uint32:  # wraps modulo 2**32, as the fragment path masks
        src = src.astype(np.uint32)
    for plane in planes:
        dst = plane[ya:yb + 1, xa:xb + 1]
        if wm == 0xFFFFFFFF:
            dst[...] = src
        else:
            dst[...] = (dst & np.uint32(~wm & 0xFFFFFFFF)) | (src & np.uint32(wm))


@gl_function(record=False)
def lrectwrite(x1: int, y1: int, x2: int, y2: int, data) -> None:
    """Write a rectangle of packed pixels, inclusive bounds (lrectwrite(3G)).

    Parameters
    ----------
    x1, y1, x2, y2 : int
        Lower-left and upper-right corners, window coordinates.
    data : bytes or sequence of int
        ``(x2-x1+1) * (y2-y1+1)`` pixels, bottom row first: little-endian 32-bit
        words as :func:`lrectread` returns them, or ints 0xAABBGGRR (colour indices
        in cmode).

    Notes
    -----
    The pixels are written unconditionally -- no z, stencil or alpha test, no
    blending or logicop -- except for the colour write mask (``wmpack``/``writemask``)
    and the viewport/screen mask; they go to the current draw buffers.  ``rectzoom``
    is applied (module docstring); ``pixmode`` is not.
    """
    args = (x1, y1, x2, y2, data)
    r = _corners("lrectwrite", args)
    ctx = current("lrectwrite", args)
    w, h = r[2] - r[0] + 1, r[3] - r[1] + 1
    words = _words("lrectwrite", args, data, w * h).reshape(h, w)
    _write_rect(ctx, r, words)


def _write_rect(ctx, r, words: np.ndarray) -> None:
    """Write words (h, w) with lower-left corner (r[0], r[1]), zoomed by rectzoom."""
    zx, zy = window_of(ctx).rectzoom
    h, w = words.shape
    if (zx, zy) != (1.0, 1.0):
        # Destination columns/rows inside the window only, then their source pixel.
        dw, dh = int(np.ceil(w * zx)), int(np.ceil(h * zy))
        xa, xb = _clip(r[0], r[0] + dw - 1, ctx.width)
        ya, yb = _clip(r[1], r[1] + dh - 1, ctx.height)
        if xa > xb or ya > yb:
            return
        sx = np.minimum(np.floor((np.arange(xa, xb + 1) - r[0]) / zx).astype(np.int64), w - 1)
        sy = np.minimum(np.floor((np.arange(ya, yb + 1) - r[1]) / zy).astype(np.int64), h - 1)
        part = words[sy[:, None], sx[None, :]]
        _write_pixels(ctx, xa, ya, part, np.ones(part.shape, bool))
        return
    # Only the part inside the window can be written: clip before any per-pixel work.
    xa, xb = _clip(r[0], r[2], ctx.width)
    ya, yb = _clip(r[1], r[3], ctx.height)
    if xa > xb or ya > yb:
        return
    part = words[ya - r[1]:yb - r[1] + 1, xa - r[0]:xb - r[0] + 1]
    _write_pixels(ctx, xa, ya, part, np.ones(part.shape, bool))


@gl_function(record=False)
def rectcopy(x1: int, y1: int, x2: int, y2: int, newx: int, newy: int) -> None:
    """Copy a rectangle of pixels to lower-left corner (newx, newy) (rectcopy(3G)).

    The source is the ``readsource`` buffer -- with SRC_ZBUFFER the z-buffer's words,
    copied as colours (how a picture saved there with zdraw(3G) comes back); the copy
    is made before anything is written, so overlapping copies work
    ("Self-intersecting copies work correctly").
    The destination is masked by the viewport, the screen mask and the write mask;
    source pixels outside the window, and pixels that would land outside it, are not
    copied.  ``rectzoom`` is not applied.
    """
    args = (x1, y1, x2, y2, newx, newy)
    r = _corners("rectcopy", args, ordered=False)
    nx = as_int("rectcopy", args, "newx", newx)
    ny = as_int("rectcopy", args, "newy", newy)
    ctx = current("rectcopy", args)
    plane = _source(ctx, "rectcopy", args)
    h, w = plane.shape
    # Clip the source to the window, then its image at (newx, newy) to the window:
    # only pixels that exist and land inside are copied, so the cost is bounded by
    # the window whatever the rectangle (Python ints: no overflow).
    xa, xb = _clip(r[0], r[2], w)
    ya, yb = _clip(r[1], r[3], h)
    dx, dy = nx - r[0], ny - r[1]  # source pixel (x, y) goes to (x + dx, y + dy)
    xa, xb = max(xa, -dx), min(xb, w - 1 - dx)
    ya, yb = max(ya, -dy), min(yb, h - 1 - dy)
    if xa > xb or ya > yb:
        return
    words = plane[ya:yb + 1, xa:xb + 1].astype(np.int64)
    _write_pixels(ctx, xa + dx, ya + dy, words, np.ones(words.shape, bool))


@gl_function(record=False)
def readRGB(n: int) -> tuple[int, list[int], list[int], list[int]]:  # noqa: N802
    """Read ``n`` pixels from the current character position along its row (readRGB(3G)).

    Returns
    -------
    tuple
        ``(count, red, green, blue)``: count pixels were read (fewer than ``n`` when
        the row ends at the window's right edge; 0 when the position is outside the
        window, whose pixels IRIS GL leaves undefined), and three lists of ints 0..255.

    Notes
    -----
    RGB mode only.  The character position (set by ``cmov``) moves to the pixel after
    the last one read; it becomes undefined (``ctx.cpos_valid`` False) when that is
    outside the viewport, and readRGB from an undefined position reads nothing.
    readRGB is one of the calls CPython's binding left out; this is the natural
    Python form of the C output arrays.
    """
    args = (n,)
    count = as_int("readRGB", args, "n", n)
    if count < 0:
        raise GLValueError(f"{describe('readRGB', args)}: n must not be negative")
    ctx = current("readRGB", args)
    if not ctx.config.rgb:
        raise GLUsageError(f"{describe('readRGB', args)}: readRGB works only in RGB mode "
                           "(call RGBmode() and gconfig() first)")
    if not ctx.cpos_valid:
        # The manual leaves reading from an undefined position undefined; nothing is
        # read and the position stays undefined.
        return 0, [], [], []
    cpos = tuple(ctx.cpos)
    x, y = int(round(float(cpos[0]))), int(round(float(cpos[1])))
    plane = _source(ctx, "readRGB", args, allow_z=False)
    h, w = plane.shape
    got = max(0, min(count, w - x)) if 0 <= y < h and 0 <= x < w else 0
    words = _region(plane, x, y, x + got - 1, y)[0] if got else np.zeros(0, np.uint32)
    ctx.cpos = (x + got, y) + cpos[2:]
    vl, vr, vb, vt = ctx.raster.viewport
    if not (vl <= x + got <= vr and vb <= y <= vt):
        # "the current character position is undefined if the new position is
        # outside the viewport" (readRGB(3G))
        ctx.cpos_valid = False
    r = [int(v) for v in words & 0xFF]
    g = [int(v) for v in (words >> 8) & 0xFF]
    b = [int(v) for v in (words >> 16) & 0xFF]
    return got, r, g, b


@gl_function(record=False)
def readdisplay(x1: int, y1: int, x2: int, y2: int, hints: int = 0) -> bytes:
    """Read a rectangle of the screen, screen coordinates (readdisplay(3G)).

    The headless screen shows every open window at its origin (later windows on
    top, colour-mapped in cmode) on black (0); the result is packed as
    :func:`lrectread`'s.  ``hints``: RD_IGNORE_PUP, RD_IGNORE_OVERLAY and
    RD_IGNORE_UNDERLAY leave those planes out of the picture (readdisplay(3G)); the
    other RD_* flags are accepted and ignored.
    """
    args = (x1, y1, x2, y2, hints)
    r = _corners("readdisplay", args)
    flags = as_int("readdisplay", args, "hints", hints)
    ignore = frozenset(name for bit, name in _IGNORE_HINTS if flags & bit)
    w, h = _returned_size("readdisplay", args, *r)
    out = np.zeros((h, w), np.uint32)
    for gid in sorted(session.windows):
        ctx = session.windows[gid]
        ox, oy = window_of(ctx).origin
        # the window's part of the rectangle, in window coordinates
        xa, xb = _clip(r[0] - ox, r[2] - ox, ctx.width)
        ya, yb = _clip(r[1] - oy, r[3] - oy, ctx.height)
        if xa > xb or ya > yb:
            continue
        img = ctx.display_rgba(ignore)
        words = np.ascontiguousarray(img).view("<u4").reshape(img.shape[:2])
        out[ya + oy - r[1]:yb + oy - r[1] + 1, xa + ox - r[0]:xb + ox - r[0] + 1] = \
            words[ya:yb + 1, xa:xb + 1]
    return np.ascontiguousarray(out, dtype="<u4").tobytes()


@gl_function(record=False)
def packrect(width: int, height: int, packfactor: int, data: bytes) -> bytes:
    """Shrink a ``width`` x ``height`` lrectread string to one grey byte per
    ``packfactor`` square (CPython's ``gl.packrect``, cpython_gl_module.md s.1.6).

    Each byte is ``(30 R + 59 G + 11 B) // 100`` of the first (lower-left) pixel of
    its block; there is no averaging.
    """
    args = (width, height, packfactor, data)
    w, h, pf = (as_int("packrect", args, n, v) for n, v in
                (("width", width), ("height", height), ("packfactor", packfactor)))
    if w <= 0 or h <= 0 or pf <= 0:
        raise GLValueError(f"{describe('packrect', args)}: sizes must be positive")
    if not isinstance(data, (bytes, bytearray, memoryview)) or len(data) != 4 * w * h:
        raise GLValueError(f"{describe('packrect', args)}: data must be exactly "
                           f"{4 * w * h} bytes (width * height longs)")
    words = np.frombuffer(bytes(data), "<u4").reshape(h, w)[::pf, ::pf].astype(np.int64)
    grey = (30 * (words & 0xFF) + 59 * ((words >> 8) & 0xFF) + 11 * ((words >> 16) & 0xFF))
    return (grey // 100).astype(np.uint8).tobytes()


@gl_function(record=False)
def unpackrect(width: int, height: int, packfactor: int, data: bytes) -> bytes:
    """Inverse of :func:`packrect`: each grey byte ``g`` becomes the word
    ``g * 0x010101`` (alpha 0) over its ``packfactor`` square; returns
    ``width * height`` words as bytes (CPython's ``gl.unpackrect``)."""
    args = (width, height, packfactor, data)
    w, h, pf = (as_int("unpackrect", args, n, v) for n, v in
                (("width", width), ("height", height), ("packfactor", packfactor)))
    if w <= 0 or h <= 0 or pf <= 0:
        raise GLValueError(f"{describe('unpackrect', args)}: sizes must be positive")
    cw, ch = -(-w // pf), -(-h // pf)
    if not isinstance(data, (bytes, bytearray, memoryview)) or len(data) != cw * ch:
        raise GLValueError(f"{describe('unpackrect', args)}: data must be exactly "
                           f"{cw * ch} bytes (one per {pf}x{pf} block)")
    small = np.frombuffer(bytes(data), np.uint8).reshape(ch, cw).astype("<u4") * 0x010101
    big = np.repeat(np.repeat(small, pf, axis=0), pf, axis=1)[:h, :w]
    return np.ascontiguousarray(big, dtype="<u4").tobytes()


_PLANES = ("color", "packed", "z", "stencil", "accum")


def read_pixels(buffer: str = "front", plane: str = "color") -> np.ndarray:
    """A copy of one plane of the current window as a numpy array, row 0 = bottom.

    Not an IRIS GL call: the library users' way to get images and buffers out.

    Parameters
    ----------
    buffer : {'front', 'back', 'display'}
        Which colour buffer ('back' needs a double-buffered window); 'display' is
        the front buffer as the monitor shows it (colour-mapped in cmode).  Ignored
        for the z, stencil and accumulation planes.
    plane : {'color', 'packed', 'z', 'stencil', 'accum'}
        'color': (H, W, 4) uint8 RGBA; 'packed': (H, W) uint32 0xAABBGGRR words
        (colour indices in cmode); 'z': (H, W) int32; 'stencil': (H, W) uint8;
        'accum': (H, W, 4) int16.

    Returns
    -------
    numpy.ndarray

    Raises
    ------
    GLUsageError
        Before winopen, or for a plane the window was not configured with.
    GLValueError
        For an unknown buffer or plane name.
    GLTypeError
        When ``buffer`` or ``plane`` is not a str.
    """
    args = (buffer, plane)
    for what, v in (("buffer", buffer), ("plane", plane)):
        if not isinstance(v, str):
            raise GLTypeError(f"{describe('read_pixels', args)}: {what} must be a str "
                              f"naming it, not {type(v).__name__}")
    if buffer not in ("front", "back", "display"):
        raise GLValueError(f"{describe('read_pixels', args)}: buffer must be 'front', "
                           "'back' or 'display'")
    if plane not in _PLANES:
        raise GLValueError(f"{describe('read_pixels', args)}: plane must be one of "
                           f"{', '.join(_PLANES)}")
    ctx = current("read_pixels", args)
    ctx.flush()
    if plane in ("z", "stencil", "accum"):
        arr = {"z": ctx.fb.z, "stencil": ctx.fb.stencil, "accum": ctx.fb.accum}[plane]
        if arr is None:
            raise GLUsageError(f"{describe('read_pixels', args)}: the window has no {plane} "
                               "planes (configure them with zbsize/stensize/acsize + gconfig)")
        return arr.copy()
    if buffer == "display":
        img = ctx.display_rgba()
        if plane == "packed":
            return np.ascontiguousarray(img).view("<u4").reshape(img.shape[:2]).astype(
                np.uint32)
        return img
    if buffer == "back" and ctx.fb.back is None:
        raise GLUsageError(f"{describe('read_pixels', args)}: the window is single-buffered "
                           "(doublebuffer() + gconfig() gives it a back buffer)")
    if plane == "packed":
        return ctx.colour_buffer(buffer).copy()
    return ctx.read_rgba(buffer)


@gl_function()
def rectzoom(xfactor: float, yfactor: float) -> None:
    """Scale factors of lrectwrite/rectwrite (rectzoom(3G)); both must be > 0."""
    args = (xfactor, yfactor)
    zx = float(xfactor) if isinstance(xfactor, (int, float)) else None
    zy = float(yfactor) if isinstance(yfactor, (int, float)) else None
    if zx is None or zy is None or isinstance(xfactor, bool) or isinstance(yfactor, bool):
        raise GLTypeError(f"{describe('rectzoom', args)}: the factors must be numbers")
    if not (0.0 < zx < 2049.0 and 0.0 < zy < 2049.0):
        raise GLValueError(f"{describe('rectzoom', args)}: the factors must be > 0 "
                           "(and at most 2048)")
    window_of(current("rectzoom", args)).rectzoom = (zx, zy)


def _cmode_only(ctx, name: str, args: tuple) -> None:
    if ctx.config.rgb:
        raise GLUsageError(f"{describe(name, args)}: {name} moves colour indices and works "
                           "only in colour-map mode (use the l* or RGB form in RGB mode)")


@gl_function(record=False)
def rectwrite(x1: int, y1: int, x2: int, y2: int, data) -> None:
    """Write a rectangle of 16-bit colour indices (rectwrite(3G)): ``data`` is bytes
    of little-endian 16-bit words (as rectread returns) or a sequence of ints."""
    args = (x1, y1, x2, y2, data)
    r = _corners("rectwrite", args)
    ctx = current("rectwrite", args)
    _cmode_only(ctx, "rectwrite", args)
    w, h = r[2] - r[0] + 1, r[3] - r[1] + 1
    n = w * h
    if isinstance(data, (bytes, bytearray, memoryview)):
        raw = bytes(data)
        if len(raw) < 2 * n:
            raise GLValueError(f"{describe('rectwrite', args)}: data has {len(raw)} bytes, "
                               f"the rectangle needs {n} pixels = {2 * n} bytes")
        words = np.frombuffer(raw, dtype="<u2", count=n).astype(np.int64)
    else:
        words = _words("rectwrite", args, data, n) & 0xFFFF
    _write_rect(ctx, r, words.reshape(h, w))


@gl_function(record=False)
def rectread(x1: int, y1: int, x2: int, y2: int) -> bytes:
    """Read a rectangle of colour indices as little-endian 16-bit words, bottom row
    first (rectread(3G)); colour-map mode only."""
    args = (x1, y1, x2, y2)
    r = _corners("rectread", args)
    _returned_size("rectread", args, *r)
    ctx = current("rectread", args)
    _cmode_only(ctx, "rectread", args)
    words = _region(_source(ctx, "rectread", args, allow_z=False), *r)
    return np.ascontiguousarray(words & 0xFFFF, dtype="<u2").tobytes()


def _row_start(ctx, name: str, args: tuple, n: int):
    """(x, y, count) of a row access at the character position, or None when the
    position is undefined (nothing is read or written, as readRGB)."""
    if n < 0:
        raise GLValueError(f"{describe(name, args)}: n must not be negative")
    if not ctx.cpos_valid:
        return None
    cpos = tuple(ctx.cpos)
    x, y = int(round(float(cpos[0]))), int(round(float(cpos[1])))
    got = max(0, min(n, ctx.width - x)) if 0 <= y < ctx.height and 0 <= x < ctx.width else 0
    return x, y, got


def _advance(ctx, x: int, y: int, n: int) -> None:
    cpos = tuple(ctx.cpos)
    ctx.cpos = (x + n, y) + cpos[2:]
    vl, vr, vb, vt = ctx.raster.viewport
    if not (vl <= x + n <= vr and vb <= y <= vt):
        ctx.cpos_valid = False


def _row_values(name: str, args: tuple, vals, n: int, lo: int, hi: int) -> np.ndarray:
    try:
        arr = np.asarray(list(vals) if not isinstance(vals, np.ndarray) else vals)
    except (TypeError, ValueError):  # not a sequence, or a ragged one
        raise GLTypeError(f"{describe(name, args)}: expected {n} integers") from None
    if arr.size != n or arr.dtype.kind not in "iub":
        raise GLTypeError(f"{describe(name, args)}: expected {n} integers")
    arr = arr.reshape(-1).astype(np.int64)
    if arr.size and (arr.min() < lo or arr.max() > hi):
        raise GLValueError(f"{describe(name, args)}: values must be {lo}..{hi}")
    return arr


@gl_function(record=False)
def writepixels(n: int, colors) -> None:
    """Write ``n`` colour indices along the row at the character position
    (writepixels(3G)); colour-map mode only.  The position moves past them."""
    args = (n, colors)
    count = as_int("writepixels", args, "n", n)
    ctx = current("writepixels", args)
    _cmode_only(ctx, "writepixels", args)
    vals = _row_values("writepixels", args, colors, count, 0, 0xFFFF)
    _write_row(ctx, "writepixels", args, vals)


@gl_function(record=False)
def writeRGB(n: int, r, g, b) -> None:  # noqa: N802
    """Write ``n`` RGB pixels (0..255 lists) along the row at the character position
    (writeRGB(3G)); RGB mode only.  Alpha is written as 0, as lrectwrite's words
    without an alpha byte."""
    args = (n, r, g, b)
    count = as_int("writeRGB", args, "n", n)
    ctx = current("writeRGB", args)
    if not ctx.config.rgb:
        raise GLUsageError(f"{describe('writeRGB', args)}: writeRGB works only in RGB mode")
    rr, gg, bb = (_row_values("writeRGB", args, c, count, 0, 255) for c in (r, g, b))
    _write_row(ctx, "writeRGB", args, rr | (gg << 8) | (bb << 16))


def _write_row(ctx, name: str, args: tuple, words: np.ndarray) -> None:
    start = _row_start(ctx, name, args, words.size)
    if start is None:
        return
    x, y, got = start
    if got:
        part = words[:got].reshape(1, got)
        _write_pixels(ctx, x, y, part, np.ones(part.shape, bool))
    _advance(ctx, x, y, got)


@gl_function(record=False)
def readpixels(n: int) -> list[int]:
    """Read ``n`` colour indices along the row at the character position
    (readpixels(3G)); fewer at the window's right edge.  Colour-map mode only."""
    args = (n,)
    count = as_int("readpixels", args, "n", n)
    ctx = current("readpixels", args)
    _cmode_only(ctx, "readpixels", args)
    start = _row_start(ctx, "readpixels", args, count)
    if start is None:
        return []
    x, y, got = start
    plane = _source(ctx, "readpixels", args, allow_z=False)
    words = _region(plane, x, y, x + got - 1, y)[0] if got else np.zeros(0, np.uint32)
    _advance(ctx, x, y, got)
    return [int(v) & 0xFFFF for v in words]
