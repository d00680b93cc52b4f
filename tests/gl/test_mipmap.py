"""MIPMAP minification filters (texdef(3G)) against hand-computed texels.

A 16 x 16 checkerboard of 2 x 2-texel squares (black and white) over a 16 x 16
window; the texgen plane s = k (x + 1/2) / 16 (likewise t) makes every pixel step k
texels of level 0, so rho = k and the level of detail is log2(k) everywhere
(docs/numeric_model.md s. 14).  By the box filter, level 1 (8 x 8) is the
one-texel checkerboard (each 2 x 2 box lies in one square) and level 2 (4 x 4) is
uniform grey (0 + 255 + 255 + 0 + 2) // 4 = 128.
"""

import functools
import math

import numpy as np
import pytest

from vgxsim import GL
from vgxsim.gl import bgnpolygon, endpolygon, v3f
from vgxsim.gl._texture import tevbind, tevdef, texbind, texdef2d, texgen
from vgxsim.state.textures import mipmap_pyramid

N = 16
_sq = (np.add.outer(np.arange(N) // 2, np.arange(N) // 2) % 2) * 255
CHECKER = np.repeat(_sq[..., None], 4, axis=2).astype(np.uint8)
CHECKER[..., 3] = 255
LEVEL1 = (np.add.outer(np.arange(8), np.arange(8)) % 2) * 255  # by hand, see above


@pytest.fixture
def win(gl_window):
    return functools.partial(gl_window, N, N)


def draw(ctx, minfilter, k, magfilter=GL.TX_POINT):
    props = (GL.TX_MINFILTER, minfilter, GL.TX_MAGFILTER, magfilter, GL.TX_NULL)
    texdef2d(1, 4, N, N, CHECKER, len(props), props)
    tevdef(1, 1, (GL.TV_NULL,))
    texbind(GL.TX_TEXTURE_0, 1)
    tevbind(GL.TV_ENV0, 1)
    texgen(GL.TX_S, GL.TG_LINEAR, (k / N, 0.0, 0.0, 0.5 * k / N))
    texgen(GL.TX_T, GL.TG_LINEAR, (0.0, k / N, 0.0, 0.5 * k / N))
    texgen(GL.TX_S, GL.TG_ON, None)
    texgen(GL.TX_T, GL.TG_ON, None)
    ctx.colour = (1.0, 1.0, 1.0, 1.0)
    bgnpolygon()
    for x, y in ((0, 0), (N, 0), (N, N), (0, N)):
        v3f((x, y, 0))
    endpolygon()
    ctx.flush()
    return ctx.read_rgba()[:, :, 0].astype(int)  # grey: red is enough


def test_box_filter_pyramid_by_hand():
    levels = mipmap_pyramid(CHECKER)
    assert [lv.shape[:2] for lv in levels] == [(8, 8), (4, 4), (2, 2), (1, 1)]
    assert np.array_equal(levels[0][..., 0], LEVEL1)
    assert (levels[1][..., :3] == 128).all() and (levels[1][..., 3] == 255).all()
    # odd and thin sizes: the last column is dropped, a 1-texel side pairs with itself
    img = np.zeros((1, 3, 4), np.uint8)
    img[0, :, 0] = (10, 21, 200)
    (lv,) = mipmap_pyramid(img)
    assert lv.shape == (1, 1, 4) and lv[0, 0, 0] == (10 + 21 + 10 + 21 + 2) // 4


@pytest.mark.parametrize("fil", [GL.TX_MIPMAP_POINT, GL.TX_MIPMAP_BILINEAR,
                                 GL.TX_MIPMAP_LINEAR, GL.TX_MIPMAP_TRILINEAR, GL.TX_MIPMAP])
def test_level_one_at_lod_one_and_grey_at_lod_two(win, fil):
    """k = 2: lambda = 1 exactly, level 1 alone (the linear filters' fraction is 0);
    pixel x samples u1 = 8 s = x + 1/2, the centre of level-1 texel x, so point and
    bilinear agree.  k = 4: lambda = 2, level 2, grey."""
    img = draw(win(), fil, 2)
    assert np.array_equal(img[:8, :8], LEVEL1)
    assert np.array_equal(img[8:, 8:], LEVEL1)  # repeat
    assert (draw(win(), fil, 4) == 128).all()


def test_magnification_keeps_level_zero(win):
    """k = 1: rho = 1 is not minification (rho^2 > 1 is): the magnification filter on
    level 0, the checkerboard itself."""
    assert np.array_equal(draw(win(), GL.TX_MIPMAP_POINT, 1), CHECKER[..., 0])


def test_nearest_level_rounds_lambda_half_down(win):
    """MIPMAP_POINT takes level ceil(lambda + 1/2) - 1: lambda = log2(1.3) = 0.38 is
    level 0, lambda = log2(1.6) = 0.68 level 1 (point samples of level 0 / level 1 at
    u = k (x + 1/2) / 16 * size)."""
    for k, level in ((1.3, 0), (1.6, 1)):
        img = draw(win(), GL.TX_MIPMAP_POINT, k)
        size = N >> level
        want = [[255 * ((((math.floor(k * (x + 0.5) / N * size) % size) >> (1 - level))
                         + ((math.floor(k * (y + 0.5) / N * size) % size) >> (1 - level))) % 2)
                 for x in range(N)] for y in range(N)]
        assert np.array_equal(img, want), k


def test_linear_mixes_the_two_levels_by_the_fraction(win):
    """MIPMAP_LINEAR at lambda = 1.5 (k = 2^1.5): half level 1 (point), half level 2
    (grey 128); the fragment colour is white, so the result is that mix, rounded."""
    k = 2 ** 1.5
    img = draw(win(), GL.TX_MIPMAP_LINEAR, k)
    rho = N * (k / N)  # du/dx of the plane, in level-0 texels per pixel
    f = 0.5 * math.log2(rho * rho) - 1  # 1/2 up to rounding (k^2 is 8 + 2e-15)
    assert f == pytest.approx(0.5)
    for y in range(N):
        for x in range(N):
            i = math.floor(k * (x + 0.5) / N * 8) % 8
            j = math.floor(k * (y + 0.5) / N * 8) % 8
            want = math.floor(((1 - f) * LEVEL1[j, i] + f * 128) * 255 / 255 + 0.5)
            assert img[y, x] == want, (x, y)
