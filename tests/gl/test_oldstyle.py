"""Old-style drawing (gl/_oldstyle.py) against hand-computed pixels."""

from __future__ import annotations

import math

import numpy as np
import pytest

from vgxsim import gl
from vgxsim.gl._core import GLValueError
from vgxsim.gl._oldstyle import CHORD_TOLERANCE, circle_segments

W, H = 64, 48


@pytest.fixture
def ctx(gl_window):
    c = gl_window(W, H, projection=False)
    gl.ortho2(-0.5, W - 0.5, -0.5, H - 0.5)
    gl.cpack(0xFFFFFFFF)
    return c


def lit_pixels(c) -> set[tuple[int, int]]:
    ys, xs = np.nonzero(c.read_rgba()[..., :3].any(axis=2))
    return {(int(x), int(y)) for x, y in zip(xs, ys, strict=True)}


def box(x0, x1, y0, y1) -> set[tuple[int, int]]:
    return {(x, y) for x in range(x0, x1 + 1) for y in range(y0, y1 + 1)}


def clear(c) -> None:
    c.fb.front[:] = 0


def test_rectf_covers_left_bottom_inclusive(ctx):
    # Right and top edges pass through pixel centres 5 and 4 and are exclusive.
    gl.rectf(2, 2, 5, 4)
    assert lit_pixels(ctx) == box(2, 4, 2, 3)
    clear(ctx)
    gl.rectfi(2, 2, 5, 4)
    gl.rectfs((5, 2, 8, 4))  # one tuple for all arguments, as the binding allowed
    assert lit_pixels(ctx) == box(2, 7, 2, 3)  # abutting rectangles tile exactly


def test_rect_outline_is_closed(ctx):
    gl.rect(2, 2, 5, 4)
    assert lit_pixels(ctx) == box(2, 5, 2, 4) - box(3, 4, 3, 3)
    with pytest.raises(gl.GLTypeError, match="recti"):
        gl.recti(2.0, 2, 5, 4)


def test_polf_and_poly(ctx):
    gl.polf([2, 2, 0, 9, 2, 0, 9, 7, 0, 2, 7, 0])
    filled = lit_pixels(ctx)
    assert filled == box(2, 8, 2, 6)
    clear(ctx)
    gl.polf2i([2, 2, 9, 2, 9, 7, 2, 7])
    assert lit_pixels(ctx) == filled
    clear(ctx)
    gl.poly2([2, 2, 9, 2, 9, 7, 2, 7])
    assert lit_pixels(ctx) == box(2, 9, 2, 7) - box(3, 8, 3, 6)
    with pytest.raises(gl.GLTypeError, match=r"polf\(\[7 values\]\).*3n"):
        gl.polf([1, 2, 3, 4, 5, 6, 7])
    with pytest.raises(gl.GLTypeError, match="polfi"):
        gl.polfi([1.5, 2, 3, 4, 5, 6, 7, 8, 9])


def test_polf_equals_bgnpolygon(ctx):
    pts = [(3.2, 4.7), (40.1, 2.2), (30.3, 33.9), (8.8, 25.1)]
    gl.polf2([c for p in pts for c in p])
    a = ctx.read_rgba().copy()
    clear(ctx)
    gl.bgnpolygon()
    for p in pts:
        gl.v2f(p)
    gl.endpolygon()
    assert np.array_equal(a, ctx.read_rgba())


def test_pnt_sets_pixel_and_graphics_position(ctx):
    gl.pnt2i(3, 4)
    gl.pnt(10.0, 11.0, 0.0)
    assert lit_pixels(ctx) == {(3, 4), (10, 11)}
    assert ctx.gpos == (10.0, 11.0, 0.0, 1.0)


def test_move_draw(ctx):
    gl.move2i(2, 3)
    gl.draw2i(8, 3)
    gl.draw2(8.0, 9.0)
    assert lit_pixels(ctx) == box(2, 8, 3, 3) | box(8, 8, 3, 9)
    assert ctx.gpos == (8.0, 9.0, 0.0, 1.0)
    clear(ctx)
    gl.move2i(20, 20)
    gl.rdr2i(5, 0)  # relative to the current graphics position
    gl.rmv2i(0, 5)
    gl.rdr2i(-5, 0)
    assert lit_pixels(ctx) == box(20, 25, 20, 20) | box(20, 25, 25, 25)


