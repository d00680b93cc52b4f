"""Pixel readback and writes (vgxsim.gl._readback).

Byte layouts are hand-computed: a pixel packed 0xAABBGGRR (lrectwrite(3G)) is the
little-endian bytes RR GG BB AA; rectangles are inclusive and bottom row first.
"""

import numpy as np
import pytest

import vgxsim.gl as gl
from vgxsim import GL
from vgxsim.gl._core import GLTypeError, GLUsageError, GLValueError, session
from vgxsim.pipeline.context import CLEAR_COLOUR, CLEAR_STENCIL, CLEAR_Z

A, B, C, D = 0x80FF4020, 0x11223344, 0x55667788, 0xFFEEDDCC


pytestmark = pytest.mark.usefixtures("fresh_session")  # tests/gl/conftest.py


def rgb_window(w=4, h=3, double=False, stencil=0):
    gl.prefsize(w, h)
    g = gl.winopen("rb")
    gl.RGBmode()
    if double:
        gl.doublebuffer()
    gl.stensize(stencil)
    gl.gconfig()
    return session.windows[g]


def words(data: bytes) -> list[int]:
    return np.frombuffer(data, "<u4").tolist()


def test_lrectread_byte_layout_of_a_cleared_window():
    ctx = rgb_window()
    ctx.clear_planes(CLEAR_COLOUR, A)
    data = gl.lrectread(0, 0, 1, 0)
    assert data == bytes([0x20, 0x40, 0xFF, 0x80] * 2)  # R, G, B, A per pixel
    assert len(gl.lrectread(0, 0, 3, 2)) == 4 * 4 * 3


def test_lrectread_rows_bottom_first():
    ctx = rgb_window()
    ctx.clear_planes(CLEAR_COLOUR, A)
    gl.scrmask(0, 3, 2, 2)  # the top row only
    ctx.clear_planes(CLEAR_COLOUR, B)
    got = words(gl.lrectread(0, 0, 3, 2))
    assert got == [A] * 8 + [B] * 4


def test_lrectread_outside_the_window_reads_zero():
    ctx = rgb_window(2, 2)
    ctx.clear_planes(CLEAR_COLOUR, A)
    assert words(gl.lrectread(-1, 1, 2, 1)) == [0, A, A, 0]


def test_lrectread_argument_errors():
    rgb_window()
    with pytest.raises(GLValueError, match=r"lrectread\(2, 0, 1, 0\)"):
        gl.lrectread(2, 0, 1, 0)
    with pytest.raises(GLTypeError, match="lrectread"):
        gl.lrectread(0.0, 0, 1, 0)


def test_lrectwrite_round_trip_ints_and_bytes():
    rgb_window()
    gl.lrectwrite(1, 1, 2, 2, [A, B, C, D])
    got = words(gl.lrectread(0, 1, 3, 2))
    assert got == [0, A, B, 0, 0, C, D, 0]
    data = gl.lrectread(1, 1, 2, 2)
    gl.lrectwrite(0, 0, 1, 1, data)  # the string lrectread returns writes back
    assert words(gl.lrectread(0, 0, 1, 1)) == [A, B, C, D]
    gl.lrectwrite(3, 0, 3, 0, [-1])  # unsigned long: -1 is 0xFFFFFFFF
    assert words(gl.lrectread(3, 0, 3, 0)) == [0xFFFFFFFF]


def test_lrectwrite_through_write_mask_and_screen_mask_only():
    ctx = rgb_window()
    ctx.clear_planes(CLEAR_COLOUR, 0x01010101)
    ctx.raster.set(wmpack=0x0000FF00)  # green bits only
    ctx.raster.set(zbuffer=True, zfunc=0)  # ZF_NEVER: pixel writes ignore the z test
    gl.lrectwrite(0, 0, 0, 0, [0xFFFFFFFF])
    assert words(gl.lrectread(0, 0, 0, 0)) == [0x0101FF01]
    ctx.raster.set(wmpack=0xFFFFFFFF)
    gl.scrmask(1, 1, 0, 0)
    gl.lrectwrite(0, 0, 2, 0, [A, B, C])
    assert words(gl.lrectread(0, 0, 2, 0)) == [0x0101FF01, B, 0x01010101]


