"""The interactive shadows program headless, from events scripts: continued spin and
soft shadows that show their intermediate images."""

from __future__ import annotations

import math
import os
import re

import numpy as np
import pytest

from vgxsim.runner import run_program
from vgxsim.shadow import api
from vgxsim.shadow.trackball import trackball
from vgxsim.sinks import MemorySink

PROGRAM = os.path.join(os.path.dirname(__file__), os.pardir, os.pardir, "vgxsim",
                       "examples", "shadows_interactive.py")
W, H = 64, 48


def _quaternion(out: str) -> np.ndarray:
    m = re.search(r"quaternion \(([^)]*)\)", out)
    return np.array([float(v) for v in m.group(1).split(",")])


def test_release_while_moving_keeps_the_scene_spinning(tmp_path, capsys):
    script = tmp_path / "spin.events"
    # the move is drawn in frame 3; the release comes at the end of that frame, so the
    # scene spins by the same rotation every frame until ESC after frame 9
    script.write_text("move 32 24\npress MIDDLEMOUSE\nafter 2 move 36 25\n"
                      "after 3 release MIDDLEMOUSE\nafter 9 key ESC\n")
    frames = MemorySink()
    assert run_program(PROGRAM, events=script, frames=frames, size=(W, H)) == 0
    q = _quaternion(capsys.readouterr().out)
    step = trackball((2 * 32 - W) / W, (2 * 24 - H) / H, (2 * 36 - W) / W, (2 * 25 - H) / H)
    turns = 2 * math.acos(q[3]) / (2 * math.acos(step[3]))
    # one rotation by the drag, then one per frame after it while spinning
    assert turns == pytest.approx(round(turns), abs=1e-6) and round(turns) >= 5
    np.testing.assert_allclose(q[:3] / np.linalg.norm(q[:3]),
                               np.array(step[:3]) / np.linalg.norm(step[:3]), atol=1e-9)
    assert len(frames) >= 9 and not np.array_equal(frames[-1], frames[-2])


def test_soft_shadows_show_each_running_average_and_end_at_the_library_render(
        tmp_path, capsys):
    script = tmp_path / "soft.events"
    script.write_text("after 20 key ESC\n")
    frames = MemorySink()
    args = ["--mode", "shadows", "--soft", "--soft-max", "4"]
    assert run_program(PROGRAM, args, events=script, frames=frames, size=(W, H)) == 0
    assert len(frames) == 4  # one image a frame, then the program waits for input
    expected = api.render(None, mode="shadows", size=(W, H), soft=4, seed=1991)
    np.testing.assert_array_equal(frames[-1][..., :3], expected.colour[..., :3])
    assert not np.array_equal(frames[0], frames[-1])  # the first average: one image