def test_draw_continues_the_line_style_and_move_restarts_it(ctx):
    ctx.raster.set(linestyle=0x0F0F)
    gl.bgnline()
    for p in [(2, 5), (13, 5), (13, 20)]:
        gl.v2i(p)
    gl.endline()
    polyline = lit_pixels(ctx)
    clear(ctx)
    gl.move2i(2, 5)
    gl.draw2i(13, 5)
    gl.draw2i(13, 20)
    assert lit_pixels(ctx) == polyline
    clear(ctx)
    gl.move2i(2, 5)
    gl.draw2i(13, 5)
    gl.move2i(13, 5)  # restarts the pattern
    gl.draw2i(13, 20)
    assert lit_pixels(ctx) != polyline
    # The second segment alone, drawn from a fresh start, is what a move gives.
    restart = lit_pixels(ctx)
    clear(ctx)
    gl.move2i(13, 5)
    gl.draw2i(13, 20)
    assert {p for p in restart if p[0] == 13 and p[1] > 5} == {
        p for p in lit_pixels(ctx) if p[1] > 5}


def test_pmv_pdr_pclos(ctx):
    gl.pmv2i(2, 2)
    gl.pdr2i(9, 2)
    gl.v2i(9, 7)  # v* calls are allowed between pmv and pclos (pmv(3G))
    gl.pdr2(2.0, 7.0)
    gl.pclos()
    assert lit_pixels(ctx) == box(2, 8, 2, 6)
    clear(ctx)
    gl.rpmv2i(2, 0)  # from the current graphics position (2, 7)
    gl.rpdr2i(7, 0)
    gl.rpdr2i(0, 5)
    gl.rpdr2i(-7, 0)
    gl.pclos()
    assert lit_pixels(ctx) == box(4, 10, 7, 11)
    with pytest.raises(gl.GLUsageError, match="pdr.*pmv"):
        gl.pdr(1.0, 2.0, 3.0)
    with pytest.raises(gl.GLUsageError, match="pclos.*without pmv"):
        gl.pclos()


def test_old_style_calls_rejected_inside_a_primitive(ctx):
    gl.bgnline()
    with pytest.raises(gl.GLUsageError, match="rectf.*bgnline"):
        gl.rectf(1, 1, 2, 2)
    with pytest.raises(gl.GLUsageError, match="draw2"):
        gl.draw2(1, 1)
    with pytest.raises(gl.GLUsageError, match="circ"):
        gl.circ(5, 5, 3)
    gl.endline()


def test_circf_area(ctx):
    r = 20
    gl.circf(32, 24, r)
    n = len(lit_pixels(ctx))
    assert abs(n - math.pi * r * r) < 0.015 * math.pi * r * r
    clear(ctx)
    gl.circfi(32, 24, 10)
    assert abs(len(lit_pixels(ctx)) - math.pi * 100) < 0.03 * math.pi * 100


def test_circ_outline_lies_on_the_circle(ctx):
    gl.circ(32.0, 24.0, 15.0)
    pts = lit_pixels(ctx)
    d = np.array([math.hypot(x - 32, y - 24) for x, y in pts])
    assert len(pts) > 80 and (np.abs(d - 15) <= 1.0).all()


def test_arcf_quarter_and_wraparound(ctx):
    gl.arcf(20, 20, 16, 0, 900)
    pts = lit_pixels(ctx)
    assert all(x >= 20 and y >= 20 for x, y in pts)
    # Pixel centres of the quarter disc; the edges on the axes are left/bottom edges,
    # which the tie rule includes.
    centres = sum(1 for dx in range(17) for dy in range(17) if dx * dx + dy * dy < 256)
    assert abs(len(pts) - centres) < 0.03 * centres
    clear(ctx)
    gl.arcf(32, 24, 16, 100, 50)  # from 10 to 5 degrees: nearly the whole disc
    nearly = len(lit_pixels(ctx))
    clear(ctx)
    gl.circf(32, 24, 16)
    assert 0.97 * len(lit_pixels(ctx)) < nearly < len(lit_pixels(ctx))
    clear(ctx)
    gl.arc(32, 24, 10, 0, 1800)  # the upper half circle
    pts = lit_pixels(ctx)
    assert all(y >= 24 for _x, y in pts) and (42, 24) in pts and (22, 24) in pts
    clear(ctx)
    gl.arcf(32, 24, 10, 300, 300)  # equal angles: nothing
    assert not lit_pixels(ctx)


