"""Old and hardware-bound IRIS GL calls that real programs still make, given the
meaning they can have headless, so such programs run unchanged.

* Obsolete spellings, done by the call that replaced them: ``setshade``/``getshade``
  are ``color``/``getcolor`` (setshade(3G)), ``spclos`` is ``pclos``, ``smoothline``
  is ``linesmooth``; ``sbox``/``sboxf`` (screen-aligned rectangles, drawn by the VGX
  on a fast path that skips nothing visible) are ``rect``/``rectf`` with the same
  arguments.
* ``splf(coords, indices)``: a filled polygon with one colour index per vertex
  (Gouraud-shaded in colour-map mode, splf(3G)), drawn as ``bgnpolygon`` with
  ``color(i)`` before each ``v3f``; the binding's form (n implied by the lists).
* ``getdepth()``: the depth range set by ``setdepth``/``lsetdepth`` as
  ``(near, far)`` (the binding returns output arguments as a tuple).
* ``nmode(NAUTO | NNORMALIZE)``: accepted; vgxsim normalises every transformed normal
  (vgxsim.lighting), which is what NNORMALIZE asks and what NAUTO does when needed.
* ``getdev(devs)``: the current value of each device (button state or valuator
  value, as getbutton/getvaluator), as a tuple; ``setvaluator(v, init, vmin, vmax)``
  sets valuator ``v`` to ``init`` as if it had moved there (its range is accepted;
  headless valuators move only where the script moves them).
* The AIX colour-map extensions ``mapcolors(start, end, r, g, b)`` and
  ``getmcolors(start, end) -> (r, g, b)`` (lists), done entry by entry with
  mapcolor/getmcolor.  ``RGBsize(8)``: the VGX's only RGB depth (8 bits per
  component, GD_BITS_NORM_SNG_RED); ``monobuffer()``: the only buffering (no stereo).
* ``pushattributes``/``popattributes``: the attribute stack (ATTRIBSTACKDEPTH 10
  levels; a push on a full stack and a pop on an empty one are ignored, as
  pushattributes(3G) says of the push).  Saved, per IRIX 6.5 pushattributes(3G):
  backbuffer, frontbuffer, colour (index and RGB), font, linestyle, lsrepeat,
  linewidth, writemask and RGB writemask, shademodel.  Not saved: cmode/RGBmode (a
  request that only gconfig acts on), pattern (not emulated here) and drawmode.
* Display and keyboard hardware with nothing to show headless: ``swapinterval``
  (every swapbuffers is one frame), ``gsync`` (no vertical retrace to wait for),
  ``ringbell``/``setbell``, ``clkon``/``clkoff`` (keyclick), ``lampon``/``lampoff``
  (keyboard lamps): validated and recorded in ``compat_state()``, no effect.
* ``scrsubdivide(mode, params)``: SS_OFF / SS_DEPTH subdivision of primitives in
  screen space, which the VGX used to correct texture and fog interpolation.
  Accepted and recorded (``compat_state().subdivide``); drawing is unchanged: vgxsim
  has no textures, and its fog is evaluated at the primitive's own vertices.
* ``gl_invert4d(m) -> list of 16 floats``: the inverse of a 4x4 matrix given as
  getmatrix returns one (IGL's helper; a singular matrix is a GLValueError).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from vgxsim import DEVICE, GL

from . import _color, _draw, _oldstyle, _raster
from ._core import (
    GLTypeError,
    GLValueError,
    as_int,
    current,
    describe,
    flat_numbers,
    gl_function,
    topic_state,
)
from ._draw import stream_call
from ._events import event_queue

__all__ = [
    "setshade", "getshade", "spclos", "smoothline", "sbox", "sboxi", "sboxs", "sboxf",
    "sboxfi", "sboxfs", "splf", "splfi", "splfs", "splf2", "splf2i", "splf2s", "getdepth",
    "nmode", "getdev", "setvaluator", "swapinterval", "gsync", "ringbell", "setbell",
    "clkon", "clkoff", "lampon", "lampoff", "mapcolors", "getmcolors", "RGBsize",
    "monobuffer", "pushattributes", "popattributes", "scrsubdivide", "gl_invert4d",
]

ATTRIBSTACKDEPTH = int(GL.ATTRIBSTACKDEPTH)
_RASTER_ATTRIBUTES = ("frontbuffer", "backbuffer", "linestyle", "lsrepeat", "linewidth",
                      "wmpack", "shademodel")


@dataclass
class CompatState:
    """What the hardware-only calls were asked (nothing else reads it)."""

    swapinterval: int = 1
    bell: int = 0
    keyclick: bool = True
    lamps: int = 0
    bells_rung: int = 0
    nmode: int = 0
    subdivide: tuple = (0, ())  # scrsubdivide (mode, params)


def compat_state() -> CompatState:
    """The session's :class:`CompatState`."""
    return topic_state("compat", CompatState)


