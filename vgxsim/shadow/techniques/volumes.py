"""Shadow-volume geometry for every technique: lights as 4-vectors, silhouettes, caps.

A light is the homogeneous 4-vector IRIS GL's ``lmdef(DEFLIGHT, ..., POSITION, x, y,
z, w)`` takes (lmdef(3G)): ``w = 1`` a point or spot light at (x, y, z), ``w = 0`` a
directional light shining from the direction (x, y, z).  Written with ``L = (l, lw)``
every formula below covers both:

* a polygon with outward normal N through p faces the light iff
  ``N . (l - lw p) > 0`` (a polygon whose plane holds the light faces away, the tie
  rule of :meth:`vgxsim.shadow.scene.Polyhedron.facing`);
* a vertex v extruded to infinity away from the light is the point at infinity
  ``(lw v - l, 0)`` (Everitt and Kilgard 2002: "(V - L, 0)"; for a directional light
  every vertex goes to the same point ``(-l, 0)``, so a dark cap collapses to a point
  and is not drawn).

Silhouettes come two ways, which must give the same set on closed meshes (tested):

* :func:`silhouettes_by_adjacency`: Heidmann's edge adjacency ("an edge shared by two
  polygons, one of which is facing toward the light and the other facing away");
* :func:`silhouettes_by_toggle`: Kolivand and Sunar 2011 (shared/seeds/003), a walk
  over the light-facing polygons that adds an edge ``(v1, v2)`` to a set unless
  ``(v2, v1)`` is in it, in which case it deletes it ("iff(V1 in S[V2], Delete V1,
  Add V2)"); what is left is the silhouette, each edge in the direction its
  light-facing polygon runs it.

:func:`signed_edge_counts` is Aldridge and Woods' (2004) counter, in Bergeron's (1986)
form: every polygon counts, light-facing ones +1 and the others -1, times +1 or -1 for
the direction it runs each edge; the product does not depend on the polygon's winding,
so it works on open, non-manifold and inconsistently wound casters (triangle soups).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from vgxsim.shadow.scene import Camera, Polyhedron, Scene


def light4(light) -> np.ndarray:
    """(4,) float64 homogeneous light position: (x, y, z, 1) or a direction (x, y, z, 0).

    Uses :func:`vgxsim.shadow.raycast.light_position` (same reading as the reference).
    """
    # Imported here: the ray-cast oracle (and its BVH and ray kernels) is not needed
    # to draw, and importing it is ~0.03 s of every start (docs/cold_start.md).
    from vgxsim.shadow.raycast import light_position

    return light_position(light)


def facing(mesh: Polyhedron, light: np.ndarray) -> np.ndarray:
    """(F,) bool: polygon faces the light, ``N . (l - lw p) > 0``."""
    lv = light[:3][None, :] - light[3] * mesh.face_points
    return np.einsum("ij,ij->i", mesh.normals, lv) > 0.0


def polygon_edges(mesh: Polyhedron) -> tuple[np.ndarray, np.ndarray]:
    """Every directed polygon edge: (F*K,) start and end vertex indices, polygon by
    polygon, in counter-clockwise order."""
    a = mesh.polygons
    b = np.roll(mesh.polygons, -1, axis=1)
    return a.reshape(-1), b.reshape(-1)


def silhouettes_by_adjacency(mesh: Polyhedron, light: np.ndarray) -> np.ndarray:
    """Silhouette edges from edge adjacency, as vertex index pairs (S, 2).

    Each pair is in the direction its light-facing polygon runs the edge (an edge of
    one polygon only: in that polygon's direction if it faces the light, reversed if
    it faces away), so the shadow face drawn from ``pair[1]`` to ``pair[0]`` has its
    normal pointing out of the volume (Heidmann 1991).
    """
    fac = facing(mesh, light)
    f0, f1 = mesh.edge_faces[:, 0], mesh.edge_faces[:, 1]
    single = f1 < 0
    fa = fac[f0]
    fb = np.where(single, ~fa, fac[np.where(single, 0, f1)])
    sil = fa != fb
    a, b = mesh.edges[sil, 0], mesh.edges[sil, 1]
    # f0 runs a -> b; when f0 faces away the light-facing side runs b -> a
    return np.stack([np.where(fa[sil], a, b), np.where(fa[sil], b, a)], axis=1)


def silhouettes_by_toggle(mesh: Polyhedron, light: np.ndarray) -> np.ndarray:
    """Silhouette edges by the Kolivand-Sunar edge set, as vertex index pairs (S, 2).

    Walks the light-facing polygons; an edge (v1, v2) is added to the set unless its
    reverse (v2, v1) is there, which is then deleted.  On a closed, consistently
    wound mesh the result equals :func:`silhouettes_by_adjacency` as a set.  Boundary
    edges of polygons facing away are not found (the paper assumes closed meshes).
    """
    fac = facing(mesh, light)
    polys = mesh.polygons[fac].tolist()
    live: dict[tuple[int, int], None] = {}
    for poly in polys:
        n = len(poly)
        for q in range(n):
            v1, v2 = poly[q], poly[(q + 1) % n]
            if (v2, v1) in live:
                del live[(v2, v1)]
            else:
                live[(v1, v2)] = None
    if not live:
        return np.zeros((0, 2), np.int64)
    return np.array(list(live), np.int64)


def weld(vertices: np.ndarray) -> np.ndarray:
    """(V,) int64: for each vertex, the lowest index of a vertex at the same position
    (exact equality), so edges of separately stored but coincident vertices meet."""
    _, first, inverse = np.unique(vertices, axis=0, return_index=True, return_inverse=True)
    return first[inverse.reshape(-1)]


def signed_edge_counts(mesh: Polyhedron, light: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Aldridge-Woods / Bergeron edge counters over every polygon.

    Returns
    -------
    pairs : ndarray, shape (S, 2), int64
        Edges with a non-zero count, each directed as a light-facing polygon would run
        it (so that its shadow face drawn ``pair[1] -> pair[0]`` points out of the
        volume); vertices are welded by position (:func:`weld`).
    weight : ndarray, shape (S,), int64
        ``|count|``: how many times the face must be drawn (2 on a closed mesh's
        silhouette, 1 on an open edge, more where several sheets meet).
    """
    fac = facing(mesh, light)
    k = mesh.polygons.shape[1]
    canon = weld(mesh.vertices)
    a, b = polygon_edges(mesh)
    a, b = canon[a], canon[b]
    s = np.repeat(np.where(fac, 1, -1), k)
    keep = a != b
    a, b, s = a[keep], b[keep], s[keep]
    lo, hi = np.minimum(a, b), np.maximum(a, b)
    c = s * np.where(a == lo, 1, -1)
    key = lo * (int(len(mesh.vertices)) + 1) + hi
    uniq, inv = np.unique(key, return_inverse=True)
    total = np.zeros(len(uniq), np.int64)
    np.add.at(total, inv.reshape(-1), c)
    first = np.zeros(len(uniq), np.int64)
    first[inv.reshape(-1)[::-1]] = np.arange(len(key))[::-1]
    nz = total != 0
    elo, ehi = lo[first[nz]], hi[first[nz]]
    pos = total[nz] > 0  # net run lo -> hi by light-facing polygons
    pairs = np.stack([np.where(pos, elo, ehi), np.where(pos, ehi, elo)], axis=1)
    return pairs.astype(np.int64), np.abs(total[nz])


