"""rot, rotate, scale, loadmatrix and multmatrix's valid paths (gl/_core.py
FAST_CALLS; MatrixState.rotate_axis, scale_by, mult_by and load_owned) give the
matrices and planes their general paths give, bit for bit, and hand every argument
they do not take to the general path, which raises the GLError naming the call and
the argument."""

from __future__ import annotations

import math

import numpy as np
import pytest

from vgxsim import GL, gl
from vgxsim.gl import _core
from vgxsim.gl._core import session

W, H = 40, 32
NAN, INF = math.nan, math.inf


def _program(rng: np.random.Generator) -> list:
    """Random matrix calls (every form the valid paths take and some they hand on:
    int angles and factors, upper-case axes) between quads, in MVIEWING."""
    calls = []
    for _ in range(60):
        r = rng.random()
        if r < 0.2:
            axis = str(rng.choice(list("xyzXYZ")))
            calls.append(("rot", (float(rng.uniform(-180, 180)), axis)))
        elif r < 0.3:
            calls.append(("rot", (int(rng.integers(-90, 90)), "z")))
        elif r < 0.45:
            axis = str(rng.choice(list("xyzZ")))
            calls.append(("rotate", (int(rng.integers(-1800, 1800)), axis)))
        elif r < 0.6:
            f = [float(rng.choice([-1.0, 1.0]) * rng.uniform(0.5, 1.5)) for _ in range(3)]
            calls.append(("scale", tuple(f) if rng.random() < 0.8 else (1, 2, 1)))
        elif r < 0.65:
            calls.append(("translate", tuple(float(v) for v in rng.uniform(-3, 3, 3))))
        elif r < 0.7:
            # A matrix near the identity, as a list or tuple of floats, some ints.
            # (Affine: the last column stays 0, 0, 0, 1.)
            m = (np.eye(4) + rng.uniform(-0.2, 0.2, (4, 4))).reshape(-1).tolist()
            m[3] = m[7] = m[11] = 0.0
            m[15] = 1.0
            if rng.random() < 0.3:
                m[int(rng.choice([0, 5, 10, 12, 13]))] = int(rng.integers(1, 2))
            name = "multmatrix" if rng.random() < 0.7 else "loadmatrix"
            calls.append((name, (m if rng.random() < 0.5 else tuple(m),)))
        elif r < 0.8:
            calls.append(("pushmatrix", ()))
        elif r < 0.9:
            calls.append(("popmatrix", ()))
        else:
            calls.append(("quad", (int(rng.integers(0, 1 << 24)),)))
    return calls


def _render(calls: list, fast: bool, monkeypatch) -> tuple[dict, list]:
    monkeypatch.setattr(_core, "FAST_CALLS", fast)
    session.reset()
    try:
        gl.prefsize(W, H)
        gl.winopen("matrix")
        gl.RGBmode()
        gl.gconfig()
        gl.mmode(GL.MVIEWING)
        gl.ortho(-12.0, 12.0, -10.0, 10.0, -20.0, 20.0)
        gl.backface(0)
        depth, matrices = 0, []
        for name, args in calls:
            if name == "quad":
                gl.cpack(0xFF000000 | args[0])
                gl.bgnpolygon()
                for p in ((-2.0, -2.0, 0.0), (2.0, -2.0, 0.0), (2.0, 2.0, 0.0), (-2.0, 2.0, 0.0)):
                    gl.v3f(p)
                gl.endpolygon()
                continue
            if name == "pushmatrix":
                if depth >= 20:
                    continue
                depth += 1
            if name == "popmatrix":
                if depth == 0:
                    continue
                depth -= 1
            getattr(gl, name)(*args)
            if name != "translate":  # (its deferred product then meets the next call)
                matrices.append(np.asarray(gl.getmatrix(), np.float64))
        ctx = session.windows[session.current]
        planes = {"rgba": ctx.read_rgba().copy(), "z": ctx.fb.z.copy()}
        return planes, matrices
    finally:
        session.reset()
        monkeypatch.setattr(_core, "FAST_CALLS", True)
        session.refresh()


@pytest.mark.parametrize("seed", range(6))
def test_matrix_calls_valid_paths_give_identical_matrices_and_planes(seed, monkeypatch):
    calls = _program(np.random.default_rng(900 + seed))
    fast_planes, fast_m = _render(calls, True, monkeypatch)
    slow_planes, slow_m = _render(calls, False, monkeypatch)
    assert len(fast_m) == len(slow_m)
    for a, b in zip(fast_m, slow_m, strict=True):
        assert a.tobytes() == b.tobytes()  # bit for bit, -0.0 included
    for k in fast_planes:
        assert np.array_equal(fast_planes[k], slow_planes[k]), k
    assert len(np.unique(fast_planes["rgba"].reshape(-1, 4), axis=0)) > 2


