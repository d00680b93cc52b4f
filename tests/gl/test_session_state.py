"""The gl layer's process state is the session's and each window's declared state
(issue 6, item 2): session.reset() clears it, and no call finds a default by
``getattr(ctx, name, default)``."""

from __future__ import annotations

import pathlib
import re

import pytest

from vgxsim import GL, gl
from vgxsim.gl._core import session, window_of
from vgxsim.pipeline.context import Context
from vgxsim.stream.opcodes import BGN, CLEAR, STATE, SYNC

W, H = 8, 6
#: Integers after each opcode in ``ops`` (vgxsim/stream/opcodes.py).
_INTS = {SYNC: 2, BGN: 1, STATE: 1, CLEAR: 1}


def _opcodes(ops: list) -> list:
    out, i = [], 0
    while i < len(ops):
        out.append(ops[i])
        i += 1 + _INTS.get(ops[i], 0)
    return out


@pytest.fixture
def ctx(gl_window):
    return gl_window(W, H, stencil=0)


def test_cpack_interns_colours_in_the_session_and_reset_drops_them(ctx):
    gl.cpack(0x80402010)
    first = ctx.colour
    assert first == (0x10 / 255, 0x20 / 255, 0x40 / 255, 0x80 / 255)
    gl.cpack(0x80402010)
    assert ctx.colour is first  # the same object: the stream sends no second SYNC
    assert session.packed == {0x80402010: first}
    gl.bgnpolygon()
    gl.v3f(0.0, 0.0, 0.0)
    gl.cpack(0x80402010)
    gl.v3f(1.0, 0.0, 0.0)
    gl.endpolygon()
    assert _opcodes(ctx.stream.ops).count(SYNC) == 1
    session.reset()
    assert session.packed == {}


def test_gl_only_window_state_lives_on_the_window_record(ctx):
    rec = window_of(ctx)
    assert rec.drawmode == GL.NORMALDRAW and gl.getdrawmode() == GL.NORMALDRAW
    assert rec.rectzoom == (1.0, 1.0) and rec.texture is None
    gl.rectzoom(2.0, 3.0)
    assert rec.rectzoom == (2.0, 3.0)
    gl.overlay(2)
    gl.gconfig()
    gl.drawmode(GL.OVERDRAW)
    assert rec.drawmode == GL.OVERDRAW and gl.getdrawmode() == GL.OVERDRAW
    assert gl.getplanes() == 2  # the overlay's planes, read through the record
    gl.drawmode(GL.NORMALDRAW)
    for name in ("drawmode", "rectzoom", "texture_unit"):
        assert not hasattr(ctx, name), name
    session.reset()
    assert window_of(ctx) is not rec and window_of(ctx).rectzoom == (1.0, 1.0)


def test_line_flags_are_declared_on_every_context(ctx):
    fresh = Context(W, H)
    assert fresh.resetls is True and fresh.lsbackup is False
    assert gl.getlsbackup() == 0 and gl.getresetls() == 1
    gl.lsbackup(1)
    gl.resetls(0)
    assert gl.getlsbackup() == 1 and gl.getresetls() == 0


def test_lmbind_light_memo_is_the_streams_and_hands_back_one_entry(ctx):
    gl.mmode(GL.MVIEWING)
    gl.lmdef(GL.DEFLIGHT, 1, [GL.POSITION, 0.0, 0.0, 1.0, 0.0, GL.LMNULL])
    gl.lmbind(GL.LIGHT0, 1)
    entry = ctx.bound["lights"][0]
    gl.lmbind(GL.LIGHT0, 1)  # same light, same modelview: the same entry
    assert ctx.bound["lights"][0] is entry
    assert [v[2] for v in ctx.stream.light_memo.values()] == [entry]
    gl.rot(90.0, "y")
    gl.lmbind(GL.LIGHT0, 1)  # another modelview: a new entry
    moved = ctx.bound["lights"][0]
    assert moved is not entry
    assert moved[1][1].tolist() == pytest.approx([1.0, 0.0, 0.0, 0.0], abs=1e-12)
    assert not hasattr(ctx, "gl_light_memo")


def test_no_gl_call_reads_a_window_attribute_through_a_getattr_default():
    src = pathlib.Path(gl.__file__).parent
    found = [f"{p.name}:{i}" for p in sorted(src.glob("*.py"))
             for i, line in enumerate(p.read_text().splitlines(), 1)
             if re.search(r"getattr\(ctx\b[^)]*,[^)]*,", line)]
    assert found == []


def _pipeline_and_stream_sources() -> list[pathlib.Path]:
    root = pathlib.Path(gl.__file__).parent.parent
    return [p for sub in ("pipeline", "stream") for p in sorted((root / sub).glob("*.py"))]


def test_no_pipeline_or_stream_code_finds_a_default_through_getattr():
    # (Three arguments without nested calls: getattr(obj, name, default).)
    found = [f"{p.parent.name}/{p.name}:{i}" for p in _pipeline_and_stream_sources()
             for i, line in enumerate(p.read_text().splitlines(), 1)
             if re.search(r"getattr\([^()]*,[^()]*,", line)]
    assert found == []


def test_pipeline_and_stream_modules_keep_no_mutable_state_of_their_own():
    """Module-level dicts, lists and sets are process state outside the session and
    its windows (issue 6, item 2): the memos live on a window's Context, stream or
    state table, and the tables of names are read-only mappings."""
    import ast

    mutable_calls = {"dict", "list", "set", "defaultdict", "OrderedDict", "WeakKeyDictionary",
                     "WeakValueDictionary", "deque", "count"}
    found = []
    for p in _pipeline_and_stream_sources():
        for node in ast.parse(p.read_text()).body:
            if not isinstance(node, (ast.Assign, ast.AnnAssign)) or node.value is None:
                continue
            names = [t.id for t in (node.targets if isinstance(node, ast.Assign)
                                    else [node.target]) if isinstance(t, ast.Name)]
            if names == ["__all__"]:
                continue
            v = node.value
            func = v.func if isinstance(v, ast.Call) else None
            fname = getattr(func, "id", getattr(func, "attr", None))
            if isinstance(v, (ast.Dict, ast.List, ast.Set, ast.DictComp, ast.ListComp,
                              ast.SetComp)) or fname in mutable_calls:
                found.append(f"{p.parent.name}/{p.name}:{node.lineno} {names}")
    assert found == []


def test_flush_memos_and_lighting_tokens_belong_to_each_window():
    a, b = Context(W, H), Context(W, H)
    assert a.row_memo is not b.row_memo
    assert a.stream.light_memo is not b.stream.light_memo
    assert a.states.last_token == b.states.last_token == 0
    # A token a table hands out is its own count: a second window's first binding
    # takes the same number, and no table's count goes back.
    ta, tb = a.states.lighting_token(a), b.states.lighting_token(b)
    assert ta == tb == 1
    a.states.clear()
    a.lighting_serial += 1
    a.bound["material"] = 1  # another binding: a new token, never an old one
    assert a.states.lighting_token(a) == 2


def test_clears_and_memo_entries_are_named_records(ctx):
    gl.RGBmode()
    gl.gconfig()
    gl.cpack(0x00FF00FF)
    gl.clear()
    (c,) = ctx.stream.clears
    assert (c.planes, c.colour) == (ctx.stream.clears[0][0], 0x00FF00FF)
    assert c.state is not None and c.z == c[2] and c.stencil == c[3]
    gl.bgnpolygon()
    gl.endpolygon()
    assert all(hasattr(m, "record") for m in ctx.stream.state_memo.values())
