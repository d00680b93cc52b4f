"""Random IRIS GL call sequences: immediate mode and display objects draw the same
planes (both go through the command stream, recorded by different paths: the gl
calls themselves, or the object recorder and callobj's splice)."""

from __future__ import annotations

import numpy as np
import pytest

from vgxsim.gl._core import session

from .random_calls import SEEDS, render, sequence


@pytest.fixture(autouse=True)
def _fresh():
    session.reset()
    yield
    session.reset()


@pytest.mark.parametrize("seed", list(SEEDS))
def test_objects_draw_what_immediate_mode_draws(seed):
    calls = sequence(seed)
    a = render(calls)
    b = render(calls, objects=True, seed=seed)
    assert a["rgba"][..., :3].any() or a["stencil"].any()
    for k in a:
        assert np.array_equal(a[k], b[k]), k


@pytest.mark.parametrize("seed", list(SEEDS)[:6])
def test_merged_fragment_states_switch_gives_identical_planes(seed, monkeypatch):
    """The fast path that sets up triangles of several fragment states in one
    geometry pass draws what one pass per state record draws."""
    from vgxsim.pipeline import draw

    calls = sequence(seed)
    a = render(calls)
    monkeypatch.setattr(draw, "MERGE_FRAGMENT_STATES", False)
    b = render(calls)
    for k in a:
        assert np.array_equal(a[k], b[k]), k
