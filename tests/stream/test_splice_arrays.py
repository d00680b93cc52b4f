"""callobj splicing a chunk as arrays into the stream's parts draws what copying its
numbers into the stream's lists draws (``SPLICE_MIN_FLOATS``: 0 splices every chunk
as arrays, a huge value copies every chunk), and both draw what immediate mode draws,
including objects whose primitives stay open across the splice and flushes inside
an open primitive."""

from __future__ import annotations

import numpy as np
import pytest

from vgxsim import gl
from vgxsim.gl._core import current, session
from vgxsim.stream import recorder

from .random_calls import SEEDS, render, sequence


@pytest.fixture(autouse=True)
def _fresh():
    session.reset()
    yield
    session.reset()


@pytest.mark.parametrize("seed", list(SEEDS)[:8])
def test_array_splice_switch_gives_identical_planes(seed, monkeypatch):
    calls = sequence(seed)
    want = render(calls)
    planes = []
    for limit in (0, 1 << 40):
        monkeypatch.setattr(recorder, "SPLICE_MIN_FLOATS", limit)
        session.reset()
        planes.append(render(calls, objects=True, seed=seed))
    for got in planes:
        for k in want:
            assert np.array_equal(got[k], want[k]), k


def _window():
    gl.prefsize(32, 32)
    gl.winopen("splice")
    gl.RGBmode()
    gl.gconfig()
    gl.ortho2(-0.5, 31.5, -0.5, 31.5)


def _rgba() -> np.ndarray:
    return current("test").read_rgba("front").copy()


@pytest.mark.parametrize("limit", [0, 1 << 40])
def test_object_opening_a_polygon_that_the_caller_closes(limit, monkeypatch):
    # The object sends bgnpolygon and three vertices; the caller adds the fourth
    # vertex and endpolygon, after a readback (a flush) inside the open polygon.
    monkeypatch.setattr(recorder, "SPLICE_MIN_FLOATS", limit)
    _window()
    gl.makeobj(1)
    gl.cpack(0xFF0000FF)
    gl.bgnpolygon()
    gl.v2f(2.0, 2.0)
    gl.v2f(20.0, 2.0)
    gl.v2f(20.0, 20.0)
    gl.closeobj()
    gl.callobj(1)
    current("test").flush()
    gl.v2f(2.0, 20.0)
    gl.endpolygon()
    img = _rgba()
    # The square from pixel centre 2 to 20 covers pixels 2..19 on both axes (the
    # fill rule leaves the right and top edges to the neighbour), red on black.
    want = np.zeros((32, 32, 4), np.uint8)
    want[2:20, 2:20] = (255, 0, 0, 255)
    assert np.array_equal(img[..., :3], want[..., :3])
