"""Raster-state calls of vgxsim.gl (_raster.py) against hand-computed pixels.

Depth values: with ortho near -1 / far 1, object z maps to z_ndc = -z and
zw = near + (z_ndc + 1) * (far - near) / 2, stored as floor(zw + 0.5)
(docs/numeric_model.md sections 1 and 4).
"""

import functools
import math

import numpy as np
import pytest

from vgxsim import GL
from vgxsim.gl import _core
from vgxsim.gl._color import cpack
from vgxsim.gl._core import GLTypeError, GLUsageError, GLValueError
from vgxsim.gl._raster import *
from vgxsim.state.planes import ZMAX, ZMIN

W = H = 8


@pytest.fixture
def win(gl_window):
    """Factory: a current W x H window (RGB, single-buffered, 8 stencil planes)."""
    return functools.partial(gl_window, W, H, acbits=16)


def square(x0, y0, x1, y1, z=0.0, cw=False):
    """Corners of an axis-aligned square; covers pixels x0..x1-1, y0..y1-1."""
    v = [[x0, y0, z], [x1, y0, z], [x1, y1, z], [x0, y1, z]]
    return np.array(v[::-1] if cw else v, float)


def draw(ctx, verts, rgba=None):
    if rgba is not None:
        ctx.colour = tuple(c / 255 for c in rgba)
    ctx.draw_arrays("polygon", verts)


def rgba_at(ctx, x, y):
    ctx.flush()
    return tuple(int(c) for c in ctx.read_rgba()[y, x])


def zw(z, near=ZMIN, far=ZMAX):
    """Stored depth of object z under the fixture's ortho projection."""
    return math.floor(near + (-z + 1) * (far - near) / 2 + 0.5)


# -- z-buffer ------------------------------------------------------------------------
def test_zbuffer_lequal_hides_farther_and_writes_depth(win):
    ctx = win()
    czclear(0, ZMAX)
    zbuffer(GL.TRUE)
    draw(ctx, square(0, 0, 4, 4, z=0.5), (0, 0, 255, 255))  # near
    draw(ctx, square(2, 2, 6, 6, z=-0.5), (255, 0, 0, 255))  # far, partly behind
    ctx.flush()
    assert rgba_at(ctx, 3, 3) == (0, 0, 255, 255)  # overlap keeps the near one
    assert rgba_at(ctx, 5, 5) == (255, 0, 0, 255)
    assert ctx.fb.z[3, 3] == zw(0.5) == -4194304
    assert ctx.fb.z[5, 5] == zw(-0.5) == 4194303
    assert ctx.fb.z[7, 7] == ZMAX
    # Equal depth passes ZF_LEQUAL (the default).
    draw(ctx, square(4, 4, 6, 6, z=-0.5), (0, 255, 0, 255))
    assert rgba_at(ctx, 5, 5) == (0, 255, 0, 255)


def test_zfunction_greater_with_reversed_lsetdepth(win):
    ctx = win()
    lsetdepth(ZMAX, ZMIN)
    assert ctx.depth_range == (ZMAX, ZMIN)
    zfunction(GL.ZF_GREATER)
    czclear(0, ZMIN)
    zbuffer(True)
    draw(ctx, square(0, 0, 4, 4, z=0.5), (0, 0, 255, 255))  # near first
    draw(ctx, square(2, 2, 6, 6, z=-0.5), (255, 0, 0, 255))  # far second: loses
    assert rgba_at(ctx, 3, 3) == (0, 0, 255, 255)
    assert rgba_at(ctx, 5, 5) == (255, 0, 0, 255)
    assert ctx.fb.z[3, 3] == zw(0.5, ZMAX, ZMIN) == 4194303
    assert ctx.fb.z[5, 5] == zw(-0.5, ZMAX, ZMIN) == -4194304


