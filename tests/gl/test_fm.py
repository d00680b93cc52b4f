"""Raster fonts (defrasterfont, font, charstr, strwidth, getheight, getdescender) and
the Font Manager (vgxsim.fm).

Expected pixels are built independently from the built-in font's bitmaps
(vgxsim.font.bitmap) replicated with numpy (np.kron) for an exact 2x face, and from
hand-written defrasterfont bitmaps.
"""

import numpy as np
import pytest

import vgxsim.fm as fm
import vgxsim.gl as gl
from vgxsim import font as builtin
from vgxsim.gl._core import GLTypeError, GLValueError

pytestmark = pytest.mark.usefixtures("fresh_session")  # tests/gl/conftest.py
W, H = 64, 40


@pytest.fixture
def win():
    gl.prefsize(W, H)
    gl.winopen("fm")
    gl.RGBmode()
    gl.gconfig()
    gl.cpack(0xFF000000)
    gl.clear()
    gl.cpack(0xFFFFFFFF)


def lit() -> np.ndarray:
    img = np.frombuffer(gl.lrectread(0, 0, W - 1, H - 1), dtype=np.uint32).reshape(H, W)
    return (img & 0xFFFFFF) != 0


def test_font0_metrics(win):
    assert (gl.getheight(), gl.getdescender(), gl.getfont()) == (13, 3, 0)
    assert gl.strwidth("Hello") == 40
    assert gl.strwidth("a\x01b") == 16  # undefined characters have no width


def test_fm_face_at_26_points_is_font0_doubled(win):
    fh = fm.findfont("Times-Roman").scalefont(26)
    fh.setfont()
    assert (gl.getheight(), gl.getdescender()) == (26, 6)
    assert fh.getstrwidth("Ab") == 32 == gl.strwidth("Ab")
    gl.cmov2i(4, 10)
    fm.prstr("Ab")
    assert gl.getcpos() == (36, 10)
    want = np.zeros((H, W), bool)
    cell = np.kron(builtin.string_bitmap("Ab"), np.ones((2, 2), bool))  # (26, 32)
    want[10 - 6:10 - 6 + 26, 4:36] = cell
    assert np.array_equal(lit(), want)


def test_fm_13_points_is_the_design_and_info(win):
    fh = fm.fmscalefont(fm.fmfindfont("Courier"), 13)
    assert fm.fmgetfontinfo(fh) == (0, 1, 0, 3, 8, 13, 13, 95)
    fm.fmsetfont(fh)
    gl.cmov2i(2, 5)
    fm.fmprstr("x")
    want = np.zeros((H, W), bool)
    want[2:15, 2:10] = builtin.bitmap("x")
    assert np.array_equal(lit(), want)
    assert fm.fmgetstrwidth(fh, "xyz") == 24


def test_fm_enumerate_findfont_and_errors():
    names = []
    assert fm.fmenumerate(names.append) == names == list(fm.FACES)
    assert fm.enumerate() == list(fm.FACES)
    assert fm.fmfindfont("NoSuchFace") is None
    with pytest.raises(RuntimeError, match="font handle"):
        fm.findfont("NoSuchFace")
    fh = fm.findfont("Helvetica")
    assert fh.getfontname() == "Helvetica" and fh.scalefont(2).scalefont(6).points == 12
    with pytest.raises(GLTypeError, match="font handle"):
        fm.fmsetfont("Helvetica")
    with pytest.raises(GLValueError):
        fh.scalefont(0)


def test_defrasterfont_bitmaps_and_metrics(win):
    # Font 3: 'A' (code 65) a 3x2 glyph, rows bottom-up, MSB leftmost:
    # bottom row 101, top row 111; placed 1 right and 2 below the position; advance 5.
    chars = [(0, 0, 0, 0, 0, 0)] * 66
    chars[65] = (0, 3, 2, 1, -2, 5)
    raster = [0b1010_0000_0000_0000, 0b1110_0000_0000_0000]
    gl.defrasterfont(3, 9, len(chars), chars, len(raster), raster)
    gl.font(3)
    assert (gl.getheight(), gl.getdescender(), gl.getfont()) == (9, 2, 3)
    assert gl.strwidth("AAB") == 10  # B is not defined
    gl.cmov2i(10, 20)
    gl.charstr("AA")
    assert gl.getcpos() == (20, 20)
    want = np.zeros((H, W), bool)
    for x0 in (11, 16):
        want[18, [x0, x0 + 2]] = True  # bottom row 101
        want[19, x0:x0 + 3] = True  # top row 111
    assert np.array_equal(lit(), want)
    gl.defrasterfont(3, 9, 0, [], 0, [])  # nc = 0 deletes
    with pytest.raises(GLValueError, match=r"font\(3\)"):
        gl.font(3)
    with pytest.raises(GLValueError, match="font 0"):
        gl.defrasterfont(0, 9, chars, raster)
    with pytest.raises(GLValueError, match="raster"):
        gl.defrasterfont(4, 9, [(0, 16, 3, 0, 0, 16)], [0])
