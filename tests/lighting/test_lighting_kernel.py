"""The lighting kernel (kernels/lighting.py, ``JIT_LIGHTING``) against the numpy form
of the equation, and the switch on whole frames.

The kernel evaluates the numpy form's arithmetic in the same order, vertex by
vertex; numpy's SIMD ``power`` and ``einsum`` may round the last bit of a
product sum or a power differently from libm's ``pow`` and a sequential sum, so the
colours are compared to 1e-12 (far below the 1/255 of a colour step), and the planes
of whole frames exactly.
"""

import numpy as np
import pytest
from stream.random_calls import SEEDS, render, sequence

from vgxsim.gl._core import session
from vgxsim.lighting import Light, LightModel, Material, equation, shade, shade_runs


def _scene(rng):
    n = int(rng.integers(1, 200))
    pos = rng.normal(size=(n, 3)) * 5
    nrm = rng.normal(size=(n, 3))
    nrm[rng.random(n) < 0.05] = 0.0  # zero normals: emission and ambient only
    lights = []
    for _ in range(int(rng.integers(0, 4))):
        w = float(rng.choice([0.0, 1.0, 2.5]))
        light = Light(ambient=tuple(rng.random(3) * 0.3), lcolor=tuple(rng.random(3)),
                      position=(*rng.normal(size=3), w),
                      spot_direction=tuple(rng.normal(size=3)),
                      spot_spread=float(rng.choice([180.0, 30.0, 90.0])),
                      spot_exponent=float(rng.choice([0.0, 2.0, 0.5, 13.0])))
        entry = (light, np.array(light.position), np.array(light.spot_direction))
        lights.append(entry if rng.random() < 0.8 else (light, None, None))
    lmodel = LightModel(ambient=tuple(rng.random(3) * 0.3),
                        local_viewer=bool(rng.random() < 0.5),
                        attenuation=(float(rng.choice([1.0, 0.0])), float(rng.random() * 0.1)),
                        attenuation2=float(rng.random() * 0.01))
    mat = Material(emission=tuple(rng.random(3) * 0.2), ambient=tuple(rng.random(3)),
                   diffuse=tuple(rng.random(3)), specular=tuple(rng.random(3)),
                   shininess=float(rng.choice([0.0, 0.5, 1.0, 7.0, 60.0, 128.0])),
                   alpha=float(rng.random() * 1.2))
    return pos, nrm, mat, lights, lmodel


def _both(monkeypatch, fn, *args, **kwargs):
    monkeypatch.setattr(equation, "JIT_LIGHTING", True)
    fast = fn(*args, **kwargs)
    monkeypatch.setattr(equation, "JIT_LIGHTING", False)
    slow = fn(*args, **kwargs)
    monkeypatch.setattr(equation, "JIT_LIGHTING", True)
    return fast, slow


def test_kernel_gives_the_numpy_colours(monkeypatch):
    rng = np.random.default_rng(1991)
    for _ in range(60):
        pos, nrm, mat, lights, lmodel = _scene(rng)
        fast, slow = _both(monkeypatch, shade, pos, nrm, mat, lights, lmodel)
        assert fast.shape == slow.shape == (pos.shape[0], 4)
        np.testing.assert_allclose(fast, slow, rtol=0, atol=1e-12)


def test_kernel_gives_the_numpy_colours_with_overrides_and_two_sides(monkeypatch):
    rng = np.random.default_rng(7)
    for mode in range(7):
        pos, nrm, mat, lights, lmodel = _scene(rng)
        lmodel = LightModel(ambient=lmodel.ambient, local_viewer=lmodel.local_viewer,
                            attenuation=lmodel.attenuation, twoside=True)
        back = Material(diffuse=(0.1, 0.9, 0.2), specular=(0.5, 0.5, 0.5), shininess=9.0)
        rgba = rng.random((pos.shape[0], 4))
        facing = rng.random(pos.shape[0]) < 0.5
        fast, slow = _both(monkeypatch, shade, pos, nrm, mat, lights, lmodel,
                           back_material=back, facing=facing, color_override=(mode, rgba))
        np.testing.assert_allclose(fast, slow, rtol=0, atol=1e-12)


