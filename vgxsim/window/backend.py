"""The window backend of ``vgxsim run --window``: SDL windows, input and menus.

:class:`WindowBackend` owns the SDL side of a run.  :meth:`WindowBackend.install` puts
it into the gl session through the seams a headless run uses -- the sink factory
(frames), the event queue (input) and the menu presenter (``dopup``) -- so a program
runs exactly as headless, and the run's recording (``--record``) and event script
(``--record-events``) are what a headless replay makes and reads.

Input semantics (IRIS GL, see :mod:`vgxsim.window.devices` for the device numbers):

* LEFTMOUSE, MIDDLEMOUSE, RIGHTMOUSE: SDL's buttons 1, 2, 3, each press and release;
  MOUSEX/MOUSEY: screen coordinates, origin at the lower left;
* key devices and KEYBD (the character typed), as :mod:`vgxsim.window.devices` maps;
* INPUTCHANGE: the gid of the window that gained the focus, 0 when the program's
  windows lost it (the first focus of a new window is the one ``winopen`` models);
* REDRAW: when SDL reports a window exposed again, and when the user resized it (a
  queue step like the events script's ``resize W H GID``: when the queue delivers it
  the window's planes take the new size and REDRAW is entered, so
  ``reshapeviewport`` and ``getsize`` see it; until then the screen keeps the
  user's size);
* closing a window: ``(WINQUIT, gid)`` if WINQUIT is queued, else ``(WINSHUT, gid)``
  if WINSHUT is, else the run ends (the workstation killed a program that did not
  queue them); the script gets a ``stop`` then.  ``winopen`` queues both (vgxsim's
  rule, :data:`vgxsim.events.queue.AUTO_QUEUED`), so a program that never reads them
  would keep its window for ever: closing the same window a second time ends the run.

Every step, a resize included, is written to the ``--record-events`` script as it is
delivered, so a headless replay resizes the window between the same frames.
"""

from __future__ import annotations

import time

import numpy as np

from vgxsim import DEVICE
from vgxsim.gl._core import window_of

from .devices import MOUSE_BUTTONS, key_device, screen_position
from .live import LiveEventQueue, LiveStep
from .menus import WindowMenuPresenter
from .screen import ScreenSink, ScreenWindow
from .script_writer import EventScriptWriter
from .sdl import pygame

__all__ = ["WindowBackend"]


def _dev(name: str) -> int:
    return int(getattr(DEVICE, name))


