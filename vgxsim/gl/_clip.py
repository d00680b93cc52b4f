"""User clip planes: clipplane(3G).

``clipplane(index, CP_DEFINE, params)`` stores the plane ``a x + b y + c z + d w >= 0``
(``params`` = (a, b, c, d)) transformed by the ModelView matrix in effect, as
clipplane(3G) specifies, i.e. in eye coordinates; ``CP_ON`` / ``CP_OFF`` switch it.
Up to six planes (getgdesc(GD_CLIPPLANES)).  A plane switched on before any
definition is (0, 0, 0, 0), which keeps every point (the OpenGL default, as glClipPlane
took the call over).  Primitives are clipped exactly in the homogeneous clipper
(kernels/clip.py) with the plane carried into clip space by the projection
(vgxsim.pipeline.records.clip_space_planes); points outside a plane are dropped.
"""

from __future__ import annotations

import numpy as np

from vgxsim import GL

from ._core import GLValueError, as_int, check_token, current, describe, flat_numbers, gl_function

__all__ = ["clipplane"]

MAX_CLIP_PLANES = 6


@gl_function()
def clipplane(index: int, mode: int, params=(0.0, 0.0, 0.0, 0.0)) -> None:
    """Define, enable or disable user clip plane ``index`` (0..5) (clipplane(3G)).

    Parameters
    ----------
    index : int
        0..5.
    mode : int
        CP_DEFINE, CP_ON or CP_OFF.
    params : sequence of 4 float
        The plane (a, b, c, d) in the coordinates of the current ModelView matrix;
        read only by CP_DEFINE.
    """
    args = (index, mode, params)
    ctx = current("clipplane", args)
    i = as_int("clipplane", args, "index", index)
    if not 0 <= i < MAX_CLIP_PLANES:
        raise GLValueError(f"{describe('clipplane', args)}: index must be 0..5 "
                           "(getgdesc(GD_CLIPPLANES) is 6)")
    m = check_token("clipplane", args, "mode", mode,
                    (int(GL.CP_DEFINE), int(GL.CP_ON), int(GL.CP_OFF)), "CP_")
    if m == GL.CP_DEFINE:
        q = np.array(flat_numbers("clipplane", (params,), 4), np.float64)
        if not np.isfinite(q).all():
            raise GLValueError(f"{describe('clipplane', args)}: the plane must be finite")
        # A point e (row, eye space) is o @ MV for o in the defining coordinates:
        # o . q = e . (MV^-1 q).
        mv = ctx.matrices.modelview_matrix()
        try:
            eye = np.linalg.solve(mv, q)
        except np.linalg.LinAlgError:
            eye = np.linalg.pinv(mv) @ q
        ctx.clip_plane_defs[i] = eye
    elif m == GL.CP_ON:
        ctx.clip_planes_on.add(i)
    else:
        ctx.clip_planes_on.discard(i)
    on = sorted(ctx.clip_planes_on)
    planes = np.array([ctx.clip_plane_defs[j] if ctx.clip_plane_defs[j] is not None
                       else np.zeros(4) for j in on], np.float64).reshape(-1, 4)
    planes.flags.writeable = False
    ctx.user_planes = planes
    ctx.vertex_serial += 1
