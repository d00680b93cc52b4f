"""SDL input arrives as IRIS devices: buttons, keys and KEYBD, screen coordinates with
the origin lower left, INPUTCHANGE, REDRAW with the new size, WINQUIT on close."""

from __future__ import annotations

import os
import subprocess
import sys
import textwrap

from window_helpers import key, motion, press, release

from vgxsim.runner import run_program

ECHO = textwrap.dedent("""
    import sys
    from gl import *
    from DEVICE import *
    prefposition(100, 163, 200, 247)     # 64 x 48, lower-left corner at (100, 200)
    gid = winopen("echo")
    for dev in (LEFTMOUSE, AKEY, F1KEY, UPARROWKEY, KEYBD, MOUSEX, MOUSEY, INPUTCHANGE):
        qdevice(dev)
    while True:
        dev, val = qread()
        if dev == REDRAW:
            reshapeviewport()
            print("REDRAW", val, getsize(), getviewport())
        elif dev == WINQUIT:
            print("WINQUIT", val)
            sys.exit(3)
        elif dev in (MOUSEX, MOUSEY):
            print(dev, val, getvaluator(MOUSEX), getvaluator(MOUSEY))
        else:
            print(dev, val, getbutton(LEFTMOUSE))
""")


def _close(backend):
    import pygame

    return [(pygame.WINDOWCLOSE, dict(window=backend.screens[1].window))]


def _run(tmp_path, backend_factory, capsys, plan):
    prog = tmp_path / "echo.py"
    prog.write_text(ECHO)
    status = run_program(prog, window=backend_factory(plan), timeout=60)
    return status, capsys.readouterr().out.splitlines()


def test_mouse_keys_and_close(tmp_path, backend_factory, capsys):
    import pygame

    plan = [(0, [motion((10, 5)), press(1, (10, 5)), release(1, (10, 5)),
                 key(pygame.K_a, "a"), key(pygame.K_a, down=False), key(pygame.K_F1),
                 key(pygame.K_UP)]),
            (0, _close)]
    status, lines = _run(tmp_path, backend_factory, capsys, plan)
    assert status == 3
    x, y = 100 + 10, 200 + (48 - 1 - 5)  # SDL row 5 from the top of a 48-row window
    assert lines[0] == "REDRAW 1 (64, 48) (0, 63, 0, 47)"
    assert lines[1:] == [
        "534 1 0",                   # INPUTCHANGE: the new window has the focus
        f"266 {x} {x} {y}", f"267 {y} {x} {y}",
        "103 1 1", "103 0 0",        # LEFTMOUSE press and release, getbutton agrees
        "11 1 0", "513 97 0", "11 0 0",  # AKEY down, KEYBD 'a', AKEY up
        "146 1 0", "81 1 0",         # F1KEY, UPARROWKEY
        "WINQUIT 1",
    ]


def test_resize_and_expose_enter_redraw(tmp_path, backend_factory, capsys):
    import pygame

    def resize(backend):
        win = backend.screens[1].window
        return [(pygame.WINDOWSIZECHANGED, dict(x=80, y=30, window=win)),
                (pygame.WINDOWEXPOSED, dict(window=win)),
                (pygame.WINDOWEXPOSED, dict(window=win))]

    plan = [(0, resize), (0, _close)]
    status, lines = _run(tmp_path, backend_factory, capsys, plan)
    assert status == 3
    redraws = [ln for ln in lines if ln.startswith("REDRAW")]
    # winopen's REDRAW (already queued, read before the resize is delivered: the old
    # size), the resize's and the second expose's (the first expose of a new window is
    # winopen's); the resize is a queue step, delivered in order as a replay would
    assert redraws == ["REDRAW 1 (64, 48) (0, 63, 0, 47)",
                       "REDRAW 1 (80, 30) (0, 79, 0, 29)", "REDRAW 1 (80, 30) (0, 79, 0, 29)"]


def test_closing_twice_ends_a_program_that_ignores_winquit(tmp_path, backend_factory,
                                                           capsys):
    prog = tmp_path / "ignore.py"
    prog.write_text("from gl import *\nwinopen('x')\nwhile True:\n    qread()\n")
    backend = backend_factory([(0, _close), (0, _close)])
    assert run_program(prog, window=backend, timeout=60) == 0


def test_headless_runs_never_import_pygame(tmp_path):
    prog = tmp_path / "draw.py"
    prog.write_text("from gl import *\nwinopen('x')\nRGBmode()\ngconfig()\nclear()\n"
                    "swapbuffers()\n")
    code = textwrap.dedent(f"""
        import sys
        import vgxsim, vgxsim.gl, vgxsim.window, vgxsim.shadow.interactive
        from vgxsim.runner import run_program
        assert run_program({str(prog)!r}, frames={str(tmp_path / 'out')!r}) == 0
        assert "pygame" not in sys.modules, "a headless run imported pygame"
        print("ok")
    """)
    env = {k: v for k, v in os.environ.items() if k != "SDL_VIDEODRIVER"}
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         env=env, timeout=600)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == "ok"


def test_undelivered_motion_is_replaced_by_newer_motion():
    from vgxsim.window.live import LiveSource, LiveStep

    src = LiveSource(backend=None)
    src.append(LiveStep(events=((103, 1),), text="press LEFTMOUSE", posted=1.0))
    for k, (x, posted) in enumerate(((10, 2.0), (11, 3.0), (12, 0.0))):
        src.append_motion(LiveStep(events=((266, x), (267, 5)), text=f"move {x} 5",
                                   posted=posted))
        assert len(src) == 2, k  # the press, then one move: the newest position
    press, move = list(src)
    assert press.text == "press LEFTMOUSE"
    # the newest position, timed from the oldest input it stands for
    assert (move.text, move.events, move.posted) == ("move 12 5", ((266, 12), (267, 5)), 2.0)
    src.append(LiveStep(events=((103, 0),), text="release LEFTMOUSE"))
    src.append_motion(LiveStep(events=((266, 20), (267, 5)), text="move 20 5"))
    assert [s.text for s in src] == ["press LEFTMOUSE", "move 12 5", "release LEFTMOUSE",
                                     "move 20 5"]  # motion after a button stays after it


def test_a_resize_of_a_window_closed_meanwhile_is_dropped_unrecorded():
    from types import SimpleNamespace

    from vgxsim.window.live import LiveSource, LiveStep

    delivered = []
    backend = SimpleNamespace(session=SimpleNamespace(windows={1: object()}),
                              delivered=delivered.append)
    src = LiveSource(backend)
    src.append(LiveStep(resize=(1, 80, 30), text="resize 80 30 1"))
    src.append(LiveStep(resize=(2, 50, 40), text="resize 50 40 2"))  # window 2 is gone
    first, second = src.pop(), src.pop()
    assert (first.resize, first.text) == ((1, 80, 30), "resize 80 30 1")
    assert (second.resize, second.text) == (None, "")
    assert delivered == [first, second]
