"""Pick and select hit testing: does any part of a primitive lie in the clip volume?

In pick and select mode (pick(3G), gselect(3G)) nothing is drawn; a primitive
*hits* when any part of it, after the full transform (the pick matrix narrows the
volume to the pick region around the cursor; gselect uses the program's own
viewing volume), lies inside the clip volume ``-w <= x, y, z <= w``.  That is the
same question the homogeneous clipper answers for drawing, asked without
rasterizing: a point hits if it is inside, a segment if its clipped part is not
empty, a polygon if clipping it leaves anything (boundary contact counts, as a
clipped primitive on the boundary is still sent on).

Pure functions over clip-space vertices (``float64``, shape ``(N, 4)``); no state.
Liang-Barsky parameter clipping for segments, Sutherland-Hodgman for polygons, both
against the six planes ``w + x >= 0``, ``w - x >= 0``, ... (the plane distances
are linear in homogeneous coordinates, so w = 0 vertices need no special case), and
against the user clip planes that are on (clipplane(3G)): picking asks what drawing
would draw, and a primitive the user planes clip away draws nothing, so it does not
hit either (OpenGL's selection mode clips against its user planes the same way).
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence

import numpy as np

#: The six clip planes as coefficient rows c: inside when c . (x, y, z, w) >= 0.
PLANES = np.array([
    [1.0, 0.0, 0.0, 1.0], [-1.0, 0.0, 0.0, 1.0],
    [0.0, 1.0, 0.0, 1.0], [0.0, -1.0, 0.0, 1.0],
    [0.0, 0.0, 1.0, 1.0], [0.0, 0.0, -1.0, 1.0],
])


def _planes(user: np.ndarray | None) -> np.ndarray:
    """The six volume planes, followed by the user clip planes (K, 4) if any."""
    if user is None or len(user) == 0:
        return PLANES
    return np.vstack([PLANES, np.asarray(user, dtype=np.float64).reshape(-1, 4)])


def point_inside(p: np.ndarray, user: np.ndarray | None = None) -> bool:
    """Whether clip-space point ``p`` (4,) lies in the clip volume (boundary included)
    and on the inside of every user plane of ``user`` ((K, 4) clip-space planes).

    A point with w = 0 is inside only if x = y = z = 0 too, which is no point at all;
    it does not hit.
    """
    d = _planes(user) @ np.asarray(p, dtype=np.float64)
    return bool(np.all(d >= 0.0)) and p[3] > 0.0


def segment_hits(a: np.ndarray, b: np.ndarray, user: np.ndarray | None = None) -> bool:
    """Whether any part of the segment from ``a`` to ``b`` (each (4,)) is inside
    (the volume and the user planes ``user``, (K, 4), as for :func:`point_inside`).

    Liang-Barsky: the segment ``a + t (b - a)``, ``0 <= t <= 1``, is cut to the
    interval where every plane distance is >= 0; it hits when that interval is not
    empty and its points have w > 0.
    """
    a = np.asarray(a, dtype=np.float64)
    b = np.asarray(b, dtype=np.float64)
    planes = _planes(user)
    da = planes @ a
    db = planes @ b
    t0, t1 = 0.0, 1.0
    for p, q in zip(da, db, strict=True):
        if p < 0.0 and q < 0.0:
            return False
        if p < 0.0:  # enters at t = p / (p - q)
            t0 = max(t0, p / (p - q))
        elif q < 0.0:  # leaves
            t1 = min(t1, p / (p - q))
        if t0 > t1:
            return False
    mid = a + 0.5 * (t0 + t1) * (b - a)
    return bool(mid[3] > 0.0 or a[3] + t0 * (b[3] - a[3]) > 0.0
                or a[3] + t1 * (b[3] - a[3]) > 0.0)


def polygon_hits(poly: np.ndarray, user: np.ndarray | None = None) -> bool:
    """Whether any part of the planar polygon with vertices ``poly`` (N, 4) is inside
    (the volume and the user planes ``user``, (K, 4), as for :func:`point_inside`).

    Sutherland-Hodgman against each plane in turn; a non-empty remainder with a
    vertex of w > 0 hits.  Works for concave polygons too (the remainder may contain
    zero-width bridges along a plane, but it is empty only when the intersection is).
    """
    verts = [np.asarray(v, dtype=np.float64) for v in poly]
    for c in _planes(user):
        if not verts:
            return False
        out = []
        n = len(verts)
        for i in range(n):
            p, q = verts[i], verts[(i + 1) % n]
            dp, dq = float(c @ p), float(c @ q)
            if dp >= 0.0:
                out.append(p)
            if (dp >= 0.0) != (dq >= 0.0):
                out.append(p + (dp / (dp - dq)) * (q - p))
        verts = out
    return any(v[3] > 0.0 for v in verts)


def primitive_hits(kind: str, clip: np.ndarray, *, segments: Iterable[Sequence[int]] = (),
                   polygons: Iterable[Sequence[int]] = (),
                   user: np.ndarray | None = None) -> bool:
    """Whether a primitive hits the clip volume.

    Parameters
    ----------
    kind : {'point', 'line', 'surface'}
        Points test each vertex; lines each of ``segments``; surfaces each of
        ``polygons``.
    clip : ndarray, shape (N, 4), float64
        Clip-space vertices.
    segments : iterable of (int, int)
        Vertex index pairs (lines).
    polygons : iterable of sequences of int
        Vertex index lists (a whole polygon, or the triangles of a mesh).
    user : ndarray, shape (K, 4), float64, optional
        The user clip planes that are on, in clip space (inside where c . v >= 0).

    Returns
    -------
    bool
    """
    clip = np.asarray(clip, dtype=np.float64)
    if kind == "point":
        return any(point_inside(p, user) for p in clip)
    if kind == "line":
        return any(segment_hits(clip[i], clip[j], user) for i, j in segments)
    return any(polygon_hits(clip[list(idx)], user) for idx in polygons)
