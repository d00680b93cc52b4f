"""Edge adjacency of a polygon mesh (the ``shadows`` program's "edge-adjacency lists").

README of ``shadows``: the program "does a significant amount of processing on the
models to make the shadow face calculation easier, such as keeping edge-adjacency
lists ... for some models this time was getting up around 30 seconds".  Here one
pass over the directed polygon edges, bucketed by their smaller vertex with a counting
sort, pairs each edge with its two polygons in linear time.

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
def edge_adjacency(poly_start, poly_verts):
    """Pair every polygon edge with the polygons on its two sides.

    The directed edges are bucketed by their smaller vertex (a counting sort, so
    memory is read in order) and matched by their larger vertex inside each bucket,
    which holds only the few edges of one vertex.

    Parameters
    ----------
    poly_start : ndarray, shape (F + 1,), int64
        Polygon ``f`` has vertices ``poly_verts[poly_start[f]:poly_start[f + 1]]``.
    poly_verts : ndarray, shape (N,), int64
        Vertex indices (>= 0), counter-clockwise seen from outside.

    Returns
    -------
    edges : ndarray, shape (E, 2), int64
        Each edge once, as ``(a, b)`` in the direction its first polygon traverses it;
        ordered by smaller vertex, then by first traversal.
    edge_faces : ndarray, shape (E, 2), int64
        The polygon traversing ``a -> b`` and the one traversing ``b -> a`` (-1 if
        none: a boundary edge).
    status : int
        ADJ_OK, ADJ_SAME_DIRECTION or ADJ_NONMANIFOLD.
    where : int
        The index into ``poly_verts`` of the directed edge that failed (-1 if OK).
    """
    n = poly_verts.shape[0]
    nf = poly_start.shape[0] - 1
    head = np.empty(n, np.int64)   # directed edge h runs head[h] -> tail[h]
    tail = np.empty(n, np.int64)
    face = np.empty(n, np.int64)
    nv = 0
    for f in range(nf):
        s = poly_start[f]
        k = poly_start[f + 1] - s
        for i in range(k):
            a = poly_verts[s + i]
            b = poly_verts[s + (i + 1) % k]
            head[s + i] = a
            tail[s + i] = b
            face[s + i] = f
            nv = max(nv, a + 1)
    # counting sort of the directed edges by their smaller vertex
    count = np.zeros(nv + 1, np.int64)
    for h in range(n):
        count[min(head[h], tail[h]) + 1] += 1
    for v in range(nv):
        count[v + 1] += count[v]
    fill = count[:-1].copy()
    order = np.empty(n, np.int64)
    for h in range(n):
        lo = min(head[h], tail[h])
        order[fill[lo]] = h
        fill[lo] += 1
    edges = np.empty((n, 2), np.int64)
    faces = np.empty((n, 2), np.int64)
    slot = np.empty(n, np.int64)  # per bucket entry: its edge, or -1 until paired
    ne = 0
    for v in range(nv):
        b0 = count[v]
        b1 = count[v + 1]
        for i in range(b0, b1):
            h = order[i]
            hi = max(head[h], tail[h])
            slot[i] = -1
            for j in range(b0, i):
                g = order[j]
                if max(head[g], tail[g]) == hi and slot[j] >= 0:
                    e = slot[j]
                    if edges[e, 0] == head[h]:
                        return edges[:ne], faces[:ne], ADJ_SAME_DIRECTION, h
                    if faces[e, 1] >= 0:
                        return edges[:ne], faces[:ne], ADJ_NONMANIFOLD, h
                    faces[e, 1] = face[h]
                    slot[i] = -2  # paired: not a candidate for later entries
                    break
            if slot[i] == -1:
                edges[ne, 0] = head[h]
                edges[ne, 1] = tail[h]
                faces[ne, 0] = face[h]
                faces[ne, 1] = -1
                slot[i] = ne
                ne += 1
    return edges[:ne].copy(), faces[:ne].copy(), ADJ_OK, -1


@jit
def newell_normals(vertices, poly_start, poly_verts):
    """Newell's normal of each polygon, unit length (zero for a polygon of no area).

    Newell's method sums, over the polygon's edges (p -> q), ``(p.y - q.y)(p.z + q.z)``
    and its cyclic permutations: the polygon's area vector, outward for vertices
    counter-clockwise seen from outside, robust for non-planar polygons.

    Parameters
    ----------
    vertices : ndarray, shape (V, 3), float64
    poly_start : ndarray, shape (F + 1,), int64
    poly_verts : ndarray, shape (N,), int64

    Returns
    -------
    ndarray, shape (F, 3), float64
    """
    nf = poly_start.shape[0] - 1
    out = np.zeros((nf, 3))
    for f in range(nf):
        s = poly_start[f]
        k = poly_start[f + 1] - s
        nx = 0.0
        ny = 0.0
        nz = 0.0
        for i in range(k):
            p = poly_verts[s + i]
            q = poly_verts[s + (i + 1) % k]
            px, py, pz = vertices[p, 0], vertices[p, 1], vertices[p, 2]
            qx, qy, qz = vertices[q, 0], vertices[q, 1], vertices[q, 2]
            nx += (py - qy) * (pz + qz)
            ny += (pz - qz) * (px + qx)
            nz += (px - qx) * (py + qy)
        length = np.sqrt(nx * nx + ny * ny + nz * nz)
        if length > 0.0:
            out[f, 0] = nx / length
            out[f, 1] = ny / length
            out[f, 2] = nz / length
    return out
