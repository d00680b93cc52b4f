"""Texture calls of vgxsim.gl (_texture.py) against hand-computed texels.

The window maps object x, y to pixel centres (ortho2(-0.5, W - 0.5, ...)); texgen
planes s = (x + 0.5) / 4, t = (y + 0.5) / 4 put a 2 x 2 texture over pixels 0..3,
so pixel centre X samples u = s * 2 = (X + 0.5) / 2 (docs/numeric_model.md s. 13).
"""

import functools

import numpy as np
import pytest

from vgxsim import GL
from vgxsim.gl._core import GLValueError, window_of
from vgxsim.gl._texture import tevbind, tevdef, texbind, texdef2d, texgen

W = H = 8
RED, GREEN, BLUE, WHITE = (255, 0, 0, 255), (0, 255, 0, 255), (0, 0, 255, 255), (255,) * 4
# Row 0 is the bottom row (t near 0): texel (i, j) = IMAGE[j, i].
IMAGE = np.array([[RED, GREEN], [BLUE, WHITE]], np.uint8)


@pytest.fixture
def win(gl_window):
    return functools.partial(gl_window, W, H)


def textured(ctx, props=(GL.TX_NULL,), env=(GL.TV_MODULATE, GL.TV_NULL), image=IMAGE,
             colour=(1.0, 1.0, 1.0, 1.0)):
    texdef2d(1, image.shape[2], image.shape[1], image.shape[0], image, len(props), props)
    tevdef(1, len(env), env)
    texbind(GL.TX_TEXTURE_0, 1)
    tevbind(GL.TV_ENV0, 1)
    texgen(GL.TX_S, GL.TG_LINEAR, (0.25, 0.0, 0.0, 0.125))
    texgen(GL.TX_T, GL.TG_LINEAR, (0.0, 0.25, 0.0, 0.125))
    texgen(GL.TX_S, GL.TG_ON, None)
    texgen(GL.TX_T, GL.TG_ON, None)
    ctx.colour = colour
    # Vertices on pixel centres (subpixel off snaps them there, numeric_model s. 2);
    # the tie rule gives pixels 0..3.
    ctx.draw_arrays("polygon", np.array([[0, 0, 0], [4, 0, 0], [4, 4, 0], [0, 4, 0]], float))
    ctx.flush()
    return ctx.read_rgba().astype(int)