@pytest.fixture
def ctx(gl_window):
    c = gl_window(16, 12)
    assert session.imm is c  # the valid paths are in effect
    return c


@pytest.mark.parametrize("call, args, kwargs, error, pattern", [
    ("rot", (NAN, "z"), {}, gl.GLValueError, r"rot\(nan, 'z'\): arguments must be finite"),
    ("rot", (INF, "x"), {}, gl.GLValueError, r"rot\(inf, 'x'\)"),
    ("rot", (1.0, "w"), {}, gl.GLValueError, r"rot\(1.0, 'w'\): axis must be"),
    ("rot", (1.0, 3), {}, gl.GLValueError, r"rot\(1.0, 3\): axis must be"),
    ("rot", ("1", "z"), {}, gl.GLTypeError, r"rot\('1', 'z'\): angle must be a number"),
    ("rot", (1.0,), {}, gl.GLTypeError, r"rot\(1.0\): expected 2 arguments"),
    ("rot", (1.0, "z", 1), {}, gl.GLTypeError, r"rot\(1.0, 'z', 1\): expected 2"),
    ("rot", (1.0,), {"axis": "z"}, gl.GLTypeError, r"rot\(1.0, axis='z'\)"),
    ("rotate", (90.0, "z"), {}, gl.GLTypeError, r"rotate\(90.0, 'z'\): Angle must be an int"),
    ("rotate", (900, "q"), {}, gl.GLValueError, r"rotate\(900, 'q'\): axis must be"),
    ("rotate", (900,), {}, gl.GLTypeError, r"rotate\(900\): expected 2 arguments"),
    ("rotate", (900, "z"), {"x": 1}, gl.GLTypeError, r"rotate\(900, 'z', x=1\)"),
    ("scale", (1.0, NAN, 1.0), {}, gl.GLValueError, r"scale\(1.0, nan, 1.0\): arguments"),
    ("scale", (1.0, 2.0), {}, gl.GLTypeError, r"scale\(1.0, 2.0\): expected 3 arguments"),
    ("scale", (1.0, None, 1.0), {}, gl.GLTypeError, r"scale\(1.0, None, 1.0\): y must be"),
    ("scale", (1.0, 1.0, 1.0, 1.0), {}, gl.GLTypeError, r"scale\(1.0, 1.0, 1.0, 1.0\)"),
    ("scale", (1.0, 1.0), {"z": 1.0}, gl.GLTypeError, r"scale\(1.0, 1.0, z=1.0\)"),
    ("multmatrix", ([1.0] * 15 + [NAN],), {}, gl.GLValueError,
     r"multmatrix\(\[16 values\]\): arguments must be finite"),
    ("multmatrix", ([1.0] * 15 + [INF],), {}, gl.GLValueError, r"arguments must be finite"),
    ("multmatrix", ([1.0] * 15,), {}, gl.GLTypeError, r"expected 16 numbers, got 15"),
    ("multmatrix", ([1.0] * 15 + ["1"],), {}, gl.GLTypeError, r"element 15 must be a number"),
    ("multmatrix", ([1.0] * 15 + [None],), {}, gl.GLTypeError, r"element 15 must be a number"),
    ("multmatrix", ([[1.0] * 4] * 4,), {}, gl.GLTypeError, r"not nested rows"),
    ("multmatrix", ([1.0] * 16,), {"x": 1}, gl.GLTypeError, r"multmatrix\(\[16 values\], x=1\)"),
    ("loadmatrix", ([1.0] * 15 + [NAN],), {}, gl.GLValueError, r"loadmatrix\(\[16 values\]\)"),
    ("loadmatrix", ((1.0,) * 17,), {}, gl.GLTypeError, r"expected 16 numbers, got 17"),
    ("loadmatrix", ([1.0] * 16, 1), {}, gl.GLTypeError, r"loadmatrix\(\[16 values\], 1\)"),
])
def test_bad_matrix_arguments_raise_naming_the_call(ctx, call, args, kwargs, error, pattern):
    before = np.asarray(gl.getmatrix())
    with pytest.raises(error, match=pattern):
        getattr(gl, call)(*args, **kwargs)
    assert np.array_equal(np.asarray(gl.getmatrix()), before)  # nothing changed


def test_matrix_calls_are_recorded_in_display_objects(ctx):
    gl.makeobj(5)
    gl.rot(30.0, "Z")
    gl.rotate(450, "x")
    gl.scale(2.0, 1.0, 0.5)
    gl.closeobj()
    before = np.asarray(gl.getmatrix())
    gl.callobj(5)
    replayed = np.asarray(gl.getmatrix())
    assert not np.array_equal(replayed, before)
    gl.loadmatrix(before.tolist())
    gl.rot(30.0, "z")
    gl.rotate(450, "x")
    gl.scale(2.0, 1.0, 0.5)
    assert np.asarray(gl.getmatrix()).tobytes() == replayed.tobytes()


