"""The fused geometry front end: transform, clip, project and snap per chunk of
vertices, then set-up per chunk of triangles, both on the worker threads.

The stage-by-stage path (vgxsim/geometry/pipeline.py with ``FUSED_FRONT`` off) runs
each stage over the whole list and hands full-size arrays from one to the next, on
one thread up to set-up.  Here a chunk of vertices goes object -> clip -> outcode ->
window -> fixed point in one pass (:func:`front_vertices`); the triangles then go
straight to :func:`~.setup.setup_triangles_states` in chunks (the kernels release
the GIL, vgxsim/threads.py runs the chunks side by side).  Only when a triangle
needs clipping (rare: the guard band keeps x and y clipping away) or is rejected does
a serial step (:func:`front_assemble`) build the list set-up reads.

Bit-identical with the stage-by-stage path: every value comes from the same
arithmetic in the same order -- the row order of :func:`~.transform.transform_points`,
:func:`~.clip.outcodes`, :func:`~.clip.project_snap`, :func:`~.clip.clip_triangles`
(called on the one triangle being clipped) and set-up itself -- each per vertex or
per triangle with a row-independent rounding order (docs/numeric_model.md s. 4).
Set-up is the existing kernel, so a cold start compiles little that is new.

Records: triangle ``t`` owns the set-up records ``slots[t] .. slots[t + 1] - 1`` (one
for a triangle inside every plane, none for one outside a plane, ``CLIP_SLOTS`` for
one that needs clipping, the unused ones dead), so chunks know where to write before
any of them has run, and the drawing order is the input order.
"""

from __future__ import annotations

import math

import numpy as np

from vgxsim.stream.opcodes import (
    CLEAR_KIND,
    P_KIND,
    P_LMCOLOR_SET,
    P_STATE,
    P_V0,
    P_V1,
    PMV,
    POLYGON,
    QSTRIP,
    TMESH,
)

from .clip import (
    MAX_POLY,
    NONFINITE,
    clip_triangles,
    project_snap,
    project_vertex,
    vertex_outcode,
)
from .lighting import _shade_vertex
from .options import inline, jit

HUGE = 1e300  # clip coordinates beyond this are rescaled (vgxsim.geometry.pipeline._tame)
CLIP_SLOTS = MAX_POLY - 2  # set-up records reserved for a triangle that needs clipping


@inline
def clip_position(p0, p1, p2, p3, m):
    """Object point ``(p0, p1, p2, p3)`` to clip space by ``m`` (the MVP's 16 entries,
    row-major): transform_points' order, ((p0*m0j + p1*m1j) + p2*m2j) + p3*m3j, then
    the same point divided by its largest magnitude where that exceeds ``HUGE``
    (geometry.pipeline._tame, row by row: keeps the clipper's plane distances
    finite).  One helper for :func:`front_vertices` and :func:`front_assemble`, which
    computes it again for the vertices of the triangles it clips rather than have
    every vertex store its clip position (32 bytes a vertex written, read by none
    but those)."""
    cx = ((p0 * m[0] + p1 * m[4]) + p2 * m[8]) + p3 * m[12]
    cy = ((p0 * m[1] + p1 * m[5]) + p2 * m[9]) + p3 * m[13]
    cz = ((p0 * m[2] + p1 * m[6]) + p2 * m[10]) + p3 * m[14]
    cw = ((p0 * m[3] + p1 * m[7]) + p2 * m[11]) + p3 * m[15]
    big = max(max(abs(cx), abs(cy)), max(abs(cz), abs(cw)))
    if big > HUGE and (np.isfinite(cx) and np.isfinite(cy) and np.isfinite(cz)
                       and np.isfinite(cw)):
        cx, cy, cz, cw = cx / big, cy / big, cz / big, cw / big
    return cx, cy, cz, cw