def test_kernel_runs_give_the_numpy_runs(monkeypatch):
    rng = np.random.default_rng(3)
    pos, nrm, mat, lights, lmodel = _scene(rng)
    mats = [mat, Material(), Material(specular=(1.0, 1.0, 1.0), shininess=30.0)]
    n = pos.shape[0]
    counts = [n // 3, n // 3, n - 2 * (n // 3)]
    fast, slow = _both(monkeypatch, shade_runs, pos, nrm, mats, counts, lights,
                       lmodel)
    np.testing.assert_allclose(fast, slow, rtol=0, atol=1e-12)


def test_kernel_hand_computed_directional_light():
    # One directional light straight above a vertex with normal +z, viewer at
    # infinity: N.L = 1, H = (0, 0, 1), N.H = 1.  rgb = emission + ambient * scene
    # ambient + ambient * light ambient + diffuse * lcolor + specular * lcolor.
    mat = Material(emission=(0.1, 0.0, 0.0), ambient=(0.5, 0.5, 0.5),
                   diffuse=(0.25, 0.5, 0.0), specular=(0.0, 0.125, 0.25), shininess=10.0,
                   alpha=0.75)
    light = Light(ambient=(0.2, 0.2, 0.2), lcolor=(1.0, 0.5, 1.0), position=(0.0, 0.0, 3.0, 0.0))
    lmodel = LightModel(ambient=(0.2, 0.4, 0.0))
    got = shade(np.zeros((1, 3)), np.array([[0.0, 0.0, 2.0]]), mat, [(light, None, None)],
                lmodel)
    want = [0.1 + 0.1 + 0.1 + 0.25, 0.2 + 0.1 + 0.25 + 0.0625, 0.0 + 0.1 + 0.0 + 0.25, 0.75]
    np.testing.assert_allclose(got[0], want, rtol=0, atol=1e-15)


def _heidmann():
    from vgxsim.examples import heidmann1991 as h91
    from vgxsim.gl._core import current

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


def test_switch_gives_the_same_heidmann_frame(monkeypatch):
    img, got = _heidmann()
    monkeypatch.setattr(equation, "JIT_LIGHTING", False)
    want_img, want = _heidmann()
    np.testing.assert_array_equal(img, want_img)
    for light in want:
        np.testing.assert_array_equal(got[light][0], want[light][0])
        np.testing.assert_array_equal(got[light][1], want[light][1])


@pytest.mark.parametrize("seed", list(SEEDS)[:8])
def test_switch_gives_identical_planes_on_random_calls(seed, monkeypatch):
    calls = sequence(seed)
    session.reset()
    a = render(calls)
    monkeypatch.setattr(equation, "JIT_LIGHTING", False)
    session.reset()
    b = render(calls)
    session.reset()
    for k in a:
        assert np.array_equal(a[k], b[k]), k


def test_object_runs_light_what_eye_space_and_shade_give(monkeypatch):
    # Independent expectation: each run's lit vertices taken to eye space by numpy
    # (p @ M, divided by w), normals by the normal matrix, lit by shade() with that
    # run's material; unlit vertices keep their colour.
    from vgxsim.lighting import shade_object_runs

    rng = np.random.default_rng(12)
    pos, nrm, _mat, lights, lmodel = _scene(rng)
    n = pos.shape[0]
    obj = np.concatenate([pos, rng.choice([1.0, 2.0], (n, 1))], axis=1)
    cols = rng.random((n, 4))
    lit = rng.random(n) < 0.7
    counts = [n // 2, n - n // 2]
    mvs = [np.eye(4), np.eye(4) * 0.5 + np.diag([0.0, 0.0, 0.0, 0.5])]
    mvs[1][3, :3] = (1.0, -2.0, 0.5)
    nms = [np.eye(3), np.array([[0.0, 1.0, 0.0], [-1.0, 0.0, 0.0], [0.0, 0.0, 2.0]])]
    mats = [Material(), Material(diffuse=(0.2, 0.4, 0.9), specular=(1.0, 1.0, 1.0),
                                 shininess=20.0)]
    want = cols.copy()
    at = 0
    for k, c in enumerate(counts):
        sel = np.zeros(n, bool)
        sel[at:at + c] = lit[at:at + c]
        eye = obj[sel] @ mvs[k]
        want[sel] = shade(eye[:, :3] / eye[:, 3:4], nrm[sel] @ nms[k], mats[k], lights, lmodel)
        at += c
    fast, slow = _both(monkeypatch, shade_object_runs, obj, nrm, cols, lit, counts, mvs, nms,
                       mats, lights, lmodel)
    np.testing.assert_allclose(fast, want, rtol=0, atol=1e-12)
    np.testing.assert_allclose(slow, want, rtol=0, atol=1e-12)
