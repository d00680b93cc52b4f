"""The texture stage of the band kernels against the naive reference, bit for bit.

Random textures (1-4 components, 1..5 texels a side, point or bilinear, repeat or
clamp, each environment) on random triangles with random perspective (1/w per
vertex), drawn through every rasterizer path; the naive reference implements
docs/numeric_model.md section 13 on its own, in Python floats.
"""

import numpy as np
import pytest
from kernel_helpers import assert_planes_equal, full_state, render_kernels, render_naive

from vgxsim.state import codes as C
from vgxsim.state.textures import TexEnv, TexGen, Texture, binding_id, mipmap_pyramid

W = H = 24
MODES = ("span", "general", "edge")


def _binding(rng, mipmap=False):
    nc = int(rng.integers(1, 5))
    h, w = (int(v) for v in rng.integers(1, 10 if mipmap else 6, size=2))
    texels = rng.integers(0, 256, size=(h, w, 4)).astype(np.uint8)
    if nc <= 2:
        texels[..., 1] = texels[..., 2] = texels[..., 0]
    if nc in (1, 3):
        texels[..., 3] = 255
    if mipmap:
        tex = Texture(texels, nc, int(rng.integers(C.TEXF_MIPMAP_POINT,
                                                   C.TEXF_MIPMAP_TRILINEAR + 1)),
                      int(rng.integers(0, 2)), int(rng.integers(0, 2)), int(rng.integers(0, 2)),
                      mipmap_pyramid(texels))
    else:
        tex = Texture(texels, nc, int(rng.integers(0, 2)), int(rng.integers(0, 2)),
                      int(rng.integers(0, 2)), int(rng.integers(0, 2)))
    env = TexEnv(int(rng.integers(0, 3)), tuple(float(v) for v in rng.random(4)))
    return binding_id(tex, env, TexGen())


def _scene(rng, mipmap=False):
    cmds = []
    for _ in range(int(rng.integers(1, 6))):
        rs = full_state(W, H, texture=_binding(rng, mipmap), subpixel=bool(rng.integers(0, 2)),
                        shademodel=int(rng.integers(0, 2)),
                        blend_sf=int(rng.choice([C.BF_ONE, C.BF_SA])),
                        blend_df=int(rng.choice([C.BF_ZERO, C.BF_MSA])))
        for _ in range(int(rng.integers(1, 4))):
            verts = []
            for _ in range(3):
                q = float(rng.uniform(0.2, 2.0))
                st = rng.uniform(-3.0, 3.0, size=2) * q * (4.0 if mipmap else 1.0)
                verts.append((float(rng.uniform(-4, W + 4)), float(rng.uniform(-4, H + 4)),
                              float(rng.uniform(-1000, 1000)),
                              tuple(float(c) for c in rng.random(4)),
                              (float(st[0]), float(st[1]), q)))
            cmds.append(("triangle", verts, rs))
    return cmds


@pytest.mark.parametrize("seed", range(12))
def test_random_textured_triangles_match_naive(seed):
    rng = np.random.default_rng(seed)
    cmds = _scene(rng)
    cfg = dict(double=False, zbits=24, stencil=8)
    want = render_naive(cmds, W, H, **cfg)
    for mode in MODES:
        got = render_kernels(cmds, W, H, mode=mode, **cfg)
        assert_planes_equal(got, want, f"seed={seed} mode={mode}")
    # The texture stage ran: the same triangles untextured give other colours.
    plain = [(k, [v[:4] for v in verts], full_state(W, H, subpixel=rs.subpixel,
                                                    shademodel=rs.shademodel,
                                                    blend_sf=rs.blend_sf,
                                                    blend_df=rs.blend_df))
             for k, verts, rs in cmds]
    assert not np.array_equal(render_naive(plain, W, H, **cfg)["front"], want["front"])


@pytest.mark.parametrize("seed", range(8))
def test_random_mipmapped_triangles_match_naive(seed):
    """The MIPMAP filters: level of detail per fragment, levels from the naive
    reference's own box filter (texture coordinates spread 4x wider, so that most
    fragments minify, through several levels)."""
    rng = np.random.default_rng(1000 + seed)
    cmds = _scene(rng, mipmap=True)
    cfg = dict(double=False, zbits=24, stencil=8)
    want = render_naive(cmds, W, H, **cfg)
    for mode in MODES:
        assert_planes_equal(render_kernels(cmds, W, H, mode=mode, **cfg), want,
                            f"seed={seed} mode={mode}")
    # The pyramid was read: the same textures with TX_POINT minification differ.
    flat = [(k, verts, full_state(W, H, texture=_without_mipmaps(rs.texture),
                                  subpixel=rs.subpixel, shademodel=rs.shademodel,
                                  blend_sf=rs.blend_sf, blend_df=rs.blend_df))
            for k, verts, rs in cmds]
    assert not np.array_equal(render_naive(flat, W, H, **cfg)["front"], want["front"])


def _without_mipmaps(ident):
    from dataclasses import replace

    from vgxsim.state.textures import binding

    b = binding(ident)
    return binding_id(replace(b.texture, minfilter=C.TEXF_POINT, levels=()), b.env, b.texgen)


def test_untextured_state_ignores_texture_coordinates():
    """A state without a texture draws as before even when coordinates are given."""
    rng = np.random.default_rng(99)
    cmds = _scene(rng)
    plain = [(k, [v[:4] for v in verts], full_state(W, H)) for k, verts, _ in cmds]
    cfg = dict(double=False, zbits=24, stencil=8)
    with_tex = [(k, verts, full_state(W, H)) for k, verts, _ in cmds]
    assert_planes_equal(render_kernels(with_tex, W, H, **cfg),
                        render_naive(plain, W, H, **cfg))
