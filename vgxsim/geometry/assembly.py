"""Primitive assembly: IRIS GL vertex sequences -> triangles and segments.

* polygon: convex, fanned from its first vertex (concave(TRUE) polygons are
  triangulated by ear clipping, :func:`triangulate_concave`);
* tmesh: each new vertex forms a triangle with the two saved vertices and replaces
  the older one; ``swaptmesh()`` exchanges the saved pair so the next triangle pivots
  on the other one (fans and arbitrary strips); winding alternates like a strip's,
  and a swap keeps it consistent (see :func:`tmesh_triangles`);
* qstrip: quadrilaterals from pairs of vertices (like GL_QUAD_STRIP), two triangles
  each;
* line / closedline: consecutive segments (closedline adds the closing segment).

Every triangle keeps the winding of the sequence so front/back facing is as drawn.
"""

from __future__ import annotations

import numpy as np


def polygon_fan(n: int) -> np.ndarray:
    """Triangles (n-2, 3) of a convex polygon of n vertices."""
    if n < 3:
        return np.zeros((0, 3), np.int64)
    i = np.arange(1, n - 1, dtype=np.int64)
    return np.stack([np.zeros_like(i), i, i + 1], axis=1)


def tmesh_triangles(n: int, swaps: list[int]) -> np.ndarray:
    """Triangles of a tmesh of n vertices; ``swaps`` lists, for every swaptmesh()
    call, how many vertices had been sent before it."""
    tris = []
    saved = [-1, -1]  # saved[0] is replaced next
    replace_slot = 0
    swap_at = sorted(swaps)
    si = 0
    for v in range(n):
        while si < len(swap_at) and swap_at[si] == v:
            saved[0], saved[1] = saved[1], saved[0]
            if saved[0] >= 0 and saved[1] >= 0:
                # The swap changes which saved vertex is replaced next, not the order in
                # which the pair is emitted: toggling the parity too keeps the shared
                # edge traversed in opposite directions by consecutive triangles, so a
                # fan (v0 v1 swaptmesh v2 swaptmesh v3 ...) faces one way throughout.
                replace_slot ^= 1
            si += 1
        if saved[0] >= 0 and saved[1] >= 0:
            a, b = saved[0], saved[1]
            # Alternate winding like a strip so every triangle faces the same way.
            tris.append((a, b, v) if replace_slot == 0 else (b, a, v))
        if saved[0] < 0:
            saved[0] = v
        elif saved[1] < 0:
            saved[1] = v
        else:
            saved[0] = saved[1]
            saved[1] = v
            replace_slot ^= 1
    return np.array(tris, dtype=np.int64).reshape(-1, 3)


def qstrip_triangles(n: int) -> np.ndarray:
    """Triangles of a quadrilateral strip (vertices 0 1 / 2 3 / ...)."""
    tris = []
    for q in range(0, n - 3, 2):
        a, b, c, d = q, q + 1, q + 3, q + 2
        tris.append((a, b, c))
        tris.append((a, c, d))
    return np.array(tris, dtype=np.int64).reshape(-1, 3)


def line_segments(n: int, closed: bool) -> np.ndarray:
    """Segments (S, 2) of a polyline of n vertices."""
    if n < 2:
        return np.zeros((0, 2), np.int64)
    i = np.arange(n - 1, dtype=np.int64)
    segs = np.stack([i, i + 1], axis=1)
    if closed and n > 2:
        segs = np.concatenate([segs, [[n - 1, 0]]])
    return segs


def triangulate_concave(xy: np.ndarray) -> np.ndarray:
    """Ear-clipping triangulation of a simple polygon given in 2-D.

    Parameters
    ----------
    xy : ndarray, shape (n, 2), float64
        The polygon projected to the plane that best preserves its area.

    Returns
    -------
    ndarray, shape (n - 2, 3), int64
        Triangles with the polygon's own winding.
    """
    n = xy.shape[0]
    if n < 3:
        return np.zeros((0, 3), np.int64)
    area = 0.5 * np.sum(xy[:, 0] * np.roll(xy[:, 1], -1) - np.roll(xy[:, 0], -1) * xy[:, 1])
    sign = 1.0 if area >= 0 else -1.0
    idx = list(range(n))
    tris = []

    def cross(o, a, b):
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])

    guard = 0
    while len(idx) > 3 and guard < 10 * n * n:
        guard += 1
        m = len(idx)
        for k in range(m):
            i0, i1, i2 = idx[(k - 1) % m], idx[k], idx[(k + 1) % m]
            a, b, c = xy[i0], xy[i1], xy[i2]
            if sign * cross(a, b, c) <= 0:
                continue  # reflex or degenerate corner
            inside = False
            for j in idx:
                if j in (i0, i1, i2):
                    continue
                p = xy[j]
                if (sign * cross(a, b, p) >= 0 and sign * cross(b, c, p) >= 0
                        and sign * cross(c, a, p) >= 0):
                    inside = True
                    break
            if not inside:
                tris.append((i0, i1, i2))
                idx.pop(k)
                break
        else:
            break  # no ear found: self-intersecting input; fan the rest
    if len(idx) >= 3:
        for k in range(1, len(idx) - 1):
            tris.append((idx[0], idx[k], idx[k + 1]))
    return np.array(tris, dtype=np.int64).reshape(-1, 3)
