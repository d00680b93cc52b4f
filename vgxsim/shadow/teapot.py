"""The Utah teapot tessellated from its 32 bicubic Bezier patches.

Points and normals use the formulas of the course slides (shared/seeds/002, "Bicubic
Bezier Patch" and "... Patch Normal")::

    P(u, v) = sum_i sum_j B_i(v) B_j(u) P_ij        B_0 = (1-t)^3, B_1 = 3(1-t)^2 t,
                                                    B_2 = 3(1-t) t^2, B_3 = t^3
    dP/du   = sum_i B_i(v) (-3(1-u)^2 P_i0 + 3(1-3u)(1-u) P_i1 + 3u(2-3u) P_i2 + 3u^2 P_i3)
    dP/dv   = the same with the roles of u and v exchanged
    N       = dP/du x dP/dv

The control points (Newell 1975, public domain) are package data,
``vgxsim/data/models/teapot_patches.txt``.  The result is what the issue calls "an
open, hollow mesh, a hard case for shadow volumes": the lid rests on the rim with a
gap, the spout is open at its end and the handle and spout pierce the body.
Patch boundaries are welded; the degenerate rows where a patch collapses to a point
(the lid's knob top and the bottom's centre) give triangles instead of quads.
"""

from __future__ import annotations

from importlib import resources

import numpy as np


def read_patches(text: str | None = None) -> tuple[np.ndarray, np.ndarray]:
    """The teapot's control points and patches.

    Returns
    -------
    points : ndarray, shape (306, 3), float64
        z up, as in Newell's data.
    patches : ndarray, shape (32, 4, 4), int64
        Zero-based indices into ``points``; ``patches[k, i, j]`` is P_ij.
    """
    if text is None:
        text = resources.files("vgxsim.data").joinpath("models/teapot_patches.txt").read_text()
    rows = [ln.split() for ln in text.splitlines() if ln.strip() and not ln.startswith("#")]
    npts = int(rows[0][1])
    points = np.array(rows[1:1 + npts], np.float64)
    patches = np.array(rows[2 + npts:], np.int64) - 1
    return points, patches.reshape(-1, 4, 4)


def _bernstein(t: np.ndarray) -> np.ndarray:
    s = 1.0 - t
    return np.stack([s ** 3, 3 * s * s * t, 3 * s * t * t, t ** 3], axis=-1)


def _bernstein_derivative(t: np.ndarray) -> np.ndarray:
    # the slides' coefficients: -3(1-t)^2, 3(1-3t)(1-t), 3t(2-3t), 3t^2
    return np.stack([-3 * (1 - t) ** 2, 3 * (1 - 3 * t) * (1 - t), 3 * t * (2 - 3 * t),
                     3 * t * t], axis=-1)


def patch_points(ctrl: np.ndarray, u: np.ndarray, v: np.ndarray
                 ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Point and partial derivatives of a bicubic Bezier patch on a (u, v) grid.

    Parameters
    ----------
    ctrl : ndarray, shape (4, 4, 3)
        P_ij (i along v, j along u, as in the slides).
    u, v : ndarray, shape (N,) and (M,)

    Returns
    -------
    P, dPdu, dPdv : ndarray, shape (M, N, 3)
    """
    bu, bv = _bernstein(u), _bernstein(v)
    du, dv = _bernstein_derivative(u), _bernstein_derivative(v)
    p = np.einsum("mi,nj,ijc->mnc", bv, bu, ctrl)
    pu = np.einsum("mi,nj,ijc->mnc", bv, du, ctrl)
    pv = np.einsum("mi,nj,ijc->mnc", dv, bu, ctrl)
    return p, pu, pv


def tessellate(n: int = 8, *, y_up: bool = True
               ) -> tuple[np.ndarray, list[list[int]], np.ndarray]:
    """Tessellate the 32 patches into an n x n grid of quads each, welded.

    Parameters
    ----------
    n : int
        Quads along each patch side (n = 8: 2,048 quads before collapsed ones go).
    y_up : bool
        Turn Newell's z-up data to y up ((x, y, z) -> (x, z, -y), a rotation).

    Returns
    -------
    vertices : ndarray, shape (V, 3), float64
    polygons : list of lists of int
        Quads, and triangles where a patch collapses to a point; counter-clockwise
        seen from the side the slides' normal N points to.
    vertex_normals : ndarray, shape (V, 3), float64
        Unit N at each vertex (at a collapsed point, from a parameter just inside).
    """
    points, patches = read_patches()
    t = np.linspace(0.0, 1.0, n + 1)
    eps = 1e-4  # the normal at a collapsed edge is 0/0: evaluate it just inside
    tn = np.clip(t, eps, 1 - eps)
    allp, alln, quads = [], [], []
    for k, pk in enumerate(patches):
        ctrl = points[pk]
        p, _, _ = patch_points(ctrl, t, t)
        _, pu, pv = patch_points(ctrl, tn, tn)
        nrm = np.cross(pu, pv)
        allp.append(p.reshape(-1, 3))
        alln.append(nrm.reshape(-1, 3))
        base = k * (n + 1) ** 2
        for i in range(n):          # along v
            for j in range(n):      # along u
                a = base + i * (n + 1) + j
                quads.append([a, a + 1, a + n + 2, a + n + 1])  # (u,v) (u+1,v) (u+1,v+1) (u,v+1)
    pts = np.concatenate(allp)
    nrm = np.concatenate(alln)
    key = np.round(pts, 7)
    uniq, first, inverse = np.unique(key, axis=0, return_index=True, return_inverse=True)
    inverse = inverse.reshape(-1)
    # one normal per welded vertex: the sum of the samples that met there
    vn = np.zeros((len(uniq), 3))
    for c in range(3):
        vn[:, c] = np.bincount(inverse, weights=nrm[:, c] / np.maximum(
            np.linalg.norm(nrm, axis=1), 1e-300), minlength=len(uniq))
    vn /= np.maximum(np.linalg.norm(vn, axis=1, keepdims=True), 1e-300)
    verts = pts[first]
    polys = []
    for q in quads:
        loop = []
        for vi in (int(inverse[x]) for x in q):
            if not loop or loop[-1] != vi:
                loop.append(vi)
        if len(loop) > 1 and loop[0] == loop[-1]:
            loop.pop()
        if len(set(loop)) >= 3 and len(set(loop)) == len(loop):
            polys.append(loop)
    if y_up:
        rot = np.array([[1.0, 0, 0], [0, 0, 1.0], [0, -1.0, 0]])
        verts, vn = verts @ rot.T, vn @ rot.T
    return verts, polys, vn
