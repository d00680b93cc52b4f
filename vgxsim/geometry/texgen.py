"""Texture coordinates per vertex for the texture stage (docs/numeric_model.md s. 14).

texgen(3G) generates s and t per coordinate:

* TG_LINEAR: the dot product of an object-space plane (a, b, c, d) with the vertex
  (x, y, z, w) (:func:`texture_coords`, at the geometry pass);
* TG_CONTOUR: the dot product of an eye-space plane (transformed by the inverse of
  the modelview in effect at the texgen call) with the eye-space vertex, and
  TG_SPHEREMAP: the sphere map of the eye-space reflection vector, OpenGL's
  GL_SPHERE_MAP (:func:`eye_texture_coords`, when the primitive is queued, while its
  modelview and normals are at hand).

A coordinate without generation comes from t2* (given per vertex, default 0).  After
clipping, the raster interpolates s/w, t/w and 1/w in the window, which makes
texturing perspective-correct.
"""

from __future__ import annotations

import numpy as np

from vgxsim.state.raster import RasterState
from vgxsim.state.textures import GEN_CONTOUR, GEN_LINEAR, GEN_SPHEREMAP, TexGen, binding

from .transform import apply


def _homogeneous(obj) -> np.ndarray:
    obj = np.asarray(obj, np.float64)
    if obj.shape[1] == 3:
        obj = np.concatenate([obj, np.ones((obj.shape[0], 1))], axis=1)
    return obj


def _dot4(plane, p: np.ndarray) -> np.ndarray:
    a, b, c, d = plane
    # Written out term by term, one rounding order for every row.
    return ((a * p[:, 0] + b * p[:, 1]) + c * p[:, 2]) + d * p[:, 3]


def texture_coords(rs: RasterState, obj, texcoords=None) -> np.ndarray:
    """(N, 2) float64 (s, t) of object-space vertices ``obj`` (N, 3 or 4) under the
    texture binding of ``rs``: TG_LINEAR coordinates generated, the others as given
    in ``texcoords`` (t2*, or what :func:`eye_texture_coords` generated; default 0)."""
    obj = _homogeneous(obj)
    n = obj.shape[0]
    out = (np.zeros((n, 2)) if texcoords is None
           else np.array(texcoords, np.float64).reshape(n, 2))
    gen = binding(rs.texture).texgen
    for k, (mode, plane) in enumerate(zip(gen.modes(), gen.planes(), strict=True)):
        if mode == GEN_LINEAR:
            out[:, k] = _dot4(plane, obj)
    return out


def sphere_map(eye: np.ndarray, normals: np.ndarray) -> np.ndarray:
    """(N, 2) float64 sphere-map (s, t) (texgen(3G) TG_SPHEREMAP; OpenGL 1.x s. 2.10.4).

    ``u`` is the unit vector from the eye to the vertex (eye-space position over w,
    normalized; 0 at the eye), ``n`` the eye-space normal as the modelview's normal
    matrix gives it (not renormalized, as GL without GL_NORMALIZE), ``r = u - 2 n
    (n . u)``, ``m = 2 sqrt(rx^2 + ry^2 + (rz + 1)^2)`` and ``s = rx / m + 1/2``,
    ``t = ry / m + 1/2``; where ``m`` is 0 (r = (0, 0, -1)) s = t = 1/2 (*choice*,
    as Mesa).

    Parameters
    ----------
    eye : ndarray, shape (N, 4), float64
        Eye-space vertices.
    normals : ndarray, shape (N, 3), float64
        Eye-space normals.
    """
    w = np.where(eye[:, 3:4] == 0, 1.0, eye[:, 3:4])
    pos = eye[:, :3] / w
    length = np.sqrt((pos[:, 0] * pos[:, 0] + pos[:, 1] * pos[:, 1]) + pos[:, 2] * pos[:, 2])
    u = pos / np.where(length == 0, 1.0, length)[:, None]
    n = normals
    nu = (n[:, 0] * u[:, 0] + n[:, 1] * u[:, 1]) + n[:, 2] * u[:, 2]
    r = u - 2.0 * n * nu[:, None]
    rz1 = r[:, 2] + 1.0
    m = 2.0 * np.sqrt((r[:, 0] * r[:, 0] + r[:, 1] * r[:, 1]) + rz1 * rz1)
    inv = np.divide(1.0, m, out=np.zeros_like(m), where=m != 0)
    return np.stack([r[:, 0] * inv + 0.5, r[:, 1] * inv + 0.5], axis=1)


def eye_texture_coords(gen: TexGen, obj, modelview: np.ndarray, normal_matrix: np.ndarray,
                       normals, texcoords=None) -> np.ndarray:
    """(N, 2) float64 (s, t) with the TG_CONTOUR and TG_SPHEREMAP coordinates of
    ``gen`` generated; the others as ``texcoords`` gives them (default 0).

    Parameters
    ----------
    gen : TexGen
    obj : ndarray, shape (N, 3) or (N, 4), float64
        Object-space vertices.
    modelview : ndarray, shape (4, 4), float64
        The modelview the vertices are drawn with (row vectors).
    normal_matrix : ndarray, shape (3, 3), float64
        Its inverse transpose (row vectors).
    normals : ndarray, shape (N, 3), float64
        Object-space vertex normals (read by the sphere map only).
    texcoords : ndarray, shape (N, 2), float64, optional
    """
    eye = apply(_homogeneous(obj), modelview)
    n = eye.shape[0]
    out = (np.zeros((n, 2)) if texcoords is None
           else np.array(texcoords, np.float64).reshape(n, 2))
    sphere = None
    for k, (mode, plane) in enumerate(zip(gen.modes(), gen.planes(), strict=True)):
        if mode == GEN_CONTOUR:
            out[:, k] = _dot4(plane, eye)
        elif mode == GEN_SPHEREMAP:
            if sphere is None:
                sphere = sphere_map(eye, apply(np.asarray(normals, np.float64), normal_matrix))
            out[:, k] = sphere[:, k]
    return out


def per_w(st: np.ndarray, w: np.ndarray) -> np.ndarray:
    """(N, 3) s/w, t/w, 1/w of clipped vertices (w > 0 after clipping)."""
    q = 1.0 / np.where(w == 0, 1e-300, w)
    return np.ascontiguousarray(np.stack([st[:, 0] * q, st[:, 1] * q, q], axis=1))