# -- obsolete spellings ------------------------------------------------------------------
@gl_function(record=False)
def setshade(*args) -> None:
    """setshade(c): the obsolete name of color(c) (setshade(3G))."""
    _color.color(*args)


@gl_function(record=False)
def getshade(*args) -> int:
    """getshade(): the obsolete name of getcolor()."""
    return _color.getcolor(*args)


@gl_function(record=False)
def spclos(*args) -> None:
    """spclos(): the obsolete name of pclos() (close a pmv/pdr polygon)."""
    _oldstyle.pclos(*args)


@gl_function(record=False)
def smoothline(*args) -> None:
    """smoothline(mode): the obsolete name of linesmooth(mode)."""
    _raster.linesmooth(*args)


def _box(filled: bool, suffix: str):
    name = f"sbox{'f' if filled else ''}{suffix}"
    integer = suffix in ("i", "s")
    return stream_call(name, _oldstyle._rect_parse(name, filled, integer),
                       f"{name}(x1, y1, x2, y2): a screen-aligned rectangle, drawn as "
                       f"rect{'f' if filled else ''}{suffix} (sbox(3G)).")


sbox, sboxi, sboxs = (_box(False, s) for s in ("", "i", "s"))
sboxf, sboxfi, sboxfs = (_box(True, s) for s in ("", "i", "s"))


def _splf(dim: int, suffix: str):
    name = f"splf{'2' if dim == 2 else ''}{suffix}"
    integer = suffix in ("i", "s")
    vertex = {3: _draw.v3f, 2: _draw.v2f}[dim]

    def call(*args) -> None:
        if len(args) != 2:
            raise GLTypeError(f"{describe(name, args)}: expected (coords, colorindices)")
        vals = flat_numbers(name, (args[0],), None, integer=integer)
        idx = flat_numbers(name, (args[1],), None, integer=True)
        if len(vals) % dim or len(vals) // dim != len(idx):
            raise GLTypeError(f"{describe(name, args)}: {dim}n coordinates and n colour "
                              f"indices needed, got {len(vals)} and {len(idx)}")
        current(name, args)
        _draw.bgnpolygon()
        for k, ci in enumerate(idx):
            _color.color(ci)
            vertex(vals[k * dim:(k + 1) * dim])
        _draw.endpolygon()

    call.__name__ = call.__qualname__ = name
    call.__doc__ = (f"{name}(coords, colorindices): a filled polygon with a colour index "
                    f"per vertex (splf(3G)), drawn as bgnpolygon / color / v{dim}f.")
    return gl_function(record=False)(call)


splf, splfi, splfs = (_splf(3, s) for s in ("", "i", "s"))
splf2, splf2i, splf2s = (_splf(2, s) for s in ("", "i", "s"))


# -- queries and modes ---------------------------------------------------------------------
@gl_function(record=False)
def getdepth(*args) -> tuple[int, int]:
    """getdepth() -> (near, far): the depth range of setdepth/lsetdepth."""
    near, far = current("getdepth", args).depth_range
    return int(near), int(far)


@gl_function(record=True)
def nmode(mode: int) -> None:
    """nmode(NAUTO | NNORMALIZE): accepted (normals are always normalised)."""
    args = (mode,)
    m = as_int("nmode", args, "mode", mode)
    if m not in (GL.NAUTO, GL.NNORMALIZE):
        raise GLValueError(f"{describe('nmode', args)}: mode must be NAUTO or NNORMALIZE")
    current("nmode", args)
    compat_state().nmode = m


