"""zdraw(3G): the z-buffer as a colour buffer, alone or with one colour buffer; its
words read back with readsource(SRC_ZBUFFER), and the save/restore idiom through it."""

import numpy as np
import pytest

import vgxsim.gl as gl
from vgxsim import GL
from vgxsim.gl._core import GLUsageError, session

pytestmark = pytest.mark.usefixtures("fresh_session")  # tests/gl/conftest.py

W, H = 8, 6
RED, BLUE = 0xFF0000FF, 0xFFFF0000


def z24(word: int) -> int:
    """What the 24-bit z-buffer gives back for a colour word: its low 24 bits as a
    signed 24-bit z, read as an unsigned 32-bit word."""
    low = word & 0xFFFFFF
    return (low - (1 << 24) if low & 0x800000 else low) & 0xFFFFFFFF


def window(double=True, rgb=True, zbits=24):
    gl.prefsize(W, H)
    gl.winopen("zdraw")
    if rgb:
        gl.RGBmode()
    else:
        gl.cmode()
    if double:
        gl.doublebuffer()
    gl.zbsize(zbits)
    gl.gconfig()
    return session.windows[gl.winget()]


def zwords(x0, y0, x1, y1):
    gl.readsource(GL.SRC_ZBUFFER)
    out = np.frombuffer(gl.lrectread(x0, y0, x1, y1), "<u4").reshape(y1 - y0 + 1, -1)
    gl.readsource(GL.SRC_AUTO)
    return out


def test_zdraw_alone_writes_colour_words_into_the_z_buffer():
    ctx = window()
    gl.zclear()
    gl.backbuffer(False)
    gl.zdraw(True)
    assert gl.getbuffer() == GL.DRAWZBUFFER
    gl.cpack(RED)
    gl.rectfi(1, 1, 4, 3)  # pixels x 1..3, y 1..2
    gl.zdraw(False)
    gl.backbuffer(True)
    assert gl.getbuffer() == GL.BCKBUFFER
    z = zwords(0, 0, W - 1, H - 1)
    want = np.full((H, W), 0x7FFFFF, np.uint32)  # zclear: GD_ZMAX
    want[1:3, 1:4] = z24(RED)  # 0x000000FF: alpha is lost
    assert z24(RED) == 0xFF and z24(BLUE) == 0xFFFF0000  # blue 255: the sign bit
    assert np.array_equal(z, want)
    ctx.flush()
    assert not ctx.fb.back.any() and not ctx.fb.front.any()  # no colour buffer drawn


def test_zdraw_with_the_back_buffer_draws_both_and_skips_the_depth_test():
    ctx = window()
    gl.zbuffer(True)
    gl.zfunction(GL.ZF_NEVER)  # would reject everything if the test were made
    gl.zdraw(True)
    gl.cpack(BLUE)
    gl.clear()
    gl.zdraw(False)
    ctx.flush()
    assert (ctx.fb.back == BLUE).all()
    assert (zwords(0, 0, W - 1, H - 1) == z24(BLUE)).all()
    assert not ctx.fb.front.any()


def test_colour_map_mode_stores_the_index():
    window(double=False, rgb=False)
    gl.frontbuffer(False)  # single-buffered: allowed only while zdraw is on
    gl.zdraw(True)
    gl.color(9)
    gl.pnt2i(2, 2)
    gl.zdraw(False)
    assert int(zwords(2, 2, 2, 2)[0, 0]) == 9


def test_save_and_restore_a_picture_through_the_z_buffer():
    ctx = window()
    gl.cpack(RED)
    gl.clear()
    gl.cpack(BLUE)
    gl.rectfi(2, 2, 5, 4)
    ctx.flush()
    picture = ctx.fb.back.copy()
    # Save: copy the back buffer into the z-buffer.
    gl.readsource(GL.SRC_BACK)
    gl.backbuffer(False)
    gl.zdraw(True)
    gl.rectcopy(0, 0, W - 1, H - 1, 0, 0)
    gl.zdraw(False)
    gl.backbuffer(True)
    gl.cpack(0)
    gl.clear()
    ctx.flush()
    assert not ctx.fb.back.any()
    # Restore: copy the z-buffer back.
    gl.readsource(GL.SRC_ZBUFFER)
    gl.rectcopy(0, 0, W - 1, H - 1, 0, 0)
    ctx.flush()
    want = np.vectorize(z24, otypes=[np.uint32])(picture)  # red, green, blue come back
    assert np.array_equal(ctx.fb.back, want)
    assert np.array_equal(ctx.fb.back & 0xFFFFFF, picture & 0xFFFFFF)


def test_changing_draw_buffers_under_zdraw_redirects_drawing():
    ctx = window()
    gl.zclear()
    gl.backbuffer(False)
    gl.zdraw(True)
    gl.cpack(RED)
    gl.pnt2i(0, 0)  # z only
    gl.frontbuffer(True)
    gl.pnt2i(1, 0)  # z and front
    gl.zdraw(False)
    ctx.flush()
    assert zwords(0, 0, 2, 0).tolist() == [[z24(RED), z24(RED), 0x7FFFFF]]
    assert ctx.fb.front[0, :3].tolist() == [0, RED, 0]
    assert not ctx.fb.back.any()


def test_gconfig_resets_zdraw_and_errors_name_the_call():
    ctx = window()
    gl.backbuffer(True)
    gl.frontbuffer(True)
    with pytest.raises(GLUsageError, match="zdraw"):
        gl.zdraw(True)  # z, front and back: three buffers
    gl.frontbuffer(False)
    gl.zdraw(True)
    with pytest.raises(GLUsageError, match="frontbuffer"):
        gl.frontbuffer(True)
    gl.gconfig()
    assert gl.getbuffer() == GL.BCKBUFFER and ctx.zdraw_batch is None
    gl.overlay(2)
    gl.gconfig()
    gl.drawmode(GL.OVERDRAW)
    with pytest.raises(GLUsageError, match="NORMALDRAW"):
        gl.zdraw(True)
    gl.drawmode(GL.NORMALDRAW)
    gl.zbsize(0)
    gl.gconfig()
    with pytest.raises(GLUsageError, match="no z-buffer"):
        gl.zdraw(True)


def test_drawmode_round_trip_keeps_zdraw():
    ctx = window()
    gl.overlay(2)
    gl.gconfig()
    gl.zclear()
    gl.backbuffer(False)
    gl.zdraw(True)
    gl.drawmode(GL.OVERDRAW)
    gl.color(1)
    gl.pnt2i(0, 0)  # the overlay, not the z-buffer
    gl.drawmode(GL.NORMALDRAW)
    gl.cpack(RED)
    gl.pnt2i(1, 0)  # the z-buffer again
    gl.zdraw(False)
    assert zwords(0, 0, 1, 0).tolist() == [[0x7FFFFF, z24(RED)]]
    assert int(ctx.plane_sets["overlay"].fb.front[0, 0]) == 1


def test_getgdesc_reports_zdraw():
    assert gl.getgdesc(GL.GD_ZDRAW_GEOM) == 1
    assert gl.getgdesc(GL.GD_ZDRAW_PIXELS) == 1
