"""drawmode, overlay, underlay, pupmode/endpupmode/pupcolor: the extra framebuffers,
their own colours, maps and write masks, and what the monitor shows (underlay(3G)'s
rule), checked on hand-placed pixels."""

import numpy as np
import pytest

import vgxsim.gl as gl
from vgxsim import GL
from vgxsim.gl._core import GLUsageError, GLValueError, session

pytestmark = pytest.mark.usefixtures("fresh_session")  # tests/gl/conftest.py

W, H = 16, 12
RED, GREEN, BLUE = (255, 0, 0, 255), (0, 255, 0, 255), (0, 0, 255, 255)


def window(rgb=True, double=False, over=0, under=0):
    gl.prefsize(W, H)
    gl.winopen("layers")
    if rgb:
        gl.RGBmode()
    else:
        gl.cmode()
    if double:
        gl.doublebuffer()
    gl.overlay(over)
    gl.underlay(under)
    gl.gconfig()
    return session.windows[gl.winget()]


def shown(ctx):
    return ctx.display_rgba()


def fill(x0, y0, x1, y1):
    """Fill pixels x0..x1, y0..y1 (inclusive): rectfi's polygon covers the pixel
    centres on its left and bottom edges, not those on its right and top edges
    (docs/numeric_model.md, the fill rule)."""
    gl.rectfi(x0, y0, x1 + 1, y1 + 1)


def test_overlay_covers_the_normal_planes_where_its_index_is_not_zero():
    ctx = window(over=2)
    gl.cpack(0xFF00FF00)  # green normal planes
    gl.clear()
    gl.drawmode(GL.OVERDRAW)
    gl.mapcolor(1, 255, 0, 0)
    gl.mapcolor(2, 0, 0, 255)
    gl.color(1)
    fill(2, 2, 5, 4)  # pixels x 2..5, y 2..4
    gl.color(2)
    gl.pnt2i(10, 7)
    gl.drawmode(GL.NORMALDRAW)
    img = shown(ctx)
    expect = np.empty((H, W, 4), np.uint8)
    expect[:] = GREEN
    expect[2:5, 2:6] = RED
    expect[7, 10] = BLUE
    assert np.array_equal(img, expect)
    # The normal planes are untouched: green everywhere.
    assert (ctx.fb.front == 0xFF00FF00).all()
    # color(0) + clear() makes the overlay transparent again.
    gl.drawmode(GL.OVERDRAW)
    gl.color(0)
    gl.clear()
    gl.drawmode(GL.NORMALDRAW)
    assert (shown(ctx) == GREEN).all()


def test_each_framebuffer_keeps_its_own_colour_map_colour_and_writemask():
    ctx = window(rgb=False, over=2)
    gl.mapcolor(1, 10, 20, 30)  # normal map
    gl.color(5)
    gl.writemask(0xF0F)
    gl.drawmode(GL.OVERDRAW)
    assert gl.getcolor() == 0 and gl.getwritemask() == 0xFFF
    assert gl.getmcolor(1) == (255, 0, 0)  # the overlay map's own start (makemap)
    gl.mapcolor(1, 1, 2, 3)
    gl.color(3)
    gl.writemask(1)  # only plane 0: color(3) stores 1
    gl.pnt2i(4, 4)
    gl.drawmode(GL.NORMALDRAW)
    assert gl.getcolor() == 5 and gl.getwritemask() == 0xF0F
    assert gl.getmcolor(1) == (10, 20, 30)
    gl.drawmode(GL.OVERDRAW)
    assert gl.getcolor() == 3 and gl.getwritemask() == 1 and gl.getmcolor(1) == (1, 2, 3)
    assert gl.getplanes() == 2
    gl.drawmode(GL.NORMALDRAW)
    assert gl.getplanes() == 12
    assert int(ctx.plane_sets["overlay"].fb.front[4, 4]) == 1
    img = shown(ctx)
    assert tuple(img[4, 4]) == (1, 2, 3, 255)  # overlay index 1 in the overlay map
    assert tuple(img[0, 0]) == (0, 0, 0, 255)  # normal index 0, black


