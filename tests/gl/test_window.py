"""Window, configuration and frame calls (vgxsim.gl._window) and inquiries (_query).

Expected values are hand-computed from the IRIS GL manual pages cited in the
module docstrings and from the VGX figures in shared/reference/irisgl_reference.md
(s.3: 1280x1024, 24-bit z, 8 stencil planes).
"""

import imageio.v3 as iio
import numpy as np
import pytest

import vgxsim.gl as gl
from vgxsim import GL
from vgxsim.gl._core import GLTypeError, GLUsageError, GLValueError, session, window_of
from vgxsim.pipeline.context import CLEAR_COLOUR
from vgxsim.sinks import MemorySink, PNGSequenceSink

pytestmark = pytest.mark.usefixtures("fresh_session")  # tests/gl/conftest.py


def ctx_of(gid):
    return session.windows[gid]


# -- winopen and the window constraints ---------------------------------------------------
def test_winopen_default_size_and_gids():
    g1 = gl.winopen("one")
    assert g1 == 1 and gl.winget() == 1
    assert gl.getsize() == (640, 512)  # session.default_size, IRIS-like 5:4
    assert gl.getorigin() == (0, 0)
    g2 = gl.winopen("two")
    assert g2 == 2 and gl.winget() == 2
    gl.winset(g1)
    assert gl.winget() == 1


def test_prefsize_before_winopen_then_used_up():
    gl.prefsize(100, 50)
    gl.winopen("a")
    assert gl.getsize() == (100, 50)
    gl.winopen("b")  # constraints were used up by the first winopen
    assert gl.getsize() == (640, 512)


def test_prefsize_after_winopen_applies_to_the_next_window_only():
    gl.winopen("a")
    gl.prefsize(32, 16)
    assert gl.getsize() == (640, 512)
    gl.winopen("b")
    assert gl.getsize() == (32, 16)


def test_prefposition_gives_size_and_origin():
    gl.prefposition(10, 109, 20, 69)
    gl.winopen("p")
    assert gl.getsize() == (100, 50)  # inclusive bounds: 109 - 10 + 1
    assert gl.getorigin() == (10, 20)


def test_default_size_keepaspect_minsize_maxsize():
    session.default_size = (300, 200)
    gl.keepaspect(1, 1)
    gl.winopen("square")
    assert gl.getsize() == (300, 300)
    gl.keepaspect(2, 1)
    gl.maxsize(250, 1000)
    gl.winopen("clamped")
    assert gl.getsize() == (250, 150)  # 300 x 150 by the aspect, then width clamped
    gl.minsize(400, 400)
    gl.winopen("grown")
    assert gl.getsize() == (400, 400)


def test_bad_window_arguments():
    with pytest.raises(GLTypeError, match=r"winopen\(123\)"):
        gl.winopen(123)
    with pytest.raises(GLValueError, match=r"prefsize\(0, 5\)"):
        gl.prefsize(0, 5)
    with pytest.raises(GLTypeError):
        gl.prefsize(10.0, 5)
    with pytest.raises(GLValueError, match="prefposition"):
        gl.prefposition(100, 10, 0, 10)
    with pytest.raises(GLValueError, match=r"winset\(7\)"):
        gl.winset(7)


def test_winclose_leaves_no_current_window():
    g = gl.winopen("w")
    gl.winclose(g)
    assert gl.winget() == -1
    with pytest.raises(GLUsageError, match="no window is open"):
        gl.getsize()
    with pytest.raises(GLValueError):
        gl.winclose(g)


def test_calls_before_winopen_are_usage_errors():
    for call, args in [(gl.viewport, (0, 1, 0, 1)), (gl.swapbuffers, ()), (gl.RGBmode, ()),
                       (gl.gconfig, ()), (gl.stensize, (8,)), (gl.getviewport, ()),
                       (gl.lrectread, (0, 0, 1, 1)), (gl.getgconfig, (GL.GC_DOUBLE,)),
                       (gl.clear, ()), (gl.bgnpolygon, ()), (gl.v3f, (0.0, 0.0, 0.0))]:
        with pytest.raises(GLUsageError, match=call.__name__):
            call(*args)


