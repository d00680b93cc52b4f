"""callobj's inlined splice of a one-chunk object (gl._core.REPLAY_OBJECTS) draws what
the chunk-by-chunk splice and immediate mode draw, with the caller's colour, normal
and lighting changed between the calls; a chunk that starts with its colour call
needs no SYNC of the caller's colour before it (SplicePlan.leads), and the stream
then holds fewer SYNC ops than with the switch off."""

from __future__ import annotations

import numpy as np
import pytest

from vgxsim import GL, gl
from vgxsim.gl import _core
from vgxsim.gl._core import session
from vgxsim.stream.opcodes import BGN, CLEAR, STATE, SYNC

W, H = 48, 20
QUAD = ((0.0, 0.0, 0.0), (6.0, 0.5, 0.1), (6.5, 7.0, 0.2), (0.5, 6.0, 0.0))
SHIFTED = tuple((x + 2.0, y + 1.0, z - 0.3) for x, y, z in QUAD)
_INTS = {SYNC: 2, BGN: 1, STATE: 1, CLEAR: 1}  # integers after each opcode


def _syncs(ops: list) -> int:
    n, i = 0, 0
    while i < len(ops):
        n += ops[i] == SYNC
        i += 1 + _INTS.get(ops[i], 0)
    return n


def _polygon(points, colour=None, normal=None):
    if colour is not None:
        gl.cpack(colour)
    if normal is not None:
        gl.n3f(normal)
    gl.bgnpolygon()
    for p in points:
        gl.v3f(p)
    gl.endpolygon()


#: The objects: polygons drawn as _polygon does, and one whose colour call comes
#: after its first vertex (the chunk does not start with it).
OBJECTS = {
    1: lambda: _polygon(QUAD, 0xFF2040C0),  # colour first, nothing else: plain
    2: lambda: _polygon(SHIFTED, 0xFF10A030, (0.0, 0.6, 0.8)),  # colour, then normal
    # a vertex before the colour call: it takes the caller's colour (Gouraud)
    3: lambda: (gl.bgnpolygon(), gl.v3f(SHIFTED[0]), gl.cpack(0xFFC0C000),
                [gl.v3f(p) for p in SHIFTED[1:]], gl.endpolygon()),
}


def _program(call):
    """The caller's attributes change before every call of an object, and each call
    draws at its own place on a 6 x 2 grid (translate between the calls)."""
    places = iter([(x * 8.0, y * 10.0) for y in range(2) for x in range(6)])

    def at(draw):
        gl.pushmatrix()
        gl.translate(*next(places), 0.0)
        draw()
        gl.popmatrix()

    gl.c3f(0.2, 0.9, 0.4)
    at(lambda: call(1))
    at(lambda: _polygon(SHIFTED))  # takes the colour object 1 left
    gl.c3f(0.7, 0.1, 0.1)
    gl.n3f(1.0, 0.0, 0.0)
    at(lambda: call(1))
    at(lambda: call(2))
    gl.zfunction(GL.ZF_ALWAYS)
    at(lambda: call(3))
    gl.c3f(0.1, 0.3, 1.0)
    at(lambda: call(3))
    gl.cpack(0xFF00FFFF)
    at(lambda: call(1))
    at(lambda: call(1))
    gl.n3f(0.0, 0.0, 1.0)
    at(lambda: call(2))
    at(lambda: _polygon(QUAD))


def _render(lit: bool, mode: str, monkeypatch) -> tuple[dict, int]:
    """Planes and SYNC count of the program: its objects through callobj with
    REPLAY_OBJECTS on (``"inline"``) or off (``"splice"``), or their calls made in
    immediate mode (``"immediate"``)."""
    monkeypatch.setattr(_core, "REPLAY_OBJECTS", mode == "inline")
    session.reset()
    gl.prefsize(W, H)
    gl.winopen("inline")
    gl.RGBmode()
    gl.gconfig()
    gl.zbuffer(1)
    gl.mmode(GL.MVIEWING)
    gl.ortho(-0.5, W - 0.5, -0.5, H - 0.5, -1.0, 1.0)
    gl.czclear(0, gl.getgdesc(GL.GD_ZMAX))
    if lit:
        gl.lmdef(GL.DEFMATERIAL, 1, [GL.DIFFUSE, 0.8, 0.6, 0.4, GL.LMNULL])
        gl.lmdef(GL.DEFLIGHT, 1, [GL.POSITION, 0.3, 0.4, 1.0, 0.0, GL.LMNULL])
        gl.lmdef(GL.DEFLMODEL, 1, [GL.LMNULL])
        gl.lmbind(GL.LIGHT0, 1)
        gl.lmbind(GL.LMODEL, 1)
        gl.lmbind(GL.MATERIAL, 1)
    if mode == "immediate":
        _program(lambda n: OBJECTS[n]())
    else:
        for n, draw in OBJECTS.items():
            gl.makeobj(n)
            draw()
            gl.closeobj()
        _program(gl.callobj)
    ctx = session.windows[session.current]
    syncs = _syncs(ctx.stream.ops)
    ctx.flush()
    planes = {"rgba": ctx.read_rgba().copy(), "z": ctx.fb.z.copy()}
    session.reset()
    return planes, syncs