class WindowBackend:
    """SDL windows, input and menus for one run.

    Parameters
    ----------
    record_events : str or path-like, optional
        Write the session's input here as an events script.
    overwrite : bool
        Replace an existing ``record_events`` file.
    max_frames : int, optional
        End the run after this many frames (as headless).
    refresh_hz : float
        Most screen updates per second of a single-buffered window (its frames still
        all go to ``--record``).

    Attributes
    ----------
    queue : LiveEventQueue
    presenter : WindowMenuPresenter
    feeders : list of callable
        ``feeder(backend, where)`` is called each time SDL is looked at (``where`` is
        ``"pump"`` or ``"menu"``): tests and benchmarks post synthesized input there.
    present_times : dict of int to float
        Frame number (1 = first) -> ``time.perf_counter()`` when it was on the screen.
    deliveries : list of (float, int, float)
        For each delivered step that carried a ``posted`` time: (posted, frames drawn
        before it was delivered, ``time.perf_counter()`` at the delivery).
    """

    def __init__(self, record_events=None, overwrite: bool = False,
                 max_frames: int | None = None, refresh_hz: float = 60.0):
        pygame.display.init()
        self.recorder = (EventScriptWriter(record_events, overwrite)
                         if record_events is not None else None)
        self.queue = LiveEventQueue(self, max_frames=max_frames)
        self.presenter = WindowMenuPresenter(self)
        self.refresh_s = 1.0 / refresh_hz
        self.session = None
        self.frame_sinks = None
        self.check_stop = lambda: None
        self.feeders: list = []
        self.screens: dict[int, ScreenWindow] = {}
        self.present_times: dict[int, float] = {}
        self.deliveries: list[tuple[float, int, float]] = []
        self._by_window: dict[int, int] = {}
        self._seen_focus: set[int] = set()
        self._seen_expose: set[int] = set()
        self._asked_to_quit: set[int] = set()
        self._motion: tuple[int, int] | None = None
        self._motion_posted = 0.0
        self._last_motion: tuple[int, int] | None = None
        self._pointer: tuple[int | None, tuple[int, int]] = (None, (0, 0))
        self._held: set[int] = set()
        self._pending: dict[int, np.ndarray] = {}
        self.resizing: dict[int, tuple[int, int]] = {}  # gid -> user's size, undelivered
        self._reposted: list = []

    # -- installing -------------------------------------------------------------------
    def install(self, session, frame_sinks=None) -> None:
        """Become the session's queue, sink factory and menu presenter.

        Parameters
        ----------
        session : vgxsim.gl._core session
            After ``session.reset()``.
        frame_sinks : callable, optional
            ``frame_sinks(gid)`` -> the recording sink of window ``gid`` or None (the
            runner's :class:`~vgxsim.runner.FrameRecorder`).
        """
        from vgxsim.gl._menus import menu_state

        self.session = session
        self.frame_sinks = frame_sinks
        session.queue = self.queue
        session.sink_factory = self.sink_factory
        menu_state().presenter = self.presenter

    def sink_factory(self, gid: int) -> ScreenSink:
        """Open the SDL window of the IRIS window ``gid`` (called by ``winopen``)."""
        ctx = self.session.windows[gid]
        rec = window_of(ctx)
        placed = rec.origin if rec.origin != (0, 0) else None
        screen = ScreenWindow(gid, rec.title, (ctx.width, ctx.height), placed)
        self.screens[gid] = screen
        self._by_window[screen.window.id] = gid
        record = self.frame_sinks(gid) if self.frame_sinks is not None else None
        return ScreenSink(self, screen, record)

    # -- frames -----------------------------------------------------------------------
    def show(self, screen: ScreenWindow, image: np.ndarray) -> None:
        """A frame of window ``screen`` (from its sink): on the screen now, or, for a
        single-buffered window updated faster than ``refresh_hz``, at the next look
        at SDL."""
        ctx = self.session.windows.get(screen.gid) if self.session else None
        single = ctx is not None and not ctx.config.double
        if single and time.perf_counter() - screen.shown_at < self.refresh_s:
            self._pending[screen.gid] = image
            return
        self._pending.pop(screen.gid, None)
        title = window_of(ctx).title if ctx is not None else None
        t = screen.show(image, title, keep_size=screen.gid in self.resizing)
        self.present_times[self.queue.frame + 1] = t

    def _refresh(self) -> None:
        """Single-buffered windows show what they have drawn so far (bounded rate)."""
        now = time.perf_counter()
        for gid, screen in list(self.screens.items()):
            ctx = self.session.windows.get(gid)
            if ctx is None:
                screen.close()
                del self.screens[gid]
                continue
            if ctx.config.double or now - screen.shown_at < self.refresh_s:
                continue
            image = self._pending.pop(gid, None)
            screen.show(image if image is not None else ctx.display_rgba(), window_of(ctx).title)

    # -- input ------------------------------------------------------------------------
    def _gid(self, ev) -> int | None:
        win = getattr(ev, "window", None)
        if win is not None:
            return self._by_window.get(win.id)
        # synthesized or window-less events: the current window, else the first
        cur = self.session.current if self.session else None
        if cur in self.screens:
            return cur
        return next(iter(self.screens), None)

    def screen_of(self, ev) -> ScreenWindow | None:
        gid = self._gid(ev)
        return self.screens.get(gid) if gid is not None else None

    def _step(self, events, text: str, posted: float = 0.0) -> None:
        self.queue.source.append(LiveStep(events=tuple(events), text=text, posted=posted))

    def _flush_motion(self) -> None:
        if self._motion is not None and self._motion != self._last_motion:
            x, y = self._motion
            self.queue.source.append_motion(LiveStep(
                events=((_dev("MOUSEX"), x), (_dev("MOUSEY"), y)), text=f"move {x} {y}",
                posted=self._motion_posted))
            self._last_motion = self._motion
        self._motion = None

    def _move(self, ev, gid: int) -> None:
        ctx = self.session.windows.get(gid)
        if ctx is None:
            return
        self._pointer = (gid, tuple(ev.pos))
        x, y = screen_position(ev.pos, window_of(ctx).origin, ctx.height)
        if self._motion is None:
            self._motion_posted = getattr(ev, "posted", 0.0)
        self._motion = (x, y)

    def _convert(self, ev) -> None:
        """One SDL event to queue steps (see the module docstring)."""
        t = ev.type
        posted = getattr(ev, "posted", 0.0)
        gid = self._gid(ev)
        if t == pygame.MOUSEMOTION and gid is not None:
            self._move(ev, gid)
        elif t in (pygame.MOUSEBUTTONDOWN, pygame.MOUSEBUTTONUP) and ev.button in MOUSE_BUTTONS:
            if gid is not None:
                self._move(ev, gid)
            self._flush_motion()
            name = MOUSE_BUTTONS[ev.button]
            down = t == pygame.MOUSEBUTTONDOWN
            (self._held.add if down else self._held.discard)(ev.button)
            self._step(((_dev(name), int(down)),), f"{'press' if down else 'release'} {name}",
                       posted)
        elif t in (pygame.KEYDOWN, pygame.KEYUP):
            self._flush_motion()
            name = key_device(ev.key)
            down = t == pygame.KEYDOWN
            if name is not None:
                self._step(((_dev(name), int(down)),), f"{name} {int(down)}", posted)
            ch = getattr(ev, "unicode", "") if down else ""
            if len(ch) == 1 and ord(ch) < 256:
                self._step(((_dev("KEYBD"), ord(ch)),), f"KEYBD {ord(ch)}", posted)
        elif gid is None:
            return
        elif t == pygame.WINDOWFOCUSGAINED:
            if gid in self._seen_focus:  # the first one is winopen's INPUTCHANGE
                self._step(((_dev("INPUTCHANGE"), gid),), f"INPUTCHANGE {gid}", posted)
            self._seen_focus.add(gid)
        elif t == pygame.WINDOWFOCUSLOST:
            self._step(((_dev("INPUTCHANGE"), 0),), "INPUTCHANGE 0", posted)
        elif t == pygame.WINDOWEXPOSED:
            if gid in self._seen_expose:  # the first one is winopen's REDRAW
                self._step(((_dev("REDRAW"), gid),), f"REDRAW {gid}", posted)
            self._seen_expose.add(gid)
        elif t in (pygame.WINDOWRESIZED, pygame.WINDOWSIZECHANGED):
            self._resize(gid, int(ev.x), int(ev.y))
        elif t == pygame.WINDOWCLOSE:
            self._flush_motion()
            q = self.queue
            if gid not in self._asked_to_quit and q.isqueued(_dev("WINQUIT")):
                self._step(((_dev("WINQUIT"), gid),), f"WINQUIT {gid}", posted)
            elif gid not in self._asked_to_quit and q.isqueued(_dev("WINSHUT")):
                self._step(((_dev("WINSHUT"), gid),), f"WINSHUT {gid}", posted)
            else:
                q.source.append(LiveStep(stop=True, text="stop",
                                         where=f"window {gid} closed"))
            self._asked_to_quit.add(gid)

    def _resize(self, gid: int, w: int, h: int) -> None:
        """The user resized the window: a queue step that reshapes its planes and
        enters REDRAW when delivered (what a replay of the script does)."""
        ctx = self.session.windows.get(gid)
        if ctx is None:
            return
        if (w, h) == self.resizing.get(gid, (ctx.width, ctx.height)):
            return  # (SDL reports each size change twice; and our own frames' sizes)
        self.resizing[gid] = (w, h)
        self.queue.source.append(LiveStep(resize=(gid, w, h), text=f"resize {w} {h} {gid}"))

    def pump(self) -> None:
        """Look at SDL: feeders, closed windows, new input, single-buffered screens."""
        for feed in list(self.feeders):
            feed(self, "pump")
        events = self._reposted + pygame.event.get()
        self._reposted = []
        for ev in events:
            self._convert(ev)
        self._flush_motion()
        self._refresh()

    def wait(self) -> None:
        """Wait up to 16 ms for SDL input (a blocking qread with nothing to deliver)."""
        ev = pygame.event.wait(16)
        if ev.type != pygame.NOEVENT:
            self._convert(ev)
        self.check_stop()

    def delivered(self, step) -> None:
        """The queue delivered ``step``: write it to the script, note its latency."""
        if step.resize is not None and self.resizing.get(step.resize[0]) == step.resize[1:]:
            del self.resizing[step.resize[0]]
        if self.recorder is not None and getattr(step, "text", ""):
            self.recorder.statement(self.queue.frame, step.text)
        if getattr(step, "posted", 0.0):
            self.deliveries.append((step.posted, self.queue.frame, time.perf_counter()))

    # -- menus ------------------------------------------------------------------------
    def pointer_screen(self) -> ScreenWindow | None:
        gid = self._pointer[0]
        if gid not in self.screens:
            gid = self.session.current if self.session.current in self.screens else None
        return self.screens.get(gid) if gid is not None else None

    def pointer_position(self, screen: ScreenWindow) -> tuple[int, int]:
        """The pointer in ``screen``'s SDL coordinates (its last known position)."""
        gid, pos = self._pointer
        if gid == screen.gid:
            return pos
        return (screen.size[0] // 2, screen.size[1] // 2)

    def mouse_held(self) -> bool:
        """A mouse button is down (as SDL reported it)."""
        return bool(self._held)

    def menu_events(self) -> list:
        """SDL events while a menu is up (waits up to 16 ms for one)."""
        for feed in list(self.feeders):
            feed(self, "menu")
        events = pygame.event.get()
        if not events:
            ev = pygame.event.wait(16)
            events = [] if ev.type == pygame.NOEVENT else [ev]
        self.check_stop()
        return events

    def repost(self, ev) -> None:
        """Keep an SDL event for the queue's next look (one the menu must not eat)."""
        self._reposted.append(ev)

    def menu_closed(self, screen: ScreenWindow, pointer, released, path) -> None:
        """After a menu: write the choice, hand the consumed input to the queue."""
        if self.recorder is not None:
            choice = " ".join(str(n) for n in path) if path else "0"
            self.recorder.statement(self.queue.frame, f"menu {choice}")
        ctx = self.session.windows.get(screen.gid)
        if ctx is not None and pointer[0] >= 0:
            self._pointer = (screen.gid, tuple(pointer))
            x, y = screen_position(pointer, window_of(ctx).origin, ctx.height)
            self._motion = (x, y)
        for ev in released:
            self._convert(ev)
        self._flush_motion()

    # -- the end ----------------------------------------------------------------------
    def latencies(self) -> list[float]:
        """Seconds from each posted input to the screen showing the frame drawn after
        it was delivered."""
        return [wait + show for wait, show in self.latency_parts()]

    def latency_parts(self) -> list[tuple[float, float]]:
        """Each latency of :meth:`latencies` in two parts, seconds: from the post to
        the queue's delivery (waiting for the program's next look at its input), and
        from the delivery to the screen (drawing the frame, swapbuffers, the blit)."""
        out = []
        for posted, frame, at in self.deliveries:
            t = self.present_times.get(frame + 1)
            if t is not None:
                out.append((at - posted, t - at))
        return out

    def close(self) -> None:
        """Close every window and the events script."""
        for screen in self.screens.values():
            screen.close()
        self.screens.clear()
        if self.recorder is not None:
            self.recorder.close()
        pygame.display.quit()
