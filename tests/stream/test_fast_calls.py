"""The common calls' valid paths (gl/_core.py FAST_CALLS) draw what their general
paths draw: the same random IRIS GL call sequences, immediately and through nested
display objects, give identical colour, z and stencil planes with the switch on and
off; and so do multi-frame programs whose objects callobj replays from prepared
blocks and whose draw-state records are kept across flushes, with the edits that
must make them stale between frames (tests/stream/frames_of_objects.py)."""

from __future__ import annotations

import numpy as np
import pytest

from vgxsim.gl import _core
from vgxsim.gl._core import session

from .frames_of_objects import FRAME_SEEDS, render_frames
from .random_calls import SEEDS, render, sequence


@pytest.fixture(autouse=True)
def _fresh():
    session.reset()
    yield
    session.reset()


def _varied(calls: list, seed: int) -> list:
    """``calls`` with every argument form the fast calls take: vertices, normals and
    colours also as one tuple or list, zwritemask changes between primitives, and
    stencil() alternating between two settings before primitives, as the 1991 shadow
    faces do (each setting's snapshot and record are found again, not rebuilt)."""
    rng = np.random.default_rng(500 + seed)
    faces = [(1, 0, 7, 0xFF, 0, 0, 3), (1, 0, 7, 0xFF, 0, 0, 4)]
    out = []
    for name, args in calls:
        r = rng.random()
        if name.startswith("bgn") and r < 0.3:
            out.append(("stencil", faces[int(rng.integers(0, 2))]))
        if name in ("v3f", "n3f", "c3f") and r < 0.4:
            args = (tuple(args) if name == "n3f" or r < 0.2 else list(args),)
        out.append((name, args))
        if name.startswith("end") and rng.random() < 0.15:
            out.append(("zwritemask", (int(rng.choice([0, 0xFFFFFFFF, 0xFF00])),)))
    return out


def _render(calls, objects: bool, seed: int, fast: bool, monkeypatch) -> dict:
    monkeypatch.setattr(_core, "FAST_CALLS", fast)
    session.refresh()
    try:
        return render(calls, objects=objects, seed=seed)
    finally:
        monkeypatch.setattr(_core, "FAST_CALLS", True)
        session.refresh()


@pytest.mark.parametrize("objects", [False, True])
@pytest.mark.parametrize("seed", list(SEEDS))
def test_fast_calls_switch_gives_identical_planes(seed, objects, monkeypatch):
    calls = _varied(sequence(seed), seed)
    a = _render(calls, objects, seed, True, monkeypatch)
    b = _render(calls, objects, seed, False, monkeypatch)
    assert a["rgba"][..., :3].any() or a["stencil"].any()
    for k in a:
        assert np.array_equal(a[k], b[k]), k


def test_the_switch_decides_which_path_runs(monkeypatch):
    from vgxsim import gl

    gid = gl.winopen("switch")
    try:
        assert session.imm is session.windows[gid]  # the valid paths read this
        gl.makeobj(1)
        assert session.imm is None  # recording: every call takes its general path
        gl.closeobj()
        assert session.imm is session.windows[gid]
        monkeypatch.setattr(_core, "FAST_CALLS", False)
        session.refresh()
        assert session.imm is None
    finally:
        gl.winclose(gid)
    assert session.imm is None


def _frames(seed: int, fast: bool, replay: bool, monkeypatch) -> list:
    monkeypatch.setattr(_core, "FAST_CALLS", fast)
    monkeypatch.setattr(_core, "REPLAY_OBJECTS", replay)
    session.refresh()
    try:
        return render_frames(seed)
    finally:
        monkeypatch.setattr(_core, "FAST_CALLS", True)
        monkeypatch.setattr(_core, "REPLAY_OBJECTS", True)
        session.refresh()
        session.reset()


@pytest.mark.parametrize("seed", list(FRAME_SEEDS))
def test_replayed_objects_and_kept_records_give_identical_planes(seed, monkeypatch):
    """REPLAY_OBJECTS on, off (the FAST_CALLS paths alone) and every fast path off
    draw the same planes, frame by frame."""
    from vgxsim.gl import _objects
    from vgxsim.pipeline.records import StateTable

    used = {"replays": 0, "kept": 0}
    replay, adopt = _objects._replay, StateTable.adopt

    def counting_replay(ctx, dobj):
        done = replay(ctx, dobj)
        used["replays"] += done
        return done

    def counting_adopt(self, rec):
        used["kept"] += 1
        return adopt(self, rec)

    monkeypatch.setattr(_objects, "_replay", counting_replay)
    monkeypatch.setattr(StateTable, "adopt", counting_adopt)
    replayed = _frames(seed, True, True, monkeypatch)
    # Both kept paths ran (else the comparison below would test nothing of them).
    assert used["replays"] > 0 and used["kept"] > 0
    used["replays"] = used["kept"] = 0
    fast = _frames(seed, True, False, monkeypatch)
    assert used["replays"] == 0 and used["kept"] == 0  # the switch turns them off
    slow = _frames(seed, False, True, monkeypatch)
    assert used["replays"] == 0 and used["kept"] == 0  # (and so does FAST_CALLS)
    assert any(f["stencil"].any() and f["rgba"][..., :3].any() for f in replayed)
    for other in (fast, slow):
        for i, (a, b) in enumerate(zip(replayed, other, strict=True)):
            for k in a:
                assert np.array_equal(a[k], b[k]), (i, k)