@gl_function(record=False)
def getdev(*args) -> tuple[int, ...]:
    """getdev(devs) -> tuple: the value of each device in ``devs`` (the binding's form
    of getdev(n, devs, vals)): 1/0 for buttons, the value for valuators."""
    if len(args) == 2:
        args = (args[1],)  # getdev(n, devs): n is implied
    if len(args) != 1 or not isinstance(args[0], (list, tuple)):
        raise GLTypeError(f"{describe('getdev', args)}: expected a list of devices")
    q = event_queue()
    out = []
    for d in args[0]:
        dev = as_int("getdev", args, "device", d)
        out.append(q.getbutton(dev) if DEVICE.is_button(dev) else q.getvaluator(dev))
    return tuple(out)


@gl_function(record=False)
def setvaluator(v: int, init: int, vmin: int, vmax: int) -> None:
    """setvaluator(v, init, vmin, vmax): valuator ``v`` takes the value ``init``."""
    args = (v, init, vmin, vmax)
    dev, val, lo, hi = (as_int("setvaluator", args, w, a) for w, a in
                        zip(("v", "init", "vmin", "vmax"), args, strict=True))
    if not DEVICE.is_valuator(dev):
        raise GLValueError(f"{describe('setvaluator', args)}: device {dev} is not a "
                           f"valuator")
    if not lo <= val <= hi:
        raise GLValueError(f"{describe('setvaluator', args)}: init must lie in "
                           f"vmin..vmax")
    event_queue().post(dev, val)


# -- hardware with nothing to show headless ---------------------------------------------------
@gl_function(record=False)
def swapinterval(interval: int) -> None:
    """swapinterval(n): accepted; every swapbuffers makes one frame headless."""
    args = (interval,)
    n = as_int("swapinterval", args, "interval", interval)
    if n < 1:
        raise GLValueError(f"{describe('swapinterval', args)}: interval must be >= 1")
    compat_state().swapinterval = n


@gl_function(record=False)
def gsync(*args) -> None:
    """gsync(): no vertical retrace to wait for headless."""


@gl_function(record=False)
def ringbell(*args) -> None:
    """ringbell(): counted in compat_state(); there is no bell headless."""
    compat_state().bells_rung += 1


@gl_function(record=False)
def setbell(durat: int) -> None:
    """setbell(0 | 1 | 2): bell off, short or long (accepted)."""
    args = (durat,)
    d = as_int("setbell", args, "durat", durat)
    if d not in (0, 1, 2):
        raise GLValueError(f"{describe('setbell', args)}: duration must be 0, 1 or 2")
    compat_state().bell = d


@gl_function(record=False)
def clkon(*args) -> None:
    """clkon(): keyclick on (accepted)."""
    compat_state().keyclick = True


@gl_function(record=False)
def clkoff(*args) -> None:
    """clkoff(): keyclick off (accepted)."""
    compat_state().keyclick = False


def _lamps(name: str, args: tuple) -> int:
    if len(args) != 1:
        raise GLTypeError(f"{describe(name, args)}: expected 1 argument")
    lamps = as_int(name, args, "lamps", args[0])
    if not 0 <= lamps <= 0xFF:
        raise GLValueError(f"{describe(name, args)}: lamps is a byte of lamp bits")
    return lamps


@gl_function(record=False)
def lampon(*args) -> None:
    """lampon(lamps): turn keyboard lamps on (bits of a byte; accepted)."""
    compat_state().lamps |= _lamps("lampon", args)


@gl_function(record=False)
def lampoff(*args) -> None:
    """lampoff(lamps): turn keyboard lamps off (accepted)."""
    compat_state().lamps &= ~_lamps("lampoff", args)


# -- colour-map extensions and the one RGB configuration ----------------------------------------
@gl_function(record=False)
def mapcolors(*args) -> None:
    """mapcolors(start, end, r, g, b): mapcolor(i, r[k], g[k], b[k]) for i = start..end
    (the AIX GL extension; the lists hold end - start + 1 values)."""
    name = "mapcolors"
    if len(args) != 5:
        raise GLTypeError(f"{describe(name, args)}: expected (start, end, r, g, b)")
    lo = as_int(name, args, "start", args[0])
    hi = as_int(name, args, "end", args[1])
    comps = [flat_numbers(name, (a,), None, integer=True) for a in args[2:]]
    n = hi - lo + 1
    if n < 1 or any(len(c) != n for c in comps):
        raise GLTypeError(f"{describe(name, args)}: r, g and b need end - start + 1 = "
                          f"{max(n, 0)} values each")
    for k in range(n):
        _color.mapcolor(lo + k, comps[0][k], comps[1][k], comps[2][k])


