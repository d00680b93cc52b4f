"""The fused geometry front end: transform, clip, project, snap and set-up per chunk.

The unfused path (vgxsim/geometry/pipeline.py with ``FUSED_FRONT`` off) runs each
stage over the whole triangle list and hands full-size arrays from one to the next;
for many small triangles those arrays, not the arithmetic, cost the time.  Here a
chunk of vertices goes object -> clip -> outcode -> window -> fixed point in one pass
(:func:`front_vertices`), and a chunk of triangles is set up straight from those
vertices (:func:`front_triangles`); chunks of either kind are independent, so the
worker threads of vgxsim/threads.py run them side by side (the kernels release the
GIL).

Bit-identical with the unfused path: every value is computed by the same routines in
the same order -- the row order of :func:`~.transform.transform_points`, :func:`~.clip.outcodes`,
:func:`~.clip.project_snap`, :func:`~.clip.clip_triangles` (called on the one
triangle that needs clipping, which is the rare case: the guard band keeps x and y
clipping away) and the set-up of :mod:`.setup` -- all of them per vertex or per
triangle with a row-independent rounding order (docs/numeric_model.md s. 4).

Slots: triangle ``t`` owns the set-up records ``slots[t] .. slots[t + 1] - 1`` (one
for a triangle inside every plane, none for one outside a plane, ``MAX_POLY - 2``
for one that needs clipping, the fan's unused ones dead), so chunks know where to
write before any of them has run and the drawing order is the input order.
"""

from __future__ import annotations

import numpy as np

from .clip import MAX_POLY, clip_triangles, outcodes, project_snap
from .options import jit
from .setup import _dead, _setup_one

HUGE = 1e300  # clip coordinates beyond this are rescaled (vgxsim.geometry.pipeline._tame)
CLIP_SLOTS = MAX_POLY - 2  # set-up records reserved for a triangle that needs clipping


@jit
def front_vertices(obj, mvp, gx, gy, vp_l, vp_r, vp_b, vp_t, znear, zfar, subpixel,
                   clip_v, code, xf, yf, zw, v0, v1):
    """Vertices ``v0 .. v1 - 1``: clip position, outcode and snapped window position.

    Parameters
    ----------
    obj : ndarray, shape (Nv, 4), float64
        Homogeneous object coordinates.
    mvp : ndarray, shape (4, 4), float64
        Object -> clip (row vectors).
    gx, gy : float
        Guard band (:func:`~.clip.outcodes`).
    vp_l, vp_r, vp_b, vp_t : int; znear, zfar : float; subpixel : bool
        As for :func:`~.clip.project_snap`.
    clip_v : ndarray, shape (Nv, 4), float64; code : ndarray, shape (Nv,), uint8
    xf, yf : ndarray, shape (Nv,), int64; zw : ndarray, shape (Nv,), float64
        Outputs, written in rows ``v0 .. v1 - 1``.
    v0, v1 : int
    """
    for i in range(v0, v1):
        # transform_points' order: ((p0*m0j + p1*m1j) + p2*m2j) + p3*m3j.
        p0, p1, p2, p3 = obj[i, 0], obj[i, 1], obj[i, 2], obj[i, 3]
        big = 0.0
        finite = True
        for q in range(4):
            v = ((p0 * mvp[0, q] + p1 * mvp[1, q]) + p2 * mvp[2, q]) + p3 * mvp[3, q]
            clip_v[i, q] = v
            a = abs(v)
            if not np.isfinite(a):
                finite = False
            elif a > big:
                big = a
        if finite and big > HUGE:
            # The same point divided by its largest magnitude (geometry.pipeline._tame,
            # row by row): keeps the clipper's plane distances finite.
            for q in range(4):
                clip_v[i, q] = clip_v[i, q] / big
    c = clip_v[v0:v1]
    code[v0:v1] = outcodes(c, gx, gy)
    x, y, z = project_snap(c, vp_l, vp_r, vp_b, vp_t, znear, zfar, subpixel)
    xf[v0:v1] = x
    yf[v0:v1] = y
    zw[v0:v1] = z