def test_zwritemask_zero_tests_but_keeps_z(win):
    ctx = win()
    czclear(0, zw(0.0))
    zbuffer(1)
    zwritemask(0)
    draw(ctx, square(0, 0, 4, 4, z=0.5), (9, 9, 9, 255))  # passes, z unchanged
    draw(ctx, square(4, 4, 8, 8, z=-0.5), (7, 7, 7, 255))  # fails against z(0)
    assert rgba_at(ctx, 1, 1) == (9, 9, 9, 255)
    assert rgba_at(ctx, 5, 5) == (0, 0, 0, 0)
    assert np.all(ctx.fb.z == zw(0.0))


def test_zwritemask_truncates_like_c_unsigned_long(win):
    ctx = win()
    zwritemask(0xFFFFFFFFF)  # the 1991 article's nine f's
    assert ctx.raster.zwritemask == 0xFFFFFFFF
    zwritemask(-1)
    assert ctx.raster.zwritemask == 0xFFFFFFFF


def test_zfunction_bad_token_names_call(win):
    win()
    with pytest.raises(GLValueError) as e:
        zfunction(9)
    assert str(e.value) == "zfunction(9): func 9 is not a valid token (ZF_*)"
    with pytest.raises(GLTypeError):
        zbuffer(1.0)


def test_zclear_honours_raster_rectangle_and_zwritemask(win):
    ctx = win()
    czclear(0, 0)
    ctx.raster.set(viewport=(2, 5, 2, 5), scrmask=(3, 6, 1, 4))  # rect x 3..5, y 2..4
    zwritemask(0xFF0000)
    zclear()
    ctx.flush()
    inside = np.zeros((H, W), bool)
    inside[2:5, 3:6] = True
    # (0 & ~m) | (0x7FFFFF & 0xFF0000) on the 24-bit representation.
    assert np.all(ctx.fb.z[inside] == 0x7F0000)
    assert np.all(ctx.fb.z[~inside] == 0)
    zclear(ZMAX)  # the 1991 article's call form: argument accepted and ignored
    with pytest.raises(GLUsageError):
        zclear(1, 2)


def test_czclear_colour_through_wmpack_and_zval_range(win):
    ctx = win()
    czclear(0x11223344, 5)
    wmpack(0x0000FF00)
    czclear(0xAABBCCDD, 7)
    ctx.flush()
    assert rgba_at(ctx, 0, 0) == (0x44, 0xCC, 0x22, 0x11)
    assert np.all(ctx.fb.z == 7)
    with pytest.raises(GLValueError, match=r"czclear\(0, 8388608\): zval"):
        czclear(0, ZMAX + 1)


def test_lsetdepth_range_and_zrangemap(win):
    ctx = win()
    with pytest.raises(GLValueError, match="near -8388609 is outside"):
        lsetdepth(ZMIN - 1, 0)
    glcompat(GL.GLC_ZRANGEMAP, 1)
    with pytest.raises(GLValueError, match="GLC_ZRANGEMAP"):
        lsetdepth(-1, 10)
    lsetdepth(0, 0x7FFFFF)
    assert ctx.depth_range == (0, 0x7FFFFF)
    with pytest.raises(GLValueError):
        glcompat(GL.GLC_ZRANGEMAP, 2)
    setdepth(-0x8000, 0x7FFF)
    assert ctx.depth_range == (-0x8000, 0x7FFF)
    with pytest.raises(GLValueError):
        setdepth(0, 0x8000)


# -- stencil -------------------------------------------------------------------------
def test_stencil_incr_counts_overlap_with_zbuffer_off(win):
    """zbuffer off: a passing stencil test applies `pass` (stencil(3G)), not zpass."""
    ctx = win()
    sclear(0)
    stencil(GL.TRUE, 0, GL.SF_ALWAYS, 0xFF, GL.ST_KEEP, GL.ST_INCR, GL.ST_KEEP)
    draw(ctx, square(0, 0, 4, 4))
    draw(ctx, square(2, 2, 6, 6))
    ctx.flush()
    expect = np.zeros((H, W), np.uint8)
    expect[0:4, 0:4] += 1
    expect[2:6, 2:6] += 1
    assert np.array_equal(ctx.fb.stencil, expect)
    # zpass is "not significant when the z-buffer is not enabled".
    stencil(GL.TRUE, 0, GL.SF_ALWAYS, 0xFF, GL.ST_KEEP, GL.ST_KEEP, GL.ST_INCR)
    draw(ctx, square(0, 0, 8, 8))
    ctx.flush()
    assert np.array_equal(ctx.fb.stencil, expect)


