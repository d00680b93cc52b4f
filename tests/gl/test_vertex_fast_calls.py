"""v3i/v3s and t2f/t2d's valid paths (gl/_core.py FAST_CALLS) record the stream their
general paths record -- the same opcodes and floats, the same current texture
coordinate -- and draw the same planes; arguments they do not take reach the general
path, which raises the GLError naming the call."""

from __future__ import annotations

import math

import numpy as np
import pytest

from vgxsim import GL, gl
from vgxsim.gl import _core
from vgxsim.gl._core import session

W, H = 32, 24


def _program(rng: np.random.Generator) -> list:
    calls = []
    for _ in range(25):
        calls.append(("bgn", ()))
        for _ in range(int(rng.integers(3, 6))):
            r = rng.random()
            if r < 0.3:
                st = [float(v) for v in rng.uniform(-2, 2, 2)]
                name = "t2f" if rng.random() < 0.7 else "t2d"
                calls.append((name, (tuple(st),) if rng.random() < 0.3 else tuple(st)))
            if rng.random() < 0.3:
                calls.append(("c3f", tuple(float(v) for v in rng.uniform(0, 1, 3))))
            x, y = (int(v) for v in rng.integers(-12, 12, 2))
            name = str(rng.choice(["v3i", "v3s", "v3f"]))
            z = int(rng.integers(-3, 3))
            calls.append((name, (x, y, z) if name != "v3f" else (float(x), float(y), float(z))))
        calls.append(("end", ()))
    return calls


def _render(calls: list, fast: bool, monkeypatch):
    monkeypatch.setattr(_core, "FAST_CALLS", fast)
    session.reset()
    try:
        gl.prefsize(W, H)
        gl.winopen("vertex")
        gl.RGBmode()
        gl.gconfig()
        gl.mmode(GL.MVIEWING)
        gl.ortho(-16.0, 16.0, -12.0, 12.0, -5.0, 5.0)
        gl.concave(1)
        ctx = session.windows[session.current]
        texcoords = []
        for name, args in calls:
            if name == "bgn":
                gl.bgnpolygon()
            elif name == "end":
                gl.endpolygon()
            else:
                getattr(gl, name)(*args)
                texcoords.append(ctx.texcoord)
        stream = (list(ctx.stream.ops), list(ctx.stream.fl), ctx.stream.has_texcoords)
        planes = {"rgba": ctx.read_rgba().copy(), "z": ctx.fb.z.copy()}
        return stream, texcoords, planes
    finally:
        session.reset()
        monkeypatch.setattr(_core, "FAST_CALLS", True)
        session.refresh()


@pytest.mark.parametrize("seed", range(5))
def test_vertex_and_texcoord_valid_paths_record_what_the_general_paths_record(
        seed, monkeypatch):
    calls = _program(np.random.default_rng(800 + seed))
    fast = _render(calls, True, monkeypatch)
    slow = _render(calls, False, monkeypatch)
    assert fast[0] == slow[0]  # opcodes, floats (bit for bit as Python floats), flag
    assert [tuple(map(float.hex, t)) for t in fast[1]] == [
        tuple(map(float.hex, t)) for t in slow[1]]
    for k in fast[2]:
        assert np.array_equal(fast[2][k], slow[2][k]), k
    assert fast[0][2] and len(np.unique(fast[2]["rgba"].reshape(-1, 4), axis=0)) > 2


@pytest.fixture
def ctx(gl_window):
    c = gl_window(16, 12)
    assert session.imm is c  # the valid paths are in effect
    return c


@pytest.mark.parametrize("call, args, kwargs, error, pattern", [
    ("v3i", (1, 2.0, 3), {}, gl.GLTypeError, r"v3i\(1, 2.0, 3\): element 1 must be an int"),
    ("v3i", (1, 2), {}, gl.GLTypeError, r"v3i\(1, 2\): expected 3"),
    ("v3i", (1, 2, 3, 4), {}, gl.GLTypeError, r"v3i\(1, 2, 3, 4\): expected 3"),
    ("v3i", (1, 2), {"z": 3}, gl.GLTypeError, r"v3i\(1, 2, z=3\)"),
    ("v3s", (1, "2", 3), {}, gl.GLTypeError, r"v3s\(1, '2', 3\)"),
    ("t2f", (0.5, math.nan), {}, gl.GLValueError, r"t2f\(0.5, nan\): coordinates must be"),
    ("t2f", (0.5,), {}, gl.GLTypeError, r"t2f\(0.5\): expected 2"),
    ("t2f", ((0.5, 0.5, 0.5),), {}, gl.GLTypeError, r"expected 2 numbers, got 3"),
    ("t2f", (0.5, None), {}, gl.GLTypeError, r"t2f\(0.5, None\)"),
    ("t2f", (0.5,), {"t": 0.5}, gl.GLTypeError, r"t2f\(0.5, t=0.5\)"),
])
def test_bad_vertex_arguments_raise_naming_the_call(ctx, call, args, kwargs, error, pattern):
    gl.bgnpolygon()  # a vertex's place: only its arguments are wrong
    n = len(ctx.stream.ops)
    with pytest.raises(error, match=pattern):
        getattr(gl, call)(*args, **kwargs)
    assert len(ctx.stream.ops) == n


def test_int_vertex_outside_a_primitive(ctx):
    with pytest.raises(gl.GLUsageError, match=r"v3i\(1, 2, 3\): vertex outside"):
        gl.v3i(1, 2, 3)