@jit
def front_slots(code, tris):
    """First set-up record of each triangle, relative to the call's first (see the
    module docstring); ``slots[Nt]`` is the number of records the call uses.

    Parameters
    ----------
    code : ndarray, shape (Nv,), uint8
        Outcodes (:func:`front_vertices`).
    tris : ndarray, shape (Nt, 3), int64

    Returns
    -------
    ndarray, shape (Nt + 1,), int64
    """
    nt = tris.shape[0]
    slots = np.empty(nt + 1, dtype=np.int64)
    n = 0
    for t in range(nt):
        slots[t] = n
        ca, cb, cc = code[tris[t, 0]], code[tris[t, 1]], code[tris[t, 2]]
        if (ca | cb | cc) == 0:
            n += 1
        elif (ca & cb & cc) == 0 and ca != 0xFF and cb != 0xFF and cc != 0xFF:
            n += CLIP_SLOTS  # the clip_triangles rule: clipped, not rejected
    slots[nt] = n
    return slots


@jit
def front_triangles(clip_v, code, xf, yf, zw, attr, tris, slots, flat_col, states, culls,
                    flat, want_colour, gx, gy, vp_l, vp_r, vp_b, vp_t, znear, zfar,
                    subpixel, t_edge, t_box, t_z, t_zlim, t_col, t_state, offset, t0, t1):
    """Set up triangles ``t0 .. t1 - 1`` into the records ``offset + slots[t]``.

    Parameters
    ----------
    clip_v, code, xf, yf, zw : ndarray
        The vertices after :func:`front_vertices`.
    attr : ndarray, shape (Nv, K), float64
        Vertex colour in [0, 1] (K = 4), or K = 0 when colour is not written.
    tris : ndarray, shape (Nt, 3), int64
    slots : ndarray, shape (Nt + 1,), int64
        From :func:`front_slots`.
    flat_col : ndarray, shape (Nt, 4) or (1, 4), float64
        Per input triangle, its flat-shading colour.
    states, culls : ndarray, shape (Nt,), int64
        State-table index and cull mode of each triangle.
    flat, want_colour : bool
    gx, gy, vp_l, vp_r, vp_b, vp_t, znear, zfar, subpixel
        As for :func:`front_vertices` (for the vertices clipping creates).
    t_edge, t_box, t_z, t_zlim, t_col, t_state : ndarray
        The batch's set-up records (:func:`~.setup.setup_triangles`).
    offset : int
        The call's first record.
    t0, t1 : int
    """
    k = attr.shape[1]
    kc = min(k, 4)
    ids = np.arange(t1, dtype=np.int64)  # src of each triangle: itself (flat_col row)
    # What a clipped triangle's set-up reads: clip_triangles' output (the three
    # inputs, then the new vertices) and its fan.
    nloc = 3 + MAX_POLY
    lx = np.zeros(nloc, dtype=np.int64)
    ly = np.zeros(nloc, dtype=np.int64)
    lz = np.zeros(nloc, dtype=np.float64)
    lcol = np.zeros((nloc, 4), dtype=np.float64)
    lsrc = np.zeros(MAX_POLY, dtype=np.int64)
    v3 = np.empty((3, 4), dtype=np.float64)
    a3 = np.empty((3, k), dtype=np.float64)
    one = np.zeros((1, 3), dtype=np.int64)
    one[0, 1] = 1
    one[0, 2] = 2
    for t in range(t0, t1):
        n = offset + slots[t]
        used = slots[t + 1] - slots[t]
        if used == 0:
            continue  # outside a clip plane: no record, as clip_triangles drops it
        if used == 1:
            # Inside every plane: set up straight from the call's vertices.
            _setup_one(xf, yf, zw, attr, tris, ids, flat_col, states[t], culls[t], flat,
                       want_colour, t_edge, t_box, t_z, t_zlim, t_col, t_state, t, n)
            continue
        for j in range(3):
            i = tris[t, j]
            for q in range(4):
                v3[j, q] = clip_v[i, q]
            for q in range(k):
                a3[j, q] = attr[i, q]
        cv, ca, fan, _src = clip_triangles(v3, a3, one, gx, gy)
        px, py, pz = project_snap(cv, vp_l, vp_r, vp_b, vp_t, znear, zfar, subpixel)
        for i in range(cv.shape[0]):
            lx[i] = px[i]
            ly[i] = py[i]
            lz[i] = pz[i]
            for q in range(kc):
                lcol[i, q] = ca[i, q]
        m = fan.shape[0]
        for f in range(m):
            lsrc[f] = t
            _setup_one(lx, ly, lz, lcol, fan, lsrc, flat_col, states[t], culls[t], flat,
                       want_colour, t_edge, t_box, t_z, t_zlim, t_col, t_state, f, n + f)
        for f in range(m, used):
            _dead(t_box, t_state, n + f, states[t])
