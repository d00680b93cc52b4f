"""Bounding-volume hierarchy over triangles with homogeneous vertices (ray-cast oracle).

The exact shadow reference (:mod:`vgxsim.shadow.raycast`) casts millions of rays
against scenes of up to ~10^5 triangles; testing every triangle is the numpy
version's cost (15 s at 1280x1024 for three cubes).  A BVH makes the cost per ray
logarithmic.  Layout (flattened, depth-first):

* node ``i`` is the record ``nodes[i]`` of 8 float64 (64 bytes, one cache line:
  the traversal reads one line per node, and two siblings are adjacent):
  ``lo x, y, z, hi x, y, z, first, count`` (the two integers stored exactly as
  floats, being far below 2**53);
* a leaf has ``count > 0`` and owns triangles ``first .. first+count-1`` of the
  reordered triangle array ``tris`` (``index`` maps them back to the caller's
  numbering);
* an interior node has ``count == 0``; its children are ``first`` and
  ``first + 1``.

Vertices are homogeneous, ``(x, y, z, w)`` with ``w`` exactly 1 (a point) or 0 (a
direction: the vertex is at infinity, as the extruded vertices of infinite shadow
volumes, Everitt and Kilgard 2002).  A triangle with a vertex at infinity is
unbounded: its box reaches +-inf along the direction's non-zero components, and the
traversal's slab test handles infinite bounds.

The split is chosen by the surface-area heuristic over 12 centroid bins (SAH,
MacDonald and Booth 1990) or, with ``sah=False``, at the object median along the
widest centroid axis; bench/raycast.py measures both.  SAH areas use boxes clamped
to a large finite cube, so unbounded triangles only look very expensive.
"""

from __future__ import annotations

from collections import namedtuple

import numpy as np

from .options import jit

#: The tree's arrays (see the module docstring).  ``nodes``: (N, 8) float64 node
#: records; ``tris``: (T, 3, 4) float64 in tree order; ``index``: (T,) int64, the
#: caller's index of each triangle of ``tris``.
BVH = namedtuple("BVH", ["nodes", "tris", "index"])

#: Columns of a node record.
LO, HI, FIRST, COUNT = 0, 3, 6, 7

#: Deepest level the builder creates (deeper nodes become leaves), so traversal
#: stacks of STACK_SIZE entries never overflow (a stack holds at most depth + 1).
MAX_DEPTH = 60
STACK_SIZE = 64
_BINS = 12


@jit
def triangle_bounds(tris):
    """Box and centroid of each triangle, and whether it can be hit at all.

    Parameters
    ----------
    tris : ndarray, shape (T, 3, 4), float64
        Homogeneous vertices, w exactly 0 or 1.

    Returns
    -------
    lo, hi : ndarray, shape (T, 3), float64
        Box; +-inf where a vertex at infinity points that way.
    centroid : ndarray, shape (T, 3), float64
        Mean of the finite vertices.
    finite : ndarray, shape (T,), bool
        At least one vertex is finite (a triangle wholly at infinity is never hit
        at a finite ray parameter).
    """
    n = tris.shape[0]
    lo = np.empty((n, 3))
    hi = np.empty((n, 3))
    cen = np.zeros((n, 3))
    finite = np.zeros(n, dtype=np.bool_)
    for i in range(n):
        nf = 0
        for c in range(3):
            lo[i, c] = np.inf
            hi[i, c] = -np.inf
        for j in range(3):
            if tris[i, j, 3] != 0.0:
                nf += 1
                for c in range(3):
                    x = tris[i, j, c]
                    lo[i, c] = min(lo[i, c], x)
                    hi[i, c] = max(hi[i, c], x)
                    cen[i, c] += x
        if nf == 0:
            continue
        finite[i] = True
        for c in range(3):
            cen[i, c] /= nf
        for j in range(3):
            if tris[i, j, 3] == 0.0:
                for c in range(3):
                    d = tris[i, j, c]
                    if d > 0.0:
                        hi[i, c] = np.inf
                    elif d < 0.0:
                        lo[i, c] = -np.inf
    return lo, hi, cen, finite


@jit
def _clamped_area(lo0, lo1, lo2, hi0, hi1, hi2, big):
    """Surface area of a box clamped to [-big, big]^3 (0 for an empty box)."""
    a = min(max(lo0, -big), big)
    b = min(max(lo1, -big), big)
    c = min(max(lo2, -big), big)
    x = min(max(hi0, -big), big) - a
    y = min(max(hi1, -big), big) - b
    z = min(max(hi2, -big), big) - c
    if x < 0.0 or y < 0.0 or z < 0.0:
        return 0.0
    return x * y + y * z + z * x


