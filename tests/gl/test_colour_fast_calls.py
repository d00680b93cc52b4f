"""c4f and RGBcolor's valid paths (gl/_core.py FAST_CALLS) set the colour their
general paths set -- lighting off and on under every lmcolor mode, values at the
ends of the range and beyond (saturated by the general path) -- so random programs
draw identical planes with the switch on and off; arguments the valid paths do not
take reach the general path, which raises the GLError naming the call."""

from __future__ import annotations

import math

import numpy as np
import pytest

from vgxsim import GL, gl
from vgxsim.gl import _core
from vgxsim.gl._core import session

W, H = 36, 28
NAN = math.nan
_LMC = (GL.LMC_COLOR, GL.LMC_EMISSION, GL.LMC_AMBIENT, GL.LMC_DIFFUSE, GL.LMC_SPECULAR,
        GL.LMC_AD, GL.LMC_NULL)


def _colour_call(rng: np.random.Generator) -> tuple:
    r = rng.random()
    if r < 0.35:
        v = [float(x) for x in rng.uniform(0.0, 1.0, 4)]
        if rng.random() < 0.2:
            v[int(rng.integers(0, 4))] = float(rng.choice([0.0, 1.0, -0.25, 1.5]))
        form = rng.random()
        return ("c4f", (tuple(v),) if form < 0.2 else (v,) if form < 0.3 else tuple(v))
    if r < 0.7:
        v = [int(x) for x in rng.integers(0, 256, 3)]
        if rng.random() < 0.15:
            v[int(rng.integers(0, 3))] = int(rng.choice([-3, 300]))
        return ("RGBcolor", tuple(v))
    if r < 0.85:
        return ("c3f", tuple(float(x) for x in rng.uniform(0.0, 1.0, 3)))
    return ("cpack", (int(rng.integers(0, 1 << 32)),))


def _program(rng: np.random.Generator) -> list:
    calls = []
    for _ in range(40):
        r = rng.random()
        if r < 0.1:
            calls.append(("lmbind", (GL.MATERIAL, int(rng.integers(0, 2)))))
        elif r < 0.15:
            calls.append(("lmcolor", (int(rng.choice(_LMC)),)))
        else:
            calls.append(_colour_call(rng))
        if rng.random() < 0.5:
            x, y = (float(v) for v in rng.uniform(-6, 6, 2))
            calls.append(("quad", (x, y, [_colour_call(rng) if rng.random() < 0.4 else None
                                          for _ in range(4)])))
    return calls


def _render(calls: list, fast: bool, monkeypatch) -> tuple[dict, list]:
    monkeypatch.setattr(_core, "FAST_CALLS", fast)
    session.reset()
    try:
        gl.prefsize(W, H)
        gl.winopen("colour")
        gl.RGBmode()
        gl.gconfig()
        gl.mmode(GL.MVIEWING)
        gl.ortho(-9.0, 9.0, -7.0, 7.0, -5.0, 5.0)
        gl.lmdef(GL.DEFMATERIAL, 1, [GL.DIFFUSE, 0.8, 0.6, 0.4, GL.SPECULAR, 0.5, 0.5, 0.5,
                                     GL.SHININESS, 20.0, GL.LMNULL])
        gl.lmdef(GL.DEFLIGHT, 1, [GL.POSITION, 0.3, 0.4, 1.0, 0.0, GL.LMNULL])
        gl.lmdef(GL.DEFLMODEL, 1, [GL.LMNULL])
        gl.lmbind(GL.LIGHT0, 1)
        gl.lmbind(GL.LMODEL, 1)
        colours = []
        ctx = session.windows[session.current]
        for name, args in calls:
            if name == "quad":
                x, y, per_vertex = args
                gl.n3f(0.0, 0.3, 0.95)
                gl.bgnpolygon()
                for (dx, dy), c in zip(((0, 0), (3, 0), (3, 3), (0, 3)), per_vertex,
                                       strict=True):
                    if c is not None:
                        getattr(gl, c[0])(*c[1])
                    gl.v3f(x + dx, y + dy, 0.0)
                gl.endpolygon()
                continue
            getattr(gl, name)(*args)
            colours.append((ctx.colour, ctx.last_sent, ctx.lmcolor_set))
        planes = {"rgba": ctx.read_rgba().copy(), "z": ctx.fb.z.copy()}
        return planes, colours
    finally:
        session.reset()
        monkeypatch.setattr(_core, "FAST_CALLS", True)
        session.refresh()


