"""MIPMAP filters of vgxsim against Mesa (llvmpipe) with the same texture state.

A floor in strong perspective (1/w from 2 at the near edge to 0.08 at the far one)
over a 64 x 48 window, with a random 32 x 32 texture repeated 8 times across it, so
that the level of detail runs from magnification to the 1 x 1 level.  The pyramid
is vgxsim's (uploaded level by level: vgxsim/reference/mesa_texture.py), so only the
level choice and the filters are compared.  The vertex colour is white (modulate).

OpenGL lets an implementation approximate the level of detail; llvmpipe takes one
per 2 x 2 quad, where vgxsim takes the exact derivatives per fragment
(docs/numeric_model.md s. 14).  Far up the floor the level of detail grows by 0.3
to 1 per row, so where it crosses a level switch (k + 1/2 for the nearest level) a
quad's shared value picks another level for one of its rows: the differences are
short runs of pixels along rows there (a texel's worth of colour); elsewhere the
two agree to the filters' rounding.  Measured (Mesa 22.3 llvmpipe, 4 seeds, the
worst of them):

* NEAREST_MIPMAP_NEAREST (TX_MIPMAP_POINT, mag TX_POINT): identical on 95.5% of
  the covered pixels, within 8 on 96.3%, mean difference 0.99;
* LINEAR_MIPMAP_LINEAR (TX_MIPMAP_TRILINEAR, mag TX_BILINEAR): within 2 on 96.0%,
  within 8 on 99.9%, mean difference 0.84.

The thresholds below sit a little under those.  The floor point-sampled from level
0 (no mipmaps) is much farther from Mesa's image, so the comparison sees the
mipmaps.
"""

from __future__ import annotations

import numpy as np
import pytest

from vgxsim.batch import CommandBatch
from vgxsim.reference import mesa
from vgxsim.state import codes as C
from vgxsim.state.planes import Framebuffer, PlaneConfig
from vgxsim.state.raster import RasterState
from vgxsim.state.textures import TexEnv, TexGen, Texture, binding_id, mipmap_pyramid

if not mesa.mesa_available():
    pytest.skip("OSMesa + PyOpenGL not available", allow_module_level=True)

pytestmark = pytest.mark.mesa

W, H = 64, 48
WHITE = (1.0, 1.0, 1.0, 1.0)


def _floor():
    """Two triangles, (s/w, t/w, 1/w) per vertex: near edge at the bottom."""
    corners = [(-0.4, -0.3), (W - 0.3, -0.2), (W * 0.62, H - 0.6), (W * 0.38, H - 0.4)]
    # turned by 0.2 rad and offset, so that no row or column of pixels runs along a
    # texel edge (where float32 and float64 coordinates may pick different texels)
    c, sn = np.cos(0.2), np.sin(0.2)
    st = [(0.0137 + c * a - sn * b, 0.0291 + sn * a + c * b)
          for a, b in ((0.0, 0.0), (8.0, 0.0), (8.0, 8.0), (0.0, 8.0))]
    q = [2.0, 2.0, 0.08, 0.08]
    verts = [(x, y, 0.0, WHITE, (s * qq, t * qq, qq))
             for (x, y), (s, t), qq in zip(corners, st, q, strict=True)]
    return [verts[0], verts[1], verts[2]], [verts[0], verts[2], verts[3]]


def _state(texels, minf, magf, levels=True):
    tex = Texture(texels, 4, minf, magf, C.TEXW_REPEAT, C.TEXW_REPEAT,
                  mipmap_pyramid(texels) if levels else ())
    return RasterState(scissor=(0, W - 1, 0, H - 1),
                       texture=binding_id(tex, TexEnv(C.TEV_MODULATE), TexGen()))


def _vgxsim(tris, rs):
    fb = Framebuffer(PlaneConfig(W, H, double=False, zbits=24, stencil=8))
    batch = CommandBatch(fb)
    for verts in tris:
        xyz = np.array([v[:3] for v in verts], np.float64)
        col = np.array([v[3] for v in verts], np.float64)
        tex = np.array([v[4] for v in verts], np.float64)
        batch.add_window_triangles(xyz[:, 0], xyz[:, 1], xyz[:, 2], col,
                                   np.array([[0, 1, 2]]), rs, tex=tex)
    batch.flush()
    return fb.front.view(np.uint8).reshape(H, W, 4).astype(int)


@pytest.fixture(scope="module")
def peer():
    p = mesa.MesaPeer(W, H)
    yield p
    p.close()


def _mesa(peer, tris, rs):
    clear = RasterState(scissor=(0, W - 1, 0, H - 1))
    peer.render([("clear", {"color", "z", "stencil"}, {"color": 0, "z": 0x7FFFFF,
                                                      "stencil": 0}, clear)]
                + [("triangle", verts, rs) for verts in tris])
    return peer.color().view(np.uint8).reshape(H, W, 4).astype(int)


# case: min and mag filter; (tolerance, fraction within it) twice; mean difference
CASES = {"nearest_mipmap_nearest": (C.TEXF_MIPMAP_POINT, C.TEXF_POINT, 0, 0.93, 8, 0.95, 1.5),
         "linear_mipmap_linear": (C.TEXF_MIPMAP_TRILINEAR, C.TEXF_BILINEAR, 2, 0.94, 8, 0.995,
                                  1.2)}


@pytest.mark.parametrize("case", sorted(CASES))
@pytest.mark.parametrize("seed", range(4))
def test_mipmapped_floor_matches_mesa(peer, case, seed):
    minf, magf, tol1, frac1, tol2, frac2, mean = CASES[case]
    rng = np.random.default_rng(seed)
    texels = rng.integers(0, 256, size=(32, 32, 4)).astype(np.uint8)
    texels[..., 3] = 255
    tris = _floor()
    rs = _state(texels, minf, magf)
    got = _vgxsim(tris, rs)
    want = _mesa(peer, tris, rs)
    covered = want[..., 3] > 0
    assert covered.mean() > 0.5
    diff = np.abs(got - want).max(axis=-1)[covered]
    assert (diff <= tol1).mean() >= frac1, np.bincount(diff)
    assert (diff <= tol2).mean() >= frac2, np.bincount(diff)
    assert diff.mean() <= mean
    # the mipmaps are what both drew: level 0 point-sampled is far from Mesa's image
    plain = _vgxsim(tris, _state(texels, C.TEXF_POINT, magf, levels=False))
    far = np.abs(plain - want).max(axis=-1)[covered]
    assert far.mean() > 3 * diff.mean() + 5