def side_quads(mesh: Polyhedron, pairs: np.ndarray, light: np.ndarray,
               length: float | np.ndarray | None) -> np.ndarray:
    """Shadow faces of edges, as (S, 4, 4) homogeneous quads ``v1, v2, v3, v4``.

    ``pairs[:, 0] -> pairs[:, 1]`` is the light-facing polygon's direction, so the
    face runs ``v1 = pairs[:, 1]``, ``v2 = pairs[:, 0]`` (the article: "drawn in the
    direction opposite that of the direction of the original edge").

    Parameters
    ----------
    length : float, ndarray of shape (V,), or None
        None: extrude to infinity (w = 0).  A float: every vertex moves that far away
        from the light (the article's "some arbitrary distance").  An array: a length
        per vertex (finite volumes, :mod:`.finite`).
    """
    v = mesh.vertices
    i1, i2 = pairs[:, 1], pairs[:, 0]
    out = np.zeros((len(pairs), 4, 4))
    out[:, 0, :3], out[:, 1, :3] = v[i1], v[i2]
    out[:, 0, 3] = out[:, 1, 3] = 1.0
    far = extrude(v, light, length)
    out[:, 2], out[:, 3] = far[i2], far[i1]
    return out


def extrude(v: np.ndarray, light: np.ndarray, length: float | np.ndarray | None
            ) -> np.ndarray:
    """(V, 4) the vertices moved away from the light: to infinity (``length`` None,
    ``(lw v - l, 0)``) or by ``length`` world units (w = 1)."""
    d = light[3] * v - light[:3][None, :]
    if length is None:
        return np.concatenate([d, np.zeros((len(v), 1))], axis=1)
    n = np.linalg.norm(d, axis=1, keepdims=True)
    unit = np.divide(d, n, out=np.zeros_like(d), where=n > 0)
    ln = np.asarray(length, np.float64).reshape(-1, 1)
    return np.concatenate([v + ln * unit, np.ones((len(v), 1))], axis=1)