@pytest.mark.parametrize("seed", range(6))
def test_colour_calls_valid_paths_draw_what_the_general_paths_draw(seed, monkeypatch):
    calls = _program(np.random.default_rng(700 + seed))
    fast_planes, fast_c = _render(calls, True, monkeypatch)
    slow_planes, slow_c = _render(calls, False, monkeypatch)
    assert fast_c == slow_c
    for k in fast_planes:
        assert np.array_equal(fast_planes[k], slow_planes[k]), k
    assert len(np.unique(fast_planes["rgba"].reshape(-1, 4), axis=0)) > 3


@pytest.fixture
def ctx(gl_window):
    c = gl_window(16, 12)
    assert session.imm is c  # the valid paths are in effect
    return c


@pytest.mark.parametrize("call, args, kwargs, error, pattern", [
    ("c4f", (0.5, NAN, 0.5, 1.0), {}, gl.GLValueError, r"c4f\(0.5, nan, 0.5, 1.0\): element 1"),
    ("c4f", (0.5, 0.5, 0.5), {}, gl.GLTypeError, r"c4f\(0.5, 0.5, 0.5\): expected 4"),
    ("c4f", ((0.5, 0.5, 0.5),), {}, gl.GLTypeError, r"expected 4 numbers, got 3"),
    ("c4f", (0.5, "g", 0.5, 1.0), {}, gl.GLTypeError, r"c4f\(0.5, 'g', 0.5, 1.0\)"),
    ("c4f", (0.5, 0.5, 0.5, 1.0, 1.0), {}, gl.GLTypeError, r"expected 4 numbers, got 5"),
    ("c4f", (0.5, 0.5, 0.5), {"a": 1.0}, gl.GLTypeError, r"c4f\(0.5, 0.5, 0.5, a=1.0\)"),
    ("RGBcolor", (1, 2, 3.5), {}, gl.GLTypeError, r"RGBcolor\(1, 2, 3.5\): b must be an int"),
    ("RGBcolor", (1, 2), {}, gl.GLTypeError, r"RGBcolor\(1, 2\): expected 3 arguments"),
    ("RGBcolor", (1, 2, 3, 4), {}, gl.GLTypeError, r"RGBcolor\(1, 2, 3, 4\): expected 3"),
    ("RGBcolor", (1, 2), {"b": 3}, gl.GLTypeError, r"RGBcolor\(1, 2, b=3\)"),
    ("RGBcolor", (1, 2, 1 << 40), {}, gl.GLValueError, r"b 1099511627776 does not fit"),
])
def test_bad_colour_arguments_raise_naming_the_call(ctx, call, args, kwargs, error, pattern):
    before = ctx.colour
    with pytest.raises(error, match=pattern):
        getattr(gl, call)(*args, **kwargs)
    assert ctx.colour is before


def test_colour_calls_in_colour_map_mode_are_errors(gl_window):
    gl_window(8, 6, rgb=False)
    with pytest.raises(gl.GLUsageError, match=r"c4f\(0.1, 0.2, 0.3, 0.4\): it is an error"):
        gl.c4f(0.1, 0.2, 0.3, 0.4)
    with pytest.raises(gl.GLUsageError, match=r"RGBcolor\(1, 2, 3\): it is an error"):
        gl.RGBcolor(1, 2, 3)
