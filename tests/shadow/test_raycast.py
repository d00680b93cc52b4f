"""The float64 ray-cast reference (the shadow oracle) checked against geometry."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from vgxsim.shadow import (
    Camera,
    PointLight,
    Scene,
    default_scene,
    make_box,
    polyhedron_from_polygons,
    shadow_faces,
)
from vgxsim.shadow.raycast import (
    homogeneous,
    intersect,
    light_position,
    nearest_hit,
    pixel_rays,
    raycast,
    shade,
    snap_to_window,
    usable_triangles,
)
from vgxsim.shadow.scene import LightModel, make_grid_box

W, H = 80, 64


@pytest.fixture(scope="module")
def scene():
    return default_scene()


@pytest.fixture(scope="module")
def result(scene):
    return raycast(scene, W, H)


def test_rays_go_through_pixel_centres(scene):
    # IRIS convention: window x of pixel X is X (centre), viewport(0, W-1, 0, H-1)
    origin, direction = pixel_rays(scene, W, H)
    mvp = scene.camera.modelview() @ scene.camera.projection(W / H)
    for t in (0.0, 0.3, 1.0):
        p = origin + t * direction
        clip = np.concatenate([p, np.ones(p.shape[:2] + (1,))], axis=2) @ mvp
        ndc = clip[..., :3] / clip[..., 3:4]
        xw = -0.5 + (ndc[..., 0] + 1) * W / 2
        yw = -0.5 + (ndc[..., 1] + 1) * H / 2
        assert np.allclose(xw, np.arange(W)[None, :], atol=1e-7)
        assert np.allclose(yw, np.arange(H)[:, None], atol=1e-7)
        if t in (0.0, 1.0):  # near plane at z_ndc = -1, far plane at +1
            assert np.allclose(ndc[..., 2], 2 * t - 1, atol=1e-9)
    # all rays start on the near plane and pass (extended backwards) through the eye
    eye = np.asarray(scene.camera.eye)
    d = origin - eye
    cos = np.einsum("ijk,ijk->ij", d, direction) / (
        np.linalg.norm(d, axis=2) * np.linalg.norm(direction, axis=2))
    assert np.allclose(cos, 1.0, atol=1e-12)


def test_moller_trumbore_single_triangle():
    tri = np.array([[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]])
    o = np.array([[0.25, 0.25, 1.0], [0.75, 0.75, 1.0], [0.2, 0.2, -1.0]])
    d = np.array([[0.0, 0.0, -2.0], [0.0, 0.0, -2.0], [0.0, 0.0, 2.0]])
    t, det = intersect(o, d, tri)
    assert t[0, 0] == 0.5 and np.isinf(t[1, 0]) and t[2, 0] == 0.5
    assert det[0, 0] > 0 > det[2, 0]  # the CCW (front, +z) side is met from above


def test_nearest_hit_equals_brute_force(scene):
    rng = np.random.default_rng(1)
    tris, _ = scene.triangles()
    o = rng.uniform(-6, 6, (2000, 3)) + np.array([0, 4, 0])
    d = rng.normal(size=(2000, 3)) * 8
    idx, t = nearest_hit(o, d, tris)
    tb, _ = intersect(o, d, tris)
    tb = np.where((tb >= 0) & (tb <= 1), tb, np.inf)
    # the two tests round differently: equal hits, t to rounding
    assert np.array_equal(np.isfinite(t), np.isfinite(tb.min(axis=1)))
    hit = np.isfinite(t)
    assert np.allclose(t[hit], tb.min(axis=1)[hit], rtol=1e-12, atol=0)
    assert hit.sum() > 200
    # the nearest triangle, except where two are hit at the same t to rounding
    # (cube bottoms lie on the floor's top plane: coplanar overlaps)
    second = np.sort(tb, axis=1)[:, 1]
    clear = hit & (second > t * (1 + 1e-12))
    assert clear.sum() > 0.9 * hit.sum()
    assert np.array_equal(idx[clear], np.argmin(tb, axis=1)[clear])
    assert np.all(idx[~hit] == -1)


def test_visible_points_are_on_the_visible_object(scene, result):
    assert set(np.unique(result.object_id)) == {-1, 0, 1, 2, 3}
    tris, tri_obj = scene.triangles()
    hit = result.hit
    assert np.array_equal(tri_obj[result.triangle[hit]], result.object_id[hit])
    # floor hits lie on its top plane y = 0 (it is seen from above)
    floor = result.object_id == 0
    assert np.allclose(result.point[floor][:, 1], 0.0, atol=1e-9)
    assert np.all(np.isnan(result.point[~hit])) and np.all(~result.lit[~hit])


def test_lit_means_the_segment_to_the_light_is_free(scene, result):
    # independent check on a sample of pixels: march the segment and measure how deep
    # it goes into each cube, using the cube's planes (inside a convex box = on the
    # inner side of every face plane)
    rng = np.random.default_rng(7)
    ys, xs = np.nonzero(result.hit)
    pick = rng.choice(len(ys), 300, replace=False)
    s = np.linspace(0.0, 1.0, 4001)
    checked = 0
    for li, light in enumerate(scene.lights):
        lp = np.asarray(light.position)
        for k in pick:
            y, x = ys[k], xs[k]
            p = result.point[y, x]
            seg = p + s[:, None] * (lp - p)
            depth = -np.inf
            for obj in scene.casters:
                dist = np.einsum("sfk,fk->sf", seg[:, None, :] - obj.face_points[None],
                                 obj.normals)
                depth = max(depth, float((-dist.max(axis=1)).max()))
            if depth > 1e-3:  # clearly passes through a cube
                assert not result.lit[y, x, li]
                checked += 1
            elif result.lit[y, x, li]:
                assert depth <= 1e-9  # never inside any cube
                checked += 1
    assert checked > 550


def test_floating_cube_shadow_matches_a_slab_test():
    # an axis-aligned cube: the segment from a floor point to the light is blocked iff
    # it meets the box (slab test, computed here independently of the ray cast)
    lo, hi = np.array([-0.5, 1.5, -0.5]), np.array([0.5, 2.5, 0.5])
    cube = make_box("c", (1.0, 1.0, 1.0), position=(0.0, 2.0, 0.0))
    floor = make_box("f", (10.0, 0.2, 10.0), position=(0.0, -0.1, 0.0), casts=False)
    light = PointLight("l", (2.5, 8.0, 1.0), (1.0, 1.0, 1.0))
    cam = Camera(fovy=450, near=1.0, far=30.0, eye=(-4.0, 9.0, 6.0), target=(0.0, 0.0, 0.0))
    sc = Scene(objects=(floor, cube), lights=(light,), lmodel=LightModel(), camera=cam)
    r = raycast(sc, 64, 64)
    fl = r.object_id == 0
    p = r.point[fl]
    d = np.asarray(light.position) - p
    with np.errstate(divide="ignore", invalid="ignore"):
        t1, t2 = (lo - p) / d, (hi - p) / d
    tn = np.nanmax(np.minimum(t1, t2), axis=1)
    tf = np.nanmin(np.maximum(t1, t2), axis=1)
    blocked = (tn < tf) & (tf > 0) & (tn < 1)
    margin = np.minimum(tf - tn, 1.0)  # how deep the segment goes through the box
    clear = ~blocked | (margin > 1e-3)
    assert blocked.sum() > 20 and (~blocked).sum() > 20
    assert np.array_equal(r.lit[fl, 0][clear], ~blocked[clear])
    assert np.all(r.occluders[fl, 0][blocked & clear] == 1)
    # the cube's top faces the light: lit
    top = (r.object_id == 1) & np.isclose(r.point[..., 1], 2.5)
    assert top.sum() > 0 and r.lit[top, 0].all()


def test_crossings_count_the_volumes_containing_the_visible_point(scene, result):
    # the eye is outside every shadow volume, so the article's signed count equals
    # the number of casters between the point and the light (convex casters)
    for li, light in enumerate(scene.lights):
        eye = np.asarray(scene.camera.eye)
        tris = np.concatenate([o.vertices[o.triangles] for o in scene.casters])
        t, _ = intersect(eye[None], (np.asarray(light.position) - eye)[None], tris)
        assert not np.any((t > 0) & (t < 1)), "eye in shadow"
        hit = result.hit
        assert np.array_equal(result.crossings[..., li][hit], result.occluders[..., li][hit])
        assert np.array_equal(result.lit[..., li][hit], result.occluders[..., li][hit] == 0)
    allr = raycast(scene, W, H, edges="all")
    assert np.array_equal(allr.crossings[result.hit], 2 * result.crossings[result.hit])


def test_moving_the_light_moves_the_shadow(scene, result):
    far = dataclasses.replace(scene, lights=(PointLight("top", (0.0, 60.0, 0.0),
                                                         (1.0, 1.0, 1.0)),))
    r = raycast(far, W, H)
    assert not np.array_equal(r.lit[..., 0], result.lit[..., 0])
    assert r.lit[..., 0][r.hit].mean() > 0.8


# -- brute force: every ray against every triangle, written apart from the kernels ----
MARGIN = 1e-9  # rays this close (relative) to an edge or interval end are left out


@dataclasses.dataclass(frozen=True)
class DirectionalLight:
    """IRIS GL POSITION with w = 0: a light infinitely far in ``position[:3]``."""

    name: str
    position: tuple
    colour: tuple = (1.0, 1.0, 1.0)
    ambient: tuple = (0.0, 0.0, 0.0)


def bf_line_hits(o, d, tris):
    """Plane intersection + normalised barycentrics of one ray against all triangles.

    Returns t (T,) (nan where parallel) and the smallest barycentric coordinate of
    the plane point (T,) (>= 0 inside; |.| small: near an edge).
    """
    a, b, c = tris[:, 0], tris[:, 1], tris[:, 2]
    n = np.cross(b - a, c - a)
    nn = np.einsum("ij,ij->i", n, n)
    den = n @ d
    with np.errstate(divide="ignore", invalid="ignore"):
        t = np.einsum("ij,ij->i", n, a - o) / den
        p = o + t[:, None] * d
        bary = np.stack([np.einsum("ij,ij->i", np.cross(c - b, p - b), n),
                         np.einsum("ij,ij->i", np.cross(a - c, p - c), n),
                         np.einsum("ij,ij->i", np.cross(b - a, p - a), n)], axis=1) / nn[:, None]
    bmin = np.where(np.isfinite(t), bary.min(axis=1), -np.inf)
    return np.where(den != 0, t, np.nan), bmin


def bf_range(o, d, tris, t0, t1):
    """(hit mask (T,), certain) for t0 <= t <= t1; uncertain when a triangle is
    within MARGIN of its edge or of an interval end (where tie rules decide)."""
    t, bmin = bf_line_hits(o, d, tris)
    ok = np.isfinite(t)
    inside = ok & (bmin >= 0) & (t >= t0) & (t <= t1)
    scale = max(1.0, abs(t1))
    near_edge = (ok & (np.abs(bmin) < MARGIN) & (t >= t0 - MARGIN * scale)
                 & (t <= t1 + MARGIN * scale))
    near_end = ok & (bmin >= -MARGIN) & ((np.abs(t - t0) < MARGIN * scale)
                                         | (np.abs(t - t1) < MARGIN * scale))
    return inside, not (near_edge.any() or near_end.any())


def brute_force(scene, w, h, faces, eps=1e-7):
    """Per pixel: visible triangle, lit, occluders, layers, crossings (+ certainty)."""
    origin, direction = pixel_rays(scene, w, h)
    tris, tri_obj = scene.triangles()
    casts = np.array([o.casts for o in scene.objects])[tri_obj]
    lights = [light_position(li) for li in scene.lights]
    # the documented offsets (raycast.segment_scales), from the bounding box
    lo, hi = tris.reshape(-1, 3).min(axis=0), tris.reshape(-1, 3).max(axis=0)
    diag = np.linalg.norm(hi - lo)
    offset = eps * diag + 1e-13 * np.abs(tris).max()
    far = 2 * (diag + np.linalg.norm(np.asarray(scene.camera.eye) - (lo + hi) / 2)) + 1
    nl = len(lights)
    out = {k: np.zeros((h, w, nl), np.int64) for k in ("lit", "occl", "layers", "cross")}
    out["tri"] = np.full((h, w), -1, np.int64)
    certain = np.ones((h, w, nl), bool)
    for y in range(h):
        for x in range(w):
            o, d = origin[y, x], direction[y, x]
            t, bmin = bf_line_hits(o, d, tris)
            inside = np.isfinite(t) & (bmin >= 0) & (t >= 0) & (t <= 1)
            tt = np.where(inside, t, np.inf)
            k = int(np.argmin(tt))
            srt = np.sort(tt)
            if np.isfinite(tt[k]):
                if bmin[k] < MARGIN or (len(srt) > 1 and srt[1] - srt[0] < MARGIN):
                    certain[y, x] = False
                if np.any(np.isfinite(t) & (np.abs(bmin) < MARGIN) & (t >= 0)
                          & (t <= tt[k] + MARGIN)):
                    certain[y, x] = False
                out["tri"][y, x] = k
                t_end = tt[k]
            else:
                k = -1
                t_end = 1.0
                if np.any(np.isfinite(t) & (np.abs(bmin) < MARGIN) & (t >= 0) & (t <= 1)):
                    certain[y, x] = False
            for li, lp in enumerate(lights):
                ft, fw = faces[li]
                crossed, ok = bf_range(o, d, ft, 0.0, t_end)
                out["cross"][y, x, li] = int(fw[crossed].sum())
                certain[y, x, li] &= ok
                if k < 0:
                    continue
                p = o + t_end * d
                seg = (lp[:3] - p) if lp[3] else far * lp[:3] / np.linalg.norm(lp[:3])
                s0 = offset / np.linalg.norm(seg)
                blk, ok = bf_range(p, seg, tris, s0, 1 - s0)
                blk &= casts
                blk[k] = False
                certain[y, x, li] &= ok
                a, b, c = tris[:, 0], tris[:, 1], tris[:, 2]
                nrm = np.cross(b - a, c - a)
                tol = (lp[:3] - a) if lp[3] else np.broadcast_to(lp[:3], a.shape)
                facing = np.einsum("ij,ij->i", nrm, tol) > 0
                out["lit"][y, x, li] = not blk.any()
                out["occl"][y, x, li] = len(np.unique(tri_obj[blk]))
                out["layers"][y, x, li] = int((blk & facing).sum())
    return out, certain


def random_scene(seed: int, directional: bool = False) -> Scene:
    rng = np.random.default_rng(seed)
    objs = [make_grid_box("floor", (12.0, 0.2, 12.0), (3, 1, 3), position=(0.0, -0.1, 0.0),
                          casts=False)]
    for i in range(4):
        objs.append(make_box(f"box{i}", tuple(rng.uniform(0.4, 1.5, 3)),
                             position=(rng.uniform(-2.5, 2.5), rng.uniform(0.8, 3.0),
                                       rng.uniform(-2.5, 2.5)),
                             rotate=tuple(rng.uniform(0, 90, 3))))
    # an open caster: a single triangle (shadow_literature.md H5)
    tri = rng.uniform(-2, 2, (3, 3)) + np.array([0.0, 3.5, 0.0])
    objs.append(polyhedron_from_polygons(tri, [[0, 1, 2]], "sheet"))
    lights = [PointLight("p", (rng.uniform(-4, 4), 8.0, rng.uniform(-4, 4)), (1.0, 1.0, 1.0))]
    if directional:
        lights.append(DirectionalLight("sun", (0.3, 1.0, -0.2, 0.0)))
    cam = Camera(fovy=500, near=1.0, far=40.0, eye=(3.0, 7.0, 9.0), target=(0.0, 1.0, 0.0))
    return Scene(objects=tuple(objs), lights=tuple(lights), lmodel=LightModel(), camera=cam)


def _point_light_faces(scene):
    quads, ingoing = shadow_faces(scene, 0, "all")
    ft = np.concatenate([quads[:, [0, 1, 2]], quads[:, [0, 2, 3]]])
    return ft, np.where(np.concatenate([ingoing, ingoing]), 1, -1)


@pytest.mark.parametrize("seed", [3, 11])
def test_equals_brute_force_on_random_scenes(seed):
    sc = random_scene(seed, directional=True)
    faces = [_point_light_faces(sc), (np.zeros((0, 3, 3)), np.zeros(0, np.int64))]
    w, h = 40, 32
    r = raycast(sc, w, h, faces=faces)
    bf, certain = brute_force(sc, w, h, faces)
    assert certain.mean() > 0.95
    every = certain.all(axis=2)
    assert np.array_equal(r.triangle[every], bf["tri"][every])
    for li in range(2):
        c = certain[..., li] & r.hit
        assert np.array_equal(r.lit[..., li][c], bf["lit"][..., li][c].astype(bool))
        assert np.array_equal(r.occluders[..., li][c], bf["occl"][..., li][c])
        assert np.array_equal(r.layers[..., li][c], bf["layers"][..., li][c])
        assert np.array_equal(r.crossings[..., li][certain[..., li]],
                              bf["cross"][..., li][certain[..., li]])
        # the scenes exercise both answers
        assert r.lit[..., li][c].any() and not r.lit[..., li][c].all()
    assert np.abs(r.crossings[..., 0]).max() > 0


def test_thread_count_split_rule_and_ray_order_do_not_change_the_result():
    sc = random_scene(5, directional=True)
    faces = [_point_light_faces(sc), (np.zeros((0, 3, 3)), np.zeros(0, np.int64))]
    base = raycast(sc, 48, 40, faces=faces, threads=1)
    for kw in ({"threads": 2}, {"sah": False}, {"threads": 3, "sah": False},
               {"split_faces": False}, {"tile": 1}, {"tile": 7, "threads": 2}):
        other = raycast(sc, 48, 40, faces=faces, **kw)
        for f in dataclasses.fields(base):
            assert np.array_equal(getattr(base, f.name), getattr(other, f.name),
                                  equal_nan=True), (kw, f.name)
    # the first-blocker fast path gives the same lit mask
    fast = raycast(sc, 48, 40, faces=faces, counts=False)
    assert np.array_equal(fast.lit, base.lit)
    assert not fast.occluders.any() and base.occluders.any()


# -- ties: shared edges and vertices, grazing rays ---------------------------------
def _grid_mesh(n: int):
    """An n x n grid of unit squares in z = 0, two triangles each, shared vertices."""
    tris = []
    for i in range(n):
        for j in range(n):
            a, b, c, d = (i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)
            if (i + j) % 2:
                tris += [(a, b, c), (a, c, d)]
            else:
                tris += [(a, b, d), (b, c, d)]
    return np.array([[(x, y, 0.0) for x, y in t] for t in tris], np.float64)


def test_rays_through_shared_edges_and_vertices_hit_exactly_one_triangle():
    grid = _grid_mesh(4)
    # every vertex, edge midpoint and diagonal midpoint of the inner grid, hit by
    # vertical and by oblique rays (dyadic numbers: every product is exact, so these
    # are true ties)
    pts = np.array([(x, y) for x in np.arange(0.5, 3.51, 0.5) for y in np.arange(0.5, 3.51, 0.5)])
    for dvec in ((0.0, 0.0, -1.0), (0.25, -0.5, -1.0), (-0.75, 0.125, 1.0)):
        dd = np.array(dvec)
        o = np.concatenate([pts, np.zeros((len(pts), 1))], axis=1) - 2.0 * dd
        d = np.broadcast_to(dd * 4.0, o.shape)
        idx, t = nearest_hit(o, d, grid)
        assert np.all(idx >= 0), dvec  # no ray falls through a crack
        assert np.allclose(t, 0.5)
        # ...and none is counted twice: every ray crosses the surface once
        assert np.all(count_hits(grid, o, d) == 1), dvec


def count_hits(tris, o, d, weights=None):
    """Kernel count of the triangles each ray meets at 0 <= t <= 1 (weights: 1)."""
    from vgxsim.kernels.raycast import count_crossings
    from vgxsim.shadow.raycast import no_window, scene_bvh

    bvh = scene_bvh(homogeneous(tris))
    w = np.ones(len(tris), np.int64) if weights is None else np.asarray(weights, np.int64)
    out = np.zeros((len(o), 1), np.int64)
    count_crossings(bvh, no_window(), np.zeros(len(tris), np.int64), w,
                    np.ascontiguousarray(o, float),
                    np.ascontiguousarray(d, float), np.ones(len(o)),
                    np.arange(len(o), dtype=np.int64), 0, len(o), out)
    return out[:, 0]


def test_rays_through_edges_and_vertices_of_a_closed_cube_cross_it_an_even_number_of_times():
    cube = make_box("c", (2.0, 2.0, 2.0))
    tris = cube.vertices[cube.triangles]
    # rays aimed at vertices, edge midpoints and face-diagonal midpoints of the
    # cube, from many dyadic directions, and rays lying in face planes (grazing)
    targets = np.array([(x, y, z) for x in (-1.0, 0.0, 1.0) for y in (-1.0, 0.0, 1.0)
                        for z in (-1.0, 0.0, 1.0) if (x, y, z) != (0.0, 0.0, 0.0)])
    dirs = np.array([(1.0, 0.5, 0.25), (-0.5, 1.0, 0.0), (0.0, 0.0, 1.0), (1.0, 1.0, 1.0),
                     (0.125, -1.0, 0.5), (1.0, 0.0, 0.0)])
    o = (targets[:, None, :] - 4.0 * dirs[None]).reshape(-1, 3)
    d = np.broadcast_to(8.0 * dirs[None], (len(targets), len(dirs), 3)).reshape(-1, 3)
    out = count_hits(tris, o, d)
    assert set(np.unique(out)) <= {0, 2}
    assert (out == 2).sum() > len(o) // 3 and (out == 0).any()
    # the signed count (+1 entering through a face whose normal faces the ray's
    # origin, -1 leaving) returns to 0: what a stencil needs
    n = np.cross(tris[:, 1] - tris[:, 0], tris[:, 2] - tris[:, 0])
    for k in range(len(o)):
        assert count_hits(tris, o[k:k + 1], d[k:k + 1], np.where(n @ d[k] < 0, 1, -1))[0] == 0


def test_light_in_a_face_plane():
    # the light lies in the plane of the cube's top face (y = 1.5) and of its side
    # x = 0.5: those faces are edge-on to every shadow segment and never block; the
    # shadow is the cube's, checked against a slab test away from its outline
    lo, hi = np.array([-0.5, 0.5, -0.5]), np.array([0.5, 1.5, 0.5])
    cube = make_box("c", (1.0, 1.0, 1.0), position=(0.0, 1.0, 0.0))
    floor = make_box("f", (10.0, 0.2, 10.0), position=(0.0, -0.1, 0.0), casts=False)
    cam = Camera(fovy=450, near=1.0, far=30.0, eye=(-4.0, 9.0, 6.0), target=(0.0, 0.0, 0.0))
    for lp in ((0.5, 1.5, 3.0), (0.5, 1.5 + 1e-7, 3.0), (0.5 - 1e-7, 1.5, 3.0)):
        sc = Scene(objects=(floor, cube), lights=(PointLight("l", lp, (1, 1, 1)),),
                   lmodel=LightModel(), camera=cam)
        r = raycast(sc, 64, 64)
        again = raycast(sc, 64, 64)
        assert np.array_equal(r.lit, again.lit) and np.array_equal(r.crossings, again.crossings)
        fl = r.object_id == 0
        p = r.point[fl]
        dd = np.asarray(lp) - p
        with np.errstate(divide="ignore", invalid="ignore"):
            t1, t2 = (lo - p) / dd, (hi - p) / dd
        tn = np.nanmax(np.minimum(t1, t2), axis=1)
        tf = np.nanmin(np.maximum(t1, t2), axis=1)
        blocked = (tn < tf) & (tf > 0) & (tn < 1)
        clear = (tf - tn > 1e-3) | (tf < tn - 1e-3)
        assert blocked[clear].sum() > 10
        assert np.array_equal(r.lit[fl, 0][clear], ~blocked[clear])
        # the point counts agree with the faces the renderer would draw
        hit = r.hit
        inner = np.zeros_like(hit)
        inner[fl] = clear
        assert np.array_equal(r.crossings[inner, 0], r.occluders[inner, 0])


def test_directional_light_is_the_limit_of_far_point_lights():
    sc = random_scene(7)
    direction = np.array([0.3, 1.0, -0.2])
    empty = [(np.zeros((0, 3, 3)), np.zeros(0, np.int64))]
    sun = dataclasses.replace(sc, lights=(DirectionalLight("sun", (*direction, 0.0)),))
    r = raycast(sun, 48, 40, faces=empty)
    assert r.lit[r.hit].any() and not r.lit[r.hit].all()
    prev = None
    for k in (3, 6, 9):
        far = dataclasses.replace(sc, lights=(PointLight(
            "far", tuple(direction / np.linalg.norm(direction) * 10.0 ** k), (1, 1, 1)),))
        rf = raycast(far, 48, 40, faces=empty)
        diff = int((rf.lit != r.lit).sum())
        if prev is not None:
            assert diff <= prev
        prev = diff
    assert prev <= 2
    # w = 0 given as a 4-vector or as light.w
    assert np.array_equal(light_position(DirectionalLight("s", (0.0, 2.0, 0.0, 0.0))),
                          [0.0, 2.0, 0.0, 0.0])
    assert np.array_equal(light_position(PointLight("p", (1.0, 2.0, 3.0), (1, 1, 1))),
                          [1.0, 2.0, 3.0, 1.0])


def test_faces_extruded_to_infinity_count_as_long_finite_ones():
    # w = 0 vertices (Everitt and Kilgard's extrusion to infinity): the same crossings
    # as faces 1e4 long for every eye ray ending on the scene
    sc = default_scene()
    faces_inf, faces_long = [], []
    for li, light in enumerate(sc.lights):
        long_sc = dataclasses.replace(sc, volume_length=1e4)
        quads, ingoing = shadow_faces(long_sc, li, "silhouette")
        lp = np.asarray(light.position)
        v1, v2 = quads[:, 0], quads[:, 1]
        inf = np.zeros(quads.shape[:2] + (4,))
        inf[:, 0, :3], inf[:, 0, 3] = v1, 1.0
        inf[:, 1, :3], inf[:, 1, 3] = v2, 1.0
        inf[:, 2, :3] = v2 - lp  # w = 0: the direction away from the light
        inf[:, 3, :3] = v1 - lp
        sign = np.where(np.concatenate([ingoing, ingoing]), 1, -1)
        faces_inf.append((np.concatenate([inf[:, [0, 1, 2]], inf[:, [0, 2, 3]]]), sign))
        faces_long.append((np.concatenate([quads[:, [0, 1, 2]], quads[:, [0, 2, 3]]]), sign))
    a = raycast(sc, W, H, faces=faces_inf)
    b = raycast(sc, W, H, faces=faces_long)
    assert np.array_equal(a.crossings[a.hit], b.crossings[b.hit])
    assert a.crossings.max() > 0


def test_eye_inside_a_volume_offsets_crossings_by_the_eye_count():
    # shadow_literature.md H1: the eye below the floating cube, in its red shadow.
    # z-pass counts from the near plane, so crossings = layers - eye_layers where the
    # near-plane rectangle lies in the same volumes as the eye.
    sc = default_scene()
    cube3 = sc.objects[3]
    lp = np.asarray(sc.lights[0].position)
    centre = cube3.vertices.mean(axis=0)
    eye = centre + 0.55 * (centre - lp) / np.linalg.norm(centre - lp) * 2.0
    cam = Camera(fovy=300, near=0.05, far=40.0, eye=tuple(eye), target=(0.0, 0.0, 0.0))
    inside = dataclasses.replace(sc, camera=cam)
    r = raycast(inside, 48, 40)
    assert r.eye_layers[0] == 1
    hit = r.hit
    diff = r.crossings[..., 0][hit] - (r.layers[..., 0][hit] - r.eye_layers[0])
    assert (diff == 0).mean() > 0.99
    # the classic z-pass failure: where the floor is lit, the count says -1
    assert (r.crossings[..., 0][hit & r.lit[..., 0]] == -1).mean() > 0.99


def test_degenerate_triangles_are_never_hit_and_bad_input_is_refused():
    tris = np.array([[[0, 0, 0], [1, 0, 0], [2, 0, 0]],      # collinear
                     [[0, 0, 0], [0, 0, 0], [0, 1, 0]],      # repeated vertex
                     [[0, 0, 0], [1, 0, 0], [0, 1, 0]]], float)
    assert usable_triangles(homogeneous(tris)).tolist() == [False, False, True]
    o = np.array([[0.5, 0.0, 1.0], [0.1, 0.1, 1.0], [1.5, 0.0, -1.0]])
    d = np.array([[0.0, 0.0, -2.0], [0.0, 0.0, -2.0], [0.0, 0.0, 2.0]])
    idx, t = nearest_hit(o, d, tris)
    assert idx.tolist() == [2, 2, -1]  # the ray along a degenerate one's line misses it
    with pytest.raises(ValueError, match="finite"):
        homogeneous(np.full((1, 3, 3), np.nan))
    with pytest.raises(ValueError, match="w < 0"):
        homogeneous(np.array([[[0, 0, 0, 1], [1, 0, 0, 1], [0, 1, 0, -1.0]]]))
    with pytest.raises(ValueError, match="non-zero direction"):
        light_position(DirectionalLight("s", (0.0, 0.0, 0.0, 0.0)))


@pytest.mark.parametrize("subpixel", [False, True])
def test_snapped_vertices_land_on_the_rasterizer_grid(subpixel):
    sc = default_scene()
    w, h = 160, 128
    mvp = sc.camera.modelview() @ sc.camera.projection(w / h)
    tris, _ = sc.triangles()
    snapped = snap_to_window(homogeneous(tris), mvp, w, h, subpixel)
    clip = snapped.reshape(-1, 4) @ mvp
    xw = -0.5 + (clip[:, 0] / clip[:, 3] + 1) * w / 2
    yw = -0.5 + (clip[:, 1] / clip[:, 3] + 1) * h / 2
    step = 1.0 / 256 if subpixel else 1.0
    for c in (xw, yw):
        assert np.allclose(c / step, np.round(c / step), atol=1e-6)
    orig = homogeneous(tris).reshape(-1, 4) @ mvp
    xo = -0.5 + (orig[:, 0] / orig[:, 3] + 1) * w / 2
    assert np.abs(xw - xo).max() <= step / 2 + 1e-6  # nearest grid point
    assert np.allclose(clip[:, 2] / clip[:, 3], orig[:, 2] / orig[:, 3])  # depth kept
    # the snapped cast agrees with the unsnapped one except near outlines
    r0 = raycast(sc, w, h)
    r1 = raycast(sc, w, h, subpixel=subpixel)
    assert (r0.object_id != r1.object_id).mean() < 0.03


def test_snapping_brings_the_reference_closer_to_the_subpixel_false_stencil():
    # subpixel(FALSE), the article's default, moves vertices by up to half a pixel;
    # the snapped cast sees the triangles the rasterizer draws (clipped, snapped,
    # covered by its tie rule), so far fewer stencil counts disagree with it than
    # with the exact cast (measured at 160 x 128: red 54 -> 3, blue 38 -> 4 pixels;
    # the rest lie on the floating cube next to its own silhouette edges, where the
    # shadow face and the cube's face meet at equal depth: 24-bit z ties, which the
    # float64 reference does not model)
    from vgxsim.examples import heidmann1991 as h91
    from vgxsim.gl._core import current, session

    w, h = 160, 128
    planes = {}

    def hook(i):
        ctx = current("test")
        ctx.flush()
        planes[i] = ctx.fb.stencil.astype(int) - h91.MYZERO

    session.reset()
    try:
        h91.render(w, h, subpixel_mode=False, stencil_hook=hook)
    finally:
        session.reset()
    sc = default_scene()
    exact = raycast(sc, w, h)
    snapped = raycast(sc, w, h, subpixel=False)
    for li in (0, 1):
        off_exact = int((planes[li] != exact.crossings[..., li]).sum())
        off_snapped = int((planes[li] != snapped.crossings[..., li]).sum())
        assert 5 * off_snapped < off_exact, (li, off_snapped, off_exact)


def test_shade_lights_only_what_the_cast_says_is_lit(scene, result):
    img = shade(scene, result)
    assert img.shape == (H, W, 4) and img.dtype == np.uint8
    assert np.all(img[~result.hit][:, :3] == 0) and np.all(img[..., 3] == 255)
    # against the same cast with every light unblocked: identical where both lights
    # reach, darker on the floor (which faces both lights) where one is blocked
    bright = shade(scene, dataclasses.replace(result, lit=result.hit[..., None]
                                              & np.ones_like(result.lit)))
    both = result.lit.all(axis=2)
    assert np.array_equal(img[both], bright[both])
    shadowed = (result.object_id == 0) & ~both
    assert shadowed.sum() > 50
    assert np.all(img[shadowed][:, :3].astype(int).sum(1)
                  < bright[shadowed][:, :3].astype(int).sum(1))
    # a directional light shades too
    sun = dataclasses.replace(scene, lights=(DirectionalLight("sun", (0.0, 1.0, 0.0, 0.0)),))
    r = raycast(sun, W, H, faces=[(np.zeros((0, 3, 3)), np.zeros(0, np.int64))])
    top = shade(sun, r)
    assert top[r.hit & r.lit[..., 0]][:, :3].astype(int).sum(1).min() > 0


def test_a_scene_moved_far_from_the_origin_keeps_its_shadows():
    # shadow_literature.md H11: everything moved by ~2^20 (the move itself rounds
    # the coordinates to 2^-32): the same pixels away from outlines and shadow edges
    sc = default_scene()
    shift = np.array([2.0 ** 20, -(2.0 ** 20), 2.0 ** 19])

    def moved(o):
        return dataclasses.replace(o, vertices=o.vertices + shift)

    cam = sc.camera
    far_sc = dataclasses.replace(
        sc, objects=tuple(moved(o) for o in sc.objects),
        lights=tuple(dataclasses.replace(li, position=tuple(np.add(li.position, shift)))
                     for li in sc.lights),
        camera=dataclasses.replace(cam, eye=tuple(np.add(cam.eye, shift)),
                                   target=tuple(np.add(cam.target, shift))))
    a = raycast(sc, W, H)
    b = raycast(far_sc, W, H)
    classes = np.where(a.hit, a.object_id * 4 + a.lit[..., 0] + 2 * a.lit[..., 1], -1)
    from vgxsim.shadow.error import near_boundary

    inner = ~near_boundary(classes)
    assert inner.mean() > 0.8
    assert np.array_equal(a.object_id[inner], b.object_id[inner])
    assert np.array_equal(a.lit[inner], b.lit[inner])
    assert np.array_equal(a.crossings[inner], b.crossings[inner])


def test_tile_order_reads_square_tiles_in_row_order():
    from vgxsim.shadow.raycast import tile_order

    # 5 x 3 pixels, tiles of 2: (0,1 | 5,6), (2,3 | 7,8), (4 | 9), then the top row
    assert tile_order(5, 3, 2).tolist() == [0, 1, 5, 6, 2, 3, 7, 8, 4, 9, 10, 11, 12, 13, 14]
    assert tile_order(5, 3, 1).tolist() == list(range(15))
    big = tile_order(37, 23, 16)
    assert np.array_equal(np.sort(big), np.arange(37 * 23))


def test_signed_box_test_equals_the_general_one():
    """The per-ray sign choice of slab planes (kernels/raycast.py _box_signed) gives
    the general test's answer and entry parameter, infinite bounds included."""
    import numba

    from vgxsim.kernels.raycast import _box, _box_signed
    from vgxsim.kernels.raycast import _ray_boxes as _helper

    @numba.njit(cache=False)
    def _ray_boxes(dx, dy, dz):  # a kernel helper is called from compiled code only
        return _helper(dx, dy, dz)

    rng = np.random.default_rng(4)
    nodes = np.zeros((400, 8))
    lo = rng.uniform(-2, 2, (400, 3))
    nodes[:, :3] = lo
    nodes[:, 3:6] = lo + rng.uniform(0, 1.5, (400, 3))
    nodes[:, :3][rng.random((400, 3)) < 0.1] = -np.inf  # unbounded boxes
    nodes[:, 3:6][rng.random((400, 3)) < 0.1] = np.inf
    agree = hits = 0
    for _ in range(300):
        o = rng.uniform(-3, 3, 3)
        d = rng.normal(size=3) * rng.choice([1e-3, 1.0, 1e3])
        ix, iy, iz, nx, ny, nz, signed = _ray_boxes(*d)
        assert signed
        for k in range(0, 400, 7):
            a = _box(nodes, k, *o, *d, ix, iy, iz, 0.0, 1.0)
            b = _box_signed(nodes, k, *o, ix, iy, iz, nx, ny, nz, 0.0, 1.0)
            assert a[0] == b[0] and (not a[0] or a[1] == b[1])
            agree += 1
            hits += a[0]
    assert 0 < hits < agree
    assert not _ray_boxes(1.0, 0.0, 2.0)[-1]  # a zero component takes the general test
