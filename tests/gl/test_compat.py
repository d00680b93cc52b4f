"""Obsolete and hardware-bound calls (vgxsim.gl._compat), against the calls they
stand for and hand-computed pixels."""

import numpy as np
import pytest

import vgxsim.gl as gl
from vgxsim import DEVICE, GL
from vgxsim.gl._compat import compat_state
from vgxsim.gl._core import GLTypeError, GLValueError

pytestmark = pytest.mark.usefixtures("fresh_session")  # tests/gl/conftest.py
W, H = 16, 12


@pytest.fixture
def cwin():
    gl.prefsize(W, H)
    gl.winopen("compat")  # colour-map mode, single-buffered


def indices() -> np.ndarray:
    # cmode: lrectread returns colour indices in the low bits
    return np.frombuffer(gl.lrectread(0, 0, W - 1, H - 1), dtype=np.uint32).reshape(H, W)


def test_setshade_is_color(cwin):
    gl.setshade(5)
    assert gl.getcolor() == 5 == gl.getshade()


def test_sbox_and_sboxf_draw_as_rect_and_rectf(cwin):
    gl.color(0)
    gl.clear()
    gl.color(3)
    gl.sboxfi(2, 2, 5, 4)
    gl.color(4)
    gl.sbox(8, 1, 12, 6)
    img = indices()
    # A filled rectangle with corners on pixel centres owns its left and bottom edges
    # (docs/numeric_model.md tie rule): x 2..4, y 2..3.
    assert (img[2:4, 2:5] == 3).all() and (img[4, 2:6] == 0).all() and (img[:, 5:8] == 0).all()
    assert (img[1, 8:13] == 4).all() and (img[6, 8:13] == 4).all()
    assert (img[2:6, 9:12] == 0).all()  # outline only


def test_splf_colours_each_vertex(cwin):
    gl.color(0)
    gl.clear()
    gl.shademodel(GL.FLAT)  # a flat polygon takes its last vertex's colour
    gl.splf2([1, 1, 10, 1, 10, 8, 1, 8], [1, 2, 3, 6])
    img = indices()
    assert (img[1:8, 1:10] == 6).all() and (img[8:, :] == 0).all()
    with pytest.raises(GLTypeError, match="colour indices"):
        gl.splf([0, 0, 0, 1, 0, 0, 1, 1, 0], [1, 2])


def test_getdepth_nmode_getdev_setvaluator(cwin):
    gl.setdepth(-100, 200)
    assert gl.getdepth() == (-100, 200)
    gl.nmode(GL.NNORMALIZE)
    with pytest.raises(GLValueError, match="NAUTO"):
        gl.nmode(7)
    gl.setvaluator(DEVICE.MOUSEX, 40, 0, 100)
    assert gl.getvaluator(DEVICE.MOUSEX) == 40
    assert gl.getdev([DEVICE.MOUSEX, DEVICE.LEFTMOUSE]) == (40, 0)
    assert gl.getdev(2, [DEVICE.MOUSEX, DEVICE.MOUSEY]) == (40, 0)
    with pytest.raises(GLValueError, match="not a valuator"):
        gl.setvaluator(DEVICE.LEFTMOUSE, 1, 0, 1)


def test_hardware_calls_are_accepted_and_recorded(cwin):
    gl.swapinterval(2)
    gl.gsync()
    gl.ringbell()
    gl.setbell(1)
    gl.clkoff()
    gl.lampon(0x5)
    gl.lampoff(0x1)
    st = compat_state()
    assert (st.swapinterval, st.bells_rung, st.bell, st.keyclick, st.lamps) == (
        2, 1, 1, False, 0x4)
    with pytest.raises(GLValueError):
        gl.setbell(3)
    with pytest.raises(GLValueError):
        gl.swapinterval(0)


def test_mapcolors_getmcolors_rgbsize_monobuffer(cwin):
    gl.mapcolors(10, 12, [1, 2, 3], [4, 5, 6], [7, 8, 9])
    assert [gl.getmcolor(i) for i in (10, 11, 12)] == [(1, 4, 7), (2, 5, 8), (3, 6, 9)]
    assert gl.getmcolors(11, 12) == ([2, 3], [5, 6], [8, 9])
    with pytest.raises(GLTypeError, match="3 values each"):
        gl.mapcolors(10, 12, [1, 2], [4, 5, 6], [7, 8, 9])
    gl.RGBsize(8)
    with pytest.raises(GLValueError, match="8 bits"):
        gl.RGBsize(12)
    gl.monobuffer()


def test_pushattributes_popattributes(cwin):
    gl.color(3)
    gl.linewidth(2)
    gl.deflinestyle(5, 0xF0F0)
    gl.setlinestyle(5)
    gl.writemask(0x0F)
    gl.shademodel(GL.FLAT)
    gl.pushattributes()
    gl.color(6)
    gl.linewidth(4)
    gl.setlinestyle(0)
    gl.writemask(0xFF)
    gl.shademodel(GL.GOURAUD)
    gl.popattributes()
    assert (gl.getcolor(), gl.getlwidth(), gl.getlstyle(), gl.getwritemask(), gl.getsm()) == (
        3, 2, 5, 0x0F, GL.FLAT)
    gl.popattributes()  # empty: ignored
    for _ in range(GL.ATTRIBSTACKDEPTH):
        gl.pushattributes()  # the stack is full of colour 3
    gl.color(6)
    gl.pushattributes()  # ignored: colour 6 is not saved
    gl.color(7)
    gl.popattributes()
    assert gl.getcolor() == 3


def test_scrsubdivide_is_accepted_and_checked(gl_window):
    from vgxsim.gl._compat import compat_state

    gl_window(4, 4)
    gl.scrsubdivide(GL.SS_DEPTH, (0.0, 50.0, 10.0))
    assert compat_state().subdivide == (1, (0.0, 50.0, 10.0))
    gl.scrsubdivide(GL.SS_OFF, ())
    assert compat_state().subdivide == (0, ())
    with pytest.raises(gl.GLValueError, match="SS_OFF or SS_DEPTH"):
        gl.scrsubdivide(5, ())
    with pytest.raises(gl.GLValueError, match="up to three"):
        gl.scrsubdivide(GL.SS_DEPTH, (1.0, 2.0, 3.0, 4.0))


def test_gl_invert4d_by_hand():
    # translate(1, 2, 3) then scale 2 (row vectors): the inverse scales by 1/2 and
    # translates by -(1, 2, 3) / 2.
    m = [2.0, 0, 0, 0, 0, 2, 0, 0, 0, 0, 2, 0, 1, 2, 3, 1]
    assert gl.gl_invert4d(m) == [0.5, 0, 0, 0, 0, 0.5, 0, 0, 0, 0, 0.5, 0,
                                 -0.5, -1.0, -1.5, 1.0]
    with pytest.raises(gl.GLValueError, match="singular"):
        gl.gl_invert4d([0.0] * 16)