def test_stencil_incr_decr_with_zbuffer_and_clamping(win):
    ctx = win()
    czclear(0, ZMAX)
    zbuffer(GL.TRUE)
    zwritemask(0)
    wmpack(0)
    sclear(1)
    stencil(GL.TRUE, 0, GL.SF_ALWAYS, 0xFF, GL.ST_KEEP, GL.ST_KEEP, GL.ST_INCR)
    draw(ctx, square(0, 0, 4, 4))
    stencil(GL.TRUE, 0, GL.SF_ALWAYS, 0xFF, GL.ST_KEEP, GL.ST_KEEP, GL.ST_DECR)
    draw(ctx, square(2, 2, 6, 6))
    draw(ctx, square(2, 2, 6, 6))  # DECR clamps at 0
    ctx.flush()
    expect = np.ones((H, W), np.int64)
    expect[0:4, 0:4] += 1
    expect[2:6, 2:6] -= 2
    assert np.array_equal(ctx.fb.stencil, np.clip(expect, 0, 255))
    sclear(255)
    stencil(GL.TRUE, 0, GL.SF_ALWAYS, 0xFF, GL.ST_KEEP, GL.ST_KEEP, GL.ST_INCR)
    draw(ctx, square(0, 0, 2, 2))
    ctx.flush()
    assert ctx.fb.stencil[0, 0] == 255  # INCR clamps at 2**planes - 1


def test_stencil_equal_masks_drawing(win):
    ctx = win()
    sclear(0)
    stencil(GL.TRUE, 1, GL.SF_ALWAYS, 0xFF, GL.ST_KEEP, GL.ST_REPLACE, GL.ST_REPLACE)
    wmpack(0)
    draw(ctx, square(1, 1, 3, 3))
    wmpack(0xFFFFFFFF)
    stencil(GL.TRUE, 1, GL.SF_EQUAL, 0xFF, GL.ST_KEEP, GL.ST_KEEP, GL.ST_KEEP)
    draw(ctx, square(0, 0, 8, 8), (255, 255, 255, 255))
    ctx.flush()
    drawn = ctx.read_rgba()[..., 0] == 255
    expect = np.zeros((H, W), bool)
    expect[1:3, 1:3] = True
    assert np.array_equal(drawn, expect)
    # Only the masked bits compare: (0x11 & 0x0F) == (0x21 & 0x0F).
    sclear(0x21)
    stencil(GL.TRUE, 0x11, GL.SF_EQUAL, 0x0F, GL.ST_KEEP, GL.ST_KEEP, GL.ST_KEEP)
    draw(ctx, square(5, 5, 6, 6), (0, 255, 0, 255))
    assert rgba_at(ctx, 5, 5) == (0, 255, 0, 255)


def test_stencil_disable_keeps_parameters_and_validates_tokens(win):
    ctx = win()
    stencil(1, 128, GL.SF_EQUAL, 0xFF, GL.ST_KEEP, GL.ST_KEEP, GL.ST_INCR)
    stencil(0, 0, 99, 0, 99, 99, 99)  # disabled: the other six are ignored
    assert ctx.raster.stencil == (False, 128, 2, 0xFF, 0, 0, 3)
    with pytest.raises(GLValueError) as e:
        stencil(1, 0, GL.SF_ALWAYS, 0xFF, GL.ST_KEEP, GL.ST_KEEP, 7)
    assert "zpass 7 is not a valid token (ST_*)" in str(e.value)
    assert str(e.value).startswith("stencil(1, 0, SF_ALWAYS, 255, ST_KEEP, ST_KEEP, 7)")
    with pytest.raises(GLValueError, match=r"func 8 is not a valid token \(SF_\*\)"):
        stencil(1, 0, 8, 0xFF, 0, 0, 0)


