"""Homogeneous clipping, perspective divide, viewport mapping and snapping.

Clipping happens before the divide (so vertices with w = 0, the shadow-volume
extrusion to infinity, and primitives crossing w = 0 are handled) against:

* the near and far planes ``-w <= z <= w`` (which also imply ``w >= 0``);
* a guard band ``|x| <= gx*w``, ``|y| <= gy*w`` far outside the viewport, chosen by
  the caller so that snapped fixed-point coordinates stay below 2**24;
* up to six user clip planes (clipplane(3G)), given in clip space as rows
  ``(a, b, c, d)`` keeping ``a*x + b*y + c*z + d*w >= 0`` (an empty (0, 4) array
  when none is on).

Pixels outside the viewport are removed later by the raster rectangle (scissor), so
x/y clipping rarely creates vertices and edges keep their exact direction.

Watertightness across clipped shared edges: an edge is always intersected from its
endpoint inside the plane, so two triangles sharing an edge compute the bit-identical
intersection point (and the parameter stays accurate when the outside endpoint is
enormously far away).
"""

from __future__ import annotations

import numpy as np

from .options import inline, inline_ir, jit

SUBPIXEL_BITS = 8
ONE = 1 << SUBPIXEL_BITS
# Window coordinates are clamped to +-COORD_LIMIT pixels (the guard band keeps real
# geometry far inside): fixed values stay below 2**24 and edge products below 2**50.
COORD_LIMIT = 1 << 16
MAX_POLY = 16  # 3 vertices + at most one more per clip plane (6 + 6 user), with slack
N_PLANES = 6
ORIGIN_BIT = 1 << N_PLANES  # inside every plane with w = 0: the clip-space origin
NONFINITE = 0xFFFF  # outcode of a vertex with a non-finite coordinate
NO_PLANES = np.zeros((0, 4))  # no user clip plane


@inline
def _plane_bit(p):
    """Outcode bit of plane p: frustum planes 0-5 bits 0-5, user plane j bit 7 + j."""
    return 1 << (p if p < N_PLANES else p + 1)


@inline
def _plane_dist(x, y, z, w, p, gx, gy, user):
    if p < N_PLANES:
        return _dist(x, y, z, w, p, gx, gy)
    j = p - N_PLANES
    return user[j, 0] * x + user[j, 1] * y + user[j, 2] * z + user[j, 3] * w


@inline
def _dist(x, y, z, w, plane, gx, gy):
    if plane == 0:
        return w + z
    if plane == 1:
        return w - z
    if plane == 2:
        return gx * w - x
    if plane == 3:
        return gx * w + x
    if plane == 4:
        return gy * w - y
    return gy * w + y


@jit
def outcodes(v, gx, gy, user):
    """Bit set when a vertex is outside a clip plane (:func:`_plane_bit`), or
    NONFINITE.

    Parameters
    ----------
    v : ndarray, shape (N, 4), float64
        Clip-space positions.
    gx, gy : float
        Guard-band half extents in normalized device units.
    user : ndarray, shape (K, 4), float64
        User clip planes in clip space (K <= 6).

    Returns
    -------
    ndarray, shape (N,), uint16
    """
    n = v.shape[0]
    out = np.zeros(n, dtype=np.uint16)
    for i in range(n):
        out[i] = vertex_outcode(v[i, 0], v[i, 1], v[i, 2], v[i, 3], gx, gy, user)
    return out


@inline_ir
def vertex_outcode(x, y, z, w, gx, gy, user):
    """The outcode of one clip-space vertex (:func:`outcodes`; a helper so that the
    fused front end, kernels/front.py, computes it from scalars by the same code).
    Inlined at the IR level: as a call it pays two atomic reference-count updates
    on ``user`` per vertex, three times the outcode's own cost."""
    if not (np.isfinite(x) and np.isfinite(y) and np.isfinite(z) and np.isfinite(w)):
        return NONFINITE
    # The six frustum planes written out (the _dist expressions, bits 0-5): a loop
    # over a plane number branches per plane and costs several times the arithmetic.
    c = 0
    if not (w + z >= 0.0):
        c |= 1
    if not (w - z >= 0.0):
        c |= 2
    if not (gx * w - x >= 0.0):
        c |= 4
    if not (gx * w + x >= 0.0):
        c |= 8
    if not (gy * w - y >= 0.0):
        c |= 16
    if not (gy * w + y >= 0.0):
        c |= 32
    for j in range(user.shape[0]):
        # _plane_dist and _plane_bit of user plane j (plane N_PLANES + j), written
        # here: a call taking ``user`` would pay the reference-count updates again.
        if not (user[j, 0] * x + user[j, 1] * y + user[j, 2] * z + user[j, 3] * w >= 0.0):
            c |= 1 << (N_PLANES + 1 + j)
    if c == 0 and not (w > 0.0):
        # Only the clip-space origin (the eye of a perspective projection) is inside
        # all six planes with w = 0: send it to the clipper, which drops polygons
        # touching it (they are edge-on and cover nothing).
        c = ORIGIN_BIT
    return c


