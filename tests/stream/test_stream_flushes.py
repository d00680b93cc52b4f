"""The stream is decoded at any flush -- also a full stream, or a flush while a
primitive is open -- and draws the same planes as one decode at the end."""

from __future__ import annotations

import numpy as np
import pytest

from vgxsim import gl
from vgxsim.gl import _draw

from .random_calls import render, sequence


@pytest.fixture
def ctx():
    from vgxsim.gl._core import current, session

    session.reset()
    gl.prefsize(32, 24)
    gl.winopen("flushes")
    gl.RGBmode()
    gl.gconfig()
    gl.ortho2(-0.5, 31.5, -0.5, 23.5)
    yield current("ctx")
    session.reset()


def test_full_stream_is_decoded_and_draws_the_same(monkeypatch):
    calls = sequence(3, n=60)
    a = render(calls)
    monkeypatch.setattr(_draw, "MAX_STREAM_OPS", 20)
    b = render(calls)
    for k in a:
        assert np.array_equal(a[k], b[k]), k


def test_stream_stays_bounded(ctx, monkeypatch):
    monkeypatch.setattr(_draw, "MAX_STREAM_OPS", 50)
    for i in range(100):
        gl.bgnpolygon()
        gl.v2f(1.0 + i % 7, 1.0)
        gl.v2f(9.0, 1.0)
        gl.v2f(9.0, 9.0)
        gl.endpolygon()
    assert len(ctx.stream.ops) < 50 + 20


def test_flush_inside_an_open_primitive_keeps_it(ctx):
    gl.cpack(0xFFFFFFFF)
    gl.bgnpolygon()
    gl.v2f(1.0, 1.0)
    gl.v2f(20.0, 1.0)
    ctx.flush()  # decodes what precedes the open polygon only
    assert not ctx.read_rgba()[..., 0].any()
    gl.cpack(0xFF0000FF)  # the last vertex red (Gouraud)
    gl.v2f(20.0, 20.0)
    gl.endpolygon()
    img = ctx.read_rgba()
    assert img[..., 0].any() and tuple(img[19, 19]) != (0, 0, 0, 0)
    # The same polygon without the flush.
    gl.bgnpolygon()
    ctx.fb.front[:] = 0
    gl.cpack(0xFFFFFFFF)
    gl.v2f(1.0, 1.0)
    gl.v2f(20.0, 1.0)
    gl.cpack(0xFF0000FF)
    gl.v2f(20.0, 20.0)
    gl.endpolygon()
    assert np.array_equal(ctx.read_rgba(), img)
