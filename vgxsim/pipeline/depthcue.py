"""Depth cueing (depthcue(3G)): each vertex colour comes from its window depth, not
from the current colour -- an RGB ramp in RGB mode (lRGBrange(3G)), a colour-index
ramp in colour-map mode (lshaderange(3G)).

Both manual pages give the same mapping: "The screen z range [znear, zfar] is mapped
linearly into the RGB color range [(rmax,gmax,bmax), (rmin,gmin,bmin)]. Screen z
values nearer than znear are mapped to (rmax,gmax,bmax); screen z values farther than
zfar are mapped to (rmin,gmin,bmin)" (lRGBrange(3G)); lshaderange(3G) maps [znear,
zfar] into [highin, lowin] the same way.  So a vertex at window depth ``z`` (after
lsetdepth, docs/numeric_model.md s. 1) gets ``high + (low - high) * t`` with ``t =
(z - znear) / (zfar - znear)`` clamped to [0, 1].  Alpha is kept in RGB mode.

RGB ramps enter as colours in [0, 1] and interpolate like any vertex colour.  An
index ramp gives each vertex a fractional index, carried as the RGBA whose bytes
spell it (vgxsim.state.colormap.index_rgba: red the low byte, green the high byte),
so between vertices the index interpolates exactly while the vertices' indices lie in
one block of 256 (always so for a ramp inside one such block, and in multimap mode);
a primitive whose vertices fall in different blocks interpolates the two bytes
separately -- a limitation of carrying indices through RGBA kernels (GD_CIFRACT 0).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from vgxsim.geometry.transform import apply


class DepthCue(NamedTuple):
    """A depth-cue ramp: ``low`` at ``zfar`` to ``high`` at ``znear`` (window depths).

    ``low``/``high`` are RGB (3 floats in 0..1, lRGBrange's min and max) or, with
    ``index``, colour indices (1-tuples, lshaderange's lowin and highin).
    """

    low: tuple
    high: tuple
    znear: float
    zfar: float
    index: bool = False


def depthcue_state(ctx) -> DepthCue | None:
    """The ramp a window's primitives are cued with now, or None: depth cueing is on
    and the normal framebuffer is drawn (the overlay, underlay and pop-up planes are
    not cued: depthcue is one of drawmode(3G)'s normal-framebuffer modes)."""
    if not ctx.depthcue_on or ctx.raster.layer_mask is not None:
        return None
    return ctx.depthcue if ctx.config.rgb else ctx.shaderange


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
    hi = np.asarray(cue.high, np.float64)
    value = hi + (lo - hi) * t[:, None]
    if not cue.index:
        out[:, :3] = value
        return out
    index = value[:, 0]
    block = np.floor(index + 0.5) // 256  # the high byte the index rounds into
    out[:, 0] = (index - 256.0 * block) / 255.0
    out[:, 1] = block / 255.0
    out[:, 2] = 0.0
    out[:, 3] = 0.0  # an index word has no alpha byte (index_rgba)
    return out
