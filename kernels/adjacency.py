"""Edge adjacency of a polygon mesh (the ``shadows`` program's "edge-adjacency lists").

README of ``shadows``: the program "does a significant amount of processing on the
models to make the shadow face calculation easier, such as keeping edge-adjacency
lists ... for some models this time was getting up around 30 seconds".  Here one
pass over the directed polygon edges with an open-addressing hash table keyed by the
unordered vertex pair pairs each edge with its two polygons in linear time.

On a consistently wound, manifold mesh every edge is traversed once in each
direction (article: "Assume all polygons ... are drawn in a counter clockwise
direction").  A second traversal in the same direction (inconsistent winding) or a
third polygon on one edge (non-manifold) is reported, not guessed at.
"""

from __future__ import annotations

import numpy as np

from .options import jit

ADJ_OK = 0
ADJ_SAME_DIRECTION = 1  # an edge traversed twice in the same direction
ADJ_NONMANIFOLD = 2  # a third polygon on one edge


@jit
def _hash(a: int, b: int, mask: int) -> int:
    # Knuth multiplicative hashing of the unordered pair; the constant is odd.
    h = (a * 0x9E3779B1 + b * 0x85EBCA77) & 0x7FFFFFFFFFFFFFFF
    return (h ^ (h >> 29)) & mask


@jit
def edge_adjacency(poly_start, poly_verts):
    """Pair every polygon edge with the polygons on its two sides.

    Parameters
    ----------
    poly_start : ndarray, shape (F + 1,), int64
        Polygon ``f`` has vertices ``poly_verts[poly_start[f]:poly_start[f + 1]]``.
    poly_verts : ndarray, shape (N,), int64
        Vertex indices, counter-clockwise seen from outside.

    Returns
    -------
    edges : ndarray, shape (E, 2), int64
        Each edge once, as ``(a, b)`` in the direction its first polygon traverses it.
    edge_faces : ndarray, shape (E, 2), int64
        The polygon traversing ``a -> b`` and the one traversing ``b -> a`` (-1 if
        none: a boundary edge).
    status : int
        ADJ_OK, ADJ_SAME_DIRECTION or ADJ_NONMANIFOLD.
    where : int
        The index into ``poly_verts`` of the directed edge that failed (-1 if OK).
    """
    n = poly_verts.shape[0]
    cap = 1
    while cap < 2 * n + 2:
        cap *= 2
    mask = cap - 1
    table = np.full(cap, -1, np.int64)
    edges = np.empty((n, 2), np.int64)
    faces = np.empty((n, 2), np.int64)
    ne = 0
    nf = poly_start.shape[0] - 1
    for f in range(nf):
        s = poly_start[f]
        e_ = poly_start[f + 1]
        k = e_ - s
        for i in range(k):
            a = poly_verts[s + i]
            b = poly_verts[s + (i + 1) % k]
            lo = min(a, b)
            hi = max(a, b)
            slot = _hash(lo, hi, mask)
            while True:
                e = table[slot]
                if e < 0:
                    table[slot] = ne
                    edges[ne, 0] = a
                    edges[ne, 1] = b
                    faces[ne, 0] = f
                    faces[ne, 1] = -1
                    ne += 1
                    break
                ea = edges[e, 0]
                eb = edges[e, 1]
                if min(ea, eb) == lo and max(ea, eb) == hi:
                    if ea == a:
                        return edges[:ne], faces[:ne], ADJ_SAME_DIRECTION, s + i
                    if faces[e, 1] >= 0:
                        return edges[:ne], faces[:ne], ADJ_NONMANIFOLD, s + i
                    faces[e, 1] = f
                    break
                slot = (slot + 1) & mask
    return edges[:ne].copy(), faces[:ne].copy(), ADJ_OK, -1