@pytest.mark.parametrize("lit", [False, True])
def test_inlined_callobj_draws_what_splice_and_immediate_mode_draw(lit, monkeypatch):
    inline, syncs_inline = _render(lit, "inline", monkeypatch)
    splice, syncs_splice = _render(lit, "splice", monkeypatch)
    immediate, _ = _render(lit, "immediate", monkeypatch)
    colours = {tuple(c) for c in inline["rgba"].reshape(-1, 4).tolist()}
    assert len(colours) >= 4  # the background and at least three polygon colours
    for k in inline:
        assert np.array_equal(inline[k], splice[k]), k
        assert np.array_equal(inline[k], immediate[k]), k
    # The caller's colour changed before three calls of object 1, whose chunk starts
    # with its cpack: the inlined path sent no SYNC for them (the splice path does).
    assert syncs_inline < syncs_splice


def _lighting_between_calls(call) -> None:
    """Object 1 at one place, nothing but lighting changed between the calls: twice
    unlit, then lighting bound under lmcolor(LMC_NULL) (the object's cpack is
    ignored: the current colour stays the caller's) and twice more -- the last call
    finds the stream's draw state unchanged since the one before, so the inlined
    path's memo of "RGB and unlit" (CommandStream.plain_colour) must have been
    dropped with the STATE op that call recorded -- then lighting off and a polygon
    without a colour call of its own, which shows the current colour the calls
    left."""
    gl.lmdef(GL.DEFMATERIAL, 1, [GL.DIFFUSE, 0.8, 0.6, 0.4, GL.LMNULL])
    gl.lmdef(GL.DEFLIGHT, 1, [GL.POSITION, 0.3, 0.4, 1.0, 0.0, GL.LMNULL])
    gl.lmdef(GL.DEFLMODEL, 1, [GL.LMNULL])
    gl.lmcolor(GL.LMC_NULL)
    gl.zfunction(GL.ZF_ALWAYS)
    call(1)
    gl.c3f(0.1, 0.9, 0.9)
    call(1)  # (unlit, same state: the memo is set)
    gl.c3f(0.1, 0.9, 0.9)
    gl.lmbind(GL.LIGHT0, 1)
    gl.lmbind(GL.LMODEL, 1)
    gl.lmbind(GL.MATERIAL, 1)
    call(1)
    call(1)
    gl.lmbind(GL.MATERIAL, 0)
    gl.pushmatrix()
    gl.translate(20.0, 0.0, 0.0)
    _polygon(QUAD)  # the current colour: the c3f above, LMC_NULL ignored the cpacks
    gl.translate(10.0, 0.0, 0.0)
    call(1)  # unlit again: the memo is found anew, then used
    call(1)
    gl.popmatrix()


@pytest.mark.parametrize("mode", ["splice", "immediate"])
def test_inlined_callobj_follows_lighting_changed_between_calls(mode, monkeypatch):
    def render(m):
        monkeypatch.setattr(_core, "REPLAY_OBJECTS", m == "inline")
        session.reset()
        gl.prefsize(W, H)
        gl.winopen("inline")
        gl.RGBmode()
        gl.gconfig()
        gl.zbuffer(1)
        gl.mmode(GL.MVIEWING)
        gl.ortho(-0.5, W - 0.5, -0.5, H - 0.5, -1.0, 1.0)
        gl.czclear(0, gl.getgdesc(GL.GD_ZMAX))
        if m == "immediate":
            _lighting_between_calls(lambda n: OBJECTS[n]())
        else:
            gl.makeobj(1)
            OBJECTS[1]()
            gl.closeobj()
            _lighting_between_calls(gl.callobj)
        ctx = session.windows[session.current]
        out = ctx.read_rgba().copy()
        session.reset()
        return out

    inline, other = render("inline"), render(mode)
    assert len({tuple(c) for c in inline.reshape(-1, 4).tolist()}) >= 3  # lit, unlit, bg
    assert np.array_equal(inline, other)