@inline
def mvp_entries(mvp):
    """The 16 entries of a (4, 4) matrix, row-major, as scalars (a tuple: no array
    reaches :func:`clip_position`)."""
    return (mvp[0, 0], mvp[0, 1], mvp[0, 2], mvp[0, 3], mvp[1, 0], mvp[1, 1], mvp[1, 2],
            mvp[1, 3], mvp[2, 0], mvp[2, 1], mvp[2, 2], mvp[2, 3], mvp[3, 0], mvp[3, 1],
            mvp[3, 2], mvp[3, 3])


@jit
def front_vertices(obj, mvp, gx, gy, user, vp_l, vp_r, vp_b, vp_t, znear, zfar, subpixel,
                   code, xf, yf, zw, v0, v1):
    """Vertices ``v0 .. v1 - 1``: outcode and snapped window position.

    Parameters
    ----------
    obj : ndarray, shape (Nv, 4) or (Nv, 3), float64
        Homogeneous object coordinates (w = 1 where there are three columns).
    mvp : ndarray, shape (4, 4), float64
        Object -> clip (row vectors).
    gx, gy : float
        Guard band (:func:`~.clip.outcodes`).
    user : ndarray, shape (K, 4), float64
        User clip planes in clip space (clipplane(3G); (0, 4) when none is on).
    vp_l, vp_r, vp_b, vp_t : int; znear, zfar : float; subpixel : bool
        As for :func:`~.clip.project_snap`.
    code : ndarray, shape (Nv,), uint16
    xf, yf : ndarray, shape (Nv,), int64; zw : ndarray, shape (Nv,), float64
        Outputs, written in rows ``v0 .. v1 - 1``.
    v0, v1 : int
    """
    # One scalar pass per vertex (no per-stage arrays): project_snap's half extents.
    hx = (vp_r - vp_l + 1) / 2.0
    hy = (vp_t - vp_b + 1) / 2.0
    hz = (zfar - znear) / 2.0
    homogeneous = obj.shape[1] > 3
    m = mvp_entries(mvp)
    for i in range(v0, v1):
        # (Nv, 3) rows are (x, y, z, 1): 1.0 * m is m, the value of a w column of ones.
        p3 = obj[i, 3] if homogeneous else 1.0
        cx, cy, cz, cw = clip_position(obj[i, 0], obj[i, 1], obj[i, 2], p3, m)
        code[i] = vertex_outcode(cx, cy, cz, cw, gx, gy, user)
        xf[i], yf[i], zw[i] = project_vertex(cx, cy, cz, cw, vp_l, vp_b, hx, hy, hz, znear,
                                             subpixel)


