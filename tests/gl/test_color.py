"""Colour calls of vgxsim.gl (_color.py): current colour, cmode indices, colour map."""

import functools

import numpy as np
import pytest

from vgxsim import GL
from vgxsim.gl import _core
from vgxsim.gl._color import *
from vgxsim.gl._core import GLTypeError, GLUsageError, GLValueError

W = H = 4


@pytest.fixture
def win(gl_window):
    """Factory: a current W x H single-buffered window (RGB unless rgb=False)."""
    return functools.partial(gl_window, W, H)


def fill(ctx):
    """Draw the whole window with the current colour."""
    ctx.draw_arrays("polygon", np.array([[0, 0, 0], [W, 0, 0], [W, H, 0], [0, H, 0]], float))
    ctx.flush()


# -- RGBmode -------------------------------------------------------------------------
def test_cpack_is_abgr_and_written_exactly(win):
    ctx = win()
    cpack(0x80402010)
    assert ctx.colour == (0x10 / 255, 0x20 / 255, 0x40 / 255, 0x80 / 255)
    assert ctx.last_sent == "colour"
    fill(ctx)
    assert np.all(ctx.fb.front == 0x80402010)
    assert gRGBcolor() == (0x10, 0x20, 0x40)
    cpack(0x1FFFFFFFF)  # unsigned long: reduced modulo 2**32
    assert gRGBcolor() == (255, 255, 255)


def test_rgbcolor_and_integer_forms_saturate(win):
    ctx = win()
    RGBcolor(10, 300, -5)
    assert gRGBcolor() == (10, 255, 0) and ctx.colour[3] == 1.0
    c3i((1, 2, 3))
    assert gRGBcolor() == (1, 2, 3) and ctx.colour[3] == 1.0
    c4i(4, 5, 6, 7)
    fill(ctx)
    assert tuple(ctx.read_rgba()[0, 0]) == (4, 5, 6, 7)
    c3s(256, 0, 128)
    assert gRGBcolor() == (255, 0, 128)
    c4s((9, 8, 7, 600))
    assert ctx.colour[3] == 1.0
    with pytest.raises(GLTypeError):
        c3i(1.0, 2, 3)  # integer arrays take ints only
    with pytest.raises(GLTypeError):
        RGBcolor(1, 2, 3.5)


def test_c3f_c4f_both_spellings_and_clamping(win):
    ctx = win()
    c3f((0.5, 2.0, -1.0))
    assert ctx.colour == (0.5, 1.0, 0.0, 1.0)
    c3f(0.25, 0.5, 0.75)
    assert ctx.colour == (0.25, 0.5, 0.75, 1.0)
    c4f([0.1, 0.2, 0.3, 0.4])
    fill(ctx)
    # floor(c * 255 + 0.5): 26, 51, 77, 102
    assert tuple(ctx.read_rgba()[1, 2]) == (26, 51, 77, 102)
    with pytest.raises(GLTypeError, match="expected 3 numbers, got 2"):
        c3f(0.1, 0.2)
    with pytest.raises(GLValueError, match="finite"):
        c4f(0.1, float("nan"), 0.0, 1.0)


def test_rgb_calls_are_errors_in_cmode(win):
    win(rgb=False)
    for call, args in ((cpack, (0,)), (RGBcolor, (1, 2, 3)), (c3f, (0, 0, 0)),
                       (c4i, (0, 0, 0, 0)), (gRGBcolor, ()), (gRGBmask, ())):
        with pytest.raises(GLUsageError, match="colour map mode"):
            call(*args)


def test_grgbmask_reads_wmpack(win):
    ctx = win()
    ctx.raster.set(wmpack=0xFF0F00F0)
    assert gRGBmask() == (0xF0, 0x00, 0x0F)


# -- cmode ---------------------------------------------------------------------------
def test_color_index_drawn_and_shown_through_the_map(win):
    ctx = win(rgb=False)
    color(GL.RED)
    assert getcolor() == 1 and ctx.last_sent == "colour"
    fill(ctx)
    assert np.all(ctx.fb.front == 1)
    assert tuple(ctx.display_rgba()[0, 0]) == (255, 0, 0, 255)
    # The map is read at display time: remapping recolours what is already drawn.
    mapcolor(1, 10, 20, 30)
    assert getmcolor(1) == (10, 20, 30)
    assert tuple(ctx.display_rgba()[3, 3]) == (10, 20, 30, 255)


def test_large_index_uses_both_low_bytes(win):
    ctx = win(rgb=False)
    mapcolor(0x9AB, 1, 2, 3)
    color(0x9AB)
    fill(ctx)
    assert np.all(ctx.fb.front == 0x9AB)
    assert tuple(ctx.display_rgba()[2, 1]) == (1, 2, 3, 255)


def test_color_clamps_and_colorf_rounds(win):
    ctx = win(rgb=False)
    color(5000)
    assert getcolor() == 4095  # "clamped to 2**n - 1" (color(3G))
    colorf(2.5)
    assert getcolor() == 3
    colorf(2.49)
    assert getcolor() == 2
    with pytest.raises(GLValueError, match="negative"):
        color(-1)
    with pytest.raises(GLTypeError):
        color(1.0)
    with pytest.raises(GLValueError):
        colorf(float("inf"))
    assert ctx.colour_index == 2


