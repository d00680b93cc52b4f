"""Exact float64 ray-cast reference for shadow scenes (the project's shadow oracle).

Eye rays.  Per pixel the ray goes through the pixel centre.  IRIS GL convention
(docs/numeric_model.md section 1): integer window coordinates are pixel centres, the
origin is the lower-left pixel and ``viewport(0, W-1, 0, H-1)`` is inclusive, so pixel
``(X, Y)`` has normalized device coordinates

    x_ndc = (2 X + 1) / W - 1,   y_ndc = (2 Y + 1) / H - 1.

The ray is ``origin + t * direction`` from the near-plane point (z_ndc = -1, t = 0) to
the far-plane point (z_ndc = +1, t = 1), both unprojected through the inverse of the
scene's modelview x projection (row-vector convention, ``clip = obj @ MV @ P``), so
near and far clipping match the renderer (``-w <= z <= w``, both ends included).

What is computed (all in float64, kernels in :mod:`vgxsim.kernels.raycast` over a
BVH, :mod:`vgxsim.kernels.bvh`):

* the **visible triangle**: the nearest scene triangle with ``0 <= t <= 1`` (equal t:
  the lowest index), its object and world point;
* per light, **lit**: the segment from the visible point P to the light meets no
  caster triangle other than P's own, leaving out the first and last ``offset``
  world units of it (:func:`segment_scales`: ``eps`` times the scene's size plus
  1e-13 times its largest coordinate, so a scene moved far from the origin keeps
  its shadows; 2e-6 units for the default scene) -- the definition of a hard
  shadow (article: "The volume of space behind the triangle ... is in shadow"),
  and P's own caster triangle does not have the light on the side the eye sees it
  from (:func:`own_side_shadowed`: a sheet seen from the side facing away from the
  light is behind itself, in the volume of its own triangle; this decides points
  on open casters, the inside of the teapot and its walls seen where light comes
  in through the lid gap, where no other triangle is met).
  Point and spot lights use their position (a spot's cone limits its light, not its
  shadow); a directional light (``w = 0``: IRIS GL's POSITION with w = 0 is a
  direction toward the light) uses ``L = P + far * unit(direction)``, ``far``
  reaching past every caster;
* per light, **occluders**: how many distinct caster objects that segment crosses;
* per light, **layers**: how many light-facing caster triangles it crosses (facing:
  ``N . (L - v0) > 0``, as :meth:`Polyhedron.facing`; ``N . direction > 0`` for
  w = 0).  For closed, consistently wound casters this is the number of shadow
  volumes containing P counted with multiplicity -- Crow's (1977) volume of each
  light-facing polygon, equivalently the region bounded by the silhouette-edge
  faces and the light-facing cap -- i.e. the value an exact z-fail stencil holds
  (volumes extruded to infinity).  ``eye_layers`` is the same count at the eye;
* per light, **crossings**: the article's count, done exactly: "as you travel along
  the path from your viewpoint to the object visible at that pixel, count the number
  of times you cross through one of these semi-transparent surfaces going into
  shadow, and subtract the number of times you cross going out of shadow", over the
  shadow faces the renderer draws (:func:`vgxsim.shadow.scene.shadow_faces`, finite
  length, or faces the caller passes).  A face counts when it is met at
  ``0 <= t <= t_P`` (the near plane and ``zfunction(ZF_LEQUAL)``'s equal case
  included; ``t <= 1`` on background pixels), with +1 for an ingoing face (ST_INCR)
  and -1 for an outgoing one (ST_DECR).  This is what a perfect z-pass stencil
  holds minus its "zero" (Heidmann 1991), whatever the eye, near plane or caster
  topology -- it is the count, not the shadow.  When the eye is outside every
  volume, the volumes are long enough and the near plane cuts none of them,
  ``crossings == layers - eye_layers`` for closed casters with silhouette faces
  (twice that with all-edge faces); where those conditions fail is exactly where
  z-pass goes wrong (shared/reference/shadow_literature.md H1-H3).

Robustness (shared/reference/shadow_literature.md section 2): the ray/triangle test
is watertight with a documented tie rule (module docstring of
:mod:`vgxsim.kernels.raycast`): a ray through a shared edge or vertex of a surface
crosses it exactly once, through a fold 0 or 2 times.  Degenerate triangles (zero
cross product, exactly) are never hit.  The segment to the light leaves out P's own
triangle and ``eps * R`` world units at each end (an absolute offset: relative to the
segment's length it would grow to whole units for far lights), so neither the
receiving surface nor one the light sits on shadows the point.  Vertices may be
homogeneous with w = 0 (faces extruded to infinity); w < 0 is refused.

Subpixel snapping (``subpixel=False/True``): every finite vertex that the camera
sees inside the near and far planes and within the rasterizer's coordinate limit is
moved, in its own depth plane, to where the rasterizer snaps it
(:func:`vgxsim.kernels.clip.snap_window`, docs/numeric_model.md section 2), so the
reference sees the same triangles as the rasterizer; ``lit``, ``occluders`` and
``layers`` then describe the snapped scene and ``crossings`` the snapped faces.
Eye rays see the pieces the rasterizer draws (its own transform, clipper and snap,
:func:`_rasterized`), tested in window space with its exact integer edge functions
and tie rule (numeric_model section 3), t taken from each piece's plane: a pixel
centre exactly on a snapped edge is decided as the rasterizer decides it, not by
rounding.  What remains different
from a stencil is depth: the rasterizer compares 24-bit z, this compares float64 t.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from vgxsim import threads as _threads
from vgxsim.geometry.pipeline import GUARD_PIXELS, to_clip
from vgxsim.geometry.transform import apply
from vgxsim.kernels.bvh import BVH, build_arrays, split_references
from vgxsim.kernels.clip import (
    COORD_LIMIT,
    NO_PLANES,
    ONE,
    clip_triangles,
    project_snap,
    snap_window,
)
from vgxsim.kernels.raycast import Window, closest_hits, count_crossings, shadow_segments

from .scene import Scene, shadow_faces


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
        Per light: the segment from the hit point to the light meets no caster, and
        the light is on the visible side of the hit point's own caster triangle.
        False on background pixels.
    occluders : ndarray, shape (H, W, L), int64
        Per light: number of caster objects the segment meets (0 when ``counts``
        was off).
    crossings : ndarray, shape (H, W, L), int64
        Per light: signed count of shadow faces crossed between the near plane and
        the hit point (+1 ingoing, -1 outgoing); on background pixels, the count along
        the whole ray.
    layers : ndarray, shape (H, W, L), int64
        Per light: light-facing caster triangles the segment to the light crosses
        (the z-fail count; 0 when ``counts`` was off).
    eye_layers : ndarray, shape (L,), int64
        ``layers`` of the eye point (the z-pass offset: shadow_literature.md H1).
    """

    object_id: np.ndarray
    triangle: np.ndarray
    point: np.ndarray
    t: np.ndarray
    lit: np.ndarray
    occluders: np.ndarray
    crossings: np.ndarray
    layers: np.ndarray
    eye_layers: np.ndarray

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
        clip = np.stack([xx, yy, z * ones, ones], axis=-1).reshape(-1, 4)
        obj = apply(clip, inv).reshape(height, width, 4)  # no BLAS threads (transform.apply)
        return obj[..., :3] / obj[..., 3:4]

    near = unproject(-1.0)
    far = unproject(1.0)
    return near, far - near


