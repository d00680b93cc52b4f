"""Depth cueing: depthcue, getdcm, lRGBrange, RGBrange (depthcue(3G)).

``depthcue(TRUE)`` makes each vertex colour a function of its window depth
(vgxsim.pipeline.depthcue) in RGB mode, with the ramp of ``lRGBrange(rmin, gmin,
bmin, rmax, gmax, bmax, znear, zfar)`` (0..255 components, window depths) or the
older ``RGBrange`` (the same arguments with short depths).  The colour-map form
(``lshaderange``/``shaderange``, index ramps) is not emulated: depthcue(TRUE) in a
colour-map window is an error.  Until lRGBrange, the ramp is black at GD_ZMIN to
white at GD_ZMAX.
"""

from __future__ import annotations

from vgxsim.pipeline.depthcue import DepthCue
from vgxsim.state.planes import ZMAX, ZMIN

from ._core import GLUsageError, GLValueError, as_int, current, describe, gl_function

__all__ = ["depthcue", "getdcm", "lRGBrange", "RGBrange"]


@gl_function()
def depthcue(mode: int) -> None:
    """Switch depth cueing on (TRUE) or off (FALSE) (depthcue(3G))."""
    args = (mode,)
    ctx = current("depthcue", args)
    on = bool(as_int("depthcue", args, "mode", mode))
    if on and not ctx.config.rgb:
        raise GLUsageError(f"{describe('depthcue', args)}: vgxsim depth-cues RGB colours "
                           "only (lshaderange is not emulated; the window is in "
                           "colour-map mode)")
    ctx.depthcue_on = on
    if on and ctx.depthcue is None:
        ctx.depthcue = DepthCue((0.0, 0.0, 0.0), (1.0, 1.0, 1.0), float(ZMIN), float(ZMAX))
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
    """The RGB depth-cue ramp: (rmin, gmin, bmin) at window depth znear to (rmax,
    gmax, bmax) at zfar (lRGBrange(3G))."""
    _range("lRGBrange", (rmin, gmin, bmin, rmax, gmax, bmax, znear, zfar))


@gl_function()
def RGBrange(rmin: int, gmin: int, bmin: int, rmax: int, gmax: int, bmax: int,  # noqa: N802
             znear: int, zfar: int) -> None:
    """The older name of :func:`lRGBrange` (short depths; the same ramp)."""
    _range("RGBrange", (rmin, gmin, bmin, rmax, gmax, bmax, znear, zfar))