def test_point_sampling_gives_the_texel_under_each_pixel_centre(win):
    img = textured(win())
    for y in range(4):
        for x in range(4):
            assert tuple(img[y, x]) == tuple(IMAGE[y // 2, x // 2]), (x, y)
    assert tuple(img[5, 5]) == (0, 0, 0, 0)  # outside the square: untouched


def test_bilinear_repeat_weights_the_four_nearest_texel_centres(win):
    img = textured(win(), (GL.TX_MINFILTER, GL.TX_BILINEAR, GL.TX_MAGFILTER, GL.TX_BILINEAR,
                           GL.TX_NULL))
    # Pixel (0, 0): u = v = 0.25, so u - 1/2 = -0.25: texels -1 (wrapped to 1) and 0
    # with weights 0.25 and 0.75 on each axis.  Red: red 0.5625 + white 0.0625.
    r = round(0.625 * 255)
    g = round((0.0625 + 0.1875) * 255)  # white + green
    assert tuple(img[0, 0]) == (r, g, g, 255)
    # Pixel (1, 1): u = v = 0.75: texels 0 and 1 at 0.75 / 0.25 weights: symmetric.
    assert tuple(img[1, 1]) == (159, 64, 64, 255)


def test_bilinear_clamp_stays_on_the_edge_texel(win):
    img = textured(win(), (GL.TX_MINFILTER, GL.TX_BILINEAR, GL.TX_MAGFILTER, GL.TX_BILINEAR,
                           GL.TX_WRAP, GL.TX_CLAMP, GL.TX_NULL))
    assert tuple(img[0, 0]) == RED  # both neighbours clamp to texel (0, 0)
    assert tuple(img[3, 3]) == WHITE


def test_modulate_multiplies_the_fragment_colour(win):
    img = textured(win(), colour=(0.5, 1.0, 1.0, 1.0))
    # floor(0.5 * 255 + 0.5) = 128 first (the fragment colour), then 128 * 255 / 255.
    assert tuple(img[0, 0]) == (128, 0, 0, 255)
    assert tuple(img[3, 3]) == (128, 255, 255, 255)


def test_decal_and_blend_environments(win):
    half = IMAGE.copy()
    half[..., 3] = 51  # alpha 0.2
    img = textured(win(), env=(GL.TV_DECAL, GL.TV_NULL), image=half,
                   colour=(0.0, 0.0, 1.0, 1.0))
    # decal: c = cf (1 - at) + ct at: red texel over blue: (51, 0, 204), fragment alpha.
    assert tuple(img[0, 0]) == (51, 0, 204, 255)
    img = textured(win(), env=(GL.TV_BLEND, GL.TV_COLOR, 0.0, 1.0, 0.0, 1.0, GL.TV_NULL),
                   colour=(0.0, 0.0, 1.0, 1.0))
    # blend: c = cf (1 - ct) + cc ct: red texel, blue fragment, green TV_COLOR.
    assert tuple(img[0, 0]) == (0, 0, 255, 255)
    # green texel: cc replaces green, the fragment keeps its blue (texel blue 0).
    assert tuple(img[0, 3]) == (0, 255, 255, 255)


def test_texturing_needs_a_texture_and_an_environment(win):
    ctx = win()
    textured(ctx)
    tevbind(GL.TV_ENV0, 0)
    assert ctx.raster.snapshot().texture == 0
    tevbind(GL.TV_ENV0, 1)
    assert ctx.raster.snapshot().texture != 0


def test_unmodelled_texture_state_is_refused_naming_the_call(win):
    win()
    with pytest.raises(GLValueError, match="texdef2d.*MIPMAP.*minification"):
        texdef2d(1, 4, 2, 2, IMAGE, 3, (GL.TX_MAGFILTER, GL.TX_MIPMAP_BILINEAR, GL.TX_NULL))
    with pytest.raises(GLValueError, match="texgen.*not modelled"):
        texgen(GL.TX_S, GL.TG_REFRACTMAP, None)
    with pytest.raises(GLValueError, match="texbind.*not defined"):
        texbind(GL.TX_TEXTURE_0, 7)
    with pytest.raises(GLValueError, match="texdef2d.*shape"):
        texdef2d(1, 4, 3, 2, IMAGE, 1, (GL.TX_NULL,))


def test_packed_words_are_read_in_the_c_layout(win):
    ctx = win()
    # nc = 4: one word per texel, bytes A B G R most significant first (cpack order).
    words = [0xFF0000FF, 0xFF00FF00, 0xFFFF0000, 0xFFFFFFFF]
    texdef2d(2, 4, 2, 2, words, 1, (GL.TX_NULL,))
    assert np.array_equal(window_of(ctx).texture.textures[2].texels, IMAGE)


def test_t2f_coordinates_are_carried_per_vertex(win):
    """Without texgen each vertex takes the t2f sent before it: (0,0)..(1,1) over
    the square is the same mapping as the texgen planes above (vertex x / 4)."""
    from vgxsim.gl._draw import bgnpolygon, endpolygon, t2f, v3f

    ctx = win()
    texdef2d(1, 4, 2, 2, IMAGE, 1, (GL.TX_NULL,))
    tevdef(1, 1, (GL.TV_NULL,))  # the default environment: TV_MODULATE
    texbind(GL.TX_TEXTURE_0, 1)
    tevbind(GL.TV_ENV0, 1)
    ctx.colour = (1.0, 1.0, 1.0, 1.0)
    bgnpolygon()
    for x, y in ((0, 0), (4, 0), (4, 4), (0, 4)):
        t2f((x / 4 + 0.125, y / 4 + 0.125))
        v3f((x, y, 0))
    endpolygon()
    ctx.flush()
    img = ctx.read_rgba().astype(int)
    for y in range(4):
        for x in range(4):
            assert tuple(img[y, x]) == tuple(IMAGE[y // 2, x // 2]), (x, y)


def test_t2f_in_a_display_object_is_carried_too(win):
    from vgxsim.gl._draw import bgnpolygon, endpolygon, t2f, v3f
    from vgxsim.gl._objects import callobj, closeobj, makeobj

    ctx = win()
    texdef2d(1, 4, 2, 2, IMAGE, 1, (GL.TX_NULL,))
    tevdef(1, 1, (GL.TV_NULL,))
    makeobj(5)
    bgnpolygon()
    for x, y in ((0, 0), (4, 0), (4, 4), (0, 4)):
        t2f((x / 4 + 0.125, y / 4 + 0.125))
        v3f((x, y, 0))
    endpolygon()
    closeobj()
    texbind(GL.TX_TEXTURE_0, 1)
    tevbind(GL.TV_ENV0, 1)
    ctx.colour = (1.0, 1.0, 1.0, 1.0)
    callobj(5)
    ctx.flush()
    img = ctx.read_rgba().astype(int)
    assert tuple(img[0, 0]) == RED and tuple(img[3, 3]) == WHITE
    assert tuple(img[0, 3]) == GREEN and tuple(img[3, 0]) == BLUE


def test_an_sgi_image_written_and_read_back_textures_the_square(win, tmp_path):
    """SGI .rgb through Pillow (vgxsim.formats.sgi): rows come back top first, so the
    texture is the image flipped (texdef2d's row 0 is the bottom row)."""
    from vgxsim.formats.sgi import read_rgb, write_rgb

    path = tmp_path / "t.rgb"
    write_rgb(path, IMAGE[::-1])  # a file shows the top row first
    image = read_rgb(path)[::-1]
    img = textured(win(), image=np.ascontiguousarray(image))
    assert tuple(img[0, 0]) == RED and tuple(img[3, 3]) == WHITE