def intersect(origin: np.ndarray, direction: np.ndarray, tris: np.ndarray
              ) -> tuple[np.ndarray, np.ndarray]:
    """Moller-Trumbore intersection of every ray with every triangle (all pairs).

    A small numpy brute force for checks by hand; :func:`raycast` does not use it
    (its watertight test and tie rule are in :mod:`vgxsim.kernels.raycast`).  Here
    triangles are closed: a ray on a shared edge meets both.

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


# --------------------------------------------------------------------------------------
# Input preparation
# --------------------------------------------------------------------------------------
def homogeneous(tris: np.ndarray) -> np.ndarray:
    """Triangles as (T, 3, 4) homogeneous vertices with w exactly 0 or 1.

    Parameters
    ----------
    tris : array_like, shape (T, 3, 3) or (T, 3, 4)
        Points, or homogeneous vertices (w = 0: a point at infinity in the
        direction x, y, z; w > 0: the point (x, y, z) / w).

    Returns
    -------
    ndarray, shape (T, 3, 4), float64

    Raises
    ------
    ValueError
        On non-finite values, w < 0, or a zero direction.
    """
    t = np.asarray(tris, dtype=np.float64)
    if t.ndim != 3 or t.shape[1] != 3 or t.shape[2] not in (3, 4):
        raise ValueError(f"triangles must have shape (T, 3, 3) or (T, 3, 4), not {t.shape}")
    if not np.all(np.isfinite(t)):
        raise ValueError("triangle vertices must be finite (use w = 0 for infinity)")
    if t.shape[2] == 3:
        return np.concatenate([t, np.ones(t.shape[:2] + (1,))], axis=2)
    w = t[..., 3]
    if np.any(w < 0.0):
        raise ValueError("vertices with w < 0 are not supported: negate the 4-vector "
                         "(it is the same point) or clip first")
    if np.any((w == 0.0) & np.all(t[..., :3] == 0.0, axis=2)):
        raise ValueError("a vertex at infinity (w = 0) needs a non-zero direction")
    out = t.copy()
    fin = w > 0.0
    out[..., :3][fin] = t[..., :3][fin] / w[fin][:, None]
    out[..., 3] = np.where(fin, 1.0, 0.0)
    return out


def usable_triangles(tris4: np.ndarray) -> np.ndarray:
    """(T,) bool: the triangle spans a plane (degenerate ones are never hit).

    A finite triangle is degenerate when the cross product of its edges is exactly
    zero; one with vertices at infinity when all four 3 x 3 minors of its 3 x 4
    vertex matrix (its plane equation) are exactly zero.
    """
    fin = np.all(tris4[..., 3] == 1.0, axis=1)
    a, b, c = tris4[:, 0, :3], tris4[:, 1, :3], tris4[:, 2, :3]
    n = np.cross(b - a, c - a)
    ok = np.any(n != 0.0, axis=1)
    if not np.all(fin):
        m = tris4[~fin]
        minors = [np.linalg.det(m[:, :, [i for i in range(4) if i != skip]])
                  for skip in range(4)]
        ok[~fin] = np.any(np.stack(minors, axis=1) != 0.0, axis=1)
    return ok


def light_position(light) -> np.ndarray:
    """The homogeneous position (4,) of a light: w = 1 point/spot, w = 0 directional.

    Reads ``light.position`` (3 or 4 numbers) and, for 3, an optional ``light.w``
    (default 1, a local light as :class:`~vgxsim.shadow.scene.PointLight`).
    """
    p = np.asarray(light.position, dtype=np.float64).reshape(-1)
    if p.size == 3:
        p = np.append(p, float(getattr(light, "w", 1.0)))
    if p.size != 4 or not np.all(np.isfinite(p)):
        raise ValueError(f"light {getattr(light, 'name', light)!r}: position must be 3 or 4 "
                         f"finite numbers, not {light.position!r}")
    if p[3] != 0.0:
        return np.append(p[:3] / p[3], 1.0)
    if not np.any(p[:3] != 0.0):
        raise ValueError(f"light {getattr(light, 'name', light)!r}: a directional light "
                         "(w = 0) needs a non-zero direction")
    return p


def snap_to_window(tris4: np.ndarray, mvp: np.ndarray, width: int, height: int,
                   subpixel: bool) -> np.ndarray:
    """Move vertices to where the rasterizer snaps them (docs/numeric_model.md s. 2).

    Each finite vertex with clip coordinates inside ``-w <= z <= w`` (w > 0) and
    window coordinates within the rasterizer's limit is projected to window
    coordinates for ``viewport(0, width-1, 0, height-1)``, snapped with
    :func:`vgxsim.kernels.clip.snap_window` and unprojected at its own clip z and w.
    Other vertices (behind the eye, clipped by near or far, at infinity) are kept:
    the rasterizer sees their clipped images, not them.

    Parameters
    ----------
    tris4 : ndarray, shape (T, 3, 4), float64
    mvp : ndarray, shape (4, 4), float64
        Modelview x projection, row-vector convention.
    width, height : int
    subpixel : bool
        As ``subpixel(TRUE/FALSE)``.

    Returns
    -------
    ndarray, shape (T, 3, 4), float64
    """
    v = tris4.reshape(-1, 4)
    clip = to_clip(v, mvp)  # the rasterizer's own transform, rounding included
    x, y, z, w = clip[:, 0], clip[:, 1], clip[:, 2], clip[:, 3]
    fin = v[:, 3] == 1.0
    hx, hy = width / 2.0, height / 2.0
    with np.errstate(divide="ignore", invalid="ignore"):
        xw = -0.5 + (x / w + 1.0) * hx
        yw = -0.5 + (y / w + 1.0) * hy
        ok = (fin & (w > 0.0) & (z >= -w) & (z <= w) & (np.abs(xw) < COORD_LIMIT)
              & (np.abs(yw) < COORD_LIMIT))
    out = v.copy()
    if np.any(ok):
        xf, yf = snap_window(np.ascontiguousarray(xw[ok]), np.ascontiguousarray(yw[ok]),
                             bool(subpixel))
        wk = w[ok]
        snapped = np.stack([((xf / ONE + 0.5) / hx - 1.0) * wk,
                            ((yf / ONE + 0.5) / hy - 1.0) * wk, z[ok], wk], axis=1)
        snapped = apply(snapped, np.linalg.inv(mvp))
        out[ok, :3] = snapped[:, :3] / snapped[:, 3:4]
    return out.reshape(tris4.shape)


def _rasterized(tris4: np.ndarray, mvp: np.ndarray, width: int, height: int,
                subpixel: bool) -> tuple[np.ndarray, Window, np.ndarray]:
    """The triangles as the rasterizer draws them, for the eye rays.

    The rasterizer's own transform, homogeneous clipper and snap
    (:func:`vgxsim.geometry.pipeline.to_clip`, :func:`vgxsim.kernels.clip.clip_triangles`,
    :func:`vgxsim.kernels.clip.project_snap`; guard band as the pipeline's) turn each
    triangle into the pieces it draws, with the fixed-point window vertices it
    rasterizes.  Sharing them is the point of this mode: it answers "what would an
    exact stencil hold on the rasterizer's geometry"; the unsnapped cast shares
    nothing with the renderer.  Each piece goes back to world space at its snapped
    window position and clip z, w (vertices at infinity stay as they are, and their
    pieces are tested in 3-D).

    Returns
    -------
    pieces : ndarray, shape (P, 3, 4), float64
    win : Window
        Window-space vertices of every piece (``exact`` False for pieces with a
        vertex at infinity).
    source : ndarray, shape (P,), int64
        The input triangle of each piece.
    """
    v = np.ascontiguousarray(tris4.reshape(-1, 4))
    n = len(v)
    if n == 0:
        return tris4.copy(), no_window(), np.zeros(0, np.int64)
    clip = np.ascontiguousarray(to_clip(v, mvp))
    hx, hy = width / 2.0, height / 2.0
    gx, gy = max(1.0, GUARD_PIXELS / hx), max(1.0, GUARD_PIXELS / hy)  # as the pipeline
    out_v, _, out_tris, out_src = clip_triangles(
        clip, np.zeros((n, 0)), np.arange(n, dtype=np.int64).reshape(-1, 3), gx, gy, NO_PLANES)
    xf, yf, _ = project_snap(np.ascontiguousarray(out_v), 0, width - 1, 0, height - 1,
                             -1.0, 1.0, bool(subpixel))
    w = out_v[:, 3]
    snapped = np.stack([((xf / ONE + 0.5) / hx - 1.0) * w, ((yf / ONE + 0.5) / hy - 1.0) * w,
                        out_v[:, 2], w], axis=1)
    snapped = apply(snapped, np.linalg.inv(mvp))
    at_inf = np.zeros(len(out_v), bool)
    at_inf[:n] = v[:, 3] == 0.0
    with np.errstate(divide="ignore", invalid="ignore"):
        world = snapped / snapped[:, 3:4]
    original = np.zeros((len(out_v), 4))
    original[:n] = v
    world[at_inf] = original[at_inf]
    ok = np.all(np.isfinite(world), axis=1)
    pieces = world[out_tris]
    keep = ok[out_tris].all(axis=1)
    win = Window(int(width), np.ascontiguousarray(xf[out_tris][keep]),
                 np.ascontiguousarray(yf[out_tris][keep]),
                 np.ascontiguousarray(~at_inf[out_tris][keep].any(axis=1)))
    return np.ascontiguousarray(pieces[keep]), win, out_src[keep].astype(np.int64)


def _bands(n: int, nthreads: int) -> list[tuple[int, int]]:
    """Contiguous ray ranges, several per thread so that uneven rows balance."""
    parts = max(1, min(n, 8 * nthreads if nthreads > 1 else 1))
    edges = np.linspace(0, n, parts + 1).astype(np.int64)
    return [(int(a), int(b)) for a, b in zip(edges[:-1], edges[1:], strict=True) if b > a]


def tile_order(width: int, height: int, tile: int = 16) -> np.ndarray:
    """Pixel indices ``x + width * y`` tile by tile: square ``tile x tile`` tiles in
    row order, each read in row order (partial tiles at the right and top edges).

    Casting in this order keeps successive rays in the same BVH nodes; measured on
    the dense torus at 1280 x 1024, primary rays per CPU-second: rows 4.8 M, tiles
    of 8: 5.1 M, 16: 5.3 M, 32: 5.2 M.  ``tile <= 1`` gives row order.

    Returns
    -------
    ndarray, shape (width * height,), int64
    """
    if tile <= 1:
        return np.arange(width * height, dtype=np.int64)
    y, x = np.divmod(np.arange(width * height, dtype=np.int64), width)
    key = np.lexsort((x, y, x // tile, y // tile))
    return key.astype(np.int64)


def run_bands(kernel, n: int, nthreads: int, *args) -> None:
    """Run ``kernel(*args, r0, r1, *outs)`` over bands of rays on worker threads.

    The kernels are nogil (kernels/options.py); each band writes disjoint rows of
    the outputs, so the result does not depend on the thread count.
    """
    *inputs, outs = args
    bands = _bands(n, nthreads)
    if nthreads <= 1 or len(bands) <= 1:
        for r0, r1 in bands:
            kernel(*inputs, r0, r1, *outs)
        return
    futures = [_threads.pool(nthreads).submit(kernel, *inputs, r0, r1, *outs)
               for r0, r1 in bands]
    for f in futures:
        f.result()


def no_window() -> Window:
    """A :data:`vgxsim.kernels.raycast.Window` that tests every triangle in 3-D."""
    return Window(0, np.zeros((0, 3), np.int64), np.zeros((0, 3), np.int64),
                  np.zeros(0, np.bool_))


def build_bvh(tris4: np.ndarray, usable: np.ndarray | None = None, *, leaf_size: int = 4,
              sah: bool = True, max_extent: float = 0.0,
              region: tuple[np.ndarray, np.ndarray] | None = None,
              max_pieces: int = 64) -> BVH:
    """A :data:`vgxsim.kernels.bvh.BVH` over the usable triangles.

    ``max_extent`` > 0 cuts long triangles into pieces inside ``region`` (default:
    everywhere), see :func:`vgxsim.kernels.bvh.split_references`; ``sah`` and
    ``leaf_size`` as :func:`vgxsim.kernels.bvh.build_arrays`.
    """
    tris4 = np.ascontiguousarray(tris4, dtype=np.float64)
    if usable is None:
        usable = np.ones(tris4.shape[0], dtype=np.bool_)
    if region is None:
        region = (np.full(3, -np.inf), np.full(3, np.inf))
    ref, lo, hi = split_references(tris4, np.ascontiguousarray(usable, dtype=np.bool_),
                                   float(max_extent), np.asarray(region[0], np.float64),
                                   np.asarray(region[1], np.float64), int(max_pieces))
    nodes, ordered, index = build_arrays(tris4, ref, lo, hi, int(leaf_size), bool(sah))
    return BVH(_cache_line_aligned(nodes), ordered, index)


def _cache_line_aligned(a: np.ndarray) -> np.ndarray:
    """A copy of ``a`` whose data starts on a 64-byte boundary, so that each 64-byte
    node record of a BVH lies in one cache line (numpy aligns to 16 bytes only)."""
    buf = np.empty(a.nbytes + 64, np.uint8)
    skip = (-buf.ctypes.data) % 64
    out = buf[skip:skip + a.nbytes].view(a.dtype).reshape(a.shape)
    out[...] = a
    return out


def scene_bvh(tris4: np.ndarray, keep: np.ndarray | None = None, *, sah: bool = True,
              split_within: np.ndarray | None = None) -> BVH:
    """A BVH over the usable triangles of ``tris4`` (and ``keep``), caller-indexed.

    ``split_within`` (shape (2, 3): a box) cuts triangles into pieces no longer than
    1/64 of the box's diagonal inside it, at most 256 per triangle
    (:func:`vgxsim.kernels.bvh.split_references`): long shadow faces otherwise
    overlap every eye ray's box tests.  Measured on 20 icospheres (8.5 k faces):
    crossings at 320 x 256 took 7.4 s uncut and 0.72 s cut at 1/32; at 640 x 512,
    1/16: 1.25, 1/32: 0.96, 1/64: 0.79, 1/128: 0.79 CPU seconds.
    """
    usable = usable_triangles(tris4)
    if keep is not None:
        usable &= keep
    if split_within is None:
        return build_bvh(tris4, usable, sah=sah)
    lo, hi = np.asarray(split_within[0], float), np.asarray(split_within[1], float)
    return build_bvh(tris4, usable, sah=sah, max_extent=float(np.linalg.norm(hi - lo)) / 64,
                     region=(lo, hi), max_pieces=256)


# --------------------------------------------------------------------------------------
# Casting
# --------------------------------------------------------------------------------------
def nearest_hit(origin: np.ndarray, direction: np.ndarray, tris: np.ndarray,
                tmax: float = 1.0, *, threads: int | None = None
                ) -> tuple[np.ndarray, np.ndarray]:
    """Nearest triangle along each segment ``origin + t direction``, 0 <= t <= tmax.

    Parameters
    ----------
    origin, direction : ndarray, shape (R, 3)
    tris : ndarray, shape (T, 3, 3) or (T, 3, 4)
    tmax : float
    threads : int, optional
        Worker threads (default :func:`vgxsim.threads.get_threads`).

    Returns
    -------
    index : ndarray, shape (R,), int64
        Triangle index, -1 where nothing is hit (ties: the lowest index).
    t : ndarray, shape (R,), float64
        Ray parameter of the hit, inf where nothing is hit.
    """
    o = np.ascontiguousarray(origin, dtype=np.float64).reshape(-1, 3)
    d = np.ascontiguousarray(direction, dtype=np.float64).reshape(-1, 3)
    bvh = scene_bvh(homogeneous(tris))
    idx = np.empty(len(o), np.int64)
    t = np.empty(len(o))
    n = _threads.get_threads() if threads is None else int(threads)
    run_bands(closest_hits, len(o), n, bvh, no_window(), o, d, 0.0, float(tmax),
              np.arange(len(o), dtype=np.int64), (idx, t))
    return idx, t


def segment_scales(tris4: np.ndarray, eye, eps: float) -> tuple[float, float]:
    """Offset at both ends of a shadow segment, and the length of a directional one.

    With D the diagonal of the scene's bounding box and M its largest |coordinate|:
    ``offset = eps * D + 1e-13 * M`` (the first term keeps a receiver from
    shadowing itself at any scale, the second stays above float64 rounding of
    coordinates near M), and ``far = 2 (D + |eye - centre|) + 1``, longer than any
    way from the eye or a scene point to a caster.

    Parameters
    ----------
    tris4 : ndarray, shape (T, 3, 4), float64
        Scene triangles (finite).
    eye : array_like, shape (3,)
    eps : float

    Returns
    -------
    offset, far : float
    """
    pts = tris4[..., :3].reshape(-1, 3)
    if len(pts) == 0:
        return 0.0, 1.0
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    diag = float(np.linalg.norm(hi - lo))
    big = float(np.abs(pts).max())
    reach = float(np.linalg.norm(np.asarray(eye, np.float64) - 0.5 * (lo + hi)))
    return float(eps) * diag + 1e-13 * big, 2.0 * (diag + reach) + 1.0


def _light_facing(tris4: np.ndarray, light: np.ndarray) -> np.ndarray:
    """(T,) bool: ``N . (L - v0) > 0`` (``N . L`` for w = 0), N = (v1-v0) x (v2-v0)."""
    a, b, c = tris4[:, 0, :3], tris4[:, 1, :3], tris4[:, 2, :3]
    n = np.cross(b - a, c - a)
    to_light = light[:3] - a if light[3] != 0.0 else np.broadcast_to(light[:3], a.shape)
    return np.einsum("ij,ij->i", n, to_light) > 0.0


def own_side_shadowed(tris4: np.ndarray, tri: np.ndarray, direction: np.ndarray,
                      lights: np.ndarray) -> np.ndarray:
    """Whether each point's own triangle lies between the side the eye sees and the light.

    The eye ray meets triangle ``tri[r]`` from the side ``-direction[r]`` points to;
    that side is lit only if the light is on it too:  with ``N = (v1 - v0) x (v2 -
    v0)``, the point is shadowed by its own triangle iff ``(N . direction) *
    (N . (l - lw v0)) > 0`` (``N . l`` for a directional light, the facing rule of
    :meth:`vgxsim.shadow.scene.Polyhedron.facing`).  This is the volume of the
    triangle itself (shadow_literature.md 1.1 and 1.3: the region behind each
    caster polygon is in shadow, and a point's count is the number of caster
    surfaces between it and the light, H5): the eye ray reaching P from behind the
    triangle comes through that volume, which is what a stencil counts.  On a
    closed caster it changes nothing away from silhouettes (the segment meets
    another triangle anyway); on an open one it decides the inside and the far side
    of a sheet.  A light exactly in the plane (0) does not shadow (H4).

    Parameters
    ----------
    tris4 : ndarray, shape (T, 3, 4), float64
    tri : ndarray, shape (R,), int64
        Triangle of each point, -1 for none (never shadowed).
    direction : ndarray, shape (R, 3), float64
        The eye rays.
    lights : ndarray, shape (L, 4), float64

    Returns
    -------
    ndarray, shape (R, L), bool
    """
    out = np.zeros((len(tri), len(lights)), bool)
    on = tri >= 0
    if not on.any():
        return out
    t = tris4[tri[on]]
    a, b, c = t[:, 0, :3], t[:, 1, :3], t[:, 2, :3]
    n = np.cross(b - a, c - a)
    seen = np.einsum("ij,ij->i", n, direction[on])
    for li, lp in enumerate(lights):
        to_light = lp[:3][None, :] - lp[3] * a
        side = np.einsum("ij,ij->i", n, to_light)
        out[on, li] = ((seen > 0.0) & (side > 0.0)) | ((seen < 0.0) & (side < 0.0))
    return out


def _scene_faces(scene: Scene, edges: str) -> list[tuple[np.ndarray, np.ndarray]]:
    """Per light: the shadow-face triangles the renderer draws and their +-1 signs."""
    out = []
    for li in range(len(scene.lights)):
        quads, ingoing = shadow_faces(scene, li, edges)
        ftris = np.concatenate([quads[:, [0, 1, 2]], quads[:, [0, 2, 3]]])
        sign = np.where(np.concatenate([ingoing, ingoing]), 1, -1)
        out.append((ftris, sign))
    return out


def raycast(scene: Scene, width: int, height: int, *, edges: str = "silhouette",
            eps: float = 1e-7, subpixel: bool | None = None,
            faces: Sequence[tuple[np.ndarray, np.ndarray]] | None = None,
            counts: bool = True, threads: int | None = None, sah: bool = True,
            split_faces: bool = True, tile: int = 16) -> RayCastResult:
    """Ray-cast the scene: visible surface, per-light lit mask and shadow counts.

    See the module docstring for exactly what is computed.

    Parameters
    ----------
    scene : Scene
    width, height : int
    edges : {'silhouette', 'all'}
        Which shadow faces ``crossings`` counts (the lit mask does not depend on it);
        ignored when ``faces`` is given.
    eps : float
        Shadow segments from the hit point P to the light count no blocker within
        ``offset`` of either end (:func:`segment_scales`).
    subpixel : bool, optional
        None: exact geometry.  False / True: vertices snapped as the rasterizer does
        under ``subpixel(FALSE)`` / ``subpixel(TRUE)``.
    faces : sequence of (triangles, weights), optional
        Per light, the faces ``crossings`` counts instead of the scene's:
        triangles of shape (F, 3, 3) or (F, 3, 4) (w = 0: at infinity) and int
        weights (F,) (+1 ST_INCR, -1 ST_DECR; other values count with multiplicity).
    counts : bool
        False skips ``occluders`` and ``layers`` (left 0): each segment to a light
        stops at its first blocker.  ``lit`` is the same either way.
    threads : int, optional
        Worker threads (default :func:`vgxsim.threads.get_threads`); the result
        does not depend on it.
    sah : bool
        BVH split rule (SAH or median); the result does not depend on it.
    split_faces : bool
        Cut long shadow faces into pieces for the BVH (:func:`scene_bvh`); the
        result does not depend on it, the time does.
    tile : int
        Rays are cast in square tiles of this many pixels (:func:`tile_order`; 1:
        row by row); the result does not depend on it, the time does.

    Returns
    -------
    RayCastResult
    """
    nthreads = _threads.get_threads() if threads is None else int(threads)
    if nthreads < 1:
        raise ValueError("raycast: threads must be at least 1")
    cam = scene.camera
    mvp = cam.modelview() @ cam.projection(width / height)
    origin, direction = pixel_rays(scene, width, height)
    o = np.ascontiguousarray(origin.reshape(-1, 3))
    d = np.ascontiguousarray(direction.reshape(-1, 3))
    n = o.shape[0]
    tris, tri_obj = scene.triangles()
    tris4 = homogeneous(tris)
    nl = len(scene.lights)
    lights = np.array([light_position(li) for li in scene.lights]).reshape(nl, 4)
    if faces is None:
        faces = _scene_faces(scene, edges)
    if len(faces) != nl:
        raise ValueError(f"raycast: faces has {len(faces)} entries for {nl} lights")
    ftris = [homogeneous(f[0]).reshape(-1, 3, 4) for f in faces]
    fweights = [np.asarray(f[1], np.int64).reshape(-1) for f in faces]
    for li, (ft, fw) in enumerate(zip(ftris, fweights, strict=True)):
        if len(ft) != len(fw):
            raise ValueError(f"raycast: light {li}: {len(ft)} faces but {len(fw)} weights")
    face4 = np.concatenate(ftris) if ftris else np.zeros((0, 3, 4))
    face_light = np.concatenate([np.full(len(ft), li, np.int64)
                                 for li, ft in enumerate(ftris)] or [np.zeros(0, np.int64)])
    face_weight = np.concatenate(fweights or [np.zeros(0, np.int64)])
    # eye rays see `visible` (pieces of the scene triangles `visible_src`), the shadow
    # segments `tris4`; they differ only when snapping
    scene_win = face_win = no_window()
    visible, visible_src = tris4, np.arange(len(tris4), dtype=np.int64)
    if subpixel is not None:
        visible, scene_win, visible_src = _rasterized(tris4, mvp, width, height, subpixel)
        face4, face_win, fsrc = _rasterized(face4, mvp, width, height, subpixel)
        face_light, face_weight = face_light[fsrc], face_weight[fsrc]
        tris4 = snap_to_window(tris4, mvp, width, height, subpixel)

    # 1. visible surface
    scene_tree = scene_bvh(visible, sah=sah)
    piece = np.empty(n, np.int64)
    thit = np.empty(n)
    order = tile_order(width, height, tile)
    run_bands(closest_hits, n, nthreads, scene_tree, scene_win, o, d, 0.0, 1.0, order,
              (piece, thit))
    hit = piece >= 0
    tri_idx = np.where(hit, visible_src[np.maximum(piece, 0)], -1) if len(visible_src) else piece
    point = o + np.where(hit, thit, np.nan)[:, None] * d

    # 2. segments to the lights
    casts = np.array([ob.casts for ob in scene.objects], bool)
    caster = casts[tri_obj] if len(tri_obj) else np.zeros(0, bool)
    caster_tree = scene_bvh(tris4, caster, sah=sah)
    layer_w = np.zeros((nl, len(tris4)), np.int64)
    for li in range(nl):
        layer_w[li] = caster & _light_facing(tris4, lights[li])
    offset, far = segment_scales(tris4, cam.eye, eps)
    blocked = np.zeros((n, nl), bool)
    occl = np.zeros((n, nl), np.int64)
    layers = np.zeros((n, nl), np.int64)
    pts = np.ascontiguousarray(np.where(hit[:, None], point, 0.0))
    run_bands(shadow_segments, n, nthreads, caster_tree, tri_obj, len(scene.objects), layer_w,
              pts, tri_idx, hit, lights, far, offset, bool(counts), order,
              (blocked, occl, layers))
    own = np.where(hit, tri_idx, -1)
    own[hit] = np.where(caster[tri_idx[hit]], tri_idx[hit], -1)
    blocked |= own_side_shadowed(tris4, own, d, lights)
    eye_b = np.zeros((1, nl), bool)
    eye_o = np.zeros((1, nl), np.int64)
    eye_l = np.zeros((1, nl), np.int64)
    shadow_segments(caster_tree, tri_obj, len(scene.objects), layer_w,
                    np.asarray(cam.eye, np.float64).reshape(1, 3), np.full(1, -1, np.int64),
                    np.ones(1, bool), lights, far, offset, True, np.zeros(1, np.int64), 0, 1,
                    eye_b, eye_o, eye_l)

    # 3. shadow-face crossings along the eye rays
    # eye rays end on the scene (or at the far plane): cut faces finely within the
    # scene's box, where the rays' intervals end
    fin = tris4[..., :3].reshape(-1, 3)
    box = np.stack([fin.min(axis=0), fin.max(axis=0)]) if len(fin) else None
    face_tree = scene_bvh(face4, sah=sah, split_within=box if split_faces else None)
    cross = np.zeros((n, nl), np.int64)
    t_end = np.where(hit, thit, 1.0)
    run_bands(count_crossings, n, nthreads, face_tree, face_win, face_light, face_weight, o,
              d, t_end, order, (cross,))

    obj = np.where(hit, tri_obj[np.maximum(tri_idx, 0)], -1) if len(tri_obj) else tri_idx
    h, w = height, width
    return RayCastResult(object_id=obj.reshape(h, w), triangle=tri_idx.reshape(h, w),
                         point=point.reshape(h, w, 3), t=thit.reshape(h, w),
                         lit=(hit[:, None] & ~blocked).reshape(h, w, nl),
                         occluders=occl.reshape(h, w, nl), crossings=cross.reshape(h, w, nl),
                         layers=layers.reshape(h, w, nl), eye_layers=eye_l[0].copy())


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
        lp = light_position(light)
        ldir = lp[:3] - p if lp[3] else np.broadcast_to(lp[:3], p.shape).copy()
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