def caps(mesh: Polyhedron, light: np.ndarray, which: str) -> np.ndarray:
    """Cap polygons as (C, K, 4) homogeneous vertices, outward from the volume.

    ``'light'``: the light-facing polygons as they are (the near cap); ``'dark'``: the
    polygons facing away, extruded to infinity (the far cap of z-fail; empty for a
    directional light, where it collapses to a point).
    """
    fac = facing(mesh, light)
    if which == "light":
        p = mesh.vertices[mesh.polygons[fac]]
        return np.concatenate([p, np.ones(p.shape[:2] + (1,))], axis=2)
    if which != "dark":
        raise ValueError(f"which must be 'light' or 'dark', not {which!r}")
    if light[3] == 0.0:
        return np.zeros((0, mesh.polygons.shape[1], 4))
    far = extrude(mesh.vertices, light, None)
    return far[mesh.polygons[~fac]]


def infinite_projection(camera: Camera, aspect: float) -> np.ndarray:
    """The camera's projection with the far plane at infinity (row-vector, 4 x 4).

    Everitt and Kilgard 2002: the limit far -> infinity of the frustum matrix; a point
    with w = 0 lands on z_ndc = 1 exactly (z_clip and w_clip are then the same sum),
    so extruded faces and dark caps are never far-clipped (the clipper keeps
    ``-w <= z <= w`` with both ends included, docs/numeric_model.md).
    """
    m = camera.projection(aspect).copy()
    m[2, 2] = -1.0
    m[3, 2] = -2.0 * camera.near
    return m


@dataclass(frozen=True)
class NearRectangle:
    """The camera's near-plane rectangle in world coordinates.

    Attributes
    ----------
    corners : ndarray, shape (4, 3)
        Counter-clockwise seen from the eye.
    normal : ndarray, shape (3,)
        Unit view direction (from the eye into the scene).
    offset : float
        ``normal . x == offset`` on the near plane.
    """

    corners: np.ndarray
    normal: np.ndarray
    offset: float


def near_rectangle(scene: Scene, aspect: float) -> NearRectangle:
    """The near-plane rectangle of the scene's camera (window aspect ``aspect``)."""
    cam = scene.camera
    mvp = cam.modelview() @ cam.projection(aspect)
    inv = np.linalg.inv(mvp)
    ndc = np.array([[-1, -1, -1, 1], [1, -1, -1, 1], [1, 1, -1, 1], [-1, 1, -1, 1]], float)
    w = ndc @ inv
    corners = w[:, :3] / w[:, 3:4]
    eye = np.asarray(cam.eye, np.float64)
    fwd = np.asarray(cam.target, np.float64) - eye
    fwd /= np.linalg.norm(fwd)
    return NearRectangle(corners, fwd, float(fwd @ corners.mean(axis=0)))


def scene_box(scene: Scene) -> tuple[np.ndarray, np.ndarray]:
    """(3,), (3,): the bounding box of every object."""
    allv = np.concatenate([o.vertices for o in scene.objects])
    return allv.min(axis=0), allv.max(axis=0)


def frustum_planes(scene: Scene, aspect: float, infinite: bool = False) -> np.ndarray:
    """(P, 4) world-space planes ``(n, d)`` of the view frustum, inside where
    ``n . x + d w >= 0`` (the far plane left out when ``infinite``)."""
    cam = scene.camera
    mvp = cam.modelview() @ cam.projection(aspect)
    cols = mvp.T  # rows of the column-vector matrix: clip_k = cols[k] . x
    planes = [cols[3] + cols[0], cols[3] - cols[0], cols[3] + cols[1], cols[3] - cols[1],
              cols[3] + cols[2]]
    if not infinite:
        planes.append(cols[3] - cols[2])
    return np.array(planes)


def volume_culled(mesh: Polyhedron, light: np.ndarray, planes: np.ndarray) -> bool:
    """Whether the mesh's shadow volume lies wholly outside one frustum plane.

    Any volume (finite or not) lies in the infinite one, which is the convex hull of
    the mesh's bounding-box corners and those corners' points at infinity
    ``(lw c - l, 0)`` (both linear in the corner), so it is culled when all 16
    homogeneous points are strictly outside one plane: conservative, never culling a
    volume that reaches the frustum.
    """
    lo, hi = mesh.vertices.min(axis=0), mesh.vertices.max(axis=0)
    corners = np.array([[x, y, z] for x in (lo[0], hi[0]) for y in (lo[1], hi[1])
                        for z in (lo[2], hi[2])])
    pts = np.concatenate([np.concatenate([corners, np.ones((8, 1))], axis=1),
                          extrude(corners, light, None)])
    # an extruded box corner can leave the hull of the extruded corners only if the
    # light is inside the box: then every direction is possible, never cull
    if np.all(lo <= light[:3]) and np.all(light[:3] <= hi) and light[3] != 0.0:
        return False
    side = pts @ planes.T  # (16, P)
    return bool(np.any(np.all(side < 0.0, axis=0)))