def test_color_larger_than_the_planes_keeps_the_low_bits():
    window(over=2)
    gl.drawmode(GL.OVERDRAW)
    gl.color(6)  # 0b110 in two planes: 2
    gl.pnt2i(1, 1)
    gl.drawmode(GL.NORMALDRAW)
    ctx = session.windows[gl.winget()]
    assert int(ctx.plane_sets["overlay"].fb.front[1, 1]) == 2


def test_underlay_shows_where_the_normal_planes_hold_zero():
    ctx = window(rgb=False, under=2)
    gl.mapcolor(7, 255, 255, 255)
    gl.color(7)
    fill(0, 0, 7, H - 1)  # left half index 7, right half index 0
    gl.drawmode(GL.UNDERDRAW)
    gl.mapcolor(0, 0, 0, 255)  # the underlay's index 0: blue
    gl.mapcolor(3, 0, 255, 0)
    gl.color(3)
    fill(12, 0, 15, 3)
    gl.drawmode(GL.NORMALDRAW)
    img = shown(ctx)
    expect = np.empty((H, W, 4), np.uint8)
    expect[:, :8] = (255, 255, 255, 255)
    expect[:, 8:] = BLUE  # underlay index 0 through the underlay map
    expect[0:4, 12:16] = GREEN
    assert np.array_equal(img, expect)


def test_no_underlay_planes_no_underlay():
    ctx = window(rgb=False)
    gl.drawmode(GL.UNDERDRAW)
    assert gl.getplanes() == 0
    gl.mapcolor(0, 0, 0, 255)
    gl.color(3)
    gl.clear()
    gl.drawmode(GL.NORMALDRAW)
    assert (shown(ctx) == (0, 0, 0, 255)).all()  # the normal index 0, black


def test_popup_covers_the_overlay_and_pup_calls():
    ctx = window(over=2)
    gl.drawmode(GL.OVERDRAW)
    gl.color(1)  # overlay index 1: red (makemap default)
    fill(0, 0, 9, 9)
    gl.drawmode(GL.PUPDRAW)
    assert gl.getplanes() == 2
    gl.color(GL.PUP_WHITE)
    fill(5, 5, 6, 6)
    gl.endpupmode()
    assert gl.getdrawmode() == GL.NORMALDRAW
    gl.pupcolor(GL.PUP_BLACK)  # the pop-up colour while normal is drawn
    gl.pupmode()
    assert gl.getdrawmode() == GL.PUPDRAW and gl.getcolor() == GL.PUP_BLACK
    gl.pnt2i(0, 0)
    gl.endpupmode()
    img = shown(ctx)
    expect = np.zeros((H, W, 4), np.uint8)  # cleared RGB planes: 0, alpha 0 too
    expect[0:10, 0:10] = RED
    expect[5:7, 5:7] = (255, 255, 255, 255)
    expect[0, 0] = (0, 0, 0, 255)  # PUP_BLACK covers the overlay
    assert np.array_equal(img, expect)


def test_overlay_drawing_ignores_the_normal_z_buffer_stencil_and_blending():
    ctx = window(over=2)
    gl.zbuffer(True)
    gl.zfunction(GL.ZF_NEVER)
    gl.blendfunction(GL.BF_ZERO, GL.BF_ONE)  # would leave every pixel as it was
    gl.drawmode(GL.OVERDRAW)
    gl.color(1)
    fill(0, 0, 3, 3)
    gl.drawmode(GL.NORMALDRAW)
    assert (ctx.plane_sets["overlay"].fb.front[0:4, 0:4] == 1).all()
    assert gl.getzbuffer() == 1  # shared modes stay as set


def test_logicop_xor_works_on_overlay_indices():
    ctx = window(over=2)
    gl.drawmode(GL.OVERDRAW)
    gl.logicop(GL.LO_XOR)
    gl.color(3)
    fill(0, 0, 3, 0)
    gl.color(1)
    fill(2, 0, 5, 0)
    gl.drawmode(GL.NORMALDRAW)
    row = ctx.plane_sets["overlay"].fb.front[0, :7].tolist()
    assert row == [3, 3, 2, 2, 1, 1, 0]