def test_winconstraints_and_winposition_reshape_the_window():
    g = gl.winopen("w")
    session.queue.qreset()
    gl.prefsize(50, 40)
    gl.winconstraints()
    assert gl.getsize() == (50, 40)
    assert ctx_of(g).fb.front.shape == (40, 50)
    assert session.queue.entries == [(528, g)]  # REDRAW after the reshape
    gl.winposition(10, 59, 20, 39)
    assert gl.getsize() == (50, 20) and gl.getorigin() == (10, 20)
    gl.winmove(3, 4)
    assert gl.getorigin() == (3, 4) and gl.getsize() == (50, 20)


def test_titles_and_no_op_requests():
    gl.noborder()
    gl.foreground()
    gl.noport()
    gl.iconsize(64, 64)
    g = gl.winopen("first")
    gl.wintitle("renamed")
    gl.icontitle("icon")
    rec = window_of(ctx_of(g))  # the gl layer's bookkeeping of the window
    assert rec.title == "renamed" and rec.icontitle == "icon"
    assert rec.constraints["noborder"] is True


# -- configuration -------------------------------------------------------------------------
def test_iris_default_configuration():
    g = gl.winopen("w")
    assert gl.getdisplaymode() == GL.DMSINGLE  # colour map, single-buffered
    assert gl.getgconfig(GL.GC_BITS_CMODE) == 12
    assert gl.getgconfig(GL.GC_BITS_RED) == 0
    assert gl.getgconfig(GL.GC_BITS_ZBUFFER) == 24
    assert gl.getgconfig(GL.GC_BITS_STENCIL) == 0
    assert gl.getgconfig(GL.GC_DOUBLE) == 0
    fb = ctx_of(g).fb
    assert fb.back is None and fb.stencil is None and fb.accum is None
    assert gl.getplanes() == 12
    assert gl.getbuffer() == GL.FRNTBUFFER


def test_requests_take_effect_only_at_gconfig():
    g = gl.winopen("w")
    gl.RGBmode()
    gl.doublebuffer()
    gl.stensize(8)
    gl.acsize(16)
    gl.zbsize(0)
    fb = ctx_of(g).fb
    assert fb.stencil is None and fb.back is None  # still the old planes
    assert gl.getgconfig(GL.GC_BITS_STENCIL) == 0
    assert gl.getdisplaymode() == GL.DMSINGLE
    gl.gconfig()
    fb = ctx_of(g).fb
    assert fb.stencil.shape == (512, 640) and fb.stencil.dtype == np.uint8
    assert fb.accum.shape == (512, 640, 4) and fb.back is not None and fb.z is None
    assert gl.getgconfig(GL.GC_BITS_STENCIL) == 8
    assert gl.getgconfig(GL.GC_BITS_ACBUF) == 16
    assert gl.getgconfig(GL.GC_BITS_ZBUFFER) == 0
    assert gl.getgconfig(GL.GC_ZMAX) == 0
    assert gl.getgconfig(GL.GC_BITS_RED) == 8 and gl.getgconfig(GL.GC_BITS_CMODE) == 0
    assert gl.getdisplaymode() == GL.DMRGBDOUBLE
    assert gl.getplanes() == 24
    assert gl.getbuffer() == GL.BCKBUFFER  # double-buffered windows draw to the back
    gl.frontbuffer(GL.TRUE)
    assert gl.getbuffer() == GL.BCKBUFFER | GL.FRNTBUFFER
    gl.backbuffer(GL.FALSE)
    assert gl.getbuffer() == GL.FRNTBUFFER
    gl.cmode()
    gl.singlebuffer()
    gl.gconfig()
    assert gl.getdisplaymode() == GL.DMSINGLE


def test_the_1991_configuration_sequence():
    # Heidmann's code: stensize(getgdesc(GD_BITS_STENCIL)); gconfig();
    gl.winopen("shadows")
    gl.RGBmode()
    gl.doublebuffer()
    gl.stensize(gl.getgdesc(GL.GD_BITS_STENCIL))
    gl.gconfig()
    assert gl.getgconfig(GL.GC_BITS_STENCIL) == 8
    assert gl.getgconfig(GL.GC_ZMIN) == -0x800000 and gl.getgconfig(GL.GC_ZMAX) == 0x7FFFFF