def test_stencil_without_planes_is_stored_but_inert(win):
    ctx = win(stencil=0)
    stencil(GL.TRUE, 5, GL.SF_NEVER, 0xFF, GL.ST_KEEP, GL.ST_KEEP, GL.ST_KEEP)
    assert ctx.raster.stencil[0] is True
    draw(ctx, square(0, 0, 2, 2), (1, 2, 3, 4))  # SF_NEVER would reject everything
    assert rgba_at(ctx, 0, 0) == (1, 2, 3, 4)
    sclear(3)  # no planes: nothing to clear, no error


def test_sclear_honours_swritemask_and_rectangle(win):
    ctx = win()
    sclear(0x50)
    swritemask(0x0F)
    ctx.raster.set(viewport=(0, 3, 0, 7), scrmask=(0, 3, 0, 7))
    sclear(0xAB)
    ctx.flush()
    assert np.all(ctx.fb.stencil[:, :4] == 0x5B)  # (0x50 & 0xF0) | (0xAB & 0x0F)
    assert np.all(ctx.fb.stencil[:, 4:] == 0x50)


# -- colour masks, blending, alpha test, logic ops ------------------------------------
def test_wmpack_red_only(win):
    ctx = win()
    czclear(0x40302010, ZMAX)
    wmpack(0xFF)
    draw(ctx, square(0, 0, 8, 8), (255, 255, 255, 255))
    assert rgba_at(ctx, 4, 4) == (255, 0x20, 0x30, 0x40)


def test_rgbwritemask_sets_alpha_mask_to_ones(win):
    ctx = win()
    czclear(0x00000000, ZMAX)
    RGBwritemask(0x1F0, 0x00, 0x0F)  # bits 8..15 ignored: red mask 0xF0
    assert ctx.raster.wmpack == 0xFF0F00F0
    draw(ctx, square(0, 0, 8, 8), (0xAB, 0xCD, 0xEF, 0x12))
    assert rgba_at(ctx, 0, 0) == (0xA0, 0x00, 0x0F, 0x12)


def test_blend_one_one_adds_and_clamps(win):
    ctx = win()
    czclear(0x003264C8 & 0x00FFFFFF | (10 << 24), ZMAX)  # r 200, g 100, b 50, a 10
    blendfunction(GL.BF_ONE, GL.BF_ONE)
    draw(ctx, square(0, 0, 8, 8), (100, 100, 250, 255))
    assert rgba_at(ctx, 3, 3) == (255, 200, 255, 255)


def test_blend_sa_msa_integer_formula(win):
    ctx = win()
    d = (0, 255, 50, 128)
    s = (200, 0, 100, 64)
    czclear(d[0] | d[1] << 8 | d[2] << 16 | d[3] << 24, ZMAX)
    blendfunction(GL.BF_SA, GL.BF_MSA)
    draw(ctx, square(0, 0, 8, 8), s)
    # out = min(255, (s*sa + d*(255-sa) + 127) // 255), computed by hand:
    # r (12800 + 0 + 127)//255 = 50, g (0 + 48705 + 127)//255 = 191,
    # b (6400 + 9550 + 127)//255 = 63, a (4096 + 24448 + 127)//255 = 112.
    assert rgba_at(ctx, 2, 5) == (50, 191, 63, 112)


def test_blendfunction_validation(win):
    win()
    with pytest.raises(GLValueError, match="not available on the VGX"):
        blendfunction(GL.BF_CA, GL.BF_ZERO)
    with pytest.raises(GLValueError, match="source factor only"):
        blendfunction(GL.BF_ONE, GL.BF_MIN_SA_MDA)
    with pytest.raises(GLValueError, match=r"sfactr 20 is not a valid token \(BF_\*\)"):
        blendfunction(20, GL.BF_ZERO)


def test_blend_and_logicop_exclude_each_other(win):
    ctx = win()
    logicop(GL.LO_XOR)
    blendfunction(GL.BF_SA, GL.BF_MSA)
    assert ctx.raster.logicop == GL.LO_SRC
    logicop(GL.LO_AND)
    assert ctx.raster.blend == (GL.BF_ONE, GL.BF_ZERO)
    with pytest.raises(GLValueError, match=r"\(LO_\*\)"):
        logicop(16)