def test_readback_in_overdraw_reads_the_overlay_indices():
    window(over=2)
    gl.drawmode(GL.OVERDRAW)
    gl.color(2)
    gl.pnt2i(1, 0)
    data = gl.rectread(0, 0, 2, 0)
    assert list(np.frombuffer(data, "<u2")) == [0, 2, 0]
    with pytest.raises(GLUsageError):
        gl.RGBcolor(1, 2, 3)  # the overlay is colour-index only (cpack(3G))
    gl.drawmode(GL.NORMALDRAW)


def test_swapbuffers_in_overdraw_swaps_the_normal_buffers_and_frames_composite():
    ctx = window(double=True, over=2)
    frames = []

    class Sink:
        def write(self, img):
            frames.append(img.copy())

    ctx.sink = Sink()
    gl.cpack(0xFFFF0000)  # blue into the back buffer
    gl.clear()
    gl.drawmode(GL.OVERDRAW)
    gl.color(1)
    gl.pnt2i(3, 2)
    gl.swapbuffers()  # still in OVERDRAW
    gl.drawmode(GL.NORMALDRAW)
    assert len(frames) == 1
    expect = np.empty((H, W, 4), np.uint8)
    expect[:] = BLUE
    expect[2, 3] = RED
    assert np.array_equal(frames[0], expect)


def test_gconfig_and_reshape_keep_the_draw_mode_and_reallocate_the_overlay():
    ctx = window(over=2)
    gl.drawmode(GL.OVERDRAW)
    gl.color(1)
    gl.clear()
    gl.mapcolor(2, 9, 9, 9)
    gl.gconfig()
    assert gl.getdrawmode() == GL.OVERDRAW and gl.getplanes() == 2
    assert (ctx.plane_sets["overlay"].fb.front == 0).all()  # granted anew, cleared
    assert gl.getmcolor(2) == (9, 9, 9)  # maps belong to the monitor: kept
    gl.drawmode(GL.NORMALDRAW)
    gl.overlay(0)
    gl.gconfig()
    gl.drawmode(GL.OVERDRAW)
    assert gl.getplanes() == 0
    gl.color(1)
    gl.clear()  # no planes: nothing is stored, nothing shows
    gl.drawmode(GL.NORMALDRAW)
    assert (shown(ctx) == (0, 0, 0, 0)).all()


def test_normal_drawing_is_unchanged_by_configured_and_visited_layers():
    # The same scene drawn three ways: no overlay; an overlay configured but empty;
    # and drawmode switched to the overlay (drawing nothing there) between every
    # primitive.  The normal planes and the picture must be identical.
    def scene(over, visit):
        window(over=over)
        ctx = session.windows[gl.winget()]
        gl.zbuffer(True)
        gl.zclear()
        rng = np.random.default_rng(3)
        for _ in range(12):
            if visit:
                gl.drawmode(GL.OVERDRAW)
                gl.drawmode(GL.NORMALDRAW)
            gl.cpack(int(rng.integers(0, 1 << 32)))
            gl.bgnpolygon()
            for _ in range(3):
                gl.v3f(*rng.uniform([-1, -1, -W], [W, H, W]).tolist())
            gl.endpolygon()
        picture = shown(ctx)  # flushes
        out = ctx.fb.front.copy(), ctx.fb.z.copy(), picture
        gl.winclose(gl.winget())
        return out

    base = scene(0, False)
    for over, visit in ((2, False), (2, True)):
        got = scene(over, visit)
        assert all(np.array_equal(a, b) for a, b in zip(base, got, strict=True))
    assert len(np.unique(base[0])) > 3  # the scene drew something


def test_getgdesc_answers_the_emulated_planes():
    assert gl.getgdesc(GL.GD_BITS_OVER_SNG_CMODE) == 4
    assert gl.getgdesc(GL.GD_BITS_UNDR_SNG_CMODE) == 4
    assert gl.getgdesc(GL.GD_BITS_PUP_SNG_CMODE) == 2
    assert gl.getgdesc(GL.GD_OVERUNDER_SHARED) == 0


