"""cmov*'s valid path (FAST_CALLS): the character position from the point times the
mvp spelled out on Python floats (gl/_text.py _position, MatrixState.mvp_flat)
against the oracle of cmov(3G)'s definition computed here with the pipeline's own
transform kernel (vgxsim.geometry.transform.apply) and the viewport mapping of
docs/numeric_model.md s. 2; with FAST_CALLS on and off, in immediate mode and from
display objects; bad arguments raise naming the call."""

from __future__ import annotations

import math
import random

import numpy as np
import pytest

from vgxsim import GL, gl
from vgxsim.geometry.transform import apply
from vgxsim.gl import _core
from vgxsim.gl._core import GLTypeError, GLValueError, session

W, H = 37, 29


@pytest.fixture
def ctx(gl_window):
    return gl_window(W, H)


def oracle(ctx, p) -> tuple[bool, int, int, int]:
    """cmov(3G): the point through the current matrices; outside the view volume
    the position is undefined; else the window pixel and the z-buffer value."""
    mvp = np.array(ctx.matrices.mvp(), dtype=np.float64)
    x, y, z, w = (float(c) for c in apply(np.asarray([p], np.float64), mvp)[0])
    if not (w > 0 and all(-w <= c <= w for c in (x, y, z))):
        return False, 0, 0, 0
    l, r, b, t = ctx.raster.viewport
    near, far = ctx.depth_range
    xw = (l - 0.5) + (x / w + 1.0) * (r - l + 1) / 2.0
    yw = (b - 0.5) + (y / w + 1.0) * (t - b + 1) / 2.0
    zw = near + (z / w + 1.0) * (far - near) / 2.0
    lo, hi = sorted((near, far))
    return (True, math.floor(xw + 0.5), math.floor(yw + 0.5),
            min(max(math.floor(zw + 0.5), lo), hi))


def _matrices(rng: random.Random) -> None:
    gl.mmode(GL.MVIEWING)
    if rng.random() < 0.5:
        gl.perspective(rng.randrange(300, 900), W / H, rng.uniform(0.1, 2.0),
                       rng.uniform(5.0, 40.0))
    else:
        gl.ortho(-rng.uniform(1, 9), rng.uniform(1, 9), -rng.uniform(1, 9),
                 rng.uniform(1, 9), -rng.uniform(1, 9), rng.uniform(8, 20))
    gl.loadmatrix([1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0,
                   0.0, 0.0, 0.0, 1.0])
    gl.translate(rng.uniform(-1, 1), rng.uniform(-1, 1), -rng.uniform(3.0, 6.0))
    gl.rot(rng.uniform(-180, 180), "y")
    gl.rot(rng.uniform(-180, 180), "x")
    if rng.random() < 0.5:
        gl.lsetdepth(rng.randrange(-0x800000, 0), rng.randrange(0, 0x7FFFFF))
    if rng.random() < 0.3:
        gl.viewport(2, W - 5, 3, H - 2)


def _point(rng: random.Random, name: str) -> tuple:
    if name.endswith("i"):
        return tuple(rng.randint(-2, 2) for _ in range(2 if "2" in name else 3))
    return tuple(rng.uniform(-2.0, 2.0) for _ in range(2 if "2" in name else 3))


@pytest.mark.parametrize("fast", [True, False])
@pytest.mark.parametrize("seed", range(6))
def test_positions_match_the_transform_kernel(ctx, seed, fast, monkeypatch):
    monkeypatch.setattr(_core, "FAST_CALLS", fast)
    session.refresh()
    rng = random.Random(seed)
    _matrices(rng)
    hits = 0
    for _ in range(300):
        name = rng.choice(("cmov", "cmov2", "cmovi", "cmov2i"))
        q = _point(rng, name)
        getattr(gl, name)(*q)
        p = (float(q[0]), float(q[1]), float(q[2]) if len(q) == 3 else 0.0, 1.0)
        valid, x, y, z = oracle(ctx, p)
        assert ctx.cpos_valid == valid
        if valid:
            hits += 1
            assert (ctx.cpos, ctx.cpos_z) == ((x, y), z)
            assert gl.getcpos() == (x, y)
        ctx.cpos_valid = True
    assert hits > 20


