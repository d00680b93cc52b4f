"""Depth cueing in RGB mode (depthcue(3G), lRGBrange(3G)): each vertex colour comes
from its window depth, not from the current colour.

With ``lRGBrange(rmin, gmin, bmin, rmax, gmax, bmax, znear, zfar)`` a vertex at window
depth ``z`` (after lsetdepth, docs/numeric_model.md s. 1) gets
``min + (max - min) * t`` with ``t = (z - znear) / (zfar - znear)`` clamped to [0, 1]
(**choice**: the manuals give the argument order, min with znear and max with zfar,
but no formula; a linear ramp in that order is the plain reading).  Alpha is kept.
The ramp's 0..255 components enter as colours in [0, 1] and interpolate like any
vertex colour.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from vgxsim.geometry.transform import apply


class DepthCue(NamedTuple):
    """lRGBrange's parameters: ``low``/``high`` RGB (3 floats in 0..1) at
    ``znear``/``zfar`` (window depth)."""

    low: tuple
    high: tuple
    znear: float
    zfar: float


def cue_vertices(cue: DepthCue, obj: np.ndarray, rgba: np.ndarray, mvp: np.ndarray,
                 depth: tuple) -> np.ndarray:
    """Depth-cued copy of vertex colours.

    Parameters
    ----------
    cue : DepthCue
    obj : ndarray, shape (N, 4), float64
    rgba : ndarray, shape (N, 4), float64
    mvp : ndarray, shape (4, 4)
    depth : (near, far) lsetdepth range

    Returns
    -------
    ndarray, shape (N, 4), float64
    """
    clip = apply(obj, mvp)
    w = np.where(clip[:, 3] == 0.0, 1.0, clip[:, 3])
    near, far = float(depth[0]), float(depth[1])
    zw = near + (clip[:, 2] / w + 1.0) * (far - near) / 2.0
    span = cue.zfar - cue.znear
    t = np.zeros_like(zw) if span == 0.0 else np.clip((zw - cue.znear) / span, 0.0, 1.0)
    out = np.array(rgba, dtype=np.float64)
    lo = np.asarray(cue.low, np.float64)
    out[:, :3] = lo + (np.asarray(cue.high, np.float64) - lo) * t[:, None]
    return out