def test_errors_name_the_call():
    window()
    with pytest.raises(GLValueError, match="drawmode"):
        gl.drawmode(GL.DUALDRAW)
    with pytest.raises(GLValueError, match="overlay"):
        gl.overlay(5)
    with pytest.raises(GLValueError, match="underlay"):
        gl.underlay(-1)
    with pytest.raises(GLValueError, match="pupcolor"):
        gl.pupcolor(4)
    gl.bgnline()
    with pytest.raises(GLUsageError, match="drawmode"):
        gl.drawmode(GL.OVERDRAW)
    gl.endline()


def test_cursordraw_keeps_a_map_and_shows_nothing():
    ctx = window()
    gl.drawmode(GL.CURSORDRAW)
    gl.mapcolor(1, 1, 1, 1)
    assert gl.getmcolor(1) == (1, 1, 1) and gl.getplanes() == 0
    gl.color(1)
    gl.clear()
    gl.drawmode(GL.NORMALDRAW)
    assert gl.getmcolor(1) == (255, 0, 0)
    assert (shown(ctx) == 0).all()


def test_readsource_reads_the_overlay_underlay_and_popup_indices():
    window(over=2)
    gl.drawmode(GL.OVERDRAW)
    gl.color(3)
    gl.pnt2i(2, 1)
    gl.drawmode(GL.PUPDRAW)
    gl.color(1)
    gl.pnt2i(0, 1)
    gl.drawmode(GL.NORMALDRAW)
    gl.cpack(0xFF0000FF)
    gl.pnt2i(1, 1)

    def words():
        return list(np.frombuffer(gl.lrectread(0, 1, 3, 1), "<u4"))

    gl.readsource(GL.SRC_OVER)
    assert words() == [0, 0, 3, 0]
    gl.readsource(GL.SRC_PUP)
    assert words() == [1, 0, 0, 0]
    gl.readsource(GL.SRC_UNDER)
    assert words() == [0, 0, 0, 0]  # no underlay planes: zero
    gl.readsource(GL.SRC_FRONT)
    assert words() == [0, 0xFF0000FF, 0, 0]


def test_readdisplay_hints_leave_framebuffers_out():
    window(over=2)
    gl.cpack(0xFF00FF00)
    gl.clear()
    gl.drawmode(GL.OVERDRAW)
    gl.color(1)  # red (makemap default)
    gl.pnt2i(0, 0)
    gl.drawmode(GL.NORMALDRAW)
    ox, oy = gl.getorigin()

    def pixel(hints):
        return int(np.frombuffer(gl.readdisplay(ox, oy, ox, oy, hints), "<u4")[0])

    assert pixel(0) == 0xFF0000FF
    assert pixel(GL.RD_IGNORE_OVERLAY) == 0xFF00FF00
    assert pixel(GL.RD_IGNORE_PUP | GL.RD_IGNORE_UNDERLAY) == 0xFF0000FF


def test_single_buffered_frames_start_from_what_fresh_planes_show():
    # A cmode window with underlay planes whose index 0 is blue: fresh planes show
    # blue (the normal planes' 0 lets the underlay show).  Clearing the normal planes
    # to index 0 leaves the screen as it was, so no frame is produced.
    ctx = window(rgb=False, under=2)
    frames = []

    class Sink:
        def write(self, img):
            frames.append(img.copy())

    ctx.sink = Sink()
    gl.drawmode(GL.UNDERDRAW)
    gl.mapcolor(0, 0, 0, 255)
    gl.drawmode(GL.NORMALDRAW)
    gl.color(0)
    gl.clear()
    gl.gflush()
    assert frames == []  # the screen did not change
    gl.drawmode(GL.OVERDRAW)  # no overlay planes: nothing stored, nothing shown
    gl.color(1)
    gl.clear()
    gl.drawmode(GL.NORMALDRAW)
    gl.gflush()
    assert frames == []
    gl.color(1)
    gl.pnt2i(0, 0)
    gl.gflush()
    assert len(frames) == 1
    assert tuple(frames[0][0, 0]) == (255, 0, 0, 255) and tuple(frames[0][1, 1]) == BLUE
