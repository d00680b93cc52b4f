"""The interactive shadows program in a window: a middle-button drag turns the scene by
the trackball rotation of the drag, and a recorded session replays headless to the
same frames."""

from __future__ import annotations

import math
import os
import re

import numpy as np
from window_helpers import key, motion, press, release

from vgxsim.runner import run_program
from vgxsim.sinks import MemorySink

PROGRAM = os.path.join(os.path.dirname(__file__), os.pardir, os.pardir, "vgxsim",
                       "examples", "shadows_interactive.py")
W, H = 96, 80


def _quaternion(out: str) -> np.ndarray:
    m = re.search(r"quaternion \(([^)]*)\)", out)
    return np.array([float(v) for v in m.group(1).split(",")])


def _unit(px, py):
    """SDL window pixel -> the trackball's [-1, 1] coordinates, y up: the IRIS screen
    y of SDL row py is H - 1 - py (origin lower left)."""
    sx, sy = px, H - 1 - py
    return (2.0 * sx - W) / W, (2.0 * sy - H) / H


def test_middle_drag_turns_the_scene_by_the_drag(backend_factory, capsys):
    import pygame

    a, b = (48, 40), (55, 36)  # both well inside the sphere part of the trackball
    plan = [(0, [motion(a), press(2, a)]), (1, [motion(b)]), (2, [release(2, b)]),
            (1, [key(pygame.K_ESCAPE, "\x1b")])]
    backend = backend_factory(plan)
    assert run_program(PROGRAM, window=backend, size=(W, H), timeout=120) == 0
    q = _quaternion(capsys.readouterr().out)
    # expected: the rotation taking sphere point p1 to p2 (axis p1 x p2, their angle)
    r = 0.8
    p1, p2 = (np.array([x, y, math.sqrt(r * r - x * x - y * y)])
              for x, y in (_unit(*a), _unit(*b)))
    axis = np.cross(p1, p2)
    axis /= np.linalg.norm(axis)
    angle = math.acos(np.dot(p1, p2) / (r * r))
    expected = np.array([*(axis * math.sin(angle / 2)), math.cos(angle / 2)])
    np.testing.assert_allclose(q, expected, atol=2e-9)


def test_recorded_session_replays_headless_to_the_same_frames(tmp_path, backend_factory,
                                                             capsys):
    import pygame

    events = tmp_path / "session.events"
    live = MemorySink()
    a, b, c = (40, 40), (52, 34), (60, 30)
    plan = [(0, [motion(a), press(2, a)]), (1, [motion(b)]), (1, [motion(c)]),
            (0, [release(2, c)]),  # released while moving: the scene spins on
            (2, [motion((30, 30)), press(1, (30, 30))]), (1, [motion((36, 26))]),
            (1, [release(1, (36, 26))]),
            (1, [press(3, (20, 20))]),
            ("menu", lambda bk: [motion(bk.presenter.panels[0].entry_rect(4).center),
                                 release(3, bk.presenter.panels[0].entry_rect(4).center)]),
            (1, [key(pygame.K_ESCAPE, "\x1b")])]
    backend = backend_factory(plan, record_events=events)
    assert run_program(PROGRAM, window=backend, frames=live, size=(W, H), timeout=120) == 0
    live_out = capsys.readouterr().out
    text = events.read_text()
    assert "menu 4" in text and "press MIDDLEMOUSE" in text

    replay = MemorySink()
    assert run_program(PROGRAM, events=events, frames=replay, size=(W, H)) == 0
    assert capsys.readouterr().out == live_out
    assert len(live) == len(replay) > 5
    for k, (x, y) in enumerate(zip(live, replay, strict=True)):
        assert np.array_equal(x, y), f"frame {k} differs"
    # the menu chose "Show Shadows": the last frames differ from the objects-only ones
    assert not np.array_equal(live[-1], live[1])


def test_a_recorded_resize_replays_headless_to_the_same_frames(tmp_path, backend_factory,
                                                               capsys):
    import pygame

    def resize(backend):
        win = backend.screens[1].window
        return [(pygame.WINDOWSIZECHANGED, dict(x=120, y=70, window=win)),
                (pygame.WINDOWEXPOSED, dict(window=win))]

    events = tmp_path / "resized.events"
    live = MemorySink()
    a, b = (40, 40), (52, 34)
    plan = [(1, resize), (1, [motion(a), press(2, a)]), (1, [motion(b)]),
            (0, [release(2, b)]), (2, [key(pygame.K_ESCAPE, "\x1b")])]
    backend = backend_factory(plan, record_events=events)
    assert run_program(PROGRAM, window=backend, frames=live, size=(W, H), timeout=120) == 0
    live_out = capsys.readouterr().out
    assert "resize 120 70 1" in events.read_text()

    replay = MemorySink()
    assert run_program(PROGRAM, events=events, frames=replay, size=(W, H)) == 0
    assert capsys.readouterr().out == live_out
    assert len(live) == len(replay) > 4
    for k, (x, y) in enumerate(zip(live, replay, strict=True)):
        assert np.array_equal(x, y), f"frame {k} differs"
    # the program redrew at the new size: its viewport and projection followed REDRAW
    assert live[0].shape == (H, W, 4) and live[-1].shape == (70, 120, 4)
    last = np.asarray(live[-1])
    assert last[:, :, :3].any(axis=(0, 2)).all()  # the scene spans the new width