def test_lrectwrite_leaves_z_and_stencil_alone():
    ctx = rgb_window(stencil=8)
    ctx.clear_planes(CLEAR_Z | CLEAR_STENCIL, 0, z=-5, stencil=9)
    ctx.raster.set(stencil=(True, 0, 0, 0xFF, 1, 1, 1))  # SF_NEVER, ST_ZERO everywhere
    gl.lrectwrite(0, 0, 0, 0, [A])
    assert words(gl.lrectread(0, 0, 0, 0)) == [A]
    assert gl.read_pixels(plane="stencil")[0, 0] == 9
    assert gl.read_pixels(plane="z")[0, 0] == -5


def test_lrectwrite_data_errors():
    rgb_window()
    with pytest.raises(GLValueError, match="needs 2 pixels = 8 bytes"):
        gl.lrectwrite(0, 0, 1, 0, b"\x00" * 7)
    with pytest.raises(GLValueError, match="3 pixel values for a rectangle of 2"):
        gl.lrectwrite(0, 0, 1, 0, [1, 2, 3])
    with pytest.raises(GLTypeError, match="lrectwrite"):
        gl.lrectwrite(0, 0, 1, 0, "abcdefgh")
    with pytest.raises(GLTypeError, match="integers"):
        gl.lrectwrite(0, 0, 1, 0, [1.5, 2.5])


def test_readsource_zbuffer_returns_z_words():
    ctx = rgb_window()
    gl.readsource(GL.SRC_ZBUFFER)
    assert np.frombuffer(gl.lrectread(0, 0, 0, 0), "<i4").tolist() == [0x7FFFFF]
    ctx.clear_planes(CLEAR_Z, z=-5)
    assert gl.lrectread(0, 0, 0, 0) == (-5).to_bytes(4, "little", signed=True)
    gl.zbsize(0)
    gl.gconfig()
    gl.readsource(GL.SRC_ZBUFFER)
    with pytest.raises(GLUsageError, match="no z-buffer"):
        gl.lrectread(0, 0, 0, 0)


def test_readsource_front_back_auto():
    ctx = rgb_window(double=True)
    ctx.clear_planes(CLEAR_COLOUR, A)  # drawing goes to the back buffer
    gl.swapbuffers()  # front = A, back = the old front (0)
    assert words(gl.lrectread(0, 0, 0, 0)) == [0]  # SRC_AUTO reads the back buffer
    gl.readsource(GL.SRC_FRONT)
    assert words(gl.lrectread(0, 0, 0, 0)) == [A]
    gl.readsource(GL.SRC_BACK)
    assert words(gl.lrectread(0, 0, 0, 0)) == [0]


def test_readRGB_from_the_character_position():
    ctx = rgb_window()
    gl.lrectwrite(0, 1, 3, 1, [0x00030201, 0x00060504, 0x00090807, 0x000C0B0A])
    ctx.cpos = (1, 1)
    assert gl.readRGB(2) == (2, [4, 7], [5, 8], [6, 9])
    assert tuple(ctx.cpos)[:2] == (3, 1)  # one pixel right of the last one read
    assert gl.readRGB(10) == (1, [10], [11], [12])  # the row ends at the window edge
    assert ctx.cpos_valid is False  # x = 4 is outside the viewport 0..3
    assert gl.readRGB(1) == (0, [], [], [])


def test_readRGB_needs_rgb_mode():
    gl.winopen("cmode window")
    with pytest.raises(GLUsageError, match=r"readRGB\(1\).*RGB mode"):
        gl.readRGB(1)