@jit
def build_arrays(tris, ref_tri, blo, bhi, leaf_size, sah):
    """Build the tree (see :data:`BVH`) over triangle references.

    Parameters
    ----------
    tris : ndarray, shape (T, 3, 4), float64
        Homogeneous vertices, w exactly 0 or 1.
    ref_tri : ndarray, shape (R,), int64
        The triangle of each reference; a triangle may have several (one per piece
        of it, :func:`split_references`), each with its own box.
    blo, bhi : ndarray, shape (R, 3), float64
        Box of each reference.
    leaf_size : int
        Largest leaf the builder aims for.
    sah : bool
        Binned SAH split (True) or object median (False).

    Returns
    -------
    nodes, tris, index
        The fields of :data:`BVH` (``tris`` holds one copy of the triangle per
        reference); no nodes at all when there is no reference.
    """
    n = ref_tri.shape[0]
    cen = np.empty((n, 3))
    for i in range(n):
        for c in range(3):
            a = blo[i, c]
            b = bhi[i, c]
            if np.isfinite(a) and np.isfinite(b):
                cen[i, c] = 0.5 * (a + b)
            elif np.isfinite(a):
                cen[i, c] = a
            elif np.isfinite(b):
                cen[i, c] = b
            else:
                cen[i, c] = 0.0
    order = np.arange(n)
    big = 1.0
    for i in range(n):
        for c in range(3):
            if np.isfinite(blo[i, c]):
                big = max(big, abs(blo[i, c]))
            if np.isfinite(bhi[i, c]):
                big = max(big, abs(bhi[i, c]))
    big *= 1e3
    cap = max(1, 2 * n)
    nlo = np.empty((cap, 3))
    nhi = np.empty((cap, 3))
    first = np.zeros(cap, dtype=np.int64)
    count = np.zeros(cap, dtype=np.int64)
    nnodes = 0
    if n > 0:
        nnodes = 1
    st_node = np.empty(2 * STACK_SIZE, dtype=np.int64)
    st_s = np.empty(2 * STACK_SIZE, dtype=np.int64)
    st_e = np.empty(2 * STACK_SIZE, dtype=np.int64)
    st_d = np.empty(2 * STACK_SIZE, dtype=np.int64)
    sp = 0
    if n > 0:
        st_node[0] = 0
        st_s[0] = 0
        st_e[0] = n
        st_d[0] = 0
        sp = 1
    bin_n = np.zeros(_BINS, dtype=np.int64)
    bin_lo = np.empty((_BINS, 3))
    bin_hi = np.empty((_BINS, 3))
    right_area = np.zeros(_BINS)
    right_n = np.zeros(_BINS, dtype=np.int64)
    clo = np.empty(3)
    chi = np.empty(3)
    while sp > 0:
        sp -= 1
        node, s, e, depth = st_node[sp], st_s[sp], st_e[sp], st_d[sp]
        for c in range(3):
            nlo[node, c] = np.inf
            nhi[node, c] = -np.inf
            clo[c] = np.inf
            chi[c] = -np.inf
        for q in range(s, e):
            i = order[q]
            for c in range(3):
                nlo[node, c] = min(nlo[node, c], blo[i, c])
                nhi[node, c] = max(nhi[node, c], bhi[i, c])
                clo[c] = min(clo[c], cen[i, c])
                chi[c] = max(chi[c], cen[i, c])
        cnt = e - s
        axis = 0
        for c in range(1, 3):
            if chi[c] - clo[c] > chi[axis] - clo[axis]:
                axis = c
        ext = chi[axis] - clo[axis]
        leaf = cnt <= leaf_size or depth >= MAX_DEPTH or not (ext > 0.0)
        mid = s
        if not leaf and sah:
            for b in range(_BINS):
                bin_n[b] = 0
                for c in range(3):
                    bin_lo[b, c] = np.inf
                    bin_hi[b, c] = -np.inf
            scale = _BINS / ext
            for q in range(s, e):
                i = order[q]
                b = min(int((cen[i, axis] - clo[axis]) * scale), _BINS - 1)
                bin_n[b] += 1
                for c in range(3):
                    bin_lo[b, c] = min(bin_lo[b, c], blo[i, c])
                    bin_hi[b, c] = max(bin_hi[b, c], bhi[i, c])
            # sweep from the right: area and count of bins b .. BINS-1
            rl0 = np.inf
            rl1 = np.inf
            rl2 = np.inf
            rh0 = -np.inf
            rh1 = -np.inf
            rh2 = -np.inf
            rn = 0
            for b in range(_BINS - 1, 0, -1):
                rn += bin_n[b]
                rl0 = min(rl0, bin_lo[b, 0])
                rl1 = min(rl1, bin_lo[b, 1])
                rl2 = min(rl2, bin_lo[b, 2])
                rh0 = max(rh0, bin_hi[b, 0])
                rh1 = max(rh1, bin_hi[b, 1])
                rh2 = max(rh2, bin_hi[b, 2])
                right_n[b] = rn
                right_area[b] = _clamped_area(rl0, rl1, rl2, rh0, rh1, rh2, big)
            ll0 = np.inf
            ll1 = np.inf
            ll2 = np.inf
            lh0 = -np.inf
            lh1 = -np.inf
            lh2 = -np.inf
            ln = 0
            best = -1
            best_cost = np.inf
            for b in range(_BINS - 1):  # split between bin b and b + 1
                ln += bin_n[b]
                ll0 = min(ll0, bin_lo[b, 0])
                ll1 = min(ll1, bin_lo[b, 1])
                ll2 = min(ll2, bin_lo[b, 2])
                lh0 = max(lh0, bin_hi[b, 0])
                lh1 = max(lh1, bin_hi[b, 1])
                lh2 = max(lh2, bin_hi[b, 2])
                if ln == 0 or right_n[b + 1] == 0:
                    continue
                cost = (ln * _clamped_area(ll0, ll1, ll2, lh0, lh1, lh2, big)
                        + right_n[b + 1] * right_area[b + 1])
                if cost < best_cost:
                    best_cost = cost
                    best = b
            if best < 0:
                mid = (s + e) // 2
            else:
                # partition order[s:e] so bins <= best come first
                lo_q = s
                hi_q = e - 1
                while lo_q <= hi_q:
                    i = order[lo_q]
                    b = min(int((cen[i, axis] - clo[axis]) * scale), _BINS - 1)
                    if b <= best:
                        lo_q += 1
                    else:
                        order[lo_q] = order[hi_q]
                        order[hi_q] = i
                        hi_q -= 1
                mid = lo_q
        elif not leaf:
            keys = np.empty(cnt)
            for q in range(s, e):
                keys[q - s] = cen[order[q], axis]
            perm = np.argsort(keys, kind="mergesort")
            tmp = order[s:e].copy()
            for q in range(cnt):
                order[s + q] = tmp[perm[q]]
            mid = (s + e) // 2
        if not leaf and (mid <= s or mid >= e):
            mid = (s + e) // 2
        if leaf:
            first[node] = s
            count[node] = cnt
            continue
        left = nnodes
        nnodes += 2
        first[node] = left
        count[node] = 0
        st_node[sp] = left + 1
        st_s[sp] = mid
        st_e[sp] = e
        st_d[sp] = depth + 1
        sp += 1
        st_node[sp] = left
        st_s[sp] = s
        st_e[sp] = mid
        st_d[sp] = depth + 1
        sp += 1
    ordered = np.empty((n, 3, 4))
    index = np.empty(n, dtype=np.int64)
    for q in range(n):
        index[q] = ref_tri[order[q]]
        for j in range(3):
            for c in range(4):
                ordered[q, j, c] = tris[index[q], j, c]
    # pad every box outward by a relative 1e-12 so that float rounding in the slab
    # test never culls a ray that meets a triangle on the box boundary
    nodes = np.empty((nnodes, 8))
    for k in range(nnodes):
        for c in range(3):
            a = nlo[k, c]
            b = nhi[k, c]
            pad = 1e-12 * (abs(a) + abs(b)) if np.isfinite(a) and np.isfinite(b) else 0.0
            nodes[k, LO + c] = a - pad
            nodes[k, HI + c] = b + pad
        nodes[k, FIRST] = first[k]
        nodes[k, COUNT] = count[k]
    return nodes, ordered, index