def test_cmode_calls_are_errors_in_rgbmode(win):
    win()
    for call, args in ((color, (1,)), (colorf, (1.0,)), (writemask, (0xF,))):
        with pytest.raises(GLUsageError, match="RGB mode"):
            call(*args)


def test_writemask_limits_index_planes(win):
    ctx = win(rgb=False)
    color(0x30)
    fill(ctx)
    writemask(0x0F)
    assert getwritemask() == 0x0F
    color(0xFF)
    fill(ctx)
    assert np.all(ctx.fb.front == 0x3F)  # (0x30 & ~0x0F) | (0xFF & 0x0F)


def test_default_map_follows_makemap(win):
    win(rgb=False)
    assert getmcolor(GL.YELLOW) == (255, 255, 0)
    assert getmcolor(8) == (85, 85, 85)
    assert getmcolor(32) == (0, 0, 0) and getmcolor(55) == (244, 244, 244)
    # 5x8x5 cube from 56: green fastest (8 levels), then red (5), blue slowest (5).
    assert getmcolor(56) == (0, 0, 0)
    assert getmcolor(57) == (0, 36, 0)
    assert getmcolor(56 + 8) == (64, 0, 0)
    assert getmcolor(56 + 40) == (0, 0, 64)
    assert getmcolor(255) == (255, 255, 255)
    assert getmcolor(300) == (0, 0, 0)


def test_mapcolor_validation(win):
    win(rgb=False)
    with pytest.raises(GLValueError, match="index 4096 is outside the colour map 0..4095"):
        mapcolor(4096, 0, 0, 0)
    with pytest.raises(GLValueError, match="g 256 is outside 0..255"):
        mapcolor(1, 0, 256, 0)
    with pytest.raises(GLValueError):
        getmcolor(-1)


def test_multimap_setmap_select_small_maps(win):
    ctx = win(rgb=False)
    assert getcmmode() == 1 and getmap() == 0
    multimap()
    assert getcmmode() == 0
    setmap(2)
    assert getmap() == 2
    mapcolor(1, 7, 8, 9)
    assert tuple(ctx.colormap[2 * 256 + 1]) == (7, 8, 9)
    color(300)
    assert getcolor() == 255  # 8 planes per map
    color(1)
    fill(ctx)
    assert tuple(ctx.display_rgba()[0, 0]) == (7, 8, 9, 255)
    setmap(0)
    assert tuple(ctx.display_rgba()[0, 0]) == (255, 0, 0, 255)
    with pytest.raises(GLValueError, match="mapnum 16"):
        setmap(16)
    with pytest.raises(GLValueError, match="0..255"):
        mapcolor(256, 0, 0, 0)
    onemap()
    assert getcmmode() == 1 and getmap() == 0


# -- lmcolor interplay ---------------------------------------------------------------
def _light_up(ctx):
    ctx.lighting.lmdef(GL.DEFMATERIAL, 1, [])
    ctx.lighting.lmdef(GL.DEFLMODEL, 1, [])
    ctx.bound["material"] = 1
    ctx.bound["lmodel"] = 1


def test_colour_calls_with_lighting_follow_lmcolor(win):
    ctx = win()
    cpack(0xFF0000FF)
    _light_up(ctx)
    ctx.last_sent = "normal"
    ctx.lmcolor_mode = int(GL.LMC_DIFFUSE)
    ctx.lmcolor_set = False
    c3f(0.0, 1.0, 0.0)  # sets the material's diffuse; the vertex stays lit
    assert ctx.colour == (0.0, 1.0, 0.0, 1.0)
    assert ctx.last_sent == "normal" and ctx.lmcolor_set
    ctx.lmcolor_mode = int(GL.LMC_NULL)
    c3f(1.0, 1.0, 1.0)  # ignored while lighting is on
    assert ctx.colour == (0.0, 1.0, 0.0, 1.0)
    ctx.lmcolor_mode = int(GL.LMC_COLOR)
    c3f(0.0, 0.0, 1.0)  # sets the current colour: the vertex is coloured
    assert ctx.last_sent == "colour" and ctx.colour == (0.0, 0.0, 1.0, 1.0)
    ctx.bound["lmodel"] = 0  # lighting off: LMC_NULL no longer matters
    ctx.lmcolor_mode = int(GL.LMC_NULL)
    ctx.last_sent = "normal"
    cpack(0xFFFFFFFF)
    assert ctx.colour == (1.0, 1.0, 1.0, 1.0) and ctx.last_sent == "colour"


def test_recorded_into_display_objects(win):
    ctx = win()
    rec = []
    _core.session.recording = rec
    try:
        cpack(0xFF)
        assert gRGBcolor() == (255, 255, 255)  # query runs now, not recorded
    finally:
        _core.session.recording = None
    assert [c.__name__ for c, _ in rec] == ["cpack"]
    assert ctx.colour == (1.0, 1.0, 1.0, 1.0)