def test_rectcopy_plain_and_overlapping():
    rgb_window()
    gl.lrectwrite(0, 0, 2, 0, [A, B, C])
    gl.rectcopy(0, 0, 1, 0, 2, 1)
    assert words(gl.lrectread(0, 1, 3, 1)) == [0, 0, A, B]
    gl.rectcopy(2, 0, 0, 0, 1, 0)  # corners in any order; copy overlaps its source
    assert words(gl.lrectread(0, 0, 3, 0)) == [A, A, B, C]


def test_read_pixels_planes():
    ctx = rgb_window(3, 2, stencil=4)
    ctx.clear_planes(CLEAR_COLOUR | CLEAR_STENCIL, A, stencil=5)
    gl.lrectwrite(0, 0, 0, 0, [B])
    rgba = gl.read_pixels()
    assert rgba.shape == (2, 3, 4) and rgba.dtype == np.uint8
    assert rgba[0, 0].tolist() == [0x44, 0x33, 0x22, 0x11]  # row 0 is the bottom
    assert rgba[1, 2].tolist() == [0x20, 0x40, 0xFF, 0x80]
    packed = gl.read_pixels(plane="packed")
    assert packed.dtype == np.uint32 and packed[0, 0] == B
    assert gl.read_pixels(plane="z").tolist() == [[0x7FFFFF] * 3] * 2
    assert gl.read_pixels(plane="stencil").tolist() == [[5] * 3] * 2
    with pytest.raises(GLUsageError, match="no accum planes"):
        gl.read_pixels(plane="accum")
    with pytest.raises(GLUsageError, match="single-buffered"):
        gl.read_pixels("back")
    with pytest.raises(GLValueError):
        gl.read_pixels(plane="colour")


def test_read_pixels_display_of_a_cmode_window():
    gl.prefsize(2, 1)
    g = gl.winopen("c")
    session.windows[g].clear_planes(CLEAR_COLOUR, int(GL.GREEN))
    assert gl.read_pixels("display").tolist() == [[[0, 255, 0, 255]] * 2]
    assert gl.read_pixels(plane="packed").tolist() == [[2, 2]]


def test_read_pixels_before_winopen():
    with pytest.raises(GLUsageError, match="read_pixels"):
        gl.read_pixels()


def test_readdisplay_composes_windows_at_their_origins():
    gl.prefposition(10, 11, 20, 20)  # a 2x1 window at screen (10, 20)
    g = gl.winopen("d")
    gl.RGBmode()
    gl.gconfig()
    session.windows[g].clear_planes(CLEAR_COLOUR, A)
    assert words(gl.readdisplay(9, 20, 12, 20, 0)) == [0, A, A, 0]


def test_packrect_and_unpackrect():
    # 2x2 pixels, packfactor 2: one byte from the lower-left pixel (no averaging)
    big = np.array([0x00000064, 0x00FFFFFF, 0, 0], "<u4").tobytes()  # first: R = 100
    assert gl.packrect(2, 2, 2, big) == bytes([30])  # (30*100 + 0 + 0) // 100
    px = 0x00C86432  # R 0x32=50, G 0x64=100, B 0xC8=200: (1500 + 5900 + 2200) // 100 = 96
    assert gl.packrect(1, 1, 1, np.array([px], "<u4").tobytes()) == bytes([96])
    out = np.frombuffer(gl.unpackrect(3, 3, 2, bytes([1, 2, 3, 4])), "<u4").reshape(3, 3)
    assert out.tolist() == [[0x010101, 0x010101, 0x020202],
                            [0x010101, 0x010101, 0x020202],
                            [0x030303, 0x030303, 0x040404]]
    with pytest.raises(GLValueError, match="packrect"):
        gl.packrect(2, 2, 2, b"\x00" * 15)