@pytest.mark.parametrize("fast", [True, False])
def test_loadmatrix_after_a_deferred_translate_replaces_it(fast, monkeypatch):
    monkeypatch.setattr(_core, "FAST_CALLS", fast)
    session.reset()
    try:
        gl.prefsize(8, 8)
        gl.winopen("load")
        gl.mmode(GL.MVIEWING)
        gl.translate(1.0, 2.0, 3.0)  # deferred (DEFER_TRANSLATE): met by loadmatrix
        m = [2.0, 0.0, 0.0, 0.0, 0.0, 2.0, 0.0, 0.0, 0.0, 0.0, 2.0, 0.0, 5.0, 6.0, 7.0, 1.0]
        gl.loadmatrix(m)
        assert gl.getmatrix() == m
        gl.translate(1.0, 0.0, 0.0)
        gl.multmatrix(m)  # m @ (translation @ m)
        t = np.eye(4)
        t[3, :3] = (1.0, 0.0, 0.0)
        want = np.asarray(m).reshape(4, 4) @ (t @ np.asarray(m).reshape(4, 4))
        assert np.array_equal(np.asarray(gl.getmatrix()).reshape(4, 4), want)
    finally:
        session.reset()
        monkeypatch.setattr(_core, "FAST_CALLS", True)
        session.refresh()


@pytest.mark.parametrize("fast", [True, False])
def test_deferred_products_before_and_after_a_load_in_order(fast, monkeypatch):
    """rot, scale and translate noted before a loadmatrix are replaced by it; those
    after it, and a multmatrix, multiply it in call order (each premultiplies:
    hand-computed with the same numpy products)."""
    from vgxsim.geometry.transform import rotation, scaling

    monkeypatch.setattr(_core, "FAST_CALLS", fast)
    session.reset()
    try:
        gl.prefsize(8, 8)
        gl.winopen("order")
        gl.mmode(GL.MVIEWING)
        gl.rot(30.0, "x")
        gl.scale(2.0, 1.0, 1.0)
        gl.translate(1.0, 2.0, 3.0)
        m = [1.0, 0.5, 0.0, 0.0, 0.0, 2.0, 0.0, 0.0, 0.0, 0.0, 3.0, 0.0, 5.0, 6.0, 7.0, 1.0]
        gl.loadmatrix(m)
        gl.rotate(450, "z")
        gl.scale(1.0, 3.0, 0.5)
        n = [1.0, 0.0, 0.0, 0.0, 0.25, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 1.0, 1.0]
        gl.multmatrix(tuple(n))
        want = np.asarray(m, np.float64).reshape(4, 4)
        for step in (rotation(45.0, "z"), scaling(1.0, 3.0, 0.5),
                     np.asarray(n, np.float64).reshape(4, 4)):
            want = step @ want
        np.testing.assert_allclose(np.asarray(gl.getmatrix()).reshape(4, 4), want,
                                   rtol=0, atol=1e-12)
        gl.pushmatrix()
        gl.loadmatrix(n)
        gl.popmatrix()  # the load (deferred) goes with its matrix
        np.testing.assert_allclose(np.asarray(gl.getmatrix()).reshape(4, 4), want,
                                   rtol=0, atol=1e-12)
    finally:
        session.reset()
        monkeypatch.setattr(_core, "FAST_CALLS", True)
        session.refresh()


def test_deferred_matrix_arguments_are_taken_at_the_call(ctx):
    """multmatrix and loadmatrix's valid paths keep a copy of the 16 numbers (the
    array is made where the product is formed, MatrixState._settle): changing the
    caller's list afterwards changes nothing; ints, bools and Fractions among floats
    give float(v) as the general path does; a complex element or a numpy array row
    goes to the general path and raises there."""
    from fractions import Fraction

    m = [1.0, 0.0, 0.0, 0.0, 0.0, 2.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 3.0, 4.0, 5.0, 1.0]
    gl.loadmatrix(m)
    m[12] = 99.0
    gl.multmatrix(m)
    m[0] = -7.0
    want = np.array(m, np.float64).reshape(4, 4)
    want[0, 0] = 1.0
    first = want.copy()
    first[3, 0] = 3.0
    assert np.array(gl.getmatrix()).reshape(4, 4).tobytes() == (want @ first).tobytes()
    odd = [1.0, 0, False, 0, 0, Fraction(1, 2), 0, 0, 0, 0, True, 0, 0, 0, 0, 1]
    gl.loadmatrix(odd)
    assert gl.getmatrix() == [float(v) for v in odd]
    with pytest.raises(gl.GLTypeError, match=r"loadmatrix\(\[16 values\]\)"):
        gl.loadmatrix([1.0] * 15 + [1j])
    with pytest.raises(gl.GLTypeError, match=r"multmatrix\("):
        gl.multmatrix([1.0] * 15 + [np.array([1.0, 2.0])])
    assert gl.getmatrix() == [float(v) for v in odd]
