"""Bounding-volume hierarchy over triangles with homogeneous vertices (ray-cast oracle).

The exact shadow reference (:mod:`vgxsim.shadow.raycast`) casts millions of rays
against scenes of up to ~10^5 triangles; testing every triangle is the numpy
version's cost (15 s at 1280x1024 for three cubes).  A BVH makes the cost per ray
logarithmic.  Layout (flattened, depth-first):

* node ``i`` has the box ``lo[i], hi[i]``;
* a leaf has ``count[i] > 0`` and owns triangles ``first[i] .. first[i]+count[i]-1``
  of the reordered triangle array ``tris`` (``index`` maps them back to the
  caller's numbering);
* an interior node has ``count[i] == 0``; its children are ``first[i]`` and
  ``first[i] + 1``.

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

#: The tree's arrays (see the module docstring).  ``lo, hi``: (N, 3) float64;
#: ``first, count``: (N,) int64; ``tris``: (T, 3, 4) float64 in tree order;
#: ``index``: (T,) int64, the caller's index of each triangle of ``tris``.
BVH = namedtuple("BVH", ["lo", "hi", "first", "count", "tris", "index"])

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
def build_arrays(tris, usable, leaf_size, sah):
    """Build the tree (see :data:`BVH`); :func:`vgxsim.shadow.raycast` wraps it.

    Parameters
    ----------
    tris : ndarray, shape (T, 3, 4), float64
        Homogeneous vertices, w exactly 0 or 1.
    usable : ndarray, shape (T,), bool
        Triangles to put in the tree (the caller drops degenerate ones).
    leaf_size : int
        Largest leaf the builder aims for.
    sah : bool
        Binned SAH split (True) or object median (False).

    Returns
    -------
    lo, hi, first, count, tris, index
        The fields of :data:`BVH`; no nodes at all when no triangle is usable.
    """
    blo, bhi, cen, finite = triangle_bounds(tris)
    n_all = tris.shape[0]
    n = 0
    for i in range(n_all):
        if usable[i] and finite[i]:
            n += 1
    order = np.empty(n, dtype=np.int64)
    m = 0
    big = 1.0
    for i in range(n_all):
        if usable[i] and finite[i]:
            order[m] = i
            m += 1
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
    for q in range(n):
        for j in range(3):
            for c in range(4):
                ordered[q, j, c] = tris[order[q], j, c]
    # pad every box outward by a relative 1e-12 so that float rounding in the slab
    # test never culls a ray that meets a triangle on the box boundary
    for k in range(nnodes):
        for c in range(3):
            a = nlo[k, c]
            b = nhi[k, c]
            pad = 1e-12 * (abs(a) + abs(b)) if np.isfinite(a) and np.isfinite(b) else 0.0
            nlo[k, c] = a - pad
            nhi[k, c] = b + pad
    return nlo[:nnodes], nhi[:nnodes], first[:nnodes], count[:nnodes], ordered, order


def build_bvh(tris: np.ndarray, usable: np.ndarray | None = None, *, leaf_size: int = 4,
              sah: bool = True) -> BVH:
    """Build a :data:`BVH` (see :func:`build_arrays` for the parameters)."""
    tris = np.ascontiguousarray(tris, dtype=np.float64)
    if usable is None:
        usable = np.ones(tris.shape[0], dtype=np.bool_)
    return BVH(*build_arrays(tris, np.ascontiguousarray(usable, dtype=np.bool_),
                             int(leaf_size), bool(sah)))