def test_plane_size_limits():
    gl.winopen("w")
    with pytest.raises(GLValueError, match=r"stensize\(9\).*GD_BITS_STENCIL.*8"):
        gl.stensize(9)
    with pytest.raises(GLValueError, match=r"stensize\(-1\)"):
        gl.stensize(-1)
    with pytest.raises(GLTypeError, match="stensize"):
        gl.stensize(1.5)
    with pytest.raises(GLValueError, match=r"acsize\(8\)"):
        gl.acsize(8)
    with pytest.raises(GLValueError, match=r"zbsize\(16\)"):
        gl.zbsize(16)
    for n in range(9):
        gl.stensize(n)


def test_gconfig_resets_write_masks():
    g = gl.winopen("w")
    ctx_of(g).raster.set(zwritemask=0, wmpack=0x00FF00FF)
    gl.gconfig()
    assert ctx_of(g).raster.zwritemask == 0xFFFFFFFF
    assert ctx_of(g).raster.wmpack == 0xFFFFFFFF


# -- viewport, screen mask, buffers ---------------------------------------------------------
def test_viewport_round_trip_and_screenmask_reset():
    gl.prefsize(100, 80)
    g = gl.winopen("w")
    assert gl.getviewport() == (0, 99, 0, 79)
    gl.scrmask(10, 20, 30, 40)
    assert gl.getscrmask() == (10, 20, 30, 40)
    gl.viewport(5, 50, 6, 60)
    assert gl.getviewport() == (5, 50, 6, 60)
    assert gl.getscrmask() == (5, 50, 6, 60)  # viewport resets the screen mask
    assert ctx_of(g).raster.raster_rect() == (5, 50, 6, 60)
    gl.reshapeviewport()
    assert gl.getviewport() == (0, 99, 0, 79) and gl.getscrmask() == (0, 99, 0, 79)
    with pytest.raises(GLValueError, match=r"viewport\(5, 4, 0, 1\)"):
        gl.viewport(5, 4, 0, 1)
    with pytest.raises(GLTypeError):
        gl.viewport(0.0, 4, 0, 1)


def test_empty_screenmask_protects_everything():
    gl.prefsize(4, 4)
    g = gl.winopen("w")
    gl.scrmask(3, 1, 0, 3)
    x0, x1, y0, y1 = ctx_of(g).raster.raster_rect()
    assert x0 > x1


def test_subpixel_and_readsource_store_registers():
    g = gl.winopen("w")
    gl.subpixel(GL.TRUE)
    assert ctx_of(g).raster.subpixel is True
    gl.readsource(GL.SRC_FRONT)
    assert ctx_of(g).readsource == GL.SRC_FRONT
    with pytest.raises(GLValueError, match=r"readsource\(SRC_FRAMEGRABBER\)"):
        gl.readsource(GL.SRC_FRAMEGRABBER)
    with pytest.raises(GLValueError, match=r"readsource\(42\)"):
        gl.readsource(42)


# -- frames ----------------------------------------------------------------------------------
def test_swapbuffers_hands_the_new_front_to_the_sink():
    gl.prefsize(6, 4)
    g = gl.winopen("w")
    gl.RGBmode()
    gl.doublebuffer()
    gl.gconfig()
    sink = ctx_of(g).sink = MemorySink()
    ctx_of(g).clear_planes(CLEAR_COLOUR, 0xFF0000FF)  # back buffer: opaque red
    assert len(sink) == 0
    gl.swapbuffers()
    assert len(sink) == 1
    assert sink[0].shape == (4, 6, 4)
    assert (sink[0] == [255, 0, 0, 255]).all()
    gl.swapbuffers()  # the old front (black) comes back
    assert len(sink) == 2 and (sink[1] == 0).all()
    assert session.queue.frame == 2  # each swapbuffers is one frame for the queue


def test_frames_go_to_a_png_directory_top_row_first(tmp_path):
    session.sink_factory = lambda gid: PNGSequenceSink(tmp_path / f"w{gid}")
    gl.prefsize(5, 3)
    g = gl.winopen("w")
    gl.RGBmode()
    gl.doublebuffer()
    gl.gconfig()
    ctx = ctx_of(g)
    ctx.clear_planes(CLEAR_COLOUR, 0xFF00FF00)  # green everywhere
    gl.scrmask(0, 4, 0, 0)  # the bottom row only (window row 0)
    ctx.clear_planes(CLEAR_COLOUR, 0xFFFF0000)  # blue
    gl.swapbuffers()
    png = iio.imread(tmp_path / "w1" / "frame_0000.png")
    assert png.shape == (3, 5, 3)
    assert (png[2] == [0, 0, 255]).all()  # the file's last row is the window's row 0
    assert (png[:2] == [0, 255, 0]).all()


