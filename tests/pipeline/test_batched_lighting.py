"""Lighting the groups of a flush together (draw.shade_groups, ``BATCH_LIGHTING``)
gives the colours of one lighting pass per group.

``shade_runs`` is checked against ``shade`` run by run on random materials, lights
and lighting models (exact equality: the equation is evaluated vertex by vertex),
and the switch is checked on the 1991 shadow frame (lit floor and objects, one
material each, per light pass) and on the random IRIS GL call sequences of
tests/stream (lighting on and off, lmcolor, materials between primitives).
"""

import numpy as np
import pytest
from stream.random_calls import SEEDS, render, sequence

from vgxsim.gl._core import session
from vgxsim.lighting import Light, LightModel, Material, shade, shade_runs
from vgxsim.pipeline import draw


def _material(rng):
    return Material(emission=tuple(rng.random(3) * 0.2), ambient=tuple(rng.random(3)),
                    diffuse=tuple(rng.random(3)), specular=tuple(rng.random(3)),
                    shininess=float(rng.choice([0.0, 0.5, 1.0, 7.0, 60.0])),
                    alpha=float(rng.random()))


def test_shade_runs_gives_each_run_the_colours_shade_gives_it():
    rng = np.random.default_rng(11)
    for _ in range(20):
        nruns = int(rng.integers(1, 6))
        counts = rng.integers(0, 30, nruns)
        n = int(counts.sum())
        pos = rng.normal(size=(n, 3)) * 5
        nrm = rng.normal(size=(n, 3))
        nrm[rng.random(n) < 0.05] = 0.0  # zero normals: emission and ambient only
        lights = []
        for _ in range(int(rng.integers(0, 4))):
            w = float(rng.choice([0.0, 1.0]))
            light = Light(ambient=tuple(rng.random(3) * 0.3), lcolor=tuple(rng.random(3)),
                          position=(*rng.normal(size=3), w),
                          spot_direction=tuple(rng.normal(size=3)),
                          spot_spread=float(rng.choice([180.0, 30.0])),
                          spot_exponent=float(rng.choice([0.0, 2.0])))
            lights.append((light, np.array(light.position), np.array(light.spot_direction)))
        lmodel = LightModel(ambient=tuple(rng.random(3) * 0.3),
                            local_viewer=bool(rng.random() < 0.5),
                            attenuation=(1.0, float(rng.random() * 0.1)),
                            attenuation2=float(rng.random() * 0.01))
        mats = [_material(rng) for _ in range(nruns)]
        got = shade_runs(pos, nrm, mats, counts, lights, lmodel)
        at = 0
        for m, c in zip(mats, counts, strict=True):
            want = shade(pos[at:at + c], nrm[at:at + c], m, lights, lmodel)
            np.testing.assert_array_equal(got[at:at + c], want)
            at += c


def _heidmann(monkeypatch, batched: bool):
    from vgxsim.examples import heidmann1991 as h91
    from vgxsim.gl._core import current

    monkeypatch.setattr(draw, "BATCH_LIGHTING", batched)
    monkeypatch.setattr(draw, "FLUSH_FRONT", False)  # the group path, which this counts
    calls = [0]
    real = draw.shade_object_runs
    monkeypatch.setattr(draw, "shade_object_runs",
                        lambda *a: (calls.__setitem__(0, calls[0] + 1), real(*a))[1])
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
    return img, planes, calls[0]


def test_batched_lighting_gives_the_same_heidmann_frame(monkeypatch):
    want_img, want, none = _heidmann(monkeypatch, False)
    img, got, batched = _heidmann(monkeypatch, True)
    assert none == 0 and batched > 0  # the switch really selects the path
    np.testing.assert_array_equal(img, want_img)
    assert got.keys() == want.keys()
    for light in want:
        np.testing.assert_array_equal(got[light][0], want[light][0])
        np.testing.assert_array_equal(got[light][1], want[light][1])


@pytest.mark.parametrize("seed", list(SEEDS)[:8])
def test_batched_lighting_switch_gives_identical_planes_on_random_calls(seed, monkeypatch):
    calls = sequence(seed)
    session.reset()
    a = render(calls)
    monkeypatch.setattr(draw, "BATCH_LIGHTING", False)
    session.reset()
    b = render(calls)
    session.reset()
    for k in a:
        assert np.array_equal(a[k], b[k]), k
