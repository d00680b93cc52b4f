"""Real windows for IRIS GL programs: ``vgxsim run PROGRAM.py --window``.

Optional (``pip install vgxsim[window]``: pygame-ce, SDL2).  Nothing here imports
pygame until a :class:`~vgxsim.window.backend.WindowBackend` is made, so ``import
vgxsim`` and every headless run stay free of it.

The backend plugs into the two seams a headless run already has:

* frames: each window's sink (``session.sink_factory``) is a
  :class:`~vgxsim.window.screen.ScreenSink` that blits the frame into an SDL window
  (and passes it on to the ``--record`` sink, so the recording holds exactly the
  frames a headless run makes);
* input: the session's queue is a :class:`~vgxsim.window.live.LiveEventQueue`, an
  :class:`~vgxsim.events.EventQueue` whose script is written as the user acts.  SDL
  events become script steps (:mod:`vgxsim.window.devices`) that the queue delivers by
  the headless rules, so ``--record-events`` writes a script that replays the session
  headless to the same frames;
* menus: ``dopup`` asks a :class:`~vgxsim.window.menus.WindowMenuPresenter`, which
  draws the menu under the pointer (the PUPDRAW planes' look) and answers with the path
  the headless model (:meth:`vgxsim.gl._menus.PopupMenu.choose`) turns into the value.

Why SDL2 through pygame (measured on the development machine, SDL dummy video
driver, 640x512): a frame goes to the screen in about 0.7 ms (one row flip of the
RGBA image and one 32-bit blit, ``RGBX`` so no alpha blending) and SDL delivers input
in the same thread, so no lock or second event loop sits between the user and the
IRIS queue; pygame-ce ships binary wheels with SDL2 inside for Linux, macOS and Windows
(no system libraries; 35 MB installed) and runs under ``SDL_VIDEODRIVER=dummy`` with
synthesized input (``pygame.event.post``) for tests.  Qt (PySide6) would bring a far
larger dependency and its own event loop, which the IRIS programs' own ``qread``
loops would have to be threaded around or re-entered.
"""

from __future__ import annotations

__all__ = ["WindowBackend", "available"]


def available() -> str | None:
    """None when the window backend can run, else the reason it cannot."""
    import importlib.util

    if importlib.util.find_spec("pygame") is None:
        return ("the window backend needs pygame-ce (SDL2): pip install 'vgxsim[window]' "
                "(or pip install pygame-ce)")
    return None


def __getattr__(name: str):
    if name == "WindowBackend":
        from vgxsim.window.backend import WindowBackend

        return WindowBackend
    raise AttributeError(name)
