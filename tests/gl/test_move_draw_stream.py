"""move/draw recorded in the command stream (issue 6): random programs of move*,
draw*, rmv*/rdr*, pnt*, bgnline polylines and rect outlines, colour, resetls,
setlinestyle and lsrepeat calls, drawn in immediate mode (FAST_CALLS on and off,
flushed at random points) and from display objects, against the naive reference.

The expected line-style positions are the model of docs/numeric_model.md s. 5,
worked out here from the naive rasterizer's own pixel counts: every line moves the
position to the end of its last segment; a draw continues from it; a move under
resetls(TRUE) puts it at 0 at once; a bgnline (or rect) line starts at 0 under
resetls(TRUE) and at the position under resetls(FALSE).
"""

from __future__ import annotations

import random

import numpy as np
import pytest

from vgxsim import gl
from vgxsim.gl import _core
from vgxsim.gl._core import GLTypeError, GLUsageError, GLValueError, session
from vgxsim.pipeline import draw
from vgxsim.reference import naive

W, H = 40, 30
STYLES = {1: 0x3C3C, 2: 0x5A0F, 3: 0xFFFF}


@pytest.fixture
def ctx(gl_window):
    c = gl_window(W, H)
    for i, s in STYLES.items():
        gl.deflinestyle(i, s)
    return c


def _coord(rng, hi, integer):
    # Quarter-pixel offsets snap away from ties (subpixel(FALSE) snaps to centres).
    v = rng.randrange(1, hi - 1)
    return v if integer else v + rng.choice((0.0, 0.25, -0.25))


