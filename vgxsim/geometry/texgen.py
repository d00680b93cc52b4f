"""Texture coordinates per vertex for the texture stage (docs/numeric_model.md s. 13).

texgen(3G) TG_LINEAR: a coordinate is the dot product of an object-space plane
(a, b, c, d) with the vertex (x, y, z, w); a coordinate without generation comes
from t2* (given per vertex, default 0).  After clipping, the raster interpolates
s/w, t/w and 1/w in the window, which makes texturing perspective-correct.
"""

from __future__ import annotations

import numpy as np

from vgxsim.state.raster import RasterState
from vgxsim.state.textures import binding


def texture_coords(rs: RasterState, obj, texcoords=None) -> np.ndarray:
    """(N, 2) float64 (s, t) of object-space vertices ``obj`` (N, 3 or 4) under the
    texture binding of ``rs``."""
    obj = np.asarray(obj, np.float64)
    n = obj.shape[0]
    if obj.shape[1] == 3:
        obj = np.concatenate([obj, np.ones((n, 1))], axis=1)
    out = (np.zeros((n, 2)) if texcoords is None
           else np.array(texcoords, np.float64).reshape(n, 2))
    gen = binding(rs.texture).texgen
    for k, plane in enumerate((gen.s_plane, gen.t_plane)):
        if plane is not None:
            a, b, c, d = plane
            # Written out term by term: the naive reference evaluates the same sum.
            out[:, k] = ((a * obj[:, 0] + b * obj[:, 1]) + c * obj[:, 2]) + d * obj[:, 3]
    return out


def per_w(st: np.ndarray, w: np.ndarray) -> np.ndarray:
    """(N, 3) s/w, t/w, 1/w of clipped vertices (w > 0 after clipping)."""
    q = 1.0 / np.where(w == 0, 1e-300, w)
    return np.ascontiguousarray(np.stack([st[:, 0] * q, st[:, 1] * q, q], axis=1))
