"""Per-call cost of the IRIS GL front end, and the Heidmann frame split in two.

    python bench/calls.py [--quick] [--no-mesa] [--cpu] [--calls-only] [--json FILE]

Reports, medians over rounds, all measured in this one run:

* ns per call of issue 6's other calls (bench ``other_calls``: move2/draw2, with the
  flush timed too, pnt2, rectf, cmov2, rot/rotate/scale/multmatrix/loadmatrix less
  push + pop, getmatrix, afunction, lsetdepth, lmcolor, mmode, frontbuffer,
  setlinestyle; push/translate/polygon/pop/polygon with state.matrices.KEEP_MVPS
  off and on, alternating round by round), vgxsim only;
* ns per call of the common immediate-mode calls (v3f, n3f, c3f, cpack,
  bgnpolygon/endpolygon, stencil, lmbind, zwritemask, wmpack,
  pushmatrix/translate/popmatrix, callobj of a small object), and the nearest
  PyOpenGL immediate-mode call for each on an OSMesa context when one can be made
  (glVertex3f/glVertex3fv, glNormal3fv, glColor3f, glColor4ub, glBegin/glEnd,
  glStencilOp, glMaterialfv, glDepthMask, glColorMask, glPush/Translate/PopMatrix,
  glCallList of a one-quad list; ``ratio`` is PyOpenGL / vgxsim, the issue's target
  is >= 5; ``--no-mesa`` or no libOSMesa: those rows are left out);
* the Heidmann 1991 frame of vgxsim/examples/heidmann1991.py at 1280 x 1024 through
  the API: the whole frame, the raster part (time inside ``CommandBatch.flush``:
  binning and the band kernels) and the front end (the rest: the calls, recording,
  transform, lighting, clipping and set-up), with the front end's fast paths
  (FUSED_FRONT, BATCH_LIGHTING) on and off, alternating frame by frame;
* the makeobj replay of the frame's DrawObjects (one callobj per pass);
* the front end of both with gl._core.REPLAY_OBJECTS (callobj's prepared replays,
  draw-state records kept across flushes) off and on, alternating, and of the
  makeobj replay with gl._objects.REPLAY_PARENTS (the DrawObjects objects replayed
  from ParentBlocks) off and on;
* callobj of the 16-face object under a new matrix at each call with
  gl._objects.REBASE_REPLAYS off (traced again) and on (rebased);
* the same frame drawn by a PyOpenGL immediate-mode transliteration of the example
  (bench/heidmann_gl.py) on llvmpipe with LP_NUM_THREADS=1 and 2.

Timings on a shared machine are noisy; compare ratios measured side by side.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

N_CALLS = 2000  # calls per timed loop
#: The per-call clock: wall time, or process CPU time with --cpu (a loaded machine).
CLOCK = {"ns": time.perf_counter_ns}


def _median_ns(loop, n: int, rounds: int, before=None, after=None) -> float:
    """Median over ``rounds`` of the time of ``loop()`` (which makes ``n`` calls), in
    ns per call; ``before()`` and ``after()`` run untimed around each round (opening
    the primitive the vertices go into, drawing it)."""
    ts = []
    for r in range(rounds + 1):
        if before is not None:
            before()
        clock = CLOCK["ns"]
        t = clock()
        loop()
        dt = clock() - t
        if after is not None:
            after()
        if r:  # the first round warms up
            ts.append(dt)
    return float(np.median(ts)) / n


def vgxsim_calls(rounds: int) -> dict[str, float]:
    """ns per call of the common calls (each loop makes N_CALLS calls or groups)."""
    from vgxsim import GL, gl
    from vgxsim.gl._core import current

    gl.prefsize(64, 64)
    gid = gl.winopen("calls")
    gl.RGBmode()
    gl.stensize(8)
    gl.gconfig()
    gl.ortho2(-0.5, 63.5, -0.5, 63.5)
    gl.lmdef(GL.DEFMATERIAL, 1, [GL.DIFFUSE, 0.8, 0.6, 0.4, GL.LMNULL])
    gl.lmdef(GL.DEFLMODEL, 1, [GL.LMNULL])
    gl.lmdef(GL.DEFLIGHT, 1, [GL.POSITION, 0.0, 0.0, 1.0, 0.0, GL.LMNULL])
    ctx = current("bench")
    n = N_CALLS
    out: dict[str, float] = {}
    v3f, n3f, c3f, cpack = gl.v3f, gl.n3f, gl.c3f, gl.cpack
    bgn, end = gl.bgnpolygon, gl.endpolygon
    p = (1.0, 2.0, 0.0)

    def close():
        end()
        ctx.flush()

    def loop_v3f():
        for _ in range(n):
            v3f(1.0, 2.0, 0.0)

    def loop_v3f_seq():
        for _ in range(n):
            v3f(p)

    nv = (0.0, 0.0, 1.0)
    cv = (0.5, 0.25, 1.0)

    def loop_n3f():
        for _ in range(n):
            n3f(0.0, 0.0, 1.0)

    def loop_n3f_seq():
        for _ in range(n):
            n3f(nv)

    def loop_c3f():
        for _ in range(n):
            c3f(0.5, 0.25, 1.0)

    def loop_c3f_seq():
        for _ in range(n):
            c3f(cv)

    def loop_cpack():
        for _ in range(n):
            cpack(0xFF00FF00)

    out["v3f(x, y, z)"] = _median_ns(loop_v3f, n, rounds, bgn, close)
    out["v3f((x, y, z))"] = _median_ns(loop_v3f_seq, n, rounds, bgn, close)
    out["n3f(x, y, z)"] = _median_ns(loop_n3f, n, rounds)
    out["n3f((x, y, z))"] = _median_ns(loop_n3f_seq, n, rounds)
    out["c3f(r, g, b)"] = _median_ns(loop_c3f, n, rounds)
    out["c3f((r, g, b))"] = _median_ns(loop_c3f_seq, n, rounds)
    out["cpack"] = _median_ns(loop_cpack, n, rounds)

    def loop_bgnend():
        for _ in range(n):
            bgn()
            end()

    out["bgnpolygon+endpolygon (empty)"] = _median_ns(loop_bgnend, n, rounds,
                                                      after=ctx.flush) / 2

    def loop_stencil():
        for i in range(n):
            gl.stencil(1, 0, GL.SF_ALWAYS, 0xFF, GL.ST_KEEP, GL.ST_KEEP,
                       GL.ST_INCR if i & 1 else GL.ST_DECR)

    out["stencil"] = _median_ns(loop_stencil, n, rounds)

    def loop_lmbind():
        for i in range(n):
            gl.lmbind(GL.MATERIAL, i & 1)

    out["lmbind(MATERIAL)"] = _median_ns(loop_lmbind, n, rounds)

    def loop_zwritemask():
        for i in range(n):
            gl.zwritemask(0xFFFFFFFF if i & 1 else 0)

    out["zwritemask"] = _median_ns(loop_zwritemask, n, rounds)

    def loop_wmpack():
        for i in range(n):
            gl.wmpack(0xFFFFFFFF if i & 1 else 0)

    out["wmpack"] = _median_ns(loop_wmpack, n, rounds)

    def loop_matrix():
        for _ in range(n):
            gl.pushmatrix()
            gl.translate(1.0, 2.0, 3.0)
            gl.popmatrix()

    out["pushmatrix+translate+popmatrix (per call)"] = _median_ns(loop_matrix, n, rounds) / 3

    # A shadow face group as the 1991 code sends it.
    quad = ((1.0, 1.0, 0.0), (30.0, 1.0, 0.0), (30.0, 30.0, 0.0), (1.0, 30.0, 0.0))

    def loop_face():
        for i in range(n):
            gl.stencil(1, 0, GL.SF_ALWAYS, 0xFF, GL.ST_KEEP, GL.ST_KEEP,
                       GL.ST_INCR if i & 1 else GL.ST_DECR)
            bgn()
            v3f(quad[0])
            v3f(quad[1])
            v3f(quad[2])
            v3f(quad[3])
            end()

    gl.zwritemask(0)
    gl.wmpack(0)
    out["stencil+bgnpolygon+4 v3f+endpolygon (per call)"] = _median_ns(
        loop_face, n, rounds, after=ctx.flush) / 7
    gl.zwritemask(0xFFFFFFFF)
    gl.wmpack(0xFFFFFFFF)
    gl.stencil(0, 0, GL.SF_ALWAYS, 0xFF, GL.ST_KEEP, GL.ST_KEEP, GL.ST_KEEP)

    gl.makeobj(1)
    gl.cpack(0xFF0000FF)
    gl.bgnpolygon()
    for q in quad:
        gl.v3f(q)
    gl.endpolygon()
    gl.closeobj()

    def loop_callobj():
        for _ in range(n // 4):
            gl.callobj(1)

    out["callobj (1 quad)"] = _median_ns(loop_callobj, n // 4, rounds, after=ctx.flush)

    # The 1991 volume cache's object: per shadow face a stencil() call and a quad.
    gl.makeobj(2)
    for i in range(N_FACES):
        gl.stencil(1, 0, GL.SF_ALWAYS, 0xFF, GL.ST_KEEP, GL.ST_KEEP,
                   GL.ST_INCR if i & 1 else GL.ST_DECR)
        gl.bgnpolygon()
        for q in quad:
            gl.v3f(q)
        gl.endpolygon()
    gl.closeobj()
    gl.zwritemask(0)
    gl.wmpack(0)

    def loop_faces():
        for _ in range(n // N_FACES):
            gl.callobj(2)

    def after_faces():
        ctx.flush()  # (the next round starts with a new state table, as a frame does)

    out[FACES_ROW] = _median_ns(loop_faces, n // N_FACES, rounds, after=after_faces) / N_FACES
    # The same two rows with gl._core.REPLAY_OBJECTS off and on, round by round.
    for name, loop, per, calls, after in (
            ("callobj 1 quad", loop_callobj, 1, n // 4, ctx.flush),
            (f"callobj {N_FACES} faces, per face", loop_faces, N_FACES, n // N_FACES,
             after_faces)):
        ab = _switch_ab_ns(loop, calls, rounds, after)
        out[f"{name}, REPLAY_OBJECTS off"] = ab[False] / per
        out[f"{name}, REPLAY_OBJECTS on"] = ab[True] / per
    # The face object under a new matrix at every call (an object drawn at several
    # places, or under a moving transform): its block rebased or traced again.
    from vgxsim.gl import _objects

    moves = [(float(k % 7), 0.5 * (k % 5), 0.0) for k in range(n // N_FACES)]

    def loop_faces_moving():
        for m in moves:
            gl.pushmatrix()
            gl.translate(*m)
            gl.callobj(2)
            gl.popmatrix()

    ab = _switch_ab_ns(loop_faces_moving, len(moves), rounds, after_faces,
                       (_objects, "REBASE_REPLAYS"))
    for on in (False, True):
        out[f"push+translate+callobj {N_FACES} faces+pop, REBASE_REPLAYS "
            f"{'on' if on else 'off'} (per face)"] = ab[on] / N_FACES
    gl.zwritemask(0xFFFFFFFF)
    gl.wmpack(0xFFFFFFFF)
    gl.winclose(gid)
    return out


def other_calls(rounds: int) -> dict[str, float]:
    """ns per call of the calls outside the common set that issue 6 brings under 1 us
    (old-style drawing, matrix and state calls), each loop of N_CALLS calls (or
    groups) on its own 64 x 64 window; drawing rows flush after each round, untimed
    (``... + flush``: the same with the flush timed, the whole cost of the drawing)."""
    from vgxsim import GL, gl
    from vgxsim.gl._core import current

    gl.prefsize(64, 64)
    gid = gl.winopen("other calls")
    gl.RGBmode()
    gl.gconfig()
    gl.ortho2(-0.5, 63.5, -0.5, 63.5)
    gl.lmdef(GL.DEFMATERIAL, 1, [GL.DIFFUSE, 0.8, 0.6, 0.4, GL.LMNULL])
    gl.lmdef(GL.DEFLMODEL, 1, [GL.LMNULL])
    gl.deflinestyle(1, 0x3C3C)
    ctx = current("bench")
    n = N_CALLS
    out: dict[str, float] = {}
    flush = ctx.flush

    def move_draw():
        for _ in range(n // 2):
            gl.move2(1.0, 2.0)
            gl.draw2(30.0, 40.0)

    def draw_only():
        for _ in range(n):
            gl.draw2(30.0, 40.0)

    def move_draw_flushed():
        move_draw()
        flush()

    def pnt2():
        for _ in range(n):
            gl.pnt2(5.0, 6.0)

    def rectf():
        for _ in range(n):
            gl.rectf(2.0, 2.0, 9.0, 7.0)

    def cmov2():
        for _ in range(n):
            gl.cmov2(3.0, 4.0)

    quad = ((1.0, 1.0, 0.0), (30.0, 1.0, 0.0), (30.0, 30.0, 0.0), (1.0, 30.0, 0.0))

    def polygon():
        gl.bgnpolygon()
        gl.v3f(quad[0])
        gl.v3f(quad[1])
        gl.v3f(quad[2])
        gl.v3f(quad[3])
        gl.endpolygon()

    def object_in_place():
        # An object drawn under its own translation, then one at the outer matrix
        # (13 calls): what popmatrix's kept mvp (state.matrices.KEEP_MVPS) saves.
        for _ in range(n // 13):
            gl.pushmatrix()
            gl.translate(1.0, 2.0, 0.0)
            polygon()
            gl.popmatrix()
            polygon()

    def kept_mvps_ab() -> dict[bool, float]:
        from vgxsim.state import matrices

        ts: dict[bool, list] = {False: [], True: []}
        try:
            for r in range(rounds + 1):
                for on in (False, True):
                    matrices.KEEP_MVPS = on
                    clock = CLOCK["ns"]
                    t = clock()
                    object_in_place()
                    dt = clock() - t
                    flush()
                    if r:
                        ts[on].append(dt)
        finally:
            matrices.KEEP_MVPS = True
        return {on: float(np.median(v)) / (n // 13 * 13) for on, v in ts.items()}

    def drawing_rows():
        ab = kept_mvps_ab()
        out["push+translate+polygon+pop+polygon, KEEP_MVPS off (per call)"] = ab[False]
        out["push+translate+polygon+pop+polygon, KEEP_MVPS on (per call)"] = ab[True]
        out["move2+draw2 (per call)"] = _median_ns(move_draw, n, rounds, after=flush)
        out["move2+draw2 + flush (per call)"] = _median_ns(move_draw_flushed, n, rounds)
        out["draw2"] = _median_ns(draw_only, n, rounds,
                                  before=lambda: gl.move2(1.0, 1.0), after=flush)
        out["pnt2"] = _median_ns(pnt2, n, rounds, after=flush)
        out["rectf"] = _median_ns(rectf, n, rounds, after=flush)

    out["cmov2"] = _median_ns(cmov2, n, rounds)

    def matrix_row(call):
        def loop():
            for _ in range(n):
                gl.pushmatrix()
                call()
                gl.popmatrix()
        return loop

    def push_pop():
        for _ in range(n):
            gl.pushmatrix()
            gl.popmatrix()

    m16 = [1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 1.0, 2.0, 3.0, 1.0]
    floor = _median_ns(push_pop, n, rounds)
    for name, call in (("rot", lambda: gl.rot(30.0, "z")),
                       ("rotate", lambda: gl.rotate(300, "x")),
                       ("scale", lambda: gl.scale(2.0, 3.0, 4.0)),
                       ("multmatrix", lambda: gl.multmatrix(m16)),
                       ("loadmatrix", lambda: gl.loadmatrix(m16))):
        # (push + call + pop, less push + pop: the call alone)
        out[f"{name} (push/pop subtracted)"] = _median_ns(matrix_row(call), n, rounds) - floor

    def getmatrix():
        for _ in range(n):
            gl.getmatrix()

    out["getmatrix"] = _median_ns(getmatrix, n, rounds)

    def toggles(call, a, b):
        def loop():
            for i in range(n):
                call(a if i & 1 else b)
        return loop

    def afunction():
        for i in range(n):
            gl.afunction(i & 1, GL.AF_GREATER)

    def lsetdepth():
        for i in range(n):
            gl.lsetdepth(0, 0x7FFFFF - (i & 1))

    out["afunction"] = _median_ns(afunction, n, rounds)
    out["lsetdepth"] = _median_ns(lsetdepth, n, rounds)
    out["lmcolor"] = _median_ns(toggles(gl.lmcolor, GL.LMC_COLOR, GL.LMC_DIFFUSE), n, rounds)
    out["mmode(MVIEWING)"] = _median_ns(toggles(gl.mmode, GL.MVIEWING, GL.MVIEWING), n,
                                        rounds)
    out["frontbuffer"] = _median_ns(toggles(gl.frontbuffer, 1, 0), n, rounds)
    out["setlinestyle"] = _median_ns(toggles(gl.setlinestyle, 1, 0), n, rounds)
    gl.lmcolor(GL.LMC_COLOR)
    # Last: the drawing rows allocate most (the flushes), which would weigh on the
    # rows measured after them.
    drawing_rows()
    gl.winclose(gid)
    return out


#: Shadow faces in the callobj row of the volume cache's object (stencil + quad each).
N_FACES = 16
FACES_ROW = f"callobj ({N_FACES} stencil+quad faces, per face)"


def _switch_ab_ns(loop, n: int, rounds: int, after=None, switch=None) -> dict[bool, float]:
    """Median ns per call of ``loop()`` with gl._core.REPLAY_OBJECTS (or ``switch``,
    a (module, name) pair of another module switch) off and on, alternating round by
    round (A/B in one process: both see the same load)."""
    from vgxsim.gl import _core

    module, name = switch if switch is not None else (_core, "REPLAY_OBJECTS")
    ts: dict[bool, list] = {False: [], True: []}
    try:
        for r in range(rounds + 1):
            for on in (False, True):
                setattr(module, name, on)
                clock = CLOCK["ns"]
                t = clock()
                loop()
                dt = clock() - t
                if after is not None:
                    after()
                if r:
                    ts[on].append(dt)
    finally:
        setattr(module, name, True)
    return {on: float(np.median(v)) / n for on, v in ts.items()}


_NO = object()


def python_floors(rounds: int) -> dict[str, tuple[float, float]]:
    """What no Python implementation of each row can beat, measured here: ns per call
    of (1) an empty Python function with the call's parameter shape (positional-only
    slots and ``*more, **kw``, or ``*args, **kwargs``: the keyword argument is what
    lets a call name itself in its GLTypeError), called as the row calls it, and (2)
    the same function storing 3 floats into a preallocated list at a running index
    (the least a vertex call records).  Same loops as the rows (loop overhead
    included alike).  A row whose 5x target lies below floor (1) cannot meet it in
    CPython, whatever the call does."""
    n = N_CALLS
    buf = [0.0] * (12 * n + 12)
    at = [0]

    def e0(*args, **kwargs):
        pass

    def e1(a=_NO, /, *more, **kw):
        pass

    def e2(a=_NO, b=_NO, /, *more, **kw):
        pass

    def e3(a=_NO, b=_NO, c=_NO, /, *more, **kw):
        pass

    def s3(a=_NO, b=_NO, c=_NO, /, *more, **kw):
        i = at[0]
        buf[i] = a
        buf[i + 1] = b
        buf[i + 2] = c
        at[0] = i + 3

    def s3_seq(a=_NO, b=_NO, c=_NO, /, *more, **kw):
        x, y, z = a
        i = at[0]
        buf[i] = x
        buf[i + 1] = y
        buf[i + 2] = z
        at[0] = i + 3

    def reset():
        at[0] = 0

    p = (1.0, 2.0, 0.0)
    ST_INCR, ST_DECR, MATERIAL = 3, 4, 1000

    def shape3(f):
        def loop():
            for _ in range(n):
                f(1.0, 2.0, 0.0)
        return loop

    def shape3_seq(f):
        def loop():
            for _ in range(n):
                f(p)
        return loop

    def loop_e1():
        for i in range(n):
            e1(0xFFFFFFFF if i & 1 else 0)

    def loop_e2():
        for i in range(n):
            e2(MATERIAL, i & 1)

    def loop_e0_pair():
        for _ in range(n):
            e0()
            e0()

    def loop_e7():
        for i in range(n):
            e0(1, 0, 7, 0xFF, 0, 0, ST_INCR if i & 1 else ST_DECR)

    def loop_matrix():
        for _ in range(n):
            e0()
            e3(1.0, 2.0, 3.0)
            e0()

    def loop_face(f):
        def loop():
            for i in range(n):
                e0(1, 0, 7, 0xFF, 0, 0, ST_INCR if i & 1 else ST_DECR)
                e0()
                f(p)
                f(p)
                f(p)
                f(p)
                e0()
        return loop

    def loop_callobj():
        for _ in range(n // 4):
            e1(1)

    def both(empty_loop, store_loop=None, per: float = 1.0, calls: int = n):
        empty = _median_ns(empty_loop, calls, rounds) / per
        store = (_median_ns(store_loop, calls, rounds, before=reset) / per
                 if store_loop is not None else float("nan"))
        return empty, store

    return {
        "v3f(x, y, z)": both(shape3(e3), shape3(s3)),
        "v3f((x, y, z))": both(shape3_seq(e3), shape3_seq(s3_seq)),
        "n3f(x, y, z)": both(shape3(e3)),
        "n3f((x, y, z))": both(shape3_seq(e3)),
        "c3f(r, g, b)": both(shape3(e3)),
        "c3f((r, g, b))": both(shape3_seq(e3)),
        "cpack": both(loop_e1),
        "bgnpolygon+endpolygon (empty)": both(loop_e0_pair, per=2),
        "stencil": both(loop_e7),
        "lmbind(MATERIAL)": both(loop_e2),
        "zwritemask": both(loop_e1),
        "wmpack": both(loop_e1),
        "pushmatrix+translate+popmatrix (per call)": both(loop_matrix, per=3),
        "stencil+bgnpolygon+4 v3f+endpolygon (per call)": both(
            loop_face(e3), loop_face(s3_seq), per=7),
        "callobj (1 quad)": both(loop_callobj, calls=n // 4),
        FACES_ROW: both(loop_callobj, per=N_FACES, calls=n // 4),
    }


def heidmann_frame(rounds: int, width: int = 1280, height: int = 1024,
                   clock=time.perf_counter) -> dict[str, float]:
    """The Heidmann frame through the API: total, raster (inside flush), front end,
    in ms; and the same frame with DrawObjects replayed from display objects.

    ``clock``: ``time.perf_counter`` (wall) or ``time.process_time`` (CPU time of
    this process, all its threads: steadier on a machine shared with other work).
    """
    from vgxsim import batch as batch_mod
    from vgxsim import gl
    from vgxsim.examples.heidmann1991 import Shadows
    from vgxsim.geometry import pipeline as geometry
    from vgxsim.gl import _objects
    from vgxsim.pipeline import draw

    spent = [0.0]
    real_flush = batch_mod.CommandBatch.flush

    def timed_flush(self, *a, **k):
        t = clock()
        try:
            return real_flush(self, *a, **k)
        finally:
            spent[0] += clock() - t

    prog = Shadows()
    gl.prefsize(width, height)
    gid = gl.winopen("shadows")
    prog.setup()
    batch_mod.CommandBatch.flush = timed_flush
    try:
        def frame():
            prog.DrawFrame()
            gl.swapbuffers()

        def measure(run):
            run()
            tot, ras = [], []
            for _ in range(rounds):
                spent[0] = 0.0
                t = clock()
                run()
                tot.append(clock() - t)
                ras.append(spent[0])
            tot_a, ras_a = np.array(tot), np.array(ras)
            return (float(np.median(tot_a)) * 1e3, float(np.median(ras_a)) * 1e3,
                    float(np.median(tot_a - ras_a)) * 1e3)

        def replay_ab(run, prefix: str, switch=None, word: str = "replay") -> dict[str, float]:
            """Front end with gl._core.REPLAY_OBJECTS (or ``switch``: (module, name))
            off and on, frame by frame."""
            from vgxsim.gl import _core

            module, name = switch if switch is not None else (_core, "REPLAY_OBJECTS")
            fe: dict = {False: [], True: []}
            try:
                for _ in range(rounds):
                    for on in (False, True):
                        setattr(module, name, on)
                        run()  # (the first frame after a switch settles its caches)
                        spent[0] = 0.0
                        t = clock()
                        run()
                        fe[on].append(clock() - t - spent[0])
            finally:
                setattr(module, name, True)
            return {f"{prefix}front_end_ms_{word}_{'on' if on else 'off'}":
                    float(np.median(v)) * 1e3 for on, v in fe.items()}

        def fast_paths(on: bool) -> None:
            geometry.FUSED_FRONT = on
            draw.BATCH_LIGHTING = on
            draw.FLUSH_FRONT = on

        out = {}
        # The front end's fast paths (fused geometry pass, lighting over whole groups)
        # on and off, alternating frame by frame; the plain figures are "on".
        samples: dict = {True: ([], []), False: ([], [])}
        frame()
        try:
            for _ in range(rounds):
                for on in (True, False):
                    fast_paths(on)
                    spent[0] = 0.0
                    t = clock()
                    frame()
                    samples[on][0].append(clock() - t)
                    samples[on][1].append(spent[0])
        finally:
            fast_paths(True)
        for on, suffix in ((True, ""), (False, "_fast_paths_off")):
            tot_a, ras_a = (np.array(v) for v in samples[on])
            out["frame_ms" + suffix] = float(np.median(tot_a)) * 1e3
            out["raster_ms" + suffix] = float(np.median(ras_a)) * 1e3
            out["front_end_ms" + suffix] = float(np.median(tot_a - ras_a)) * 1e3
        # DrawObjects compiled into display objects, one per material part.
        draw_objects = prog.DrawObjects
        for part in range(3):
            gl.makeobj(100 + part)
            draw_objects(part)
            gl.closeobj()
        prog.DrawObjects = lambda matl: gl.callobj(100 + matl)
        try:
            (out["objects_frame_ms"], out["objects_raster_ms"],
             out["objects_front_end_ms"]) = measure(frame)
            out.update(replay_ab(frame, "objects_"))
            out.update(replay_ab(frame, "objects_", (_objects, "REPLAY_PARENTS"), "parents"))
        finally:
            prog.DrawObjects = draw_objects
        out.update(replay_ab(frame, ""))
        out["polygons_per_frame"] = _count_polygons(prog)
    finally:
        batch_mod.CommandBatch.flush = real_flush
        gl.winclose(gid)
    return out


def _count_polygons(prog) -> int:
    """Polygons one frame hands to the pipeline, counted where the stream is decoded
    (so polygons replayed from display objects, as the volume cache draws them, count
    too)."""
    import numpy as np

    from vgxsim import gl
    from vgxsim.pipeline import decode
    from vgxsim.stream.opcodes import P_KIND, PMV, POLYGON

    count = [0]
    real = decode.decode_stream

    def counting(*args):
        out = real(*args)
        prims = out[4]
        count[0] += int(np.count_nonzero(np.isin(prims[:, P_KIND], (POLYGON, PMV))))
        return out

    decode.decode_stream = counting
    try:
        prog.DrawFrame()
        gl.swapbuffers()
    finally:
        decode.decode_stream = real
    return count[0]


def mesa_calls(rounds: int) -> dict[str, float] | None:
    """The same call mix through PyOpenGL immediate mode on an OSMesa context, or
    None when OSMesa cannot be made."""
    try:
        os.environ.setdefault("PYOPENGL_PLATFORM", "osmesa")
        from vgxsim.reference import mesa
        peer = mesa.MesaPeer(64, 64)
    except Exception:  # noqa: BLE001 - no OSMesa: the rows are left out
        return None
    from OpenGL import GL as G

    peer._make_current()
    n = N_CALLS
    out: dict[str, float] = {}
    v = (1.0, 2.0, 0.0)

    def loop_vertex():
        G.glBegin(G.GL_POLYGON)
        for _ in range(n):
            G.glVertex3fv(v)
        G.glEnd()

    nv = (0.0, 0.0, 1.0)
    cv = (0.5, 0.25, 1.0)

    def loop_normal():
        for _ in range(n):
            G.glNormal3f(0.0, 0.0, 1.0)

    def loop_normal_v():
        for _ in range(n):
            G.glNormal3fv(nv)

    def loop_colour():
        for _ in range(n):
            G.glColor3f(0.5, 0.25, 1.0)

    def loop_colour_v():
        for _ in range(n):
            G.glColor3fv(cv)

    def loop_bgnend():
        for _ in range(n):
            G.glBegin(G.GL_POLYGON)
            G.glEnd()

    def loop_stencil():
        for i in range(n):
            G.glStencilOp(G.GL_KEEP, G.GL_KEEP, G.GL_INCR if i & 1 else G.GL_DECR)

    def loop_matrix():
        for _ in range(n):
            G.glPushMatrix()
            G.glTranslatef(1.0, 2.0, 3.0)
            G.glPopMatrix()

    def loop_vertex_seq():
        G.glBegin(G.GL_POLYGON)
        for _ in range(n):
            G.glVertex3f(1.0, 2.0, 0.0)
        G.glEnd()

    def loop_cpack():
        # cpack(0xFF00FF00): the packed ABGR colour as four unsigned bytes.
        for _ in range(n):
            G.glColor4ub(0x00, 0xFF, 0x00, 0xFF)

    mats = ((0.8, 0.6, 0.4, 1.0), (0.2, 0.3, 0.4, 1.0))

    def loop_material():
        # lmbind(MATERIAL, i): the nearest OpenGL call re-specifies the material.
        for i in range(n):
            G.glMaterialfv(G.GL_FRONT, G.GL_DIFFUSE, mats[i & 1])

    def loop_depthmask():
        for i in range(n):
            G.glDepthMask(G.GL_TRUE if i & 1 else G.GL_FALSE)

    def loop_colormask():
        for i in range(n):
            on = G.GL_TRUE if i & 1 else G.GL_FALSE
            G.glColorMask(on, on, on, on)

    quad = ((1.0, 1.0, 0.0), (30.0, 1.0, 0.0), (30.0, 30.0, 0.0), (1.0, 30.0, 0.0))
    lst = G.glGenLists(1)
    G.glNewList(lst, G.GL_COMPILE)
    G.glColor4ub(0xFF, 0x00, 0x00, 0xFF)
    G.glBegin(G.GL_POLYGON)
    for q in quad:
        G.glVertex3fv(q)
    G.glEnd()
    G.glEndList()

    def loop_calllist():
        for _ in range(n // 4):
            G.glCallList(lst)

    faces = G.glGenLists(1)
    G.glNewList(faces, G.GL_COMPILE)
    for i in range(N_FACES):
        G.glStencilOp(G.GL_KEEP, G.GL_KEEP, G.GL_INCR if i & 1 else G.GL_DECR)
        G.glBegin(G.GL_POLYGON)
        for q in quad:
            G.glVertex3fv(q)
        G.glEnd()
    G.glEndList()

    def loop_faces():
        for _ in range(n // N_FACES):
            G.glCallList(faces)

    out["v3f(x, y, z)"] = _median_ns(loop_vertex_seq, n, rounds)
    out["v3f((x, y, z))"] = _median_ns(loop_vertex, n, rounds)
    out["n3f(x, y, z)"] = _median_ns(loop_normal, n, rounds)
    out["n3f((x, y, z))"] = _median_ns(loop_normal_v, n, rounds)
    out["c3f(r, g, b)"] = _median_ns(loop_colour, n, rounds)
    out["c3f((r, g, b))"] = _median_ns(loop_colour_v, n, rounds)
    out["cpack"] = _median_ns(loop_cpack, n, rounds)
    out["bgnpolygon+endpolygon (empty)"] = _median_ns(loop_bgnend, n, rounds) / 2
    out["stencil"] = _median_ns(loop_stencil, n, rounds)
    out["lmbind(MATERIAL)"] = _median_ns(loop_material, n, rounds)
    out["zwritemask"] = _median_ns(loop_depthmask, n, rounds)
    out["wmpack"] = _median_ns(loop_colormask, n, rounds)
    out["pushmatrix+translate+popmatrix (per call)"] = _median_ns(loop_matrix, n, rounds) / 3
    def loop_face():
        # The shadow face group: glStencilOp, then the quad (7 calls).
        for i in range(n):
            G.glStencilOp(G.GL_KEEP, G.GL_KEEP, G.GL_INCR if i & 1 else G.GL_DECR)
            G.glBegin(G.GL_POLYGON)
            G.glVertex3fv(quad[0])
            G.glVertex3fv(quad[1])
            G.glVertex3fv(quad[2])
            G.glVertex3fv(quad[3])
            G.glEnd()

    out["stencil+bgnpolygon+4 v3f+endpolygon (per call)"] = _median_ns(
        loop_face, n, rounds) / 7
    out["callobj (1 quad)"] = _median_ns(loop_calllist, n // 4, rounds)
    out[FACES_ROW] = _median_ns(loop_faces, n // N_FACES, rounds) / N_FACES
    G.glFinish()
    G.glDeleteLists(lst, 1)
    G.glDeleteLists(faces, 1)
    return out


def llvmpipe_frames() -> dict[str, float]:
    """The PyOpenGL immediate-mode transliteration of the frame (bench/heidmann_gl.py)
    on llvmpipe with 1 and 2 threads, each in its own process; ms."""
    import subprocess

    out = {}
    for threads in (1, 2):
        env = dict(os.environ, LP_NUM_THREADS=str(threads))
        try:
            res = subprocess.run([sys.executable, os.path.join(HERE, "heidmann_gl.py"),
                                  str(threads)], env=env, capture_output=True, text=True,
                                 timeout=600)
            data = json.loads(res.stdout.strip().splitlines()[-1])
        except (subprocess.SubprocessError, ValueError, IndexError):
            continue
        if "frame_s" in data:
            out[f"llvmpipe_{threads}_thread_frame_ms"] = data["frame_s"] * 1e3
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--no-mesa", action="store_true")
    ap.add_argument("--cpu", action="store_true",
                    help="time calls and frame in process CPU time (a busy shared machine)")
    ap.add_argument("--calls-only", action="store_true",
                    help="only the per-call table (no Heidmann frame, no llvmpipe)")
    ap.add_argument("--json")
    args = ap.parse_args(argv)
    rounds = 5 if args.quick else 15
    if args.cpu:
        CLOCK["ns"] = time.process_time_ns
    calls = vgxsim_calls(rounds)
    calls.update(other_calls(rounds))
    floors = python_floors(rounds)
    mesa = None if args.no_mesa else mesa_calls(rounds)
    print(f"{'call':48s} {'vgxsim':>7s} {'PyOpenGL':>8s} {'ratio':>5s} {'5x':>5s} "
          f"{'empty':>5s} {'store':>5s}")
    print("(ns per call; 5x: PyOpenGL / 5, the target; empty, store: the Python floors, "
          "see python_floors)")
    for name, ns in calls.items():
        fe, fs = floors.get(name, (float("nan"), float("nan")))
        m = mesa.get(name) if mesa else None
        gl_cols = (f"{m:8.0f} {m / ns:5.1f} {m / 5:5.0f}" if m is not None
                   else f"{'':8s} {'':5s} {'':5s}")
        note = ""
        if m is not None:
            if ns <= m / 5:
                note = "  met"
            elif m / 5 < fe:
                note = "  impossible: 5x is below the empty call"
            elif m / 5 < fs:
                note = "  impossible: 5x is below the 3-float store"
        store = "" if fs != fs else f"{fs:5.0f}"  # (NaN: not a recording row)
        print(f"{name:48s} {ns:7.0f} {gl_cols} {fe:5.0f} {store:>5s}{note}")
    if args.calls_only:
        if args.json:
            with open(args.json, "w") as f:
                json.dump({"calls": calls, "mesa": mesa, "floors": floors}, f, indent=1)
        return 0
    frame = heidmann_frame(3 if args.quick else 7,
                           clock=time.process_time if args.cpu else time.perf_counter)
    if not args.no_mesa:
        frame.update(llvmpipe_frames())
    print()
    for k, v in frame.items():
        print(f"heidmann 1280x1024 {k:30s} {v:10.2f}")
    if args.json:
        with open(args.json, "w") as f:
            json.dump({"calls": calls, "mesa": mesa, "floors": floors, "frame": frame}, f,
                  indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