def test_single_buffered_frames_only_when_the_screen_changed():
    gl.prefsize(4, 4)
    g = gl.winopen("w")
    gl.RGBmode()
    gl.gconfig()
    ctx = ctx_of(g)
    sink = ctx.sink = MemorySink()
    gl.gflush()
    assert len(sink) == 0  # nothing drawn yet: the screen still shows the cleared planes
    ctx.clear_planes(CLEAR_COLOUR, 0xFF00FFFF)  # yellow
    gl.gflush()
    assert len(sink) == 1 and (sink[0] == [255, 255, 0, 255]).all()
    gl.finish()
    gl.swapbuffers()  # IRIS ignores it single-buffered: no exchange, no new picture
    assert len(sink) == 1
    assert (ctx.fb.front.view(np.uint8).reshape(4, 4, 4) == [255, 255, 0, 255]).all()
    assert session.queue.frame == 4  # two gflush, finish and swapbuffers: one frame each


def test_cmode_frames_are_colour_mapped():
    gl.prefsize(2, 2)
    g = gl.winopen("w")
    ctx = ctx_of(g)
    sink = ctx.sink = MemorySink()
    ctx.clear_planes(CLEAR_COLOUR, int(GL.RED))  # colour index 1 of the default map
    gl.gflush()
    assert (sink[0] == [255, 0, 0, 255]).all()


def test_winclose_emits_a_changed_single_buffered_screen():
    gl.prefsize(2, 2)
    g = gl.winopen("w")
    gl.RGBmode()
    gl.gconfig()
    sink = ctx_of(g).sink = MemorySink()
    ctx_of(g).clear_planes(CLEAR_COLOUR, 0xFFFFFFFF)
    gl.winclose(g)
    assert len(sink) == 1 and (sink[0] == 255).all()


def test_gflush_without_a_window_is_harmless():
    gl.gflush()
    gl.finish()


# -- getgdesc and friends ------------------------------------------------------------------
# Hand-copied VGX answers (irisgl_reference.md s.1.2, s.1.4, s.3 and the task brief).
VGX = {
    "GD_XPMAX": 1280, "GD_YPMAX": 1024, "GD_ZMIN": -0x800000, "GD_ZMAX": 0x7FFFFF,
    "GD_BITS_NORM_SNG_RED": 8, "GD_BITS_NORM_SNG_GREEN": 8, "GD_BITS_NORM_SNG_BLUE": 8,
    "GD_BITS_NORM_DBL_RED": 8, "GD_BITS_NORM_DBL_GREEN": 8, "GD_BITS_NORM_DBL_BLUE": 8,
    "GD_BITS_NORM_SNG_ALPHA": 8, "GD_BITS_NORM_DBL_ALPHA": 8,
    "GD_BITS_NORM_ZBUFFER": 24, "GD_BITS_STENCIL": 8, "GD_BITS_ACBUF": 16, "GD_BLEND": 1,
    "GD_SUBPIXEL_LINE": 1, "GD_SUBPIXEL_PNT": 1, "GD_SUBPIXEL_POLY": 1,
    "GD_LIGHTING_TWOSIDE": 1, "GD_NVERTEX_POLY": 256, "GD_NMMAPS": 16,
    "GD_TIMERHZ": 60, "GD_WSYS": 1, "GD_MULTISAMPLE": 0, "GD_FRAMEGRABBER": 0,
}
ANSWERS = {"GD_NOLIMIT", "GD_WSYS_NONE", "GD_WSYS_4S", "GD_SCRNTYPE_WM", "GD_SCRNTYPE_NOWM"}


def test_getgdesc_vgx_answers_before_winopen():
    assert session.current is None
    for name, value in VGX.items():
        assert gl.getgdesc(getattr(GL, name)) == value, name
    assert gl.getgdesc(GL.GD_WSYS) == GL.GD_WSYS_4S


def test_getgdesc_answers_every_inquiry_token():
    inquiries = [n for n in GL.__all__ if n.startswith("GD_") and n not in ANSWERS]
    assert len(inquiries) == 80  # 70 from IRIX 5 GL.py + 10 post-IRIX-5 (GD_MULTISAMPLE..)
    for name in inquiries:
        assert isinstance(gl.getgdesc(getattr(GL, name)), int), name


