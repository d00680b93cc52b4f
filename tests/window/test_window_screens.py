"""What the SDL windows show: several IRIS windows at once, each its own front buffer;
a single-buffered window shows what it draws before any gflush."""

from __future__ import annotations

import textwrap

from vgxsim.runner import run_program

TWO = textwrap.dedent("""
    from gl import *
    prefsize(40, 30); a = winopen("red")
    RGBmode(); doublebuffer(); gconfig()
    prefsize(24, 16); b = winopen("blue")
    RGBmode(); doublebuffer(); gconfig()
    winset(a); cpack(0x000000ff); clear(); swapbuffers()
    winset(b); cpack(0x00ff0000); clear(); swapbuffers()
    winset(a); cpack(0x0000ff00); clear()   # drawn to the back buffer: not shown yet
    qtest()
""")

SINGLE = textwrap.dedent("""
    from gl import *
    prefsize(32, 32); winopen("single")
    RGBmode(); gconfig()
    cpack(0x00ffffff); clear()
    cpack(0x000000ff); rectf(0, 0, 15, 15)   # lower-left quarter, no gflush
    import time
    time.sleep(0.05)
    qtest()                                   # the backend looks at SDL here
    time.sleep(0.05)
    qtest()
""")


def _pixel(screen, x, y):
    return tuple(screen.window.get_surface().get_at((x, y)))[:3]


def test_each_window_shows_its_own_front_buffer(tmp_path, backend_factory):
    prog = tmp_path / "two.py"
    prog.write_text(TWO)
    seen = {}

    def look(backend, where):
        if backend.queue.frame >= 2 and len(backend.screens) == 2:
            seen.update({g: (s.size, _pixel(s, 1, 1)) for g, s in backend.screens.items()})

    backend = backend_factory([])
    backend.feeders.append(look)
    assert run_program(prog, window=backend, timeout=60) == 0
    assert seen == {1: ((40, 30), (255, 0, 0)), 2: ((24, 16), (0, 0, 255))}


def test_single_buffered_drawing_is_shown_without_gflush(tmp_path, backend_factory):
    prog = tmp_path / "single.py"
    prog.write_text(SINGLE)
    seen = []

    def look(backend, where):
        if backend.screens:
            s = backend.screens[1]
            if s.top_down is not None:
                # SDL rows run top down: the IRIS lower-left quarter is rows 16..31
                seen.append((_pixel(s, 2, 29), _pixel(s, 29, 2)))

    backend = backend_factory([])
    backend.feeders.append(look)
    assert run_program(prog, window=backend, timeout=60) == 0
    assert ((255, 0, 0), (255, 255, 255)) in seen
