"""Soft shadows' shared ambient pass (``accumulate(share_ambient=True)``): the jittered
frames put the first frame's ambient picture back instead of drawing it again, and the
accumulated image, its z and every running average are those of drawing every frame
whole; scenes where a light's ambient term depends on where it is are not shared."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from vgxsim.gl._core import session
from vgxsim.shadow import program as prog_mod
from vgxsim.shadow.api import load_scene, render
from vgxsim.shadow.program import Shadows, ambient_pass_shareable
from vgxsim.shadow.scene import default_scene

W, H = 96, 80


@pytest.fixture(autouse=True)
def _fresh_session():
    session.reset()
    yield
    session.reset()


def _soft(scene, share: bool, **kw):
    averages = []
    frame = render(scene, size=(W, H), soft=5, share_ambient=share,
                   on_soft_frame=lambda n, img: averages.append(img), **kw)
    return frame, averages


@pytest.mark.parametrize("name,signs", [(None, "screen"), (None, "article"),
                                        ("textured_floor", "screen")])
def test_shared_ambient_pass_gives_the_pixels_of_whole_frames(name, signs, monkeypatch):
    scene = load_scene(name)
    drawn = []
    real = Shadows.DrawObjects

    def counting(self, matl):
        drawn.append(matl)
        return real(self, matl)

    monkeypatch.setattr(Shadows, "DrawObjects", counting)
    shared, shared_avg = _soft(scene, True, signs=signs)
    ambient_passes = drawn.count(prog_mod.matl_emitambient)
    drawn.clear()
    whole, whole_avg = _soft(scene, False, signs=signs)
    assert ambient_passes == 1 and drawn.count(prog_mod.matl_emitambient) == 5
    assert np.array_equal(shared.colour, whole.colour)
    assert np.array_equal(shared.depth, whole.depth)
    assert len(shared_avg) == len(whole_avg) == 5
    for n, (a, b) in enumerate(zip(shared_avg, whole_avg, strict=True), start=1):
        assert np.array_equal(a, b), f"running average of {n} frames differs"
    # soft: the jitter moved the shadows, the average is not one of the frames
    assert not np.array_equal(shared_avg[0], shared_avg[-1])


def test_attenuation_or_a_spot_cone_keeps_every_ambient_pass():
    scene = default_scene()
    assert ambient_pass_shareable(Shadows(scene))
    attenuated = replace(scene, lmodel=replace(scene.lmodel, attenuation=(1.0, 0.2)))
    assert not ambient_pass_shareable(Shadows(attenuated))
    spot = replace(scene, lights=(replace(scene.lights[0], spot_direction=(0.0, -1.0, 0.0),
                                          spot=(2.0, 40.0)), *scene.lights[1:]))
    assert not ambient_pass_shareable(Shadows(spot))
    assert not ambient_pass_shareable(Shadows(scene, mode="objects"))
    assert not ambient_pass_shareable(Shadows(scene, effective_zclear=True))
