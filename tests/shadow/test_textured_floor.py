"""The shipped textured_floor scene shows its TEXTURE (README: mapped onto the x-z
plane in object space with texgen; tex_sparams, tex_tparams in program.py).

Each pass's colour is modulated by the texture (TV_MODULATE), so on the floor the
textured colour over the untextured one is a texel value / 255: between the
image's dark (90, 70, 60) and light (200, 190, 160) texels, bilinear mixes between.
"""

from dataclasses import replace

import numpy as np

from vgxsim.shadow.api import load_scene, render

DARK, LIGHT = np.array([90, 70, 60]), np.array([200, 190, 160])


def test_textured_floor_modulates_the_floor_by_its_texels():
    scene = load_scene("textured_floor")
    assert scene.objects[0].texture is not None
    plain = replace(scene, objects=[replace(o, texture=None) for o in scene.objects])
    size = (96, 72)
    got = render(scene, size=size, mode="objects").colour[..., :3].astype(float)
    base = render(plain, size=size, mode="objects").colour[..., :3].astype(float)
    changed = np.any(got != base, axis=2)
    assert changed.sum() > 0.2 * size[0] * size[1]  # the floor is textured
    bright = changed & (base.min(axis=2) > 60)  # enough colour for a ratio to mean much
    ratio = got[bright] / base[bright]
    tol = 1.5 / base[bright]  # two roundings of up to 1/2 each, and one more for safety
    assert (ratio >= DARK / 255 - tol).all() and (ratio <= LIGHT / 255 + tol).all()
    # both kinds of stripe are on the floor
    assert (np.abs(ratio - DARK / 255) < tol + 0.01).all(axis=1).any()
    assert (np.abs(ratio - LIGHT / 255) < tol + 0.01).all(axis=1).any()