@jit
def front_slots(code, tris):
    """First set-up record of each triangle, relative to the call's first (see the
    module docstring); ``slots[Nt]`` is the number of records the call uses.

    Parameters
    ----------
    code : ndarray, shape (Nv,), uint16
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
        elif (ca & cb & cc) == 0 and ca != NONFINITE and cb != NONFINITE and cc != NONFINITE:
            n += CLIP_SLOTS  # the clip_triangles rule: clipped, not rejected
    slots[nt] = n
    return slots


@jit
def front_assemble(obj, mvp, code, xf, yf, zw, attr, tris, slots, gx, gy, user, vp_l, vp_r,
                   vp_b, vp_t, znear, zfar, subpixel):
    """The triangles set-up reads, one per record (see the module docstring), when
    some triangle is clipped or rejected: the clipped ones' vertices appended.

    Parameters
    ----------
    obj, mvp : ndarray
        As for :func:`front_vertices` (clip positions are computed again for the
        vertices of clipped triangles).
    code, xf, yf, zw : ndarray, shape (Nv,)
        The vertices after :func:`front_vertices`.
    attr : ndarray, shape (Nv, K), float64
        Vertex colour in [0, 1] (K = 4), or K = 0 when colour is not written.
    tris : ndarray, shape (Nt, 3), int64
    slots : ndarray, shape (Nt + 1,), int64
        From :func:`front_slots`.
    gx, gy, user, vp_l, vp_r, vp_b, vp_t, znear, zfar, subpixel
        As for :func:`front_vertices`.

    Returns
    -------
    xf, yf, zw, attr : ndarray
        The vertices with those clipping made appended.
    rec_tris : ndarray, shape (slots[Nt], 3), int64
        Per record, its triangle; a clipped triangle's unused records get the
        degenerate (0, 0, 0), which set-up makes a dead record (zero area).
    rec_src : ndarray, shape (slots[Nt],), int64
        Per record, its input triangle.
    """
    nt = tris.shape[0]
    nv = xf.shape[0]
    k = attr.shape[1]
    nrec = slots[nt]
    homogeneous = obj.shape[1] > 3
    m = mvp_entries(mvp)
    nclip = 0
    for t in range(nt):
        if slots[t + 1] - slots[t] > 1:
            nclip += 1
    cap = nv + nclip * (3 + MAX_POLY)
    oxf = np.empty(cap, dtype=np.int64)
    oyf = np.empty(cap, dtype=np.int64)
    ozw = np.empty(cap, dtype=np.float64)
    oattr = np.empty((cap, k), dtype=np.float64)
    oxf[:nv] = xf
    oyf[:nv] = yf
    ozw[:nv] = zw
    oattr[:nv] = attr
    rec_tris = np.zeros((nrec, 3), dtype=np.int64)
    rec_src = np.empty(nrec, dtype=np.int64)
    v3 = np.empty((3, 4), dtype=np.float64)
    a3 = np.empty((3, k), dtype=np.float64)
    one = np.zeros((1, 3), dtype=np.int64)
    one[0, 1] = 1
    one[0, 2] = 2
    top = nv
    for t in range(nt):
        n = slots[t]
        used = slots[t + 1] - n
        for f in range(used):
            rec_src[n + f] = t
        if used == 1:
            for j in range(3):
                rec_tris[n, j] = tris[t, j]
        elif used > 1:
            for j in range(3):
                i = tris[t, j]
                p3 = obj[i, 3] if homogeneous else 1.0
                v3[j, 0], v3[j, 1], v3[j, 2], v3[j, 3] = clip_position(
                    obj[i, 0], obj[i, 1], obj[i, 2], p3, m)
                for q in range(k):
                    a3[j, q] = attr[i, q]
            cv, ca, fan, _src = clip_triangles(v3, a3, one, gx, gy, user)
            px, py, pz = project_snap(cv, vp_l, vp_r, vp_b, vp_t, znear, zfar, subpixel)
            for i in range(cv.shape[0]):
                oxf[top + i] = px[i]
                oyf[top + i] = py[i]
                ozw[top + i] = pz[i]
                for q in range(k):
                    oattr[top + i, q] = ca[i, q]
            for f in range(fan.shape[0]):
                for j in range(3):
                    rec_tris[n + f, j] = top + fan[f, j]
            top += cv.shape[0]
    return oxf[:top], oyf[:top], ozw[:top], oattr[:top], rec_tris, rec_src


@jit
def light_transform_rows(pos, col, nrm, sent, row_v0, row_v1, row_rec, mvp, light_mode,
                         modelview, normal_matrix, emission, ambient, diffuse, specular,
                         shininess, alpha, light_lo, light_hi, lights, lmodel, min_shininess,
                         clip_v, rgba):
    """The vertex work of a whole flush in one pass: each primitive row's vertices
    lit (in their record's modelview, material, lights and lighting model) and taken
    to clip space (their record's transform).

    The arithmetic is that of :func:`~.lighting.light_object_runs` (eye position in
    transform.apply's order, divided by w unless 0; normal matrix, normalised; the
    equation of :func:`~.lighting._shade_vertex`) and of
    :func:`~.transform.transform_points` for ``p @ mvp`` (rescaled near overflow as
    ``vgxsim.geometry.pipeline._tame`` does), vertex by vertex, so every
    value is the one the group-by-group passes give (vgxsim/pipeline/flush_front.py).

    Parameters
    ----------
    pos : ndarray, shape (V, 4), float64; col : ndarray, shape (V, 4), float64
    nrm : ndarray, shape (V, 3), float64; sent : ndarray, shape (V,), bool
        The decoded vertices (vgxsim.kernels.decode.decode_stream).
    row_v0, row_v1, row_rec : ndarray, shape (P,), int64
        Per primitive row, its vertices ``row_v0 .. row_v1 - 1`` and its record.
    mvp : ndarray, shape (R, 4, 4), float64
        Per record, object -> clip (row vectors).
    light_mode : ndarray, shape (R,), int64
        Per record: 0 the vertex keeps its colour, 1 lit where ``sent`` (LMC_COLOR),
        2 every vertex lit (lmcolor(3G)).
    modelview : ndarray, shape (R, 4, 4); normal_matrix : ndarray, shape (R, 3, 3)
    emission, ambient, diffuse, specular : ndarray, shape (R, 3), float64
    shininess, alpha : ndarray, shape (R,), float64
        Per record, its lighting (unused where ``light_mode`` is 0).
    light_lo, light_hi : ndarray, shape (R,), int64
        Per record, its rows of ``lights``.
    lights : ndarray, shape (L, LIGHT_COLUMNS), float64
    lmodel : ndarray, shape (R, LMODEL_COLUMNS), float64
    min_shininess : float
    clip_v : ndarray, shape (V, 4), float64; rgba : ndarray, shape (V, 4), float64
        Outputs, written in the rows' vertices.
    """
    rgb = np.empty(3)
    for j in range(row_v0.shape[0]):
        r = row_rec[j]
        m = mvp[r]
        mode = light_mode[r]
        lts = lights[light_lo[r]:light_hi[r]]
        lm = lmodel[r]
        e = modelview[r]
        q = normal_matrix[r]
        for i in range(row_v0[j], row_v1[j]):
            p0, p1, p2, p3 = pos[i, 0], pos[i, 1], pos[i, 2], pos[i, 3]
            big = 0.0
            finite = True
            for c in range(4):
                v = ((p0 * m[0, c] + p1 * m[1, c]) + p2 * m[2, c]) + p3 * m[3, c]
                clip_v[i, c] = v
                a = abs(v)
                if not np.isfinite(a):
                    finite = False
                elif a > big:
                    big = a
            if finite and big > HUGE:
                # geometry.pipeline._tame, row by row (as front_vertices does).
                for c in range(4):
                    clip_v[i, c] = clip_v[i, c] / big
            if mode == 0 or (mode == 1 and not sent[i]):
                for c in range(4):
                    rgba[i, c] = col[i, c]
                continue
            ex = ((p0 * e[0, 0] + p1 * e[1, 0]) + p2 * e[2, 0]) + p3 * e[3, 0]
            ey = ((p0 * e[0, 1] + p1 * e[1, 1]) + p2 * e[2, 1]) + p3 * e[3, 1]
            ez = ((p0 * e[0, 2] + p1 * e[1, 2]) + p2 * e[2, 2]) + p3 * e[3, 2]
            ew = ((p0 * e[0, 3] + p1 * e[1, 3]) + p2 * e[2, 3]) + p3 * e[3, 3]
            if ew == 0.0:
                ew = 1.0
            n0, n1, n2 = nrm[i, 0], nrm[i, 1], nrm[i, 2]
            nx = (n0 * q[0, 0] + n1 * q[1, 0]) + n2 * q[2, 0]
            ny = (n0 * q[0, 1] + n1 * q[1, 1]) + n2 * q[2, 1]
            nz = (n0 * q[0, 2] + n1 * q[1, 2]) + n2 * q[2, 2]
            length = math.sqrt(nx * nx + ny * ny + nz * nz)
            if length > 0.0:
                nx, ny, nz = nx / length, ny / length, nz / length
            else:
                nx, ny, nz = 0.0, 0.0, 0.0
            _shade_vertex(rgba, i, ex / ew, ey / ew, ez / ew, nx, ny, nz, emission, ambient,
                          diffuse, specular, shininess, alpha, r, lts, lm, min_shininess, rgb)


@jit
def flush_segments(rows, rec_of, klass, rast, colour, tri_row, out_src):
    """Cut a flush's rows into segments and its clipped triangles among them.

    A CLEAR row is a segment of its own; consecutive triangle rows whose records
    share a class (one clip, projection and set-up call) form one
    (vgxsim/pipeline/flush_front.py).

    Parameters
    ----------
    rows : ndarray, shape (P, PRIM_COLUMNS), int64
        Clears and triangle primitives, in order.
    rec_of : ndarray, shape (Pt,), int64
        Per triangle row (the non-clear rows, in order), its record's dense number.
    klass, rast, colour : ndarray, shape (R,), int64
        Per record, its segment class, its raster's number and 1 when it writes
        (or tests) colour.
    tri_row : ndarray, shape (T,), int64
        Per assembled triangle, its triangle row.
    out_src : ndarray, shape (T2,), int64
        Per clipped triangle, its assembled triangle (nondecreasing).

    Returns
    -------
    segs : ndarray, shape (S, 6), int64
        Per segment: its first row, 1 for a clear (else 0), its clipped triangles
        ``t0 .. t1 - 1``, 1 when they are of several rasters, 1 when one of its
        records needs colour.
    out_rast : ndarray, shape (T2,), int64
        Per clipped triangle, its raster's number.
    present : ndarray, shape (S, NR), bool
        Per segment, which raster numbers its triangles have (NR = ``rast.max() + 1``).
    local : ndarray, shape (T2,), int64
        Per clipped triangle, its raster's rank among its segment's present ones.
    """
    np_ = rows.shape[0]
    segs = np.zeros((np_, 6), np.int64)
    row_seg = np.empty(rec_of.shape[0], np.int64)
    s = -1
    prev = -2  # the previous row's class; -1 for a clear
    k = 0  # triangle rows seen
    for p in range(np_):
        if rows[p, P_KIND] == CLEAR_KIND:
            s += 1
            segs[s, 0] = p
            segs[s, 1] = 1
            prev = -1
            continue
        c = klass[rec_of[k]]
        if c != prev:
            s += 1
            segs[s, 0] = p
            prev = c
        if colour[rec_of[k]] != 0:
            segs[s, 5] = 1
        row_seg[k] = s
        k += 1
    nseg = s + 1
    out_rast = np.empty(out_src.shape[0], np.int64)
    for q in range(nseg):
        segs[q, 2] = -1
    for t in range(out_src.shape[0]):
        r = tri_row[out_src[t]]
        q = row_seg[r]
        v = rast[rec_of[r]]
        out_rast[t] = v
        if segs[q, 2] < 0:
            segs[q, 2] = t
            segs[q, 4] = 0
        elif out_rast[segs[q, 2]] != v:
            segs[q, 4] = 1
        segs[q, 3] = t + 1
    nr = 0
    for i in range(rast.shape[0]):
        nr = max(nr, rast[i] + 1)
    present = np.zeros((nseg, nr), np.bool_)
    local = np.zeros(out_src.shape[0], np.int64)
    rank = np.empty(nr, np.int64)
    for q in range(nseg):
        if segs[q, 2] < 0:
            segs[q, 2] = 0
            segs[q, 3] = 0
            continue
        for t in range(segs[q, 2], segs[q, 3]):
            present[q, out_rast[t]] = True
        n = 0
        for k in range(nr):
            rank[k] = n
            n += present[q, k]
        for t in range(segs[q, 2], segs[q, 3]):
            local[t] = rank[out_rast[t]]
    return segs[:nseg], out_rast, present, local


@jit
def fast_rows(prims, code):
    """Per primitive row, whether the flush pass draws it: a clear, or a triangle
    primitive (polygon, pmv, tmesh, qstrip) of a record coded 1, or coded 2 without
    a set lmcolor colour (vgxsim/pipeline/flush_front.py ``Tables.code``).

    Parameters
    ----------
    prims : ndarray, shape (P, PRIM_COLUMNS), int64
    code : ndarray, shape (R,), int64

    Returns
    -------
    fast : ndarray, shape (P,), bool
    n : int
        How many are.
    """
    npr = prims.shape[0]
    fast = np.zeros(npr, np.bool_)
    n = 0
    for p in range(npr):
        kind = prims[p, P_KIND]
        if kind == CLEAR_KIND:
            ok = True
        elif kind == POLYGON or kind == PMV or kind == TMESH or kind == QSTRIP:
            c = code[prims[p, P_STATE]]
            ok = c == 1 or (c == 2 and prims[p, P_LMCOLOR_SET] == 0)
        else:
            ok = False
        fast[p] = ok
        n += ok
    return fast, n


@jit
def flush_rows(prims, rec_proj):
    """The rows a flush pass draws, and its triangle rows' vertices and records.

    Parameters
    ----------
    prims : ndarray, shape (P, PRIM_COLUMNS), int64
        Decoded primitive rows: clears and triangle primitives.
    rec_proj : ndarray, shape (R,), int64
        Per record of the window's table, its projection's number.

    Returns
    -------
    rows : ndarray, shape (P2, PRIM_COLUMNS), int64
        The clears and the primitives with vertices, in order.
    tri_rows : ndarray, shape (Pt, PRIM_COLUMNS), int64
        The primitives of ``rows``, vertex columns counted from ``vlo``.
    rec_of : ndarray, shape (Pt,), int64
        Each one's record.
    row_v0, row_v1 : ndarray, shape (Pt,), int64
        The vertex columns of ``tri_rows``.
    vlo, vhi : int
        Their vertices are ``vlo .. vhi - 1`` (the decoder writes them in order).
    nproj : int
        How many projections their records have.
    """
    npr = prims.shape[0]
    nrec = rec_proj.shape[0]
    n = 0
    nt = 0
    for p in range(npr):
        if prims[p, P_KIND] == CLEAR_KIND:
            n += 1
        elif prims[p, P_V1] > prims[p, P_V0]:
            n += 1
            nt += 1
    rows = np.empty((n, prims.shape[1]), np.int64)
    tri_rows = np.empty((nt, prims.shape[1]), np.int64)
    seen = np.zeros(nrec + 1, np.bool_)
    k = 0
    j = 0
    ncol = prims.shape[1]
    for p in range(npr):
        clear = prims[p, P_KIND] == CLEAR_KIND
        if not clear and prims[p, P_V1] <= prims[p, P_V0]:
            continue
        # Element by element: a row assigned from an array row (rows[k] = prims[p])
        # compiles Numba's shape-mismatch error message, string formatting and all
        # (~3.8 s of this kernel's 4.7 s cold compile, bench/startup.py --compiles).
        for c in range(ncol):
            rows[k, c] = prims[p, c]
        k += 1
        if not clear:
            for c in range(ncol):
                tri_rows[j, c] = prims[p, c]
            seen[rec_proj[prims[p, P_STATE]]] = True
            j += 1
    vlo = tri_rows[0, P_V0] if nt > 0 else 0
    vhi = tri_rows[nt - 1, P_V1] if nt > 0 else 0
    nproj = 0
    for r in range(nrec + 1):
        nproj += seen[r]
    rec_of = np.empty(nt, np.int64)
    row_v0 = np.empty(nt, np.int64)
    row_v1 = np.empty(nt, np.int64)
    for i in range(nt):
        tri_rows[i, P_V0] -= vlo
        tri_rows[i, P_V1] -= vlo
        rec_of[i] = tri_rows[i, P_STATE]
        row_v0[i] = tri_rows[i, P_V0]
        row_v1[i] = tri_rows[i, P_V1]
    return rows, tri_rows, rec_of, row_v0, row_v1, vlo, vhi, nproj