@jit
def clip_triangles(v, attr, tris, gx, gy, user):
    """Clip triangles in homogeneous space.

    Parameters
    ----------
    v : ndarray, shape (Nv, 4), float64
        Clip-space vertex positions.
    attr : ndarray, shape (Nv, K), float64
        Per-vertex attributes interpolated linearly in clip space (colour, ...).
    tris : ndarray, shape (Nt, 3), int64
        Vertex indices of each triangle.
    gx, gy : float
        Guard band (see module docstring).
    user : ndarray, shape (K, 4), float64
        User clip planes in clip space (see module docstring).

    Returns
    -------
    out_v : ndarray, shape (M, 4), float64
        Input vertices followed by the vertices created by clipping.
    out_attr : ndarray, shape (M, K), float64
    out_tris : ndarray, shape (T, 3), int64
        Surviving triangles, in input order (clipped polygons fanned in place).
    out_src : ndarray, shape (T,), int64
        Index of the input triangle each output triangle came from.
    """
    nv = v.shape[0]
    nt = tris.shape[0]
    k = attr.shape[1]
    code = outcodes(v, gx, gy, user)
    # Pass 1: how many triangles need real clipping.
    nclip = 0
    for t in range(nt):
        a, b, c = tris[t, 0], tris[t, 1], tris[t, 2]
        if (code[a] | code[b] | code[c]) != 0 and (code[a] & code[b] & code[c]) == 0:
            if code[a] == NONFINITE or code[b] == NONFINITE or code[c] == NONFINITE:
                continue
            nclip += 1
    if nclip == 0:
        # Nothing to clip (the usual case): the input vertices are the output ones.
        out_v = v
        out_attr = attr
    else:
        out_v = np.empty((nv + nclip * MAX_POLY, 4), dtype=np.float64)
        out_attr = np.empty((nv + nclip * MAX_POLY, k), dtype=np.float64)
        for i in range(nv):
            for q in range(4):
                out_v[i, q] = v[i, q]
            for q in range(k):
                out_attr[i, q] = attr[i, q]
    out_tris = np.empty((nt + nclip * (MAX_POLY - 3), 3), dtype=np.int64)
    out_src = np.empty(nt + nclip * (MAX_POLY - 3), dtype=np.int64)
    poly = np.empty((MAX_POLY, 4 + k), dtype=np.float64)
    tmp = np.empty((MAX_POLY, 4 + k), dtype=np.float64)
    nvo = nv
    nto = 0
    for t in range(nt):
        a, b, c = tris[t, 0], tris[t, 1], tris[t, 2]
        ca, cb, cc = code[a], code[b], code[c]
        if (ca | cb | cc) == 0:
            out_tris[nto, 0] = a
            out_tris[nto, 1] = b
            out_tris[nto, 2] = c
            out_src[nto] = t
            nto += 1
            continue
        if (ca & cb & cc) != 0 or ca == NONFINITE or cb == NONFINITE or cc == NONFINITE:
            continue
        # Sutherland-Hodgman against each plane some vertex is outside of.
        for j in range(3):
            src = tris[t, j]
            for q in range(4):
                poly[j, q] = v[src, q]
            for q in range(k):
                poly[j, 4 + q] = attr[src, q]
        n = 3
        planes = ca | cb | cc
        for p in range(N_PLANES + user.shape[0]):
            if not (planes & _plane_bit(p)):
                continue
            m = 0
            for i in range(n):
                i2 = (i + 1) % n
                d1 = _plane_dist(poly[i, 0], poly[i, 1], poly[i, 2], poly[i, 3], p, gx, gy,
                                 user)
                d2 = _plane_dist(poly[i2, 0], poly[i2, 1], poly[i2, 2], poly[i2, 3], p, gx,
                                 gy, user)
                in1 = d1 >= 0.0
                in2 = d2 >= 0.0
                if in1:
                    for q in range(4 + k):
                        tmp[m, q] = poly[i, q]
                    m += 1
                if in1 != in2:
                    # Intersect from the endpoint inside this plane: the parameter is
                    # then small and exact enough even when the other endpoint is
                    # enormously far out, and -- being independent of the traversal
                    # direction -- a shared edge gets the same point in both triangles.
                    if in1:
                        lo, hi, dlo, dhi = i, i2, d1, d2
                    else:
                        lo, hi, dlo, dhi = i2, i, d2, d1
                    s = dlo / (dlo - dhi)
                    for q in range(4 + k):
                        tmp[m, q] = poly[lo, q] + s * (poly[hi, q] - poly[lo, q])
                    m += 1
            n = m
            for i in range(n):
                for q in range(4 + k):
                    poly[i, q] = tmp[i, q]
            if n < 3:
                break
        if n < 3:
            continue
        ok = True
        for i in range(n):
            if not (poly[i, 3] > 0.0) or not np.isfinite(poly[i, 0] + poly[i, 1] + poly[i, 2]):
                ok = False  # touches the eye point: edge-on, covers nothing
        if not ok:
            continue
        base = nvo
        for i in range(n):
            for q in range(4):
                out_v[nvo, q] = poly[i, q]
            for q in range(k):
                out_attr[nvo, q] = poly[i, 4 + q]
            nvo += 1
        for i in range(1, n - 1):
            out_tris[nto, 0] = base
            out_tris[nto, 1] = base + i
            out_tris[nto, 2] = base + i + 1
            out_src[nto] = t
            nto += 1
    return out_v[:nvo], out_attr[:nvo], out_tris[:nto], out_src[:nto]


