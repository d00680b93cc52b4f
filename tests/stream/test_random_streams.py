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


def test_objects_called_under_changing_matrices_draw_what_immediate_mode_draws(monkeypatch):
    """The same objects called again under other matrices (three passes, each under a
    translation of its own, each middle object under one more) draw what the same
    calls draw in immediate mode: with gl._core.REPLAY_OBJECTS on, prepared replays
    rebased to the caller's matrix (_objects.REBASE_REPLAYS) or traced again, and
    with REPLAY_OBJECTS off.  Odd seeds draw only stencil() calls and polygons, whose
    objects are replayed from blocks."""
    from vgxsim.gl import _core, _objects

    used = {"replays": 0, "rebases": 0}
    replay, rebase = _objects._replay, _objects._rebase

    def counting_replay(ctx, dobj):
        done = replay(ctx, dobj)
        used["replays"] += done
        return done

    def counting_rebase(ctx, blk, mvp):
        used["rebases"] += 1
        return rebase(ctx, blk, mvp)

    monkeypatch.setattr(_objects, "_replay", counting_replay)
    monkeypatch.setattr(_objects, "_rebase", counting_rebase)
    for seed in list(SEEDS):
        calls = sequence(seed, faces=seed % 2 == 1)
        a = render(calls, passes=3, seed=seed)
        others = {"rebased": render(calls, objects=True, seed=seed, passes=3)}
        monkeypatch.setattr(_objects, "REBASE_REPLAYS", False)
        others["traced"] = render(calls, objects=True, seed=seed, passes=3)
        monkeypatch.setattr(_objects, "REBASE_REPLAYS", True)
        monkeypatch.setattr(_core, "REPLAY_OBJECTS", False)
        others["spliced"] = render(calls, objects=True, seed=seed, passes=3)
        monkeypatch.setattr(_core, "REPLAY_OBJECTS", True)
        session.reset()
        assert a["rgba"][..., :3].any() or a["stencil"].any()
        for name, b in others.items():
            for k in a:
                assert np.array_equal(a[k], b[k]), (seed, name, k)
    # Blocks were replayed under other matrices than they were traced under.
    assert used["replays"] > 0 and used["rebases"] > 0
