"""The event queue of a window session: a script written as the user acts.

SDL input becomes :class:`LiveStep` s appended to the queue's source (an
:class:`~vgxsim.events.EventSource`), and the inherited
:class:`~vgxsim.events.EventQueue` delivers them by the rules of a headless run: at
``swapbuffers`` (one step), at ``qtest`` on an empty queue (one step), and in a
blocking ``qread`` (until an entry is queued).  ``qdevice``, ``tie``, ``noise``,
``getbutton`` and ``getvaluator`` are the headless ones, untouched.  Each delivered
step is written to the ``--record-events`` script at the frame it was delivered, so
the replay delivers it in the same frame.

Pointer motion is coalesced: all motion between two looks at SDL becomes one ``move
X Y`` step (MOUSEX then MOUSEY), and a ``move`` still waiting at the end of the queue's
source when more motion comes is replaced by the newer position (keeping the older
post time), so a fast drag cannot queue up steps faster than a program that reads one
a frame takes them, and the program never draws a position older than the newest it
was sent (latency: no frame drawn for input already superseded).  A blocking
``qread`` with nothing to deliver waits for SDL (16 ms at a time, showing
single-buffered windows and letting SIGINT/SIGTERM/--timeout end the run); with a
timer device queued it adds a ``tick`` step every 1/60 s, the workstation's timer
rate.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, replace

from vgxsim.events import EventQueue, EventSource, Step
from vgxsim.events._devices import TIMERS as D_TIMERS

__all__ = ["LiveStep", "LiveSource", "LiveEventQueue"]

TIMER_PERIOD_S = 1.0 / 60.0


@dataclass(frozen=True)
class LiveStep(Step):
    """A step made from SDL input.

    Parameters
    ----------
    text : str
        The statement that makes the same events in an events script.
    posted : float
        ``time.perf_counter()`` when the input was posted, if known (for latency).
    """

    text: str = ""
    posted: float = 0.0


class LiveSource(EventSource):
    """The live queue's source: records each step as it is delivered."""

    def __init__(self, backend):
        super().__init__()
        self.backend = backend

    def pop(self) -> Step:
        step = super().pop()
        if step.resize is not None and step.resize[0] not in self.backend.session.windows:
            # the user resized a window the program has closed since: nothing to do,
            # and nothing to record (a replay would find no such window)
            step = replace(step, resize=None, text="")
        self.backend.delivered(step)
        return step

    def append_motion(self, step: LiveStep) -> None:
        """Append a ``move`` step, or let it replace an undelivered ``move`` at the
        end (keeping that one's post time: the latency counts from the older input)."""
        last = self._steps[-1] if self._steps else None
        if isinstance(last, LiveStep) and last.text.startswith("move "):
            self._steps[-1] = replace(step, posted=last.posted or step.posted)
        else:
            self._steps.append(step)


class LiveEventQueue(EventQueue):
    """:class:`~vgxsim.events.EventQueue` fed by a window backend's SDL input.

    Parameters
    ----------
    backend : WindowBackend
    max_frames : int, optional
        As for :class:`~vgxsim.events.EventQueue`.
    """

    def __init__(self, backend, max_frames: int | None = None):
        super().__init__(LiveSource(backend), max_frames=max_frames)
        self.backend = backend

    def frame_done(self) -> None:
        self.backend.pump()
        super().frame_done()

    def qtest(self) -> int:
        self.backend.pump()
        return super().qtest()

    def getbutton(self, dev: int) -> int:
        self.backend.pump()
        return super().getbutton(dev)

    def getvaluator(self, dev: int) -> int:
        self.backend.pump()
        return super().getvaluator(dev)

    def qread(self) -> tuple[int, int]:
        """Block until an entry is queued: deliver steps as a headless run would, wait
        for SDL input when there are none."""
        last_tick = time.perf_counter()
        while True:
            self.backend.pump()
            if len(self):
                return super().qread()
            if self.source.peek() is not None:
                super().qtest()  # delivers one due step, as a headless qread does
                continue
            self.backend.wait()
            if any(self.isqueued(t) for t in D_TIMERS):
                now = time.perf_counter()
                n = int((now - last_tick) / TIMER_PERIOD_S)
                if n:
                    last_tick += n * TIMER_PERIOD_S
                    self.source.append(LiveStep(ticks=n, text=f"tick {n}"))