def test_circle_argument_errors(ctx):
    with pytest.raises(gl.GLTypeError, match="arc.*Angle"):
        gl.arc(0.0, 0.0, 1.0, 0.0, 90.0)
    with pytest.raises(gl.GLValueError, match="circf.*negative"):
        gl.circf(1, 1, -2)
    with pytest.raises(gl.GLTypeError, match="circi"):
        gl.circi(1.0, 1, 2)


def test_circle_segments_keep_chords_within_tolerance(ctx):
    for r in (3.0, 10.0, 40.0, 200.0):
        n = circle_segments(ctx, 32, 24, r)
        assert 16 <= n <= 1024
        sagitta = r * (1 - math.cos(math.pi / n))
        assert sagitta <= CHORD_TOLERANCE or n == 16
    gl.scale(4, 4, 1)  # the radius is measured in pixels, through the matrix
    assert circle_segments(ctx, 8, 6, 40.0) > circle_segments(ctx, 8, 6, 10.0)


def test_getgpos_is_transformed_by_the_current_matrix(ctx):
    gl.move2i(10, 20)
    # ortho2(-0.5, 63.5, -0.5, 47.5): x_clip = (10 + 0.5) / 32 - 1, y = 20.5 / 24 - 1
    np.testing.assert_allclose(gl.getgpos(), (10.5 / 32 - 1, 20.5 / 24 - 1, 0.0, 1.0))


@pytest.mark.parametrize("name", ["circ", "circf", "arc", "arcf"])
def test_huge_radius_draws_a_bounded_shape(ctx, name):
    call = getattr(gl, name)
    angles = (0, 900) if name.startswith("arc") else ()
    call(W / 2, H / 2, 1e17, *angles)  # ZeroDivisionError before the clamp
    gl.gflush()
    # a circle far past every edge: an outline lights nothing inside the window, a
    # fill covers all of it (arcf: the quarter 0..90 degrees above-right of the centre)
    lit = lit_pixels(ctx)
    if name == "circf":
        assert lit == box(0, W - 1, 0, H - 1)
    elif name == "arcf":
        assert lit == box(W // 2, W - 1, H // 2, H - 1)
    else:
        assert not lit


@pytest.mark.parametrize("name", ["circ", "circf", "arc", "arcf"])
@pytest.mark.parametrize("radius", [1e17, 1e300, 1.7e308])
def test_every_finite_radius_is_finite_work(ctx, name, radius):
    # Past ~1e15 pixels the chord formula's angle rounds to 0 (a ZeroDivisionError
    # before); past 1e308 the radius in pixels is inf: both get a clamped count.
    assert circle_segments(ctx, 0.0, 0.0, radius) == (1024 if radius < 1e308 else 16)
    angles = (0, 900) if name.startswith("arc") else ()
    with np.errstate(all="ignore"):  # the pipeline meets inf coordinates; no error
        getattr(gl, name)(0.0, 0.0, radius, *angles)
        gl.gflush()
    assert ctx.read_rgba().shape == (H, W, 4)


@pytest.mark.parametrize("name", ["circi", "circfi", "circs", "arci", "arcfi", "arcfs"])
def test_integer_forms_take_the_largest_long_radius(ctx, name):
    args = (0, 0, 2 ** 31 - 1) + ((0, 900) if "arc" in name else ())
    getattr(gl, name)(*args)
    gl.gflush()
    with pytest.raises(GLValueError, match="32 bits"):
        getattr(gl, name)(*(args[:2] + (2 ** 32,) + args[3:]))
