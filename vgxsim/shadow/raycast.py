"""Exact float64 ray-cast reference for shadow scenes (the project's shadow oracle).

Per pixel the ray goes through the pixel centre.  IRIS GL convention
(docs/numeric_model.md section 1): integer window coordinates are pixel centres, the
origin is the lower-left pixel and ``viewport(0, W-1, 0, H-1)`` is inclusive, so pixel
``(X, Y)`` has normalized device coordinates

    x_ndc = (2 X + 1) / W - 1,   y_ndc = (2 Y + 1) / H - 1.

The ray is the segment from the near-plane point (z_ndc = -1) to the far-plane point
(z_ndc = +1), both unprojected through the inverse of the scene's modelview x
projection (row-vector convention, ``clip = obj @ MV @ P``), so near and far clipping
match the renderer.  The nearest triangle along it (Moller-Trumbore, vectorised over
all scene triangles) is the visible surface.  Per light, the segment from the hit
point to the light is tested against every caster triangle: the point is lit iff no
caster is hit strictly between them.  This is the definition of a hard shadow
(article: "The volume of space behind the triangle ... is in shadow").

Two counts come with it:

* ``occluders``: how many distinct caster objects the segment to the light passes
  through -- for closed convex casters, the number of shadow volumes containing the
  point;
* ``crossings``: the article's count, done exactly: "as you travel along the path
  from your viewpoint to the object visible at that pixel, count the number of times
  you cross through one of these semi-transparent surfaces going into shadow, and
  subtract the number of times you cross going out of shadow", over the same finite
  shadow faces the renderer draws (:func:`vgxsim.shadow.scene.shadow_faces`).  With
  the eye outside every volume it equals the z-pass stencil count minus the stencil
  "zero".
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .scene import Scene, shadow_faces

_CHUNK = 16384  # rays per block: keeps (rays x triangles x 3) float64 temporaries small


@dataclass(frozen=True)
class RayCastResult:
    """Ray-cast reference images, row 0 = bottom (as the framebuffer planes).

    Attributes
    ----------
    object_id : ndarray, shape (H, W), int64
        Index into ``scene.objects`` of the visible object, -1 for background.
    triangle : ndarray, shape (H, W), int64
        Index into ``scene.triangles()`` of the visible triangle, -1 for background.
    point : ndarray, shape (H, W, 3), float64
        World-space hit point (NaN for background).
    t : ndarray, shape (H, W), float64
        Ray parameter of the hit, 0 at the near plane and 1 at the far plane (inf for
        background).
    lit : ndarray, shape (H, W, L), bool
        Per light: the segment from the hit point to the light meets no caster.
        False on background pixels.
    occluders : ndarray, shape (H, W, L), int64
        Per light: number of caster objects the segment meets.
    crossings : ndarray, shape (H, W, L), int64
        Per light: signed count of shadow faces crossed between the near plane and
        the hit point (+1 ingoing, -1 outgoing); on background pixels, the count along
        the whole ray.
    """

    object_id: np.ndarray
    triangle: np.ndarray
    point: np.ndarray
    t: np.ndarray
    lit: np.ndarray
    occluders: np.ndarray
    crossings: np.ndarray

    @property
    def hit(self) -> np.ndarray:
        """(H, W) bool: some object is visible."""
        return self.object_id >= 0


def pixel_rays(scene: Scene, width: int, height: int) -> tuple[np.ndarray, np.ndarray]:
    """Near-plane origins and near-to-far directions of every pixel-centre ray.

    Parameters
    ----------
    scene : Scene
    width, height : int
        Window size; the viewport is the whole window.

    Returns
    -------
    origin, direction : ndarray, shape (H, W, 3), float64
        The ray is ``origin + t * direction``, t in [0, 1] from the near plane to the
        far plane.
    """
    cam = scene.camera
    mvp = cam.modelview() @ cam.projection(width / height)
    inv = np.linalg.inv(mvp)
    x = (2.0 * np.arange(width) + 1.0) / width - 1.0
    y = (2.0 * np.arange(height) + 1.0) / height - 1.0
    xx, yy = np.meshgrid(x, y)  # (H, W), row 0 = bottom
    ones = np.ones_like(xx)

    def unproject(z: float) -> np.ndarray:
        clip = np.stack([xx, yy, z * ones, ones], axis=-1)
        obj = clip @ inv
        return obj[..., :3] / obj[..., 3:4]

    near = unproject(-1.0)
    far = unproject(1.0)
    return near, far - near


def intersect(origin: np.ndarray, direction: np.ndarray, tris: np.ndarray
              ) -> tuple[np.ndarray, np.ndarray]:
    """Moller-Trumbore intersection of every ray with every triangle.

    Parameters
    ----------
    origin, direction : ndarray, shape (R, 3)
    tris : ndarray, shape (T, 3, 3)

    Returns
    -------
    t : ndarray, shape (R, T), float64
        Ray parameter of the hit, ``inf`` where the ray's line misses the (closed)
        triangle or is parallel to it.
    det : ndarray, shape (R, T), float64
        ``e1 . (d x e2)``: positive when the ray meets the triangle's front
        (counter-clockwise) side.
    """
    v0 = tris[:, 0]
    e1 = (tris[:, 1] - v0).T[:, None, :]  # (3, 1, T): components, broadcast over rays
    e2 = (tris[:, 2] - v0).T[:, None, :]
    dx, dy, dz = (direction.T[:, :, None])  # (R, 1) each
    # pvec = d x e2, det = e1 . pvec
    px = dy * e2[2] - dz * e2[1]
    py = dz * e2[0] - dx * e2[2]
    pz = dx * e2[1] - dy * e2[0]
    det = e1[0] * px + e1[1] * py + e1[2] * pz
    ok = det != 0.0
    inv = np.where(ok, 1.0 / np.where(ok, det, 1.0), 0.0)
    tx, ty, tz = origin.T[:, :, None] - v0.T[:, None, :]
    u = (tx * px + ty * py + tz * pz) * inv
    # qvec = tvec x e1
    qx = ty * e1[2] - tz * e1[1]
    qy = tz * e1[0] - tx * e1[2]
    qz = tx * e1[1] - ty * e1[0]
    v = (dx * qx + dy * qy + dz * qz) * inv
    t = (e2[0] * qx + e2[1] * qy + e2[2] * qz) * inv
    inside = ok & (u >= 0.0) & (v >= 0.0) & (u + v <= 1.0)
    return np.where(inside, t, np.inf), det


def _groups(tris: np.ndarray, size: int = 16) -> list[tuple[np.ndarray, np.ndarray, np.ndarray]]:
    """Consecutive runs of ``size`` triangles with their (slightly padded) boxes."""
    out = []
    for s in range(0, len(tris), size):
        idx = np.arange(s, min(len(tris), s + size))
        lo = tris[idx].min(axis=(0, 1))
        hi = tris[idx].max(axis=(0, 1))
        pad = 1e-9 * max(1.0, float(np.abs(np.concatenate([lo, hi])).max()))
        out.append((idx, lo - pad, hi + pad))
    return out


def _box_hit(origin: np.ndarray, direction: np.ndarray, lo: np.ndarray, hi: np.ndarray,
             tmax: np.ndarray) -> np.ndarray:
    """(R,) bool: the segment ``origin + t direction``, 0 <= t <= tmax, meets the box."""
    d = np.where(direction == 0.0, 1e-300, direction)
    with np.errstate(over="ignore", invalid="ignore"):
        t1 = (lo - origin) / d
        t2 = (hi - origin) / d
    tn = np.minimum(t1, t2).max(axis=1)
    tf = np.maximum(t1, t2).min(axis=1)
    return (tn <= tf) & (tf >= 0.0) & (tn <= tmax)


def nearest_hit(origin: np.ndarray, direction: np.ndarray, tris: np.ndarray,
                tmax: float = 1.0) -> tuple[np.ndarray, np.ndarray]:
    """Nearest triangle along each segment ``origin + t direction``, 0 <= t <= tmax.

    Triangles are tested in runs of 16 whose bounding boxes cull the rays that
    cannot meet them; the result is the same as testing every pair.

    Parameters
    ----------
    origin, direction : ndarray, shape (R, 3)
    tris : ndarray, shape (T, 3, 3)
    tmax : float

    Returns
    -------
    index : ndarray, shape (R,), int64
        Triangle index, -1 where nothing is hit (ties: the lowest index).
    t : ndarray, shape (R,), float64
        Ray parameter of the hit, inf where nothing is hit.
    """
    n = len(origin)
    best_t = np.full(n, np.inf)
    best_i = np.full(n, -1, np.int64)
    for idx, lo, hi in _groups(tris):
        rays = np.nonzero(_box_hit(origin, direction, lo, hi,
                                   np.minimum(best_t, tmax)))[0]
        if len(rays) == 0:
            continue
        t, _ = intersect(origin[rays], direction[rays], tris[idx])
        t = np.where((t >= 0.0) & (t <= tmax), t, np.inf)
        k = np.argmin(t, axis=1)
        tk = t[np.arange(len(k)), k]
        better = tk < best_t[rays]
        best_t[rays[better]] = tk[better]
        best_i[rays[better]] = idx[k[better]]
    return best_i, best_t


def raycast(scene: Scene, width: int, height: int, *, edges: str = "silhouette",
            eps: float = 1e-7) -> RayCastResult:
    """Ray-cast the scene: visible surface, per-light lit mask and shadow counts.

    Parameters
    ----------
    scene : Scene
    width, height : int
    edges : {'silhouette', 'all'}
        Which shadow faces ``crossings`` counts (the lit mask does not depend on it).
    eps : float
        Shadow segments from the hit point P to the light L count blockers at
        parameters ``eps < s < 1 - eps`` of ``P + s (L - P)``, so the surface P lies
        on does not shadow itself.

    Returns
    -------
    RayCastResult
    """
    origin, direction = pixel_rays(scene, width, height)
    o = origin.reshape(-1, 3)
    d = direction.reshape(-1, 3)
    n = o.shape[0]
    tris, tri_obj = scene.triangles()
    cast_obj = [i for i, ob in enumerate(scene.objects) if ob.casts]
    cast_mask = np.isin(tri_obj, cast_obj)
    cast_tris = tris[cast_mask]
    cast_ids = tri_obj[cast_mask]
    nl = len(scene.lights)
    faces = []
    for li in range(nl):
        quads, ingoing = shadow_faces(scene, li, edges)
        ftris = np.concatenate([quads[:, [0, 1, 2]], quads[:, [0, 2, 3]]])
        sign = np.where(np.concatenate([ingoing, ingoing]), 1, -1)
        faces.append((ftris, sign))

    tri_idx = np.full(n, -1, np.int64)
    thit = np.full(n, np.inf)
    lit = np.zeros((n, nl), bool)
    occl = np.zeros((n, nl), np.int64)
    cross = np.zeros((n, nl), np.int64)
    for s in range(0, n, _CHUNK):
        sl = slice(s, min(n, s + _CHUNK))
        ro, rd = o[sl], d[sl]
        best, tb = nearest_hit(ro, rd, tris)
        hit = best >= 0
        tri_idx[sl] = best
        thit[sl] = tb
        p = ro + np.where(hit, tb, 0.0)[:, None] * rd
        for li, light in enumerate(scene.lights):
            lp = np.asarray(light.position, np.float64)
            ts, _ = intersect(p, lp[None] - p, cast_tris)
            blocked = (ts > eps) & (ts < 1.0 - eps)
            per_obj = np.zeros((len(p), len(scene.objects)), bool)
            for k in cast_obj:
                per_obj[:, k] = blocked[:, cast_ids == k].any(axis=1)
            occl[sl, li] = per_obj.sum(axis=1)
            lit[sl, li] = hit & ~blocked.any(axis=1)
            ftris, sign = faces[li]
            tf, _ = intersect(ro, rd, ftris)
            limit = np.where(hit, tb, 1.0)[:, None]
            crossed = (tf > 0.0) & (tf < limit)
            cross[sl, li] = (crossed * sign[None]).sum(axis=1)

    obj = np.where(tri_idx >= 0, tri_obj[np.maximum(tri_idx, 0)], -1)
    point = o + np.where(np.isfinite(thit), thit, np.nan)[:, None] * d
    h, w = height, width
    return RayCastResult(object_id=obj.reshape(h, w), triangle=tri_idx.reshape(h, w),
                         point=point.reshape(h, w, 3), t=thit.reshape(h, w),
                         lit=lit.reshape(h, w, nl), occluders=occl.reshape(h, w, nl),
                         crossings=cross.reshape(h, w, nl))


def shade(scene: Scene, result: RayCastResult) -> np.ndarray:
    """A float64 preview of the shadowed image from the ray cast (per-pixel lighting).

    Uses the IRIS lighting equation with each object's full material, the light
    model's ambient, each light's ambient, and diffuse + specular only where the light
    is visible (``lit``); infinite viewer (LOCALVIEWER off), no attenuation.  Meant for
    choosing camera and lights and for eyeballing, not for pixel comparisons
    (the renderer lights per vertex and interpolates).

    Parameters
    ----------
    scene : Scene
    result : RayCastResult

    Returns
    -------
    ndarray, shape (H, W, 4), uint8, row 0 = bottom
    """
    h, w = result.object_id.shape
    out = np.zeros((h, w, 3))
    tris, tri_obj = scene.triangles()
    hit = result.hit
    tri = result.triangle[hit]
    tv = tris[tri]
    nrm = np.cross(tv[:, 1] - tv[:, 0], tv[:, 2] - tv[:, 0])
    nrm /= np.linalg.norm(nrm, axis=1, keepdims=True)
    mats = [scene.objects[k].material for k in tri_obj[tri]]
    em = np.array([m.emission for m in mats])
    am = np.array([m.ambient for m in mats])
    di = np.array([m.diffuse for m in mats])
    sp = np.array([m.specular for m in mats])
    sh = np.array([m.shininess for m in mats])
    col = em + am * np.asarray(scene.lmodel.ambient)
    p = result.point[hit]
    mv = scene.camera.modelview()
    # the infinite viewer looks along eye-space -z: toward it is eye +z, whose world
    # coordinates are column 2 of the row-vector modelview
    view_dir = mv[:3, 2] / np.linalg.norm(mv[:3, 2])
    for li, light in enumerate(scene.lights):
        lc = np.asarray(light.colour)
        col += am * np.asarray(light.ambient)
        ldir = np.asarray(light.position) - p
        ldir /= np.linalg.norm(ldir, axis=1, keepdims=True)
        ndl = np.maximum(np.einsum("ij,ij->i", nrm, ldir), 0.0)
        hv = ldir + view_dir
        hv /= np.linalg.norm(hv, axis=1, keepdims=True)
        ndh = np.maximum(np.einsum("ij,ij->i", nrm, hv), 0.0)
        spec = np.where((sh >= 1.0) & (ndl > 0), ndh ** sh, 0.0)
        on = result.lit[..., li][hit][:, None]
        col += on * (di * ndl[:, None] + sp * spec[:, None]) * lc
    out[hit] = np.clip(col, 0.0, 1.0)
    rgba = np.zeros((h, w, 4), np.uint8)
    rgba[..., :3] = np.floor(out * 255.0 + 0.5).astype(np.uint8)
    rgba[..., 3] = 255
    return rgba