def test_display_objects_set_the_same_positions(ctx):
    rng = random.Random(7)
    _matrices(rng)
    pts = [(name, _point(rng, name)) for name in ("cmov", "cmov2", "cmovi", "cmov2i") * 20]
    for k, (name, q) in enumerate(pts):
        gl.makeobj(1 + k)
        getattr(gl, name)(*q)
        gl.closeobj()
    for k, (_name, q) in enumerate(pts):
        ctx.cpos_valid = True
        gl.callobj(1 + k)
        p = (float(q[0]), float(q[1]), float(q[2]) if len(q) == 3 else 0.0, 1.0)
        valid, x, y, z = oracle(ctx, p)
        assert ctx.cpos_valid == valid
        if valid:
            assert (ctx.cpos, ctx.cpos_z) == ((x, y), z)


def test_a_matrix_change_is_seen_at_the_next_cmov(ctx):
    """The Python-float copy of the mvp follows every change (MatrixState.mvp_flat
    keys it by the mvp object, which each change replaces)."""
    gl.cmov2(3.0, 4.0)
    assert gl.getcpos() == (3, 4)
    gl.translate(5.0, 2.0, 0.0)  # deferred translate: settled by the next mvp()
    gl.cmov2(3.0, 4.0)
    assert gl.getcpos() == (8, 6)
    gl.pushmatrix()
    gl.scale(2.0, 2.0, 1.0)
    gl.cmov2i(3, 4)
    assert gl.getcpos() == (11, 10)
    gl.popmatrix()
    gl.cmov2i(3, 4)
    assert gl.getcpos() == (8, 6)


def test_viewport_and_depth_changes_are_seen_at_the_next_cmov(ctx):
    """cmov's window map (gl/_text.py _window_map) is keyed by the mvp, viewport and
    depth-range objects: a change of any one between two cmovs of the same point
    moves the position as the oracle says."""
    gl.mmode(GL.MVIEWING)
    gl.ortho(-4.0, 4.0, -3.0, 3.0, -5.0, 5.0)
    p = (1.25, -0.75, 0.5)
    seen = []
    for change in (lambda: None, lambda: gl.viewport(3, W - 7, 2, H - 4),
                   lambda: gl.lsetdepth(-0x1000, 0x7000),
                   lambda: gl.lsetdepth(0x7000, -0x1000),  # near above far
                   lambda: gl.translate(0.5, 0.25, 0.0), lambda: gl.viewport(0, W - 1, 0, H - 1)):
        change()
        gl.cmov(*p)
        valid, x, y, z = oracle(ctx, p + (1.0,))
        assert valid and ctx.cpos_valid
        assert (ctx.cpos, ctx.cpos_z) == ((x, y), z)
        seen.append((ctx.cpos, ctx.cpos_z))
    assert len(set(seen)) == len(seen)  # each change moved the point


@pytest.mark.parametrize("call, args, error", [
    ("cmov2", (float("nan"), 1.0), GLValueError),
    ("cmov", (1.0, 2.0, float("inf")), GLValueError),
    ("cmov2", ("a", 1.0), GLTypeError),
    ("cmov2i", (1.5, 2), GLTypeError),
    ("cmov", (1.0, 2.0), GLTypeError),
    ("cmov2", (1.0, 2.0, 3.0), GLTypeError),
])
def test_bad_arguments_raise_naming_the_call(ctx, call, args, error):
    with pytest.raises(error, match=call + r"\("):
        getattr(gl, call)(*args)
    with pytest.raises(GLTypeError, match=call + r"\("):
        getattr(gl, call)(1, 2, 3, kw=1)