def test_logicop_xor_twice_restores(win):
    ctx = win()
    czclear(0x80C0E0F0, ZMAX)
    logicop(GL.LO_XOR)
    draw(ctx, square(0, 0, 4, 8), (0x0F, 0xF0, 0x55, 0xAA))
    assert rgba_at(ctx, 1, 1) == (0xF0 ^ 0x0F, 0xE0 ^ 0xF0, 0xC0 ^ 0x55, 0x80 ^ 0xAA)
    draw(ctx, square(0, 0, 4, 8), (0x0F, 0xF0, 0x55, 0xAA))
    assert rgba_at(ctx, 1, 1) == (0xF0, 0xE0, 0xC0, 0x80)
    assert rgba_at(ctx, 6, 6) == (0xF0, 0xE0, 0xC0, 0x80)


def test_afunction_alpha_test(win):
    ctx = win()
    afunction(128, GL.AF_GREATER)
    draw(ctx, square(0, 0, 4, 4), (255, 0, 0, 128))  # 128 > 128 fails
    draw(ctx, square(4, 4, 8, 8), (0, 255, 0, 129))
    assert rgba_at(ctx, 1, 1) == (0, 0, 0, 0)
    assert rgba_at(ctx, 5, 5) == (0, 255, 0, 129)
    with pytest.raises(GLValueError, match="ref 256 is outside 0..255"):
        afunction(256, GL.AF_ALWAYS)
    with pytest.raises(GLValueError, match=r"\(AF_\*\)"):
        afunction(0, 8)


def test_rgb_masks_are_errors_in_cmode(win):
    win(rgb=False)
    with pytest.raises(GLUsageError, match="colour map mode"):
        wmpack(0xFF)
    with pytest.raises(GLUsageError):
        RGBwritemask(1, 2, 3)


# -- faces, shading, lines ----------------------------------------------------------------
def test_backface_culls_clockwise_only(win):
    ctx = win()
    backface(GL.TRUE)
    assert getbackface() == 1
    draw(ctx, square(0, 0, 4, 4, cw=True), (255, 0, 0, 255))
    draw(ctx, square(4, 4, 8, 8), (0, 255, 0, 255))
    assert rgba_at(ctx, 1, 1) == (0, 0, 0, 0)
    assert rgba_at(ctx, 5, 5) == (0, 255, 0, 255)
    backface(GL.FALSE)
    frontface(GL.TRUE)
    assert getbackface() == 0
    draw(ctx, square(0, 0, 4, 4, cw=True), (255, 0, 0, 255))
    draw(ctx, square(4, 4, 8, 8), (0, 0, 255, 255))  # front-facing: culled
    assert rgba_at(ctx, 1, 1) == (255, 0, 0, 255)
    assert rgba_at(ctx, 5, 5) == (0, 255, 0, 255)


def test_shademodel_flat_uses_last_vertex(win):
    ctx = win()
    assert getsm() == GL.GOURAUD
    shademodel(GL.FLAT)
    assert getsm() == GL.FLAT
    cols = np.array([[1, 0, 0, 1], [0, 1, 0, 1], [0, 0, 1, 1], [1, 1, 1, 1]], float)
    ctx.draw_arrays("polygon", square(0, 0, 8, 8), cols)
    ctx.flush()
    assert np.all(ctx.read_rgba() == 255)
    with pytest.raises(GLValueError, match=r"\(FLAT or GOURAUD\)"):
        shademodel(2)


def test_linestyle_pattern_and_repeat_reach_the_rasterizer(win):
    ctx = win()
    assert getlstyle() == 0
    deflinestyle(1, 0x5555)
    setlinestyle(1)
    assert getlstyle() == 1 and ctx.raster.linestyle == 0x5555
    ctx.colour = (1.0, 1.0, 1.0, 1.0)
    ctx.draw_arrays("line", np.array([[0, 0, 0], [7, 0, 0]], float))
    ctx.flush()
    assert list(ctx.read_rgba()[0, :, 0] > 0) == [True, False] * 4  # bit 0 first
    czclear(0, ZMAX)
    lsrepeat(2)
    assert getlsrepeat() == 2
    ctx.draw_arrays("line", np.array([[0, 0, 0], [7, 0, 0]], float))
    ctx.flush()
    assert list(ctx.read_rgba()[0, :, 0] > 0) == [True, True, False, False] * 2
    deflinestyle(1, 0xFFFF)  # redefining the style in use takes effect
    assert ctx.raster.linestyle == 0xFFFF


