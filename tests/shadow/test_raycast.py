"""The float64 ray-cast reference (the shadow oracle) checked against geometry."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from vgxsim.shadow import Camera, PointLight, Scene, default_scene, make_box
from vgxsim.shadow.raycast import intersect, nearest_hit, pixel_rays, raycast
from vgxsim.shadow.scene import LightModel

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
