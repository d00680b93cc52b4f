"""Clears are CLEAR ops of the command stream, drawn in order with the primitives at
the next flush.  Random call sequences with clears between primitives (sclear,
zclear, czclear, clear under the sequences' write masks and stencil state) draw the
planes that flushing after every call draws (each clear then reaches the batch at
once, as before clears joined the stream), and display objects draw what immediate
mode draws."""

from __future__ import annotations

import numpy as np
import pytest

from vgxsim import gl
from vgxsim.gl._core import current, session

from .random_calls import SEEDS, _setup, render, sequence


@pytest.fixture(autouse=True)
def _fresh():
    session.reset()
    yield
    session.reset()


def _with_clears(seed: int) -> list:
    rng = np.random.default_rng(7000 + seed)
    out, depth = [], 0
    for name, args in sequence(seed, n=50):
        out.append((name, args))
        depth += name.startswith("bgn") - name.startswith("end")
        if depth == 0 and rng.random() < 0.12:
            choices = [
                ("sclear", (int(rng.integers(0, 256)),)),
                ("zclear", ()),
                ("czclear", (int(rng.integers(0, 2**32)), int(rng.integers(-2**23, 2**23)))),
                ("clear", ()),
                ("zwritemask", (int(rng.choice([0, 0xFFFFFFFF, 0x00FFFF00])),)),
            ]
            out.append(choices[int(rng.integers(0, len(choices)))])
    return out


def _flushing(calls) -> dict:
    gid = _setup()
    try:
        ctx = current("test")
        for name, args in calls:
            getattr(gl, name)(*args)
            ctx.flush()
        return {"rgba": ctx.read_rgba().copy(), "z": ctx.fb.z.copy(),
                "stencil": ctx.fb.stencil.copy()}
    finally:
        gl.winclose(gid)


@pytest.mark.parametrize("seed", list(SEEDS))
def test_clears_in_the_stream_draw_what_flushing_every_call_draws(seed):
    calls = _with_clears(seed)
    assert any(c[0] in ("sclear", "zclear", "czclear", "clear") for c in calls)
    want = _flushing(calls)
    session.reset()
    got = render(calls)
    session.reset()
    objects = render(calls, objects=True, seed=seed)
    for k in want:
        assert np.array_equal(got[k], want[k]), k
        assert np.array_equal(objects[k], want[k]), k


def test_clear_after_a_polygon_in_one_flush_hides_it():
    # A red square, then clear() to black and a green square beside it, one flush:
    # only the green square is left (the clear comes after the red one).
    _setup()
    gl.cpack(0xFF0000FF)
    gl.rectf(2.0, 2.0, 8.0, 8.0)
    gl.cpack(0xFF000000)
    gl.clear()
    gl.cpack(0xFF00FF00)
    gl.rectf(10.0, 2.0, 14.0, 8.0)
    img = current("test").read_rgba()
    assert not img[2:8, 2:8, :3].any()
    assert (img[3, 11, :3] == (0, 255, 0)).all()