@gl_function(record=False)
def getmcolors(*args) -> tuple[list[int], list[int], list[int]]:
    """getmcolors(start, end) -> (r, g, b): the map entries start..end as three lists."""
    name = "getmcolors"
    if len(args) != 2:
        raise GLTypeError(f"{describe(name, args)}: expected (start, end)")
    lo = as_int(name, args, "start", args[0])
    hi = as_int(name, args, "end", args[1])
    if hi < lo:
        raise GLValueError(f"{describe(name, args)}: end must not be below start")
    entries = [_color.getmcolor(i) for i in range(lo, hi + 1)]
    return tuple([e[c] for e in entries] for c in range(3))


@gl_function(record=False)
def RGBsize(planes: int) -> None:  # noqa: N802 - the IRIS GL name
    """RGBsize(planes): bits per RGB component; the VGX has 8 (others are an error)."""
    args = (planes,)
    n = as_int("RGBsize", args, "planes", planes)
    if n != 8:
        raise GLValueError(f"{describe('RGBsize', args)}: the VGX has 8 bits per component "
                           f"(getgdesc(GD_BITS_NORM_SNG_RED))")
    current("RGBsize", args)


@gl_function(record=False)
def monobuffer(*args) -> None:
    """monobuffer(): mono (not stereo) buffering, the only mode vgxsim has."""
    current("monobuffer", args)


# -- the attribute stack ---------------------------------------------------------------------
def _attribute_stack(ctx) -> list:
    return topic_state("attribute-stacks", dict).setdefault(id(ctx), [])


@gl_function(record=True)
def pushattributes(*args) -> None:
    """pushattributes(): save the global state attributes (module docstring)."""
    ctx = current("pushattributes", args)
    stack = _attribute_stack(ctx)
    if len(stack) >= ATTRIBSTACKDEPTH:
        return  # pushattributes(3G): "ignored if the stack is full"
    stack.append({
        "colour": ctx.colour, "colour_index": ctx.colour_index, "font": ctx.font,
        "linestyle_index": ctx.linestyle_index,
        "raster": {k: getattr(ctx.raster, k) for k in _RASTER_ATTRIBUTES},
    })


@gl_function(record=True)
def popattributes(*args) -> None:
    """popattributes(): restore the attributes saved last (ignored on an empty
    stack)."""
    ctx = current("popattributes", args)
    stack = _attribute_stack(ctx)
    if not stack:
        return
    saved = stack.pop()
    ctx.colour, ctx.colour_index = saved["colour"], saved["colour_index"]
    ctx.font, ctx.linestyle_index = saved["font"], saved["linestyle_index"]
    ctx.raster.set(**saved["raster"])


@gl_function()
def scrsubdivide(mode: int, params=()) -> None:
    """Screen-space subdivision (scrsubdivide(3G)): accepted, see the module
    docstring.  ``params`` (SS_DEPTH): up to three finite numbers."""
    args = (mode, params)
    m = as_int("scrsubdivide", args, "mode", mode)
    if m not in (int(GL.SS_OFF), int(GL.SS_DEPTH)):
        raise GLValueError(f"{describe('scrsubdivide', args)}: mode {m} is not a valid "
                           "token (SS_OFF or SS_DEPTH)")
    vals = flat_numbers("scrsubdivide", (params,), None) if m == GL.SS_DEPTH else []
    if len(vals) > 3 or not all(math.isfinite(v) for v in vals):
        raise GLValueError(f"{describe('scrsubdivide', args)}: params are up to three "
                           "finite numbers")
    current("scrsubdivide", args)
    compat_state().subdivide = (m, tuple(vals))


@gl_function(record=False)
def gl_invert4d(m) -> list[float]:
    """The inverse of the 4x4 matrix ``m`` (16 numbers, row-major as getmatrix)."""
    args = (m,)
    vals = np.array(flat_numbers("gl_invert4d", args, 16), np.float64).reshape(4, 4)
    try:
        inv = np.linalg.inv(vals)
    except np.linalg.LinAlgError:
        raise GLValueError(f"{describe('gl_invert4d', args)}: the matrix is singular") from None
    if not np.isfinite(inv).all():
        raise GLValueError(f"{describe('gl_invert4d', args)}: the matrix is singular")
    return [float(x) for x in inv.reshape(-1)]
