"""Line styles counted per pixel drawn (deflinestyle(3G): one bit per pixel, lowest
bit first, continuing across the vertices of one bgnline), on zig-zags whose
vertices lie on pixel centres (integer coordinates under the standard ortho2).

Expected pixels are worked out by hand in each test's comments: a polyline's pixels
are numbered from 0 along it, the vertex shared by two segments being one pixel.
"""

import functools

import numpy as np
import pytest

from vgxsim import GL
from vgxsim.gl import (
    bgnline,
    deflinestyle,
    draw2i,
    endline,
    lsrepeat,
    move2i,
    setlinestyle,
    subpixel,
    v2f,
    v2i,
)

W, H = 16, 10


@pytest.fixture
def win(gl_window):
    return functools.partial(gl_window, W, H)


def lit_pixels(ctx):
    ctx.flush()
    ys, xs = np.nonzero(ctx.read_rgba()[..., 0])
    return {(int(x), int(y)) for x, y in zip(xs, ys, strict=True)}


def polyline(points):
    bgnline()
    for p in points:
        v2i(*p)
    endline()


def styled(style, repeat=1):
    deflinestyle(1, style)
    setlinestyle(1)
    lsrepeat(repeat)


def test_diagonal_zigzag_of_odd_segments_keeps_the_phase(win):
    ctx = win()
    ctx.colour = (1.0, 1.0, 1.0, 1.0)
    styled(0x5555)  # bits 0, 2, 4, ... on: even pixel numbers drawn
    # 45-degree segments of 3 steps: pixel numbers 0-3 (1,1)..(4,4), 3-6 (4,4)..(7,1),
    # 6-9 (7,1)..(10,4).  Even numbers: 0 (1,1), 2 (3,3), 4 (5,3), 6 (7,1), 8 (9,3).
    polyline([(1, 1), (4, 4), (7, 1), (10, 4)])
    assert lit_pixels(ctx) == {(1, 1), (3, 3), (5, 3), (7, 1), (9, 3)}