def test_huge_rectangles_cost_what_the_window_holds():
    rgb_window(4, 3)
    gl.lrectwrite(0, 0, 1, 0, [A, B])
    # 8388607 x 2147483647 pixels asked for; only the window's 4x3 exist
    gl.rectcopy(0, 0, 8388607, 2147483647, 2, 1)
    # source (x, y) lands on (x + 2, y + 1); only (0..1, 0..1) lands inside
    assert words(gl.lrectread(0, 0, 3, 2)) == [A, B, 0, 0,
                                               0, 0, A, B,
                                               0, 0, 0, 0]
    gl.rectcopy(-(2 ** 31), -(2 ** 31), 2 ** 31 - 1, 2 ** 31 - 1, 0, 0)  # lands far away
    assert words(gl.lrectread(0, 0, 3, 0)) == [A, B, 0, 0]
    # a rectangle reaching far outside the window writes only the window's part
    data = np.arange(1, 10 * 10 + 1, dtype=np.uint32).reshape(10, 10)
    gl.lrectwrite(-3, -5, 6, 4, data.reshape(-1).tolist())
    got = np.frombuffer(gl.lrectread(0, 0, 3, 2), "<u4").reshape(3, 4)
    assert got.tolist() == data[5:8, 3:7].tolist()


def test_returned_rectangles_are_bounded():
    from vgxsim.gl._window import MAX_WINDOW_SIZE

    rgb_window(4, 3)
    n = MAX_WINDOW_SIZE
    with pytest.raises(GLValueError, match=r"lrectread.*larger than the largest window"):
        gl.lrectread(0, 0, n, 0)  # n + 1 pixels wide
    with pytest.raises(GLValueError, match="does not fit in 32 bits"):
        gl.lrectread(0, 0, 2 ** 62, 2 ** 62)
    with pytest.raises(GLValueError, match="does not fit in 32 bits"):
        gl.lrectread(0, 0, 2 ** 63, 2 ** 63)
    with pytest.raises(GLValueError, match="readdisplay"):
        gl.readdisplay(0, 0, 0, n, 0)
    # the largest allowed read still returns every pixel asked for
    assert len(gl.lrectread(-n + 1, 0, 0, 0)) == 4 * n


def test_readRGB_outside_the_window_reads_nothing():
    rgb_window(4, 3)
    ctx = session.windows[session.current]
    ctx.cpos, ctx.cpos_valid = (-2 ** 31, 1), True
    assert gl.readRGB(2 ** 31 - 1) == (0, [], [], [])


def test_read_pixels_argument_types():
    rgb_window()
    with pytest.raises(GLTypeError, match=r"read_pixels\(<array \(3,\)>, 'color'\): buffer"):
        gl.read_pixels(np.zeros(3))
    with pytest.raises(GLTypeError, match="plane must be a str"):
        gl.read_pixels("front", ["z"])
    with pytest.raises(GLValueError, match="buffer must be"):
        gl.read_pixels("left")