@inline
def snap(v, subpixel):
    """One window coordinate (pixel units) to fixed point, docs/numeric_model.md s. 2:
    ``floor(v * 256 + 0.5)`` with subpixel(TRUE), else the nearest pixel centre
    ``floor(v + 0.5) * 256`` (ties upward)."""
    if subpixel:
        return np.int64(np.floor(v * ONE + 0.5))
    return np.int64(np.floor(v + 0.5)) * ONE


@jit
def project_snap(v, vp_l, vp_r, vp_b, vp_t, znear, zfar, subpixel):
    """Divide by w, map to IRIS window coordinates and snap to fixed point.

    Implements docs/numeric_model.md sections 1-2.

    Parameters
    ----------
    v : ndarray, shape (N, 4), float64
        Clip-space positions (w > 0 for every vertex a primitive uses).
    vp_l, vp_r, vp_b, vp_t : int
        Inclusive viewport bounds.
    znear, zfar : float
        lsetdepth range.
    subpixel : bool
        False snaps to pixel centres (IRIS default), True keeps 8 fractional bits.

    Returns
    -------
    xf, yf : ndarray, shape (N,), int64
        Fixed-point window coordinates (pixel centre X is X * 256).
    zw : ndarray, shape (N,), float64
        Window depth in lsetdepth units.
    """
    n = v.shape[0]
    xf = np.zeros(n, dtype=np.int64)
    yf = np.zeros(n, dtype=np.int64)
    zw = np.zeros(n, dtype=np.float64)
    hx = (vp_r - vp_l + 1) / 2.0
    hy = (vp_t - vp_b + 1) / 2.0
    hz = (zfar - znear) / 2.0
    for i in range(n):
        xf[i], yf[i], zw[i] = project_vertex(v[i, 0], v[i, 1], v[i, 2], v[i, 3], vp_l, vp_b,
                                             hx, hy, hz, znear, subpixel)
    return xf, yf, zw


@inline
def project_vertex(x, y, z, w, vp_l, vp_b, hx, hy, hz, znear, subpixel):
    """One vertex of :func:`project_snap` (``hx, hy, hz``: the half extents it
    computes): its fixed-point x, y and window z, (0, 0, 0.0) where w <= 0 or the
    result is not finite.  A helper so that the fused front end (kernels/front.py)
    projects from scalars by the same code."""
    if not (w > 0.0):
        return np.int64(0), np.int64(0), 0.0
    xw = (vp_l - 0.5) + (x / w + 1.0) * hx
    yw = (vp_b - 0.5) + (y / w + 1.0) * hy
    zw = znear + (z / w + 1.0) * hz
    if not (np.isfinite(xw) and np.isfinite(yw) and np.isfinite(zw)):
        return np.int64(0), np.int64(0), 0.0
    limit = float(COORD_LIMIT)
    xw = min(max(xw, -limit), limit)
    yw = min(max(yw, -limit), limit)
    return snap(xw, subpixel), snap(yw, subpixel), zw