@pytest.mark.parametrize("seed", list(FRAME_SEEDS)[:3])
def test_kept_clear_states_give_identical_planes(seed, monkeypatch):
    """The frames clear between passes (czclear, sclear): registers' kept clear
    state on and off draw the same planes."""
    from vgxsim.state import registers

    kept = _frames(seed, True, True, monkeypatch)
    monkeypatch.setattr(registers, "KEEP_CLEAR_STATE", False)
    fresh = _frames(seed, True, True, monkeypatch)
    for i, (a, b) in enumerate(zip(kept, fresh, strict=True)):
        for k in a:
            assert np.array_equal(a[k], b[k]), (i, k)


def test_the_kept_clear_state_follows_the_registers():
    from dataclasses import replace

    from vgxsim.state.registers import RasterRegisters

    regs = RasterRegisters(8, 8, False)
    first = regs.clear_state()
    assert regs.clear_state() is first  # the same snapshot: the same clear state
    regs.set(wmpack=0x00FF00FF, zwritemask=0)
    second = regs.clear_state()
    assert second is not first
    assert second == replace(regs.snapshot(), zbuffer=False, stencil=False, blend_sf=1,
                             blend_df=0, logicop=3, afunc=7, cull=0, texture=0)
    assert second.wmpack == 0x00FF00FF and second.zwritemask == 0 and not second.zbuffer
    regs.set(wmpack=0xFFFFFFFF, zwritemask=0xFFFFFFFF)
    assert regs.clear_state() is first  # the first registers again: their clear state


@pytest.mark.parametrize("seed", list(FRAME_SEEDS))
def test_replayed_parents_give_identical_planes(seed, monkeypatch):
    """_objects.REPLAY_PARENTS on and off draw the same planes frame by frame, and
    the parent's block is replayed (and made stale by the edits between frames)."""
    from vgxsim.gl import _objects

    used = {"replays": 0, "traces": 0}
    replay, trace = _objects._replay_parent, _objects._trace_parent

    def counting_replay(ctx, dobj):
        done = replay(ctx, dobj)
        used["replays"] += done
        return done

    def counting_trace(ctx, obj, dobj):
        used["traces"] += 1
        return trace(ctx, obj, dobj)

    # The streams decoded, too: a block appends what the walk appends, STATE and SYNC
    # ops included (so a state the block leaves wrong cannot hide behind equal pixels).
    from vgxsim.stream.recorder import CommandStream

    streams: list = []
    arrays = CommandStream.arrays

    def recording_arrays(self):
        out = arrays(self)
        streams.append((out[0].copy(), out[1].copy()))
        return out

    monkeypatch.setattr(_objects, "_replay_parent", counting_replay)
    monkeypatch.setattr(_objects, "_trace_parent", counting_trace)
    monkeypatch.setattr(CommandStream, "arrays", recording_arrays)
    replayed = _frames(seed, True, True, monkeypatch)
    assert used["replays"] > 0 and used["traces"] > 0
    replayed_streams, streams[:] = streams[:], []
    monkeypatch.setattr(_objects, "REPLAY_PARENTS", False)
    walked = _frames(seed, True, True, monkeypatch)
    for i, (a, b) in enumerate(zip(replayed, walked, strict=True)):
        for k in a:
            assert np.array_equal(a[k], b[k]), (i, k)
    assert len(replayed_streams) == len(streams)
    for (ops_a, fl_a), (ops_b, fl_b) in zip(replayed_streams, streams, strict=True):
        assert np.array_equal(ops_a, ops_b) and np.array_equal(fl_a, fl_b)


def test_the_int_payloads_are_the_decoders():
    from vgxsim.gl._objects import _INT_PAYLOAD
    from vgxsim.kernels.decode import _int_payload

    for op in range(16):
        assert _INT_PAYLOAD.get(op, 0) == _int_payload.py_func(op), op
