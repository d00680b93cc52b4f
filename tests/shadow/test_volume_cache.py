"""The shadow-volume cache of the shadows program (``cache_volumes``): frames drawn
with it are the frames drawn without it -- colour, z and every light's stencil, bit
for bit -- while the light stays, moves (the cache must notice) and comes back, and
for soft shadows, whose lights move every frame; and with it on, a frame with nothing
moved computes no shadow face again."""

from __future__ import annotations

import numpy as np
import pytest

from vgxsim.gl import finish, prefsize, read_pixels, swapbuffers, winclose, winopen
from vgxsim.gl._core import session
from vgxsim.shadow import program as prog_mod
from vgxsim.shadow.api import render
from vgxsim.shadow.program import Shadows, jittered_lights
from vgxsim.shadow.scene import default_scene

W, H = 96, 80


@pytest.fixture(autouse=True)
def _fresh_session():
    session.reset()
    yield
    session.reset()


def _frames(cache: bool, signs: str, edges: str) -> list[tuple[np.ndarray, ...]]:
    """Planes after each frame: the light still, moved, back, still again."""
    scene = default_scene()
    moved = jittered_lights(scene, [[0.3, -0.2, 0.25], [-0.4, 0.1, 0.0]])
    stencils: dict[int, np.ndarray] = {}
    prog = Shadows(scene, signs=signs, edges=edges, cache_volumes=cache,
                   stencil_hook=lambda i: stencils.__setitem__(
                       i, read_pixels("back", "stencil")))
    prefsize(W, H)
    gid = winopen("cache")
    out = []
    try:
        prog.setup()
        for sc in (scene, scene, moved, scene, scene):
            prog.scene = sc
            prog.define_lighting()
            stencils.clear()
            prog.DrawFrame()
            swapbuffers()
            finish()
            out.append((read_pixels("front"), read_pixels("front", "z"),
                        *(stencils[i] for i in sorted(stencils))))
    finally:
        prog.teardown()
        winclose(gid)
    return out


@pytest.mark.parametrize("signs,edges", [("screen", "silhouette"), ("article", "silhouette"),
                                         ("article", "all")])
def test_cached_volumes_give_the_planes_of_immediate_ones(signs, edges):
    cached, immediate = _frames(True, signs, edges), _frames(False, signs, edges)
    assert len(cached) == len(immediate) == 5
    for k, (a, b) in enumerate(zip(cached, immediate, strict=True)):
        assert len(a) == len(b) == 4  # colour, z, the stencil of each of the two lights
        for plane, (x, y) in zip(("colour", "z", "stencil 0", "stencil 1"), zip(a, b,
                                                                              strict=True),
                                 strict=True):
            assert np.array_equal(x, y), f"frame {k}: {plane} differs"
    # the frames are not all one picture: the moved light casts other shadows
    assert not np.array_equal(cached[2][2], cached[0][2])
    assert np.array_equal(cached[3][2], cached[0][2])


def test_soft_shadows_are_the_same_with_and_without_the_cache():
    a = render(size=(W, H), soft=4, cache_volumes=True)
    b = render(size=(W, H), soft=4, cache_volumes=False)
    assert np.array_equal(a.colour, b.colour) and np.array_equal(a.depth, b.depth)


def test_a_still_frame_computes_no_faces_and_a_moved_light_does(monkeypatch):
    calls = []
    real = prog_mod.shadow_faces

    def counting(scene, i, edges):
        calls.append(i)
        return real(scene, i, edges)

    monkeypatch.setattr(prog_mod, "shadow_faces", counting)
    scene = default_scene()
    prog = Shadows(scene, signs="screen")
    prefsize(W, H)
    gid = winopen("cache")
    try:
        prog.setup()
        prog.DrawFrame()
        assert calls == [0, 1]
        prog.DrawFrame()
        assert calls == [0, 1]  # nothing moved: the faces and their objects are kept
        prog.scene = jittered_lights(scene, [[0.0, 0.0, 0.0], [0.5, 0.0, 0.0]])
        prog.define_lighting()
        prog.DrawFrame()
        assert calls == [0, 1, 1]  # only light 1 moved
        objects = {name for _, name in prog._face_objects.values()}
        assert len(objects) == 2 and objects <= set(session.objects)
        prog.teardown()
        assert not objects & set(session.objects)  # the face objects are deleted
    finally:
        winclose(gid)