@jit
def _clip_axis(poly, n, out, axis, value, keep_below):
    """Clip a convex polygon (n points in ``poly``) to ``x[axis] <= value`` (or >=)."""
    m = 0
    for i in range(n):
        j = (i + 1) % n
        di = poly[i, axis] - value
        dj = poly[j, axis] - value
        if not keep_below:
            di = -di
            dj = -dj
        if di <= 0.0:
            for c in range(3):
                out[m, c] = poly[i, c]
            m += 1
        if (di < 0.0 < dj) or (dj < 0.0 < di):
            s = di / (di - dj)
            for c in range(3):
                out[m, c] = poly[i, c] + s * (poly[j, c] - poly[i, c])
            out[m, axis] = value
            m += 1
    return m


@jit
def split_references(tris, usable, max_extent, region_lo, region_hi, max_pieces):
    """References to the usable triangles, long ones cut into pieces with tight boxes.

    Early split clipping (Ernst and Greiner 2007): a finite triangle whose box is
    longer than ``max_extent`` inside the region of interest is cut in half along
    its box's longest axis, each half clipped exactly to the triangle, recursively.
    Every piece refers to the whole triangle (the hit test is the triangle's), so
    pieces only shrink the boxes the traversal sees; a query that counts hits must
    count a triangle once (kernels/raycast.py marks them).  Long thin shadow-volume
    faces, whose boxes otherwise cover the scene, are why.

    Parameters
    ----------
    tris : ndarray, shape (T, 3, 4), float64
    usable : ndarray, shape (T,), bool
    max_extent : float
        Pieces are cut until no box side exceeds this (0: no cutting).
    region_lo, region_hi : ndarray, shape (3,), float64
        Boxes entirely outside this region are not cut further.
    max_pieces : int
        At most this many pieces per triangle.

    Returns
    -------
    ref_tri : ndarray, shape (R,), int64
    lo, hi : ndarray, shape (R, 3), float64
    """
    blo, bhi, cen, finite = triangle_bounds(tris)
    nt = tris.shape[0]
    cap = 0
    for i in range(nt):
        if usable[i] and finite[i]:
            cap += 1
    size = cap + 16
    ref_tri = np.empty(size, dtype=np.int64)
    rlo = np.empty((size, 3))
    rhi = np.empty((size, 3))
    nref = 0
    depth_cap = 2 * max_pieces + 2
    polys = np.empty((depth_cap, 12, 3))
    plen = np.empty(depth_cap, dtype=np.int64)
    tmp = np.empty((12, 3))
    for i in range(nt):
        if not (usable[i] and finite[i]):
            continue
        if nref + max_pieces + 2 > size:
            size = 2 * size + max_pieces + 2
            ref_tri = _grow_int(ref_tri, size)
            rlo = _grow_box(rlo, size)
            rhi = _grow_box(rhi, size)
        allfinite = tris[i, 0, 3] == 1.0 and tris[i, 1, 3] == 1.0 and tris[i, 2, 3] == 1.0
        if not allfinite or max_extent <= 0.0:
            ref_tri[nref] = i
            for c in range(3):
                rlo[nref, c] = blo[i, c]
                rhi[nref, c] = bhi[i, c]
            nref += 1
            continue
        for j in range(3):
            for c in range(3):
                polys[0, j, c] = tris[i, j, c]
        plen[0] = 3
        sp = 1
        pieces = 0
        while sp > 0:
            sp -= 1
            n = plen[sp]
            lo0 = np.inf
            lo1 = np.inf
            lo2 = np.inf
            hi0 = -np.inf
            hi1 = -np.inf
            hi2 = -np.inf
            for q in range(n):
                lo0 = min(lo0, polys[sp, q, 0])
                lo1 = min(lo1, polys[sp, q, 1])
                lo2 = min(lo2, polys[sp, q, 2])
                hi0 = max(hi0, polys[sp, q, 0])
                hi1 = max(hi1, polys[sp, q, 1])
                hi2 = max(hi2, polys[sp, q, 2])
            e0 = hi0 - lo0
            e1 = hi1 - lo1
            e2 = hi2 - lo2
            axis = 0
            ext = e0
            if e1 > ext:
                axis = 1
                ext = e1
            if e2 > ext:
                axis = 2
                ext = e2
            inside = (lo0 <= region_hi[0] and hi0 >= region_lo[0] and lo1 <= region_hi[1]
                      and hi1 >= region_lo[1] and lo2 <= region_hi[2] and hi2 >= region_lo[2])
            if ext <= max_extent or not inside or pieces + sp + 2 > max_pieces:
                ref_tri[nref] = i
                rlo[nref, 0] = lo0
                rlo[nref, 1] = lo1
                rlo[nref, 2] = lo2
                rhi[nref, 0] = hi0
                rhi[nref, 1] = hi1
                rhi[nref, 2] = hi2
                nref += 1
                pieces += 1
                continue
            mid = 0.5 * ((lo0 if axis == 0 else (lo1 if axis == 1 else lo2))
                         + (hi0 if axis == 0 else (hi1 if axis == 1 else hi2)))
            for q in range(n):
                for c in range(3):
                    tmp[q, c] = polys[sp, q, c]
            nb = _clip_axis(tmp, n, polys[sp], axis, mid, True)
            na = _clip_axis(tmp, n, polys[sp + 1], axis, mid, False)
            plen[sp] = nb
            plen[sp + 1] = na
            if nb >= 3 and na >= 3:
                sp += 2
            elif nb >= 3:
                sp += 1
            elif na >= 3:
                for q in range(na):
                    for c in range(3):
                        polys[sp, q, c] = polys[sp + 1, q, c]
                plen[sp] = na
                sp += 1
    return ref_tri[:nref], rlo[:nref], rhi[:nref]


@jit
def _grow_int(a, size):
    out = np.empty(size, dtype=np.int64)
    out[:a.shape[0]] = a
    return out


@jit
def _grow_box(a, size):
    out = np.empty((size, 3))
    out[:a.shape[0]] = a
    return out
