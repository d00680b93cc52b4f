"""Depth cueing: depthcue, getdcm, lRGBrange, RGBrange, lshaderange, shaderange
(depthcue(3G)).

``depthcue(TRUE)`` makes each vertex colour a function of its window depth
(vgxsim.pipeline.depthcue): in RGB mode the ramp of ``lRGBrange(rmin, gmin, bmin,
rmax, gmax, bmax, znear, zfar)`` (0..255 components, window depths) or the older
``RGBrange`` (the same arguments with short depths); in colour-map mode the index
ramp of ``lshaderange(lowin, highin, znear, zfar)`` or the older ``shaderange``.
The nearer depth ``znear`` takes the max colour / ``highin``, the farther ``zfar``
the min colour / ``lowin`` (lRGBrange(3G), lshaderange(3G)).  Until lRGBrange the
RGB ramp is white at GD_ZMIN to black at GD_ZMAX (*assumed*: no page gives a
default); lshaderange's default is the manual's, ``lshaderange(0, 7, Zmin, Zmax)``.
Depth cueing is a normal-framebuffer mode: drawing in OVERDRAW, UNDERDRAW or PUPDRAW
is not cued.
"""

from __future__ import annotations

from vgxsim.pipeline.depthcue import DepthCue
from vgxsim.state import colormap
from vgxsim.state.planes import ZMAX, ZMIN

from ._core import GLValueError, as_int, current, describe, gl_function

__all__ = ["depthcue", "getdcm", "lRGBrange", "RGBrange", "lshaderange", "shaderange"]

#: lshaderange(3G): "The default is lshaderange(0, 7, Zmin, Zmax)".
DEFAULT_SHADERANGE = DepthCue((0.0,), (7.0,), float(ZMIN), float(ZMAX), index=True)


@gl_function()
def depthcue(mode: int) -> None:
    """Switch depth cueing on (TRUE) or off (FALSE) (depthcue(3G))."""
    args = (mode,)
    ctx = current("depthcue", args)
    on = bool(as_int("depthcue", args, "mode", mode))
    ctx.depthcue_on = on
    if on and ctx.depthcue is None:
        ctx.depthcue = DepthCue((0.0, 0.0, 0.0), (1.0, 1.0, 1.0), float(ZMIN), float(ZMAX))
    if on and ctx.shaderange is None:
        ctx.shaderange = DEFAULT_SHADERANGE
    ctx.vertex_serial += 1


@gl_function(record=False)
def getdcm() -> int:
    """1 when depth cueing is on, else 0 (getdcm(3G))."""
    return int(bool(current("getdcm").depthcue_on))


def _range(name: str, args: tuple) -> None:
    names = ("rmin", "gmin", "bmin", "rmax", "gmax", "bmax", "znear", "zfar")
    vals = [as_int(name, args, n, v) for n, v in zip(names, args, strict=True)]
    for n, v in zip(names[:6], vals[:6], strict=True):
        if not 0 <= v <= 255:
            raise GLValueError(f"{describe(name, args)}: {n} must be 0..255")
    ctx = current(name, args)
    ctx.depthcue = DepthCue(tuple(v / 255.0 for v in vals[:3]),
                            tuple(v / 255.0 for v in vals[3:6]), float(vals[6]),
                            float(vals[7]))
    ctx.vertex_serial += 1


@gl_function()
def lRGBrange(rmin: int, gmin: int, bmin: int, rmax: int, gmax: int, bmax: int,  # noqa: N802
              znear: int, zfar: int) -> None:
    """The RGB depth-cue ramp: (rmax, gmax, bmax) at the nearer window depth znear to
    (rmin, gmin, bmin) at the farther zfar (lRGBrange(3G))."""
    _range("lRGBrange", (rmin, gmin, bmin, rmax, gmax, bmax, znear, zfar))


@gl_function()
def RGBrange(rmin: int, gmin: int, bmin: int, rmax: int, gmax: int, bmax: int,  # noqa: N802
             znear: int, zfar: int) -> None:
    """The older name of :func:`lRGBrange` (short depths; the same ramp)."""
    _range("RGBrange", (rmin, gmin, bmin, rmax, gmax, bmax, znear, zfar))


def _shaderange(name: str, args: tuple) -> None:
    names = ("lowin", "highin", "znear", "zfar")
    lo, hi, zn, zf = (as_int(name, args, n, v) for n, v in zip(names, args, strict=True))
    top = colormap.MAP_SIZE - 1
    for n, v in (("lowin", lo), ("highin", hi)):
        if not 0 <= v <= top:
            raise GLValueError(f"{describe(name, args)}: {n} {v} is outside the colour "
                               f"map 0..{top}")
    ctx = current(name, args)
    ctx.shaderange = DepthCue((float(lo),), (float(hi),), float(zn), float(zf), index=True)
    ctx.vertex_serial += 1


@gl_function()
def lshaderange(lowin: int, highin: int, znear: int, zfar: int) -> None:
    """The colour-index depth-cue ramp: ``highin`` at the nearer window depth znear to
    ``lowin`` at the farther zfar, linear between (lshaderange(3G)); colour-map mode.

    Each vertex gets its fractional index from its depth and indices interpolate
    between vertices like colours (exactly within a block of 256 indices; see
    vgxsim.pipeline.depthcue).
    """
    _shaderange("lshaderange", (lowin, highin, znear, zfar))


@gl_function()
def shaderange(lowindex: int, highindex: int, z1: int, z2: int) -> None:
    """The older name of :func:`lshaderange` (short depths; the same ramp)."""
    _shaderange("shaderange", (lowindex, highindex, z1, z2))
