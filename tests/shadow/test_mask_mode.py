""""Show Mask" counts ins and outs apart (README of the original: "the stencil value
is accumulated differently, effectively counting the times gone in and the times
gone out, not just the running total").

The stencil after one light's shadow faces, top half ins and bottom half outs
(vgxsim.shadow.program.mask_fields), against the exact ray cast counting the
ingoing faces and the outgoing faces apart (vgxsim/shadow/raycast.py with ``faces``:
each list counted with weight +1), on the default scene with subpixel on (the ray
cast snaps the faces as the rasterizer does), away from count boundaries.
"""

from __future__ import annotations

import numpy as np
import pytest

from vgxsim.gl._core import session
from vgxsim.shadow.api import render
from vgxsim.shadow.error import near_boundary
from vgxsim.shadow.program import (
    MASK_BLUE,
    MASK_BLUEGREEN,
    MASK_MAGENTA,
    SILHOUETTE_YELLOW,
    mask_fields,
)
from vgxsim.shadow.raycast import raycast
from vgxsim.shadow.scene import default_scene, shadow_faces

W, H = 160, 128


@pytest.fixture(autouse=True)
def _fresh_session():
    session.reset()
    yield
    session.reset()


def _counts(scene, light: int, ingoing_wanted: bool) -> np.ndarray:
    """(H, W) crossings of the light's ingoing (or outgoing) faces, image order."""
    quads, ingoing = shadow_faces(scene, light)
    q = quads[ingoing == ingoing_wanted]
    tris = np.concatenate([q[:, [0, 1, 2]], q[:, [0, 2, 3]]])
    empty = (np.zeros((0, 3, 3)), np.zeros(0, np.int64))
    faces = [empty] * len(scene.lights)
    faces[light] = (tris, np.ones(len(tris), np.int64))
    r = raycast(scene, W, H, faces=faces, subpixel=True, counts=False)
    return r.crossings[::-1, :, light], r.hit[::-1]


def test_mask_layout_is_two_halves():
    assert mask_fields(8) == (4, 0xF)
    assert mask_fields(2) == (1, 1)


@pytest.mark.parametrize("light", [0, 1])
def test_ins_and_outs_match_the_ray_cast_counts(light):
    scene = default_scene()
    frame = render(scene, mode="mask", size=(W, H), light=light, subpixel=True)
    shift, field = mask_fields(8)
    st = frame.stencil[0].astype(int)
    got_in, got_out = (st >> shift) & field, st & field
    ins, hit = _counts(scene, light, True)
    outs, _ = _counts(scene, light, False)
    assert ins.max() < field and outs.max() < field  # no overflow on this scene
    far = ~near_boundary(ins) & ~near_boundary(outs) & hit
    assert far.mean() > 0.5
    assert np.array_equal(got_in[far], ins[far])
    assert np.array_equal(got_out[far], outs[far])
    # both counts are exercised, and separately: some pixels cross faces both ways
    assert (ins[far] > 0).sum() > 100 and (outs[far] > 0).sum() > 100
    assert ((ins[far] > 0) & (ins[far] == outs[far])).sum() > 20
    # the colours follow the counts: in - out = 0 (some face), 1, 2; clear elsewhere
    p = np.ascontiguousarray(frame.colour).view("<u4").reshape(H, W)
    objects = render(scene, mode="objects", size=(W, H), subpixel=True).colour
    objects = np.ascontiguousarray(objects).view("<u4").reshape(H, W)
    diff = ins - outs
    want = np.where((diff == 0) & (ins > 0), MASK_MAGENTA,
                    np.where(diff == 1, MASK_BLUE, np.where(diff == 2, MASK_BLUEGREEN, 0)))
    painted = want != 0
    silhouette = p == SILHOUETTE_YELLOW  # the silhouette lines drawn over the mask
    ok = far & ~silhouette
    assert np.array_equal(p[ok & painted], want[ok & painted])
    assert np.array_equal(p[ok & ~painted], objects[ok & ~painted])  # "clear"
    assert (ok & painted & (diff == 0)).sum() > 20 and (ok & painted & (diff == 1)).sum() > 100