def test_getgdesc_answers_minus_one_for_unknown_inquiries():
    # getgdesc(3G): -1 for an invalid inquiry (tests/gl/test_query.py has more).
    for bad in (20, 29, 1000, -2):
        assert gl.getgdesc(bad) == -1
    with pytest.raises(GLTypeError):
        gl.getgdesc(1.0)


def test_gversion_and_mode_getters():
    v = gl.gversion()
    assert v.startswith("GL4DVGX") and len(v) <= 11  # fits gversion's char[12]
    g = gl.winopen("w")
    assert gl.getzbuffer() == 0
    ctx_of(g).raster.set(zbuffer=True)
    assert gl.getzbuffer() == 1
    assert gl.getdrawmode() == GL.NORMALDRAW
    with pytest.raises(GLValueError, match=r"getgconfig\(99\)"):
        gl.getgconfig(99)


def test_window_sizes_past_the_limit_are_refused_before_allocation():
    from vgxsim.gl._window import MAX_WINDOW_SIZE

    assert MAX_WINDOW_SIZE >= 16384
    big = MAX_WINDOW_SIZE + 1
    with pytest.raises(GLValueError, match=r"prefsize\(100000, 100000\).*16384x16384"):
        gl.prefsize(100000, 100000)
    with pytest.raises(GLValueError, match=r"prefsize\(1, 16385\)"):
        gl.prefsize(1, big)
    with pytest.raises(GLValueError, match="prefposition"):
        gl.prefposition(0, big - 1, 0, 9)  # big pixels wide, inclusive bounds
    with pytest.raises(GLValueError, match="minsize"):
        gl.minsize(big, 1)
    gl.prefposition(0, MAX_WINDOW_SIZE - 1, 0, 0)  # exactly the limit is a window
    # keepaspect makes the size at winopen: refused there, nothing opened
    session.reset()
    session.default_size = (64, 48)
    gl.keepaspect(1, 1000)
    with pytest.raises(GLValueError, match=r"winopen\('tall'\).*64x64000"):
        gl.winopen("tall")
    assert session.windows == {}
    session.reset()  # the failed winopen left its constraints pending, as before it
    session.default_size = (big, 1)  # what `vgxsim run --size` would set
    with pytest.raises(GLValueError, match="winopen"):
        gl.winopen("wide")
    session.default_size = (4, 4)
    gl.winopen("w")
    with pytest.raises(GLValueError, match="winposition"):
        gl.winposition(0, big, 0, 3)
    assert gl.getsize() == (4, 4)


def test_integers_past_32_bits_are_refused():
    with pytest.raises(GLValueError, match=r"prefsize\(2\*\*40|does not fit in 32 bits"):
        gl.prefsize(2 ** 40, 5)
    gl.winopen("w")
    gl.RGBmode()
    gl.gconfig()
    gl.viewport(-(2 ** 31), 2 ** 32 - 1, 0, 3)  # the ends of the 32-bit range are fine
    for bad in (2 ** 32, -(2 ** 31) - 1, 2 ** 63, np.uint64(2 ** 63)):
        with pytest.raises(GLValueError, match="does not fit in 32 bits"):
            gl.viewport(0, bad, 0, 3)
    with pytest.raises(GLValueError, match=r"winset\(9223372036854775808\)"):
        gl.winset(2 ** 63)
    # unsigned long masks and colours are reduced modulo 2**32 as C does
    gl.cpack(2 ** 63 + 0x10)
    assert gl.gRGBcolor() == (0x10, 0, 0)


def test_session_reset_clears_the_window_bookkeeping():
    # Constraints pending for the next winopen, the focus entry still to come and the
    # Window records are session state: reset() drops them all.
    gl.keepaspect(1, 2)
    gl.noborder()
    g = gl.winopen("before")
    gl.winmove(30, 40)
    ctx = ctx_of(g)
    gl.maxsize(100, 100)
    session.reset()
    assert session.constraints == {} and session.focus_pending is None
    assert ctx not in session.window_records
    g = gl.winopen("after")
    assert gl.getsize() == (640, 512)  # no maxsize, no keepaspect: the default size
    assert gl.getorigin() == (0, 0)
    assert window_of(ctx_of(g)).constraints == {}