def test_linestyle_errors(win):
    win()
    with pytest.raises(GLValueError, match="line style 3 is not defined"):
        setlinestyle(3)
    with pytest.raises(GLValueError, match="index 0 is reserved"):
        deflinestyle(0, 0xF0F0)
    with pytest.raises(GLValueError, match="ls 65536 is outside"):
        deflinestyle(2, 0x10000)
    with pytest.raises(GLValueError):
        lsrepeat(0)
    with pytest.raises(GLValueError):
        lsrepeat(256)


def test_line_and_point_sizes(win):
    ctx = win()
    linewidth(3)
    assert getlwidth() == 3
    linewidthf(2.4)
    assert getlwidth() == 2
    linewidthf(0.2)
    assert getlwidth() == 1
    pntsize(4)
    assert ctx.raster.pntsize == 4
    pntsizef(2.6)
    assert ctx.raster.pntsize == 3
    with pytest.raises(GLValueError):
        linewidth(0)
    with pytest.raises(GLValueError):
        linewidthf(float("nan"))
    with pytest.raises(GLValueError):
        pntsizef(-1.0)


def test_accepted_but_unmodelled_modes_are_validated(win):
    ctx = win()
    linesmooth(GL.SML_ON | GL.SML_END_CORRECT)
    pntsmooth(GL.SMP_ON)
    polysmooth(GL.PYSM_SHRINK)
    assert ctx.smooth == {"line": 5, "point": 1, "polygon": 2}
    polymode(GL.PYM_LINE)
    assert getpolymode() == GL.PYM_LINE
    dither(GL.DT_OFF)
    assert ctx.dither == 0
    glcompat(GL.GLC_OLDPOLYGON, 1)
    for call, bad in ((linesmooth, 8), (pntsmooth, 4), (polysmooth, 3), (polymode, 0),
                      (dither, 2)):
        with pytest.raises(GLValueError, match=call.__name__):
            call(bad)
    with pytest.raises(GLValueError, match=r"\(GLC_\*\)"):
        glcompat(11, 0)


# -- clear -----------------------------------------------------------------------------
def test_clear_uses_current_colour_viewport_and_wmpack(win):
    ctx = win()
    cpack(0x11223344)
    clear()
    ctx.raster.set(viewport=(4, 7, 0, 7), scrmask=(4, 7, 0, 7))
    cpack(0xFFEEDDCC)
    wmpack(0x00FF00FF)
    clear()
    assert rgba_at(ctx, 0, 0) == (0x44, 0x33, 0x22, 0x11)
    assert rgba_at(ctx, 5, 0) == (0xCC, 0x33, 0xEE, 0x11)


def test_clear_in_cmode_writes_the_index(win):
    ctx = win(rgb=False)
    from vgxsim.gl._color import color
    color(GL.CYAN)
    clear()
    ctx.flush()
    assert np.all(ctx.fb.front == 6)
    assert tuple(ctx.display_rgba()[0, 0]) == (0, 255, 255, 255)


def test_no_window_and_recording(win):
    _core.session.reset()
    with pytest.raises(GLUsageError, match="no window is open"):
        zbuffer(1)
    ctx = win()
    rec = []
    _core.session.recording = rec
    try:
        zbuffer(1)
        stencil(1, 0, 7, 0xFF, 0, 0, 0)
        assert getsm() == GL.GOURAUD  # queries are not recorded
    finally:
        _core.session.recording = None
    assert [c.__name__ for c, _ in rec] == ["zbuffer", "stencil"]
    assert ctx.raster.zbuffer is False