def program(seed: int, n: int = 60) -> list[tuple]:
    rng = random.Random(seed)
    # (A patterned style from the start: a solid one hides every pattern offset.)
    ops: list[tuple] = [("cpack", 0xFF0000FF), ("setlinestyle", 1 + seed % 2)]
    for _ in range(n):
        r = rng.random()
        integer = rng.random() < 0.4
        p = (_coord(rng, W, integer), _coord(rng, H, integer))
        if r < 0.3:
            ops.append(("draw2i" if integer else "draw2", *p))
        elif r < 0.42:
            ops.append(("move2i" if integer else "move2", *p))
        elif r < 0.47:
            ops.append(("draw" if not integer else "drawi", *p, 0))
        elif r < 0.50:
            ops.append(("move" if not integer else "movei", *p, 0))
        elif r < 0.54:
            d = (float(rng.randint(-4, 4)), float(rng.randint(-4, 4)))
            ops.append(("rdr2" if rng.random() < 0.7 else "rmv2", *d))
        elif r < 0.62:
            ops.append(("cpack", 0xFF000000 | rng.randrange(1, 1 << 24)))
        elif r < 0.67:
            ops.append(("resetls", rng.randint(0, 1)))
        elif r < 0.72:
            ops.append(("setlinestyle", rng.choice((1, 1, 2, 2, 3))))
        elif r < 0.75:
            ops.append(("lsrepeat", rng.randint(1, 3)))
        elif r < 0.77:
            ops.append(("lsbackup", int(rng.random() < 0.4)))
        elif r < 0.81:
            ops.append(("polyline", [(rng.randrange(1, W - 1), rng.randrange(1, H - 1))
                                     for _ in range(rng.randint(2, 4))]))
        elif r < 0.84:
            x1, y1 = rng.randrange(1, W // 2), rng.randrange(1, H // 2)
            box = (x1, y1, x1 + rng.randint(1, 9), y1 + rng.randint(1, 9))
            form = rng.choice(("rect", "recti", "rectf", "rectfi"))
            ops.append((form, *(box if form.endswith("i") else map(float, box))))
        elif r < 0.88:
            q = (rng.randrange(W), rng.randrange(H))
            ops.append(("pnt2i", *q) if integer else ("pnt2", *map(float, q)))
        else:
            ops.append(("flush",))
    return ops


def run(ops: list[tuple], ctx) -> None:
    """Execute the program on the current window (flush ops included)."""
    for op in ops:
        name, args = op[0], op[1:]
        if name == "flush":
            ctx.flush()
        elif name == "polyline":
            gl.bgnline()
            for q in args[0]:
                gl.v2i(*q)
            gl.endline()
        elif name in ("move", "movei", "draw", "drawi"):
            x, y, z = args
            z = float(z) if name in ("move", "draw") else int(z)
            getattr(gl, name)(x, y, z)
        else:
            getattr(gl, name)(*args)


def expected(ops: list[tuple]) -> np.ndarray:
    """The naive reference's front buffer for the program (windows coordinates are
    object coordinates under the fixture's ortho2)."""
    from vgxsim.state.registers import RasterRegisters

    regs = RasterRegisters(W, H, False)
    fb = naive.NaiveFramebuffer(W, H, stencil_planes=8, double=False)
    colour = (0.0, 0.0, 0.0, 0.0)
    gpos = (0.0, 0.0)
    pos = 0
    resetls = True
    lsbackup = False
    cmds: list = []

    def steps(a, b) -> int:
        p0, p1 = naive.snap(*a, False), naive.snap(*b, False)
        return len(naive.line_pixels(p0, p1, True)) - 1

    def line(a, b, start) -> int:
        cmds.append(("line", [(a[0], a[1], 0.0, colour), (b[0], b[1], 0.0, colour)],
                     regs.snapshot(), start))
        return start + steps(a, b)

    def backup(segments, end) -> None:
        # lsbackup(3G): the line's last two pixels (positions end - 1 and end) are
        # drawn whatever the style says; the colour is constant along these lines.
        if not lsbackup:
            return
        for a, b, start in segments:
            p0, p1 = naive.snap(*a, False), naive.snap(*b, False)
            for x, y, i, _t, _m in naive.line_pixels(p0, p1, True):
                if start + i >= end - 1:
                    cmds.append(("point", (float(x), float(y), 0.0, colour),
                                 regs.snapshot()))

    def polyline(pts, closed) -> None:
        nonlocal pos
        start = 0 if resetls else pos
        seq = list(pts) + ([pts[0]] if closed else [])
        segments = []
        for a, b in zip(seq[:-1], seq[1:], strict=True):
            segments.append((a, b, start))
            start = line(a, b, start)
        backup(segments, start)
        pos = start

    for op in ops:
        name, args = op[0], op[1:]
        if name == "cpack":
            w = args[0]
            colour = tuple(((w >> s) & 0xFF) / 255.0 for s in (0, 8, 16, 24))
        elif name in ("move2", "move2i", "move", "movei", "rmv2"):
            gpos = ((gpos[0] + args[0], gpos[1] + args[1]) if name == "rmv2"
                    else (float(args[0]), float(args[1])))
            if resetls:
                pos = 0
        elif name in ("draw2", "draw2i", "draw", "drawi", "rdr2"):
            p = ((gpos[0] + args[0], gpos[1] + args[1]) if name == "rdr2"
                 else (float(args[0]), float(args[1])))
            start = pos
            pos = line(gpos, p, pos)
            backup([(gpos, p, start)], pos)
            gpos = p
        elif name == "resetls":
            resetls = bool(args[0])
        elif name == "lsbackup":
            lsbackup = bool(args[0])
        elif name == "setlinestyle":
            regs.set(linestyle=STYLES[args[0]])
        elif name == "lsrepeat":
            regs.set(lsrepeat=args[0])
        elif name == "polyline":
            polyline([(float(x), float(y)) for x, y in args[0]], False)
        elif name in ("rect", "recti"):
            x1, y1, x2, y2 = (float(v) for v in args)
            polyline([(x1, y1), (x2, y1), (x2, y2), (x1, y2)], True)
        elif name in ("rectf", "rectfi"):
            # rect(3G) coverage under the tie rule (gl/_oldstyle.py): columns x1..x2-1
            # and rows y1..y2-1 of a rectangle with integer corners.
            x1, y1, x2, y2 = (int(v) for v in args)
            for y in range(y1, y2):
                for x in range(x1, x2):
                    cmds.append(("point", (float(x), float(y), 0.0, colour),
                                 regs.snapshot()))
        elif name in ("pnt2i", "pnt2"):
            cmds.append(("point", (float(args[0]), float(args[1]), 0.0, colour),
                         regs.snapshot()))
            gpos = (float(args[0]), float(args[1]))
    naive.render(fb, cmds)
    return fb.front


SEEDS = range(8)


@pytest.mark.parametrize("merge", [True, False])
@pytest.mark.parametrize("fast", [True, False])
@pytest.mark.parametrize("seed", SEEDS)
def test_immediate_mode_draws_the_naive_lines(ctx, seed, fast, merge, monkeypatch):
    monkeypatch.setattr(_core, "FAST_CALLS", fast)
    monkeypatch.setattr(draw, "MERGE_SEGMENTS", merge)
    session.refresh()
    ops = program(seed)
    run(ops, ctx)
    got = ctx.colour_buffer("front")
    want = expected(ops)
    assert want.any()
    assert np.array_equal(got, want), int((got != want).sum())


@pytest.mark.parametrize("seed", SEEDS)
def test_display_objects_draw_the_naive_lines(ctx, seed):
    """The program cut into objects at its flush ops, each called in turn (with the
    flush between), then the whole program as one object called once."""
    ops = program(seed)
    parts, cur = [], []
    for op in ops:
        if op[0] == "flush":
            parts.append(cur)
            cur = []
        else:
            cur.append(op)
    parts.append(cur)
    for k, part in enumerate(parts):
        gl.makeobj(10 + k)
        run(part, ctx)
        gl.closeobj()
    for k in range(len(parts)):
        gl.callobj(10 + k)
        ctx.flush()
    want = expected(ops)
    got = ctx.colour_buffer("front")
    assert np.array_equal(got, want), int((got != want).sum())


#: A restart whose segment lies wholly outside (beyond the far plane, z = 5 under
#: ortho2's -1..1), last in its run: the position after the run is 0, where the
#: polyline under resetls(FALSE) then starts.
_TRAILING_RESTART = [("setlinestyle", 2), ("cpack", 0xFF00FFFF), ("move2", 1.0, 1.0),
                     ("draw2", 12.0, 1.0), ("move", 3.0, 9.0, 5.0), ("draw", 30.0, 9.0, 5.0),
                     ("resetls", 0), ("polyline", [(1, 5), (30, 5)])]


@pytest.mark.parametrize("seed", [*range(6), "trailing restart"])
def test_merged_segments_draw_what_one_line_each_draws_clipped_too(gl_window, seed,
                                                                    monkeypatch):
    """Segments reaching past the window (clipped: the pattern counts from the
    clipped start), some wholly outside, restarts among them: MERGE_SEGMENTS on and
    off give the same planes, as does the same program in a display object."""
    rng = random.Random(100 + (seed if isinstance(seed, int) else 0))
    ops: list[tuple] = [("setlinestyle", 2), ("cpack", 0xFF00FFFF)]
    for _ in range(80 if isinstance(seed, int) else 0):
        r = rng.random()
        p = (rng.uniform(-30.0, W + 30.0), rng.uniform(-30.0, H + 30.0))
        if r < 0.55:
            ops.append(("draw2", *p))
        elif r < 0.75:
            ops.append(("move2", *p))
        elif r < 0.8:
            ops.append(("resetls", rng.randint(0, 1)))
        elif r < 0.85:
            ops.append(("lsrepeat", rng.randint(1, 2)))
        elif r < 0.9:
            ops.append(("cpack", 0xFF000000 | rng.randrange(1, 1 << 24)))
        else:
            ops.append(("polyline", [(rng.randrange(-5, W + 5), rng.randrange(-5, H + 5))
                                     for _ in range(3)]))
    if not isinstance(seed, int):
        ops = _TRAILING_RESTART
    out = []
    for merge, objects in ((True, False), (False, False), (True, True)):
        monkeypatch.setattr(draw, "MERGE_SEGMENTS", merge)
        c = gl_window(W, H)
        for i, st in STYLES.items():
            gl.deflinestyle(i, st)
        if objects:
            gl.makeobj(1)
            run(ops, c)
            gl.closeobj()
            gl.callobj(1)
        else:
            run(ops, c)
        out.append(c.colour_buffer("front").copy())
    assert out[0].any()
    assert np.array_equal(out[0], out[1])
    assert np.array_equal(out[0], out[2])


def _bgnline_row3():
    gl.bgnline()
    gl.v2i(1, 3)
    gl.v2i(30, 3)
    gl.endline()


def _object_row28():
    gl.makeobj(5)
    gl.bgnline()
    gl.v2i(1, 28)
    gl.v2i(38, 28)
    gl.endline()
    gl.closeobj()


#: Where each line of the restart test lies: (rows, the call drawing it alone).
_RESTART_LINES = {
    "bgnline": (slice(3, 4), _bgnline_row3),
    "circ": (slice(7, 26), lambda: gl.circi(20, 16, 8)),
    "callobj": (slice(28, 29), lambda: (_object_row28(), gl.callobj(5))),
}


def test_pattern_restart_of_a_move_reaches_a_line_under_resetls_false(ctx, gl_window):
    """A move under resetls(TRUE) puts the position at 0 at once: a bgnline line, a
    circle (drawn from arrays) and an object's line drawn after resetls(FALSE) start
    there -- as each does drawn first in a fresh window -- not where the draw before
    the move ended (position 7 or 8, which the 0x5A0F style tells apart)."""
    gl.setlinestyle(2)
    gl.cpack(0xFFFFFFFF)
    _object_row28()
    for name in _RESTART_LINES:
        gl.resetls(1)
        gl.move2i(1, 1)
        gl.draw2i(8 if name != "circ" else 9, 1)  # the position is 7 (8) after it
        gl.move2i(0, 0)  # the restart
        gl.resetls(0)
        if name == "callobj":
            gl.callobj(5)
        else:
            _RESTART_LINES[name][1]()
    got = ctx.colour_buffer("front")
    for name, (rows, draw_one) in _RESTART_LINES.items():
        gl_window(W, H)
        for i, s in STYLES.items():
            gl.deflinestyle(i, s)
        gl.setlinestyle(2)
        gl.resetls(0)
        gl.cpack(0xFFFFFFFF)
        draw_one()
        one = session.windows[1].colour_buffer("front")
        assert one[rows].any(), name
        assert np.array_equal(got[rows], one[rows]), name


def test_draw_is_recorded_not_drawn_at_the_call(ctx):
    """A draw appends its segment to the stream (BGN, kind, two V, END) and flushes
    nothing: a second draw under the same state and colour adds exactly those."""
    gl.move2(1.0, 1.0)
    gl.draw2(10.0, 1.0)
    n = len(ctx.stream)
    assert n > 0
    gl.draw2(10.0, 10.0)
    assert len(ctx.stream) == n + 5
    assert ctx.gpos == (10.0, 10.0, 0.0, 1.0)


@pytest.mark.parametrize("call, args, error, words", [
    ("move2", (float("nan"), 1.0), GLValueError, "move2("),
    ("draw2", (1.0, float("inf")), GLValueError, "draw2("),
    ("draw2", ("a", 1.0), GLTypeError, "draw2("),
    ("draw2i", (1.5, 2), GLTypeError, "draw2i("),
    ("draw", (1.0, 2.0), GLTypeError, "draw("),
    ("move2", (1.0, 2.0, 3.0), GLTypeError, "move2("),
    ("rectf", (1.0, 2.0, float("nan"), 3.0), GLValueError, "rectf("),
    ("rect", (1.0, 2.0, 3.0), GLTypeError, "rect("),
    ("rectfi", (1, 2, 3.5, 4), GLTypeError, "rectfi("),
    ("pnt2", (1.0,), GLTypeError, "pnt2("),
    ("pnt2", ("x", 1.0), GLTypeError, "pnt2("),
    ("pnt", (1.0, 2.0, float("inf")), GLValueError, "pnt("),
    ("pnt2i", (1, 2.0), GLTypeError, "pnt2i("),
])
def test_bad_arguments_raise_naming_the_call(ctx, call, args, error, words):
    with pytest.raises(error, match=words.replace("(", r"\(")):
        getattr(gl, call)(*args)


def test_keyword_and_inside_a_primitive_raise(ctx):
    with pytest.raises(GLTypeError, match=r"draw2\("):
        gl.draw2(1.0, 2.0, x=3)
    gl.bgnpolygon()
    with pytest.raises(GLUsageError, match=r"draw2\("):
        gl.draw2(1.0, 2.0)
    with pytest.raises(GLUsageError, match=r"move2\("):
        gl.move2(1.0, 2.0)
    with pytest.raises(GLUsageError, match=r"rectf\("):
        gl.rectf(1.0, 2.0, 3.0, 4.0)
    with pytest.raises(GLUsageError, match=r"pnt2\("):
        gl.pnt2(1.0, 2.0)
    gl.endpolygon()


def test_pick_hits_draw_segments_under_their_names(fresh_session):
    """In pick mode a recorded draw segment is hit-tested as a line under the name
    loaded when it was drawn (pick(3G)); the picking region is the cursor's +-5
    pixels."""
    from vgxsim import DEVICE
    from vgxsim.events import EventQueue

    gl.prefsize(100, 100)
    gl.winopen("pick")
    gl.RGBmode()
    gl.gconfig()
    session.queue = EventQueue()
    session.queue.post(DEVICE.MOUSEX, 50)
    session.queue.post(DEVICE.MOUSEY, 50)
    gl.pick(50)
    gl.loadname(7)
    gl.move2(0.0, 0.0)
    gl.draw2(100.0, 100.0)  # through the region's centre, no vertex in it
    gl.loadname(8)
    gl.move2i(0, 80)
    gl.draw2i(100, 80)  # 30 pixels above
    gl.loadname(9)
    gl.draw2i(0, 20)  # from (100, 80) to (0, 20): through (50, 50)
    assert gl.endpick() == [1, 7, 1, 9]


def test_a_move_while_picking_restarts_the_pattern_after_it(ctx, gl_window):
    """A move under resetls(TRUE) inside pick mode puts the position at 0, and no
    picked line moves it: a draw after endpick that continues (no move) starts the
    pattern at 0, as it does drawn first in a fresh window."""
    from vgxsim import DEVICE
    from vgxsim.events import EventQueue

    gl.setlinestyle(2)
    gl.cpack(0xFFFFFFFF)
    gl.move2i(1, 1)
    gl.draw2i(8, 1)  # the position is 7 after it
    session.queue = EventQueue()
    session.queue.post(DEVICE.MOUSEX, 20)
    session.queue.post(DEVICE.MOUSEY, 20)
    gl.pick(10)
    gl.move2i(2, 20)
    gl.draw2i(30, 20)
    gl.endpick()
    gl.resetls(0)
    gl.move2i(1, 10)  # (no restart under resetls(FALSE))
    gl.draw2i(35, 10)  # continues from the position the pick left: 0
    got = ctx.colour_buffer("front")
    gl_window(W, H)
    for i, st in STYLES.items():
        gl.deflinestyle(i, st)
    gl.setlinestyle(2)
    gl.cpack(0xFFFFFFFF)
    gl.move2i(1, 10)
    gl.draw2i(35, 10)
    one = session.windows[1].colour_buffer("front")
    assert one[10].any()
    assert np.array_equal(got[10], one[10])
