"""Soft shadows (Heidmann 1991, Figure 6): jittered lights through the accumulation
buffer equal the average of the separately rendered hard-shadow images."""

import numpy as np

from vgxsim.examples.heidmann1991 import render
from vgxsim.examples.soft_shadows import jitter_offsets, jittered_scene, render_soft
from vgxsim.shadow.scene import default_scene


def test_offsets_stay_inside_the_jitter_cube_and_repeat():
    a = jitter_offsets(32, 0.6)
    assert a.shape == (32, 3)
    assert np.all(np.abs(a) <= 0.3)
    assert np.array_equal(a, jitter_offsets(32, 0.6))
    assert len({tuple(r) for r in a}) == 32


def test_accumulated_image_is_the_average_of_the_hard_images():
    w, h, n = 96, 80, 4
    soft = render_soft(w, h, images=n, jitter=0.8).astype(np.int64)
    base = default_scene()
    hard = [render(w, h, scene=jittered_scene(base, off)).astype(np.int64)
            for off in jitter_offsets(n, 0.8)]
    # acbuf keeps the exact integer sum; AC_RETURN rounds sum / n once.
    expect = np.floor(np.sum(hard, axis=0)[..., :3] / n + 0.5)
    assert np.abs(soft[..., :3] - expect).max() <= 1
    # Penumbrae exist: some pixels lie strictly between the darkest and brightest
    # of the hard images (lit in some, shadowed in others).
    lo = np.min(hard, axis=0)[..., :3]
    hi = np.max(hard, axis=0)[..., :3]
    penumbra = ((soft[..., :3] > lo + 2) & (soft[..., :3] < hi - 2)).any(axis=2)
    assert penumbra.sum() > 20
