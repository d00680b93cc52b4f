"""dopup in a window: a click on a drawn entry returns that entry's value."""

from __future__ import annotations

import textwrap

import pytest
from window_helpers import motion, press, release

from vgxsim.runner import run_program

PROGRAM = textwrap.dedent("""
    from gl import *
    from DEVICE import *
    prefsize(200, 160)
    winopen("menus")
    RGBmode(); gconfig(); cpack(0x00336699); clear(); gflush()
    sub = defpup("more %t|deep %x7")
    menu = defpup("pick %t|alpha %x10|beta %x20|gamma %x30%l|off %x40|nested %m", sub)
    setpup(menu, 4, PUP_GREY)
    qdevice(MENUBUTTON)
    while True:
        dev, val = qread()
        if dev == WINQUIT:
            break
        if dev == MENUBUTTON and val:
            print("chose", dopup(menu), flush=True)
""")


def _entry(n, depth=0):
    def aim(backend):
        pos = backend.presenter.panels[depth].entry_rect(n).center
        return [motion(pos), release(3, pos)]
    return aim


def _run(tmp_path, backend_factory, capsys, plan, **kw):
    prog = tmp_path / "menus.py"
    prog.write_text(PROGRAM)
    b = backend_factory(plan, **kw)
    status = run_program(prog, window=b, timeout=60)
    return status, capsys.readouterr().out, b


def _close(backend):
    import pygame
    return [(pygame.WINDOWCLOSE, dict(window=backend.screens[1].window))]


@pytest.mark.parametrize("entry, value", [(1, 10), (2, 20), (3, 30), (4, -1)])
def test_release_on_an_entry_returns_its_value(tmp_path, backend_factory, capsys, entry,
                                               value):
    plan = [(0, [motion((60, 50)), press(3, (60, 50))]), ("menu", _entry(entry)),
            (0, _close)]
    status, out, _ = _run(tmp_path, backend_factory, capsys, plan)
    assert status == 0
    assert f"chose {value}\n" in out  # entry 4 is greyed: -1, as dopup(3G) says


def test_submenu_entry_and_release_outside(tmp_path, backend_factory, capsys):
    def into_sub(backend):
        # hover "nested" (opens the submenu), then release on its first entry
        import pygame
        pos = backend.presenter.panels[0].entry_rect(5).center
        pygame.event.post(pygame.event.Event(pygame.MOUSEMOTION, pos=pos, rel=(0, 0),
                                             buttons=(0, 0, 0)))
        return []

    plan = [(0, [motion((20, 20)), press(3, (20, 20))]), ("menu", into_sub),
            ("menu", _entry(1, depth=1)),
            (0, [press(3, (30, 30))]), ("menu", [motion((199, 159)), release(3, (199, 159))]),
            (0, _close)]
    status, out, _ = _run(tmp_path, backend_factory, capsys, plan)
    assert status == 0
    assert out.splitlines() == ["chose 7", "chose -1"]


def test_click_mode_menu_and_recorded_choice_replays(tmp_path, backend_factory, capsys):
    """A menu opened after the button came up waits for a click; the recorded script
    answers the same dopup headless with the same value."""
    rec = tmp_path / "session.events"
    plan = [(0, [motion((60, 50)), press(3, (60, 50)), release(3, (60, 50))]),
            ("menu", lambda b: [press(1, b.presenter.panels[0].entry_rect(2).center)]),
            ("menu", lambda b: [release(1, b.presenter.panels[0].entry_rect(2).center)]),
            (0, _close)]
    status, out, _ = _run(tmp_path, backend_factory, capsys, plan, record_events=rec)
    assert status == 0 and out == "chose 20\n"
    assert "menu 2" in rec.read_text()
    prog = tmp_path / "menus.py"
    assert run_program(prog, events=rec) == 0
    assert capsys.readouterr().out == "chose 20\n"
