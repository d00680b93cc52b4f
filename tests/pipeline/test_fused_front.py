"""The fused geometry front end (kernels/front.py, ``FUSED_FRONT``) changes no plane.

Random scenes are drawn through the array path with the switch on and off: triangles
crossing the near and far planes, the guard band and user clip planes (clipping),
vertices at w = 0
and non-finite ones, culling, flat and Gouraud shading, colour written or not, on one
thread and on two with chunks small enough that every call is split; and the 1991
shadow frame (its shadow faces change stencil() between polygons, so one pass sets
up triangles of several states).  Colour, z and stencil must be identical.
"""

import numpy as np
import pytest

from vgxsim import batch as batch_mod
from vgxsim import threads
from vgxsim.geometry import pipeline as geometry
from vgxsim.geometry.transform import perspective
from vgxsim.pipeline.context import Context
from vgxsim.state.raster import FLAT, GOURAUD

W, H = 96, 72


def _scene(rng):
    """Random triangle soup: (obj (N, 3), colours (N, 4), indices (T, 3), state)."""
    n = int(rng.integers(20, 300))
    centre = rng.uniform([-8, -8, -30], [8, 8, 2], (n, 1, 3))
    size = rng.choice([0.3, 2.0, 40.0, 4000.0], (n, 1, 1))  # small .. guard band
    obj = (centre + rng.normal(size=(n, 3, 3)) * size).reshape(-1, 3)
    special = rng.random(obj.shape[0])
    obj[special < 0.01] = [0.0, 0.0, 0.0]  # the eye: w = 0 after the projection
    obj[(special > 0.01) & (special < 0.015), 1] = np.nan
    col = rng.random((obj.shape[0], 4))
    tris = np.arange(obj.shape[0]).reshape(-1, 3)
    if rng.random() < 0.5:  # shared vertices: a vertex used by several triangles
        tris = rng.integers(0, obj.shape[0], (n, 3))
    state = dict(zbuffer=bool(rng.random() < 0.8),
                 shademodel=FLAT if rng.random() < 0.3 else GOURAUD,
                 backface=bool(rng.random() < 0.3), frontface=bool(rng.random() < 0.2),
                 subpixel=bool(rng.random() < 0.5),
                 wmpack=0xFFFFFFFF if rng.random() < 0.8 else 0)
    planes = rng.normal(size=(int(rng.choice([0, 0, 1, 3])), 4))  # clipplane(3G), eye space
    return obj, col, tris, state, planes


def _draw(scene, fused: bool, monkeypatch):
    obj, col, tris, state, planes = scene
    monkeypatch.setattr(geometry, "FUSED_FRONT", fused)
    ctx = Context(W, H, rgb=True, double=False)
    ctx.matrices.load_projection(perspective(700, W / H, 0.5, 25.0))
    ctx.raster.set(**state)
    ctx.user_planes = planes
    ctx.draw_arrays("triangles", obj, col, indices=tris)
    ctx.flush()
    return ctx.fb.front.copy(), ctx.fb.z.copy()


@pytest.mark.parametrize("nthreads", [1, 2])
def test_fused_front_end_gives_identical_planes_on_random_scenes(monkeypatch, nthreads):
    monkeypatch.setattr(batch_mod, "PARALLEL_FRONT", 8)  # split every call into chunks
    threads.set_threads(nthreads)
    try:
        rng = np.random.default_rng(7)
        drawn = 0
        for i in range(25):
            scene = _scene(rng)
            want = _draw(scene, False, monkeypatch)
            got = _draw(scene, True, monkeypatch)
            for name, a, b in zip(("colour", "z"), got, want, strict=True):
                np.testing.assert_array_equal(a, b, err_msg=f"scene {i}: {name}")
            drawn += bool(want[0].any())
        assert drawn > 10  # the scenes really draw something
    finally:
        threads.set_threads(None)


def test_fused_front_end_clips_like_the_stage_by_stage_passes(monkeypatch):
    """One triangle through the near plane: both paths draw the clipped part only."""
    obj = np.array([[-3.0, -2.0, -5.0], [3.0, -2.0, -5.0], [0.0, 3.0, 5.0]])
    col = np.array([[1.0, 0, 0, 1], [0, 1.0, 0, 1], [0, 0, 1.0, 1]])
    scene = (obj, col, np.array([[0, 1, 2]]), dict(zbuffer=True), np.zeros((0, 4)))
    want = _draw(scene, False, monkeypatch)
    got = _draw(scene, True, monkeypatch)
    assert 0 < np.count_nonzero(want[0]) < W * H
    np.testing.assert_array_equal(got[0], want[0])
    np.testing.assert_array_equal(got[1], want[1])


def _heidmann(monkeypatch, fused: bool):
    from vgxsim.examples import heidmann1991 as h91
    from vgxsim.gl._core import current, session

    monkeypatch.setattr(geometry, "FUSED_FRONT", fused)
    session.reset()
    planes = {}

    def hook(i):
        ctx = current("test")
        ctx.flush()
        planes[i] = (ctx.fb.stencil.copy(), ctx.fb.z.copy())

    try:
        img = h91.render(320, 256, stencil_hook=hook)
    finally:
        session.reset()
    return img, planes


def test_fused_front_end_gives_the_same_heidmann_frame(monkeypatch):
    want_img, want = _heidmann(monkeypatch, False)
    img, got = _heidmann(monkeypatch, True)
    assert want and got.keys() == want.keys()
    np.testing.assert_array_equal(img, want_img)
    for light in want:
        np.testing.assert_array_equal(got[light][0], want[light][0])
        np.testing.assert_array_equal(got[light][1], want[light][1])