@jit
def snap_window(x, y, subpixel):
    """Snap window coordinates (already in pixel units) to fixed point."""
    n = x.shape[0]
    xf = np.empty(n, dtype=np.int64)
    yf = np.empty(n, dtype=np.int64)
    limit = float(COORD_LIMIT)
    for i in range(n):
        xi = min(max(x[i], -limit), limit)
        yi = min(max(y[i], -limit), limit)
        if not (np.isfinite(xi) and np.isfinite(yi)):
            xi = 0.0
            yi = 0.0
        xf[i] = snap(xi, subpixel)
        yf[i] = snap(yi, subpixel)
    return xf, yf


@jit
def clip_segments(v, attr, segs, gx, gy, user):
    """Clip line segments in homogeneous space (Liang-Barsky on the six planes and
    the user planes).

    Parameters
    ----------
    v : ndarray, shape (Nv, 4), float64
    attr : ndarray, shape (Nv, K), float64
    segs : ndarray, shape (Ns, 2), int64
        Vertex indices of each segment.
    gx, gy : float
        Guard band, as for :func:`clip_triangles`.
    user : ndarray, shape (K, 4), float64
        User clip planes in clip space.

    Returns
    -------
    out_v : ndarray, shape (M, 2, 4), float64
    out_attr : ndarray, shape (M, 2, K), float64
    out_src : ndarray, shape (M,), int64
        Surviving (possibly shortened) segments and the segment each came from.
    out_t0 : ndarray, shape (M,), float64
        Parameter along the original segment where the kept part starts.
    """
    ns = segs.shape[0]
    k = attr.shape[1]
    out_v = np.empty((ns, 2, 4), dtype=np.float64)
    out_attr = np.empty((ns, 2, k), dtype=np.float64)
    out_src = np.empty(ns, dtype=np.int64)
    out_t0 = np.empty(ns, dtype=np.float64)
    m = 0
    for s in range(ns):
        a, b = segs[s, 0], segs[s, 1]
        ok = True
        for q in range(4):
            if not (np.isfinite(v[a, q]) and np.isfinite(v[b, q])):
                ok = False
        if not ok:
            continue
        # Entering point measured from b (s0), leaving point from a (t1): each is
        # interpolated from the endpoint inside the plane that cuts it.
        s0 = 1.0
        t1 = 1.0
        for p in range(N_PLANES + user.shape[0]):
            da = _plane_dist(v[a, 0], v[a, 1], v[a, 2], v[a, 3], p, gx, gy, user)
            db = _plane_dist(v[b, 0], v[b, 1], v[b, 2], v[b, 3], p, gx, gy, user)
            if not (np.isfinite(da) and np.isfinite(db)):
                ok = False
                break
            if da < 0.0 and db < 0.0:
                ok = False
                break
            if da < 0.0:
                t = db / (db - da)
                if t < s0:
                    s0 = t
            elif db < 0.0:
                t = da / (da - db)
                if t < t1:
                    t1 = t
        if not ok or (1.0 - s0) > t1:
            continue
        t0 = 1.0 - s0
        for q in range(4):
            out_v[m, 0, q] = v[a, q] if s0 >= 1.0 else v[b, q] + s0 * (v[a, q] - v[b, q])
            out_v[m, 1, q] = v[b, q] if t1 >= 1.0 else v[a, q] + t1 * (v[b, q] - v[a, q])
        for q in range(k):
            out_attr[m, 0, q] = (attr[a, q] if s0 >= 1.0
                                 else attr[b, q] + s0 * (attr[a, q] - attr[b, q]))
            out_attr[m, 1, q] = (attr[b, q] if t1 >= 1.0
                                 else attr[a, q] + t1 * (attr[b, q] - attr[a, q]))
        if not (out_v[m, 0, 3] > 0.0 and out_v[m, 1, 3] > 0.0):
            continue
        out_src[m] = s
        out_t0[m] = t0
        m += 1
    return out_v[:m], out_attr[:m], out_src[:m], out_t0[:m]