def test_axis_zigzag_with_mixed_majors(win):
    ctx = win()
    ctx.colour = (1.0, 1.0, 1.0, 1.0)
    styled(0x0F0F)  # pixels 0-3 on, 4-7 off, 8-11 on, 12-15 off, ...
    # (1,1)->(6,1): x-major, numbers 0..5 at x = 1..6;
    # (6,1)->(6,8): y-major, numbers 5..12 at y = 1..8;
    # (6,8)->(1,8): numbers 12..17 at x = 6..1.
    polyline([(1, 1), (6, 1), (6, 8), (1, 8)])
    on = {n for n in range(18) if (n % 16) // 4 % 2 == 0}
    pixels = ([(1 + k, 1) for k in range(6)] + [(6, 1 + k) for k in range(1, 8)]
              + [(6 - k, 8) for k in range(1, 6)])
    assert lit_pixels(ctx) == {p for n, p in enumerate(pixels) if n in on}


def test_repeat_counts_pixels_too(win):
    ctx = win()
    ctx.colour = (1.0, 1.0, 1.0, 1.0)
    styled(0x0001, repeat=3)  # bit 0 only, each bit 3 pixels: numbers 0-2 and 48-50
    # Numbers 0..3 along (2,2)->(5,2) then 3..8 up (5,2)->(5,7): 0, 1, 2 drawn.
    polyline([(2, 2), (5, 2), (5, 7)])
    assert lit_pixels(ctx) == {(2, 2), (3, 2), (4, 2)}


def test_half_open_lines_number_every_pixel_once(win):
    ctx = win()
    ctx.colour = (1.0, 1.0, 1.0, 1.0)
    subpixel(GL.TRUE)  # half-open: the last pixel of each segment is not drawn
    styled(0x5555)
    # (1,1)->(4,1) draws x = 1, 2, 3 (numbers 0-2); (4,1)->(4,6) draws y = 1..5
    # (numbers 3-7): even numbers 0 (1,1), 2 (3,1), 4 (4,2), 6 (4,4).
    polyline([(1, 1), (4, 1), (4, 6)])
    assert lit_pixels(ctx) == {(1, 1), (3, 1), (4, 2), (4, 4)}


def test_move_draw_continues_the_pattern_and_move_restarts_it(win):
    ctx = win()
    ctx.colour = (1.0, 1.0, 1.0, 1.0)
    styled(0x5555)
    move2i(1, 1)
    draw2i(4, 1)  # numbers 0-3: (1,1), (3,1)
    draw2i(4, 6)  # numbers 3-8 at y = 1..6: 4 (4,2), 6 (4,4), 8 (4,6)
    move2i(8, 3)
    draw2i(11, 3)  # restarts: 0 (8,3), 2 (10,3)
    assert lit_pixels(ctx) == {(1, 1), (3, 1), (4, 2), (4, 4), (4, 6), (8, 3), (10, 3)}


# -- conventions of docs/numeric_model.md s. 13 ---------------------------------------
def segment(a, b):
    bgnline()
    v2f(*a)
    v2f(*b)
    endline()


@pytest.mark.parametrize("reverse", [False, True])
def test_tie_at_half_pixel_goes_to_the_larger_coordinate_either_way(win, reverse):
    ctx = win()
    ctx.colour = (1.0, 1.0, 1.0, 1.0)
    subpixel(GL.TRUE)
    # y-major, x = 2 + y/4: rows 0..4 have x = 2, 2.25, 2.5 (tie -> 3), 2.75, 3.
    # Half-open: (2,0)->(3,4) draws rows 0-3, (3,4)->(2,0) rows 4-1.
    a, b = (2.0, 0.0), (3.0, 4.0)
    segment(*((b, a) if reverse else (a, b)))
    rows = {0: 2, 1: 2, 2: 3, 3: 3, 4: 3}
    drawn = range(4, 0, -1) if reverse else range(4)
    assert lit_pixels(ctx) == {(rows[y], y) for y in drawn}


def test_subpixel_line_follows_its_unsnapped_ends(win):
    ctx = win()
    ctx.colour = (1.0, 1.0, 1.0, 1.0)
    subpixel(GL.TRUE)
    # (0.375, 1) -> (4.375, 3): columns floor(0.875) = 0 .. floor(4.875) = 4, the last
    # not drawn; y(X) = 1 + (X - 0.375)/2 = 0.8125, 1.3125, 1.8125, 2.3125 -> 1, 1, 2, 2.
    # (Between the end pixels' centres (0,1)-(4,3), column 1 would be 1.5 -> 2.)
    segment((0.375, 1.0), (4.375, 3.0))
    assert lit_pixels(ctx) == {(0, 1), (1, 1), (2, 2), (3, 2)}


def test_resetls_false_continues_the_pattern_across_lines(win):
    from vgxsim.gl import getresetls, resetls

    ctx = win()
    ctx.colour = (1.0, 1.0, 1.0, 1.0)
    styled(0x5555)
    assert getresetls() == 1
    resetls(GL.FALSE)
    assert getresetls() == 0
    polyline([(1, 1), (4, 1)])  # numbers 0-3: (1,1), (3,1)
    polyline([(1, 3), (4, 3)])  # continues at 3 (the last pixel's number): 4 (2,3), 6 (4,3)
    move2i(1, 5)
    draw2i(4, 5)  # a move does not restart either: 6..9 -> (1,5), (3,5)
    resetls(GL.TRUE)
    polyline([(1, 7), (4, 7)])  # restarts: (1,7), (3,7)
    assert lit_pixels(ctx) == {(1, 1), (3, 1), (2, 3), (4, 3), (1, 5), (3, 5), (1, 7),
                               (3, 7)}


# -- lsbackup(3G): the last two pixels of a line are drawn ---------------------------------
def test_lsbackup_draws_the_last_two_pixels_of_each_line(win):
    from vgxsim.gl import getlsbackup, lsbackup

    ctx = win()
    ctx.colour = (1.0, 1.0, 1.0, 1.0)
    styled(0x0F0F)  # numbers 0-3 on, 4-7 off, 8-11 on, 12-15 off
    assert getlsbackup() == 0
    lsbackup(GL.TRUE)
    assert getlsbackup() == 1
    # (0,1)->(13,1): numbers 0..13 at x = 0..13; the pattern draws 0-3, 8-11, and
    # backup adds the last two, 12 and 13.
    polyline([(0, 1), (13, 1)])
    # A polyline: numbers 0..6 along (0,3)->(6,3), 6..13 up (6,3)->(6,10) clipped to
    # y <= 9: numbers 6..12 at y = 3..9.  The window edge clips the end, so the last
    # two pixels drawn are numbers 11 and 12 (at y = 8, 9); 12 is off in the pattern.
    polyline([(0, 3), (6, 3), (6, 10)])
    # move/draw: each draw is a line: (8,5)->(15,5) numbers 0..7, backup adds 6, 7.
    move2i(8, 5)
    draw2i(15, 5)
    lsbackup(GL.FALSE)
    polyline([(0, 7), (5, 7)])  # numbers 0..5: 0-3 only, no backup
    row1 = {(x, 1) for x in (0, 1, 2, 3, 8, 9, 10, 11, 12, 13)}
    path = [(x, 3) for x in range(7)] + [(6, y) for y in range(4, 10)]
    poly = {p for n, p in enumerate(path) if (n % 16) // 4 % 2 == 0 or n >= 11}
    row5 = {(x, 5) for x in (8, 9, 10, 11, 14, 15)}
    row7 = {(x, 7) for x in (0, 1, 2, 3)}
    assert lit_pixels(ctx) == row1 | poly | row5 | row7


def test_lsbackup_with_half_open_lines_and_no_double_drawing(win):
    from vgxsim.gl import logicop, lsbackup

    ctx = win()
    ctx.colour = (1.0, 1.0, 1.0, 1.0)
    subpixel(GL.TRUE)  # half-open: (0,1)->(9,1) draws x = 0..8, numbers 0..8
    styled(0x000F)  # numbers 0-3 on
    lsbackup(GL.TRUE)
    polyline([(0, 1), (9, 1)])
    # Solid style under XOR: a pixel drawn twice would come back to 0.
    styled(0xFFFF)
    logicop(GL.LO_XOR)
    polyline([(0, 3), (9, 3)])
    assert lit_pixels(ctx) == ({(x, 1) for x in (0, 1, 2, 3, 7, 8)}
                               | {(x, 3) for x in range(9)})