def _pixel_write_scene(seed: int):
    """Random window, draw state and pixel writes (lrectwrite, zoomed lrectwrite,
    rectcopy, writeRGB) on top of queued drawing; returns the colour, z and stencil
    planes after everything has been rendered."""
    rng = np.random.default_rng(seed)
    w, h = int(rng.integers(5, 24)), int(rng.integers(4, 18))
    double = bool(rng.integers(2))
    ctx = rgb_window(w, h, double=double, stencil=4)
    ctx.clear_planes(CLEAR_COLOUR | CLEAR_Z | CLEAR_STENCIL, int(rng.integers(0, 1 << 32)),
                     z=-3, stencil=5)
    for _ in range(4):
        if double:
            gl.frontbuffer(int(rng.integers(2)))
            gl.backbuffer(int(rng.integers(2)))
        # Per-fragment state that pixel writes must ignore.
        gl.zbuffer(int(rng.integers(2)))
        gl.blendfunction(*[(GL.BF_ONE, GL.BF_ZERO), (GL.BF_SA, GL.BF_MSA)][rng.integers(2)])
        gl.logicop([GL.LO_SRC, GL.LO_XOR][rng.integers(2)])
        gl.afunction(200, [GL.AF_ALWAYS, GL.AF_NEVER][rng.integers(2)])
        gl.wmpack([0xFFFFFFFF, 0, int(rng.integers(0, 1 << 32))][rng.integers(3)])
        l, b = int(rng.integers(0, w)), int(rng.integers(0, h))
        gl.viewport(l, int(rng.integers(l, w + 3)), b, int(rng.integers(b, h + 3)))
        if rng.integers(2):
            gl.scrmask(int(rng.integers(0, w)), int(rng.integers(0, w)),
                       int(rng.integers(0, h)), int(rng.integers(0, h)))
        gl.rectzoom(*[(1, 1), (2, 1), (1.5, 3)][rng.integers(3)])
        x1, y1 = int(rng.integers(-4, w)), int(rng.integers(-4, h))
        x2, y2 = x1 + int(rng.integers(0, w + 4)), y1 + int(rng.integers(0, h + 4))
        data = rng.integers(0, 1 << 32, (x2 - x1 + 1) * (y2 - y1 + 1)).tolist()
        gl.lrectwrite(x1, y1, x2, y2, data)
        gl.rectcopy(int(rng.integers(-2, w)), int(rng.integers(-2, h)), int(rng.integers(0, w)),
                    int(rng.integers(0, h)), int(rng.integers(-3, w)), int(rng.integers(-3, h)))
        gl.cmov2i(int(rng.integers(0, w)), int(rng.integers(0, h)))
        gl.writeRGB(3, [1, 2, 3], [4, 5, 6], [7, 8, 9])
    ctx.flush()
    planes = [ctx.fb.front.copy(), ctx.fb.z.copy(), ctx.fb.stencil.copy()]
    if double:
        planes.append(ctx.fb.back.copy())
    return planes


@pytest.mark.parametrize("seed", range(40))
def test_plane_copy_writes_what_the_fragment_path_writes(seed, monkeypatch):
    """The PLANE_COPY switch (vgxsim/gl/_readback.py): pixel writes copied straight
    into the planes give the same planes as one queued fragment per pixel (the
    OpenGL backend's batch always takes the fragment path)."""
    from vgxsim.backends import get_backend
    from vgxsim.gl import _readback

    copies = []
    real = _readback._copy_into_planes
    monkeypatch.setattr(_readback, "_copy_into_planes",
                        lambda *a: (copies.append(1), real(*a)))
    got = {}
    for flag in (True, False):
        monkeypatch.setattr(_readback, "PLANE_COPY", flag)
        session.reset()
        got[flag] = _pixel_write_scene(seed)
        assert bool(copies) == (flag and get_backend() == "software")
        copies.clear()
    for fast, general in zip(got[True], got[False], strict=True):
        np.testing.assert_array_equal(fast, general)


@pytest.mark.parametrize("flag", [True, False])
def test_lrectwrite_into_the_overlay_planes_keeps_their_bits(flag, monkeypatch):
    """drawmode(OVERDRAW): a 2-bit overlay keeps the low two bits of each word, by
    either write path; the normal planes are untouched."""
    from vgxsim.gl import _readback

    monkeypatch.setattr(_readback, "PLANE_COPY", flag)
    gl.prefsize(4, 2)
    g = gl.winopen("ov")
    gl.RGBmode()
    gl.overlay(2)
    gl.gconfig()
    ctx = session.windows[g]
    gl.drawmode(GL.OVERDRAW)
    gl.lrectwrite(0, 0, 3, 1, [4, 5, 6, 7, 0xFF, 9, 10, 11])
    gl.drawmode(GL.NORMALDRAW)
    assert ctx.layer_buffer("overlay").tolist() == [[0, 1, 2, 3], [3, 1, 2, 3]]
    assert not ctx.colour_buffer("front").any()
