"""Vertex fog: fogvertex(3G).

``fogvertex(FG_VTX_EXP | FG_VTX_EXP2, (density, r, g, b))`` and
``fogvertex(FG_VTX_LIN, (start, end, r, g, b))`` define the fog and its colour (the
parameter layouts IGL reads); ``fogvertex(FG_ON)`` / ``fogvertex(FG_OFF)`` switch
it.  FG_DEFINE is FG_VTX_EXP's old name (gl.h).  The FG_PIX_* modes define the same
fog evaluated per vertex (vgxsim.pipeline.fog; getgdesc(GD_FOGPIXEL) is 0).  The
fog applies in RGB mode to every vertex colour after lighting
(vgxsim.pipeline.fog); fog switched on in colour-map mode is an error (vgxsim does
not blend colour indices).  Until a definition, the fog is FG_VTX_EXP with density
0: switched on, it changes nothing.
"""

from __future__ import annotations

import numpy as np

from vgxsim import GL
from vgxsim.pipeline.fog import FogState

from ._core import (
    GLUsageError,
    GLValueError,
    check_token,
    current,
    describe,
    flat_numbers,
    gl_function,
)

__all__ = ["fogvertex"]

_MODES = {int(GL.FG_VTX_EXP): "exp", int(GL.FG_PIX_EXP): "exp",
          int(GL.FG_VTX_EXP2): "exp2", int(GL.FG_PIX_EXP2): "exp2",
          int(GL.FG_VTX_LIN): "lin", int(GL.FG_PIX_LIN): "lin"}


@gl_function()
def fogvertex(mode: int, params=()) -> None:
    """Define or switch vertex fog (fogvertex(3G)).

    Parameters
    ----------
    mode : int
        FG_ON, FG_OFF, or a fog mode FG_VTX_EXP (FG_DEFINE), FG_VTX_EXP2, FG_VTX_LIN,
        FG_PIX_EXP, FG_PIX_EXP2, FG_PIX_LIN.
    params : sequence of float
        (density, r, g, b) for the exponential modes, (start, end, r, g, b) for the
        linear ones; not read by FG_ON / FG_OFF.
    """
    args = (mode, params)
    ctx = current("fogvertex", args)
    m = check_token("fogvertex", args, "mode", mode,
                    {int(GL.FG_ON), int(GL.FG_OFF), *_MODES}, "FG_")
    if m in (GL.FG_ON, GL.FG_OFF):
        if m == GL.FG_ON and not ctx.config.rgb:
            raise GLUsageError(f"{describe('fogvertex', args)}: vgxsim fogs RGB colours "
                               "only (the window is in colour-map mode)")
        ctx.fog_on = m == GL.FG_ON
        if ctx.fog_on and ctx.fog_def is None:
            ctx.fog_def = FogState("exp", 0.0, 0.0, 1.0, (0.0, 0.0, 0.0), None)
        ctx.vertex_serial += 1
        return
    kind = _MODES[m]
    vals = flat_numbers("fogvertex", (params,), 5 if kind == "lin" else 4)
    if not np.isfinite(vals).all():
        raise GLValueError(f"{describe('fogvertex', args)}: the parameters must be finite")
    if kind == "lin":
        start, end, colour = vals[0], vals[1], tuple(vals[2:5])
        density = 0.0
    else:
        density, colour = vals[0], tuple(vals[1:4])
        start, end = 0.0, 1.0
        if density < 0.0:
            raise GLValueError(f"{describe('fogvertex', args)}: density must be >= 0")
    ctx.fog_def = FogState(kind, float(density), float(start), float(end), colour, None)
    ctx.vertex_serial += 1
