"""IRIS GL's event queue, fed by a scripted input source instead of hardware.

The model
---------
IRIS GL keeps one input queue per process.  A device only makes queue entries
after ``qdevice(dev)``; input on other devices still changes the device state
that ``getbutton``/``getvaluator`` report.  :class:`EventQueue` models that:

* **Queued devices.**  ``qdevice``/``unqdevice``/``isqueued`` keep the set.
  :meth:`EventQueue.window_opened` (called by ``winopen``) queues
  :data:`AUTO_QUEUED` -- REDRAW, INPUTCHANGE, WINQUIT, WINSHUT and DEPTHCHANGE,
  the devices the window manager reports without being asked (mclock calls
  ``unqdevice(INPUTCHANGE)`` for that reason) -- and enters ``(REDRAW, gid)``,
  the implicit first redraw.
* **Input** comes from an :class:`EventSource`: a list of :class:`Step` objects,
  usually parsed from a text script by :mod:`vgxsim.events.script`.  Each step
  is one or more raw ``(device, value)`` input events, timer ticks, or a stop.
  :meth:`EventQueue.post` applies one raw event exactly as hardware input would:

  - *buttons* (device numbers 1-255 and the BUT2/user button ranges) set the
    state read by ``getbutton`` (1 for a non-zero value); a queued button makes
    an entry, followed by the current values of the valuators tied to it
    with ``tie`` (made whether or not those valuators are queued);
  - *valuators* (256-511 and the user valuator range) set the value read by
    ``getvaluator``; a queued valuator makes an entry only once its value has
    moved by at least its ``noise`` delta (default 1) from the value last
    entered, as IRIS GL's ``noise`` man page describes -- so repeating the
    current value makes no entry;
  - anything else (KEYBD, REDRAW, WINQUIT, TIMERn, ...) makes an entry if the
    device is queued; no state is kept for it.

  A step may also reshape a window (a script's ``resize``): the window's planes
  take the new size and ``(REDRAW, gid)`` is entered, through the hook
  :attr:`EventQueue.window_resizer` the gl layer installs.

  ``qenter(dev, val)`` bypasses all of this: the entry is made whatever the
  device, and no state changes.  Queue values are C shorts (``qread`` returns
  ``short *val``), so they wrap to -32768..32767.
* **Frames and time.**  ``swapbuffers`` calls :meth:`EventQueue.frame_done`,
  which counts a frame, ticks the timers once and delivers at most one due
  script step.  A step is *due* once the frame count reaches its ``after``
  value and ``wait`` frames have passed since the previous step was delivered.
* **Timers.**  TIMER0..TIMER3 tick once per frame (and see blocking reads
  below).  A queued timer makes an entry ``(TIMERn, 0)`` every ``n``-th tick,
  ``n`` being its ``noise`` value (default 1): ``noise(TIMER0, 60)`` gives one
  entry per 60 frames.  Many ticks at once (a script's ``tick N``) are counted in one
  step, not one by one, and make at most :data:`MAX_TIMER_BACKLOG` (256) entries per
  timer: vgxsim's choice -- the workstation's queue was a small fixed FIFO, so a
  program that read nothing while a timer came due a million times never saw a
  million entries -- which keeps ``tick 1000000000`` instant.
* **Reads.**  ``qtest()`` on an empty queue delivers at most one due step, then
  returns the device at the head (0 if none).  ``qread()`` blocks: while the
  queue is empty it delivers due steps; if the next step is not yet due, time
  passes as it would for a waiting program -- queued timers tick (idle ticks,
  at most ``max_idle_ticks`` since the last frame) so a timer-driven program
  such as mclock keeps drawing frames; with no queued timer (or past that
  limit) nothing could change, so the rest of the delay is skipped and the
  next step is delivered at once.
* **The end.**  When ``qread()`` finds the queue empty and the script used up,
  it raises :class:`ScriptExhausted`.  Queued timers do not keep a run alive.
  A script ``stop`` step, and ``max_frames`` frames, raise it too.
"""

from __future__ import annotations

import operator
from collections import deque
from collections.abc import Iterable, Iterator
from dataclasses import dataclass
from os import PathLike

from vgxsim.events import _devices as D

#: Most ``(TIMERn, 0)`` entries one :meth:`EventQueue.tick` call makes per timer.
MAX_TIMER_BACKLOG = 256

#: Devices that ``winopen`` queues without a ``qdevice`` call (vgxsim's rule).
AUTO_QUEUED: tuple[int, ...] = (D.REDRAW, D.INPUTCHANGE, D.WINQUIT, D.WINSHUT, D.DEPTHCHANGE)


class ScriptExhausted(BaseException):
    """The scripted input has ended: the run is over.

    Raised by :meth:`EventQueue.qread` when the queue is empty and the script has
    no steps left, by a script ``stop`` step, and by :meth:`EventQueue.frame_done`
    once ``max_frames`` frames have been drawn.  It derives from
    :class:`BaseException`, like :class:`SystemExit`, so that a demo's
    ``except Exception:`` cannot swallow it.  The runner that executes a program
    catches it and treats it as a normal, clean end::

        try:
            program.main()
        except ScriptExhausted:
            pass  # the script has been played to the end

    Attributes
    ----------
    frame : int
        Frames drawn (``frame_done`` calls) when the run ended.
    reason : str
        ``"exhausted"``, ``"stop"`` or ``"max_frames"``.
    """

    def __init__(self, message: str, frame: int = 0, reason: str = "exhausted"):
        super().__init__(message)
        self.frame = frame
        self.reason = reason


@dataclass(frozen=True)
class Step:
    """One unit of scripted input, delivered all at once.

    Parameters
    ----------
    events : tuple of (int, int)
        Raw ``(device, value)`` input events, applied in order with
        :meth:`EventQueue.post`.
    after : int
        Not delivered before this many frames have been drawn.
    wait : int
        Not delivered before this many frames after the previous step.
    ticks : int
        Timer ticks to run after the events (see :meth:`EventQueue.tick`).
    stop : bool
        End the run (raise :class:`ScriptExhausted`) when delivered.
    where : str
        Where the step came from (``"file:line"``), for messages.
    resize : (int, int, int) or None
        ``(gid, width, height)``: the user reshaped window ``gid`` (0: the current
        window) to that size, before the step's events (see
        :attr:`EventQueue.window_resizer`).
    """

    events: tuple[tuple[int, int], ...] = ()
    after: int = 0
    wait: int = 0
    ticks: int = 0
    stop: bool = False
    where: str = ""
    resize: tuple[int, int, int] | None = None


class EventSource:
    """An ordered supply of :class:`Step` objects: the scripted input.

    Parameters
    ----------
    steps : iterable of Step, optional
        The steps, in delivery order.
    """

    def __init__(self, steps: Iterable[Step] = ()):
        self._steps: deque[Step] = deque(steps)

    @classmethod
    def from_events(cls, events: Iterable[tuple[int, int]]) -> EventSource:
        """Make a source with one undelayed step per ``(device, value)`` pair."""
        return cls(Step(events=((operator.index(d), operator.index(v)),)) for d, v in events)

    @classmethod
    def from_text(cls, text: str, filename: str = "<script>", resolve=None) -> EventSource:
        """Parse script text (see :mod:`vgxsim.events.script`) into a source."""
        from vgxsim.events.script import parse_script

        return cls(parse_script(text, filename=filename, resolve=resolve))

    @classmethod
    def from_file(cls, path: str | PathLike, resolve=None) -> EventSource:
        """Read and parse a script file (see :mod:`vgxsim.events.script`)."""
        from vgxsim.events.script import load_script

        return load_script(path, resolve=resolve)

    def add(
        self,
        *events: tuple[int, int],
        after: int = 0,
        wait: int = 0,
        ticks: int = 0,
        stop: bool = False,
    ) -> None:
        """Append one step built from the arguments (see :class:`Step`)."""
        evs = tuple((operator.index(d), operator.index(v)) for d, v in events)
        self._steps.append(Step(evs, after=after, wait=wait, ticks=ticks, stop=stop))

    def append(self, step: Step) -> None:
        """Append ``step`` after the existing steps."""
        self._steps.append(step)

    def peek(self) -> Step | None:
        """Return the next step without removing it, or None when exhausted."""
        return self._steps[0] if self._steps else None

    def pop(self) -> Step:
        """Remove and return the next step (IndexError when exhausted)."""
        return self._steps.popleft()

    @property
    def exhausted(self) -> bool:
        """True when no steps are left."""
        return not self._steps

    def __len__(self) -> int:
        return len(self._steps)

    def __iter__(self) -> Iterator[Step]:
        return iter(tuple(self._steps))


def _short(val: int) -> int:
    """Wrap an int to a signed 16-bit value, as a C ``short`` would."""
    return ((operator.index(val) + 0x8000) & 0xFFFF) - 0x8000


class EventQueue:
    """IRIS GL's input queue and device state, driven by an :class:`EventSource`.

    The method names and return values follow the Python ``gl`` module:
    ``qread()`` returns a ``(dev, val)`` tuple, ``qtest``/``getbutton``/
    ``isqueued``/``getvaluator`` return ints.  Device numbers must be ints
    (a float raises TypeError, as in the original binding).  See the module
    docstring for the full model.

    Parameters
    ----------
    source : EventSource, optional
        Scripted input; an empty source when omitted (the first blocking
        ``qread`` on an empty queue then ends the run).
    max_frames : int, optional
        If given, ``frame_done`` raises :class:`ScriptExhausted` when the frame
        count reaches it (a limit for programs that never block in ``qread``).
    max_idle_ticks : int
        Timer ticks a blocking ``qread`` may spend waiting for a delayed step
        between two frames before the delay is skipped.

    Attributes
    ----------
    frame : int
        Frames drawn so far (``frame_done`` calls).
    ticks : int
        Timer ticks so far (frames, idle ticks and script ``tick`` steps).
    source : EventSource
        The scripted input still to come.
    window_resizer : callable or None
        ``window_resizer(gid, width, height)`` reshapes a window for a delivered
        :attr:`Step.resize` (the gl layer installs it at ``winopen``: the window's
        planes take the size and ``(REDRAW, gid)`` is entered, as when a user drags
        the window's corner).  A resize step delivered without one is an error.
    """

    def __init__(
        self,
        source: EventSource | None = None,
        *,
        max_frames: int | None = None,
        max_idle_ticks: int = 100_000,
    ):
        self.source = source if source is not None else EventSource()
        self.max_frames = max_frames
        self.max_idle_ticks = max_idle_ticks
        self.frame = 0
        self.ticks = 0
        self._queue: deque[tuple[int, int]] = deque()
        self._queued: set[int] = set()
        self._state: dict[int, int] = {}
        self._reported: dict[int, int] = {}
        self._noise: dict[int, int] = {}
        self._ties: dict[int, tuple[int, ...]] = {}
        self._timer_count: dict[int, int] = {}
        self._last_delivery = 0
        self._idle = 0
        self.window_resizer = None

    # ------------------------------------------------------------------ setup
    def window_opened(self, gid: int = 1) -> None:
        """Do what ``winopen`` does to the queue.

        Queues the :data:`AUTO_QUEUED` devices and enters ``(REDRAW, gid)``.

        Parameters
        ----------
        gid : int
            The new window's id, used as the REDRAW value.
        """
        for dev in AUTO_QUEUED:
            self.qdevice(dev)
        self.qenter(D.REDRAW, gid)

    def qdevice(self, dev: int) -> None:
        """Make ``dev`` enter its input into the queue."""
        dev = operator.index(dev)
        if dev not in self._queued:
            self._queued.add(dev)
            self._reported[dev] = self._state.get(dev, 0)
            self._timer_count[dev] = 0

    def unqdevice(self, dev: int) -> None:
        """Stop queuing ``dev``; its entries already in the queue stay there."""
        self._queued.discard(operator.index(dev))

    def isqueued(self, dev: int) -> int:
        """Return 1 if ``dev`` is queued, else 0."""
        return int(operator.index(dev) in self._queued)

    def tie(self, button: int, val1: int, val2: int) -> None:
        """Tie up to two valuators to a button.

        After each queue entry for ``button`` the current values of ``val1``
        and ``val2`` are entered, in that order.  A valuator of 0 means none;
        ``tie(b, 0, 0)`` unties.

        Raises
        ------
        ValueError
            If ``button`` is not a button or a non-zero ``val1``/``val2`` is
            not a valuator.
        """
        button, val1, val2 = (operator.index(x) for x in (button, val1, val2))
        if not D.is_button(button):
            raise ValueError(f"tie: device {button} is not a button")
        for v in (val1, val2):
            if v and not D.is_valuator(v):
                raise ValueError(f"tie: device {v} is not a valuator")
        tied = tuple(v for v in (val1, val2) if v)
        if tied:
            self._ties[button] = tied
        else:
            self._ties.pop(button, None)

    def noise(self, dev: int, delta: int) -> None:
        """Set the noise delta of a valuator or the divisor of a timer.

        A queued valuator makes an entry only when it has moved by at least
        ``delta`` since its last entry; a queued timer makes an entry every
        ``delta``-th tick (its tick count restarts).  Values below 1 count as 1.
        """
        dev = operator.index(dev)
        self._noise[dev] = max(1, operator.index(delta))
        if dev in D.TIMERS:
            self._timer_count[dev] = 0

    # ------------------------------------------------------------------ input
    def post(self, dev: int, val: int) -> None:
        """Apply one raw input event as the hardware would.

        Updates the device state and makes queue entries according to the
        queued set, ``tie`` and ``noise`` (see the module docstring).

        Parameters
        ----------
        dev : int
            Device number.
        val : int
            Value: 1/0 for buttons, a position for valuators, a character
            code for KEYBD, anything for pseudo devices.
        """
        dev, val = operator.index(dev), operator.index(val)
        if D.is_button(dev):
            self._state[dev] = 1 if val else 0
            if dev in self._queued:
                self._queue.append((dev, _short(val)))
                for v in self._ties.get(dev, ()):
                    self._queue.append((v, _short(self._state.get(v, 0))))
        elif D.is_valuator(dev):
            self._state[dev] = val
            if dev in self._queued:
                if abs(val - self._reported.get(dev, 0)) >= self._noise.get(dev, 1):
                    self._queue.append((dev, _short(val)))
                    self._reported[dev] = val
        elif dev in self._queued:
            self._queue.append((dev, _short(val)))

    def tick(self, n: int = 1) -> None:
        """Advance the timers by ``n`` ticks, in O(1) per queued timer.

        Each queued TIMERn device enters ``(TIMERn, 0)`` every ``noise``-th tick, at
        most :data:`MAX_TIMER_BACKLOG` entries per call: a script's ``tick 1000000000``
        fast-forwards the clock without a billion queue entries (see the module
        docstring).
        """
        n = operator.index(n)
        if n <= 0:
            return
        self.ticks += n
        for dev in D.TIMERS:
            if dev in self._queued:
                noise = self._noise.get(dev, 1)
                due, count = divmod(self._timer_count.get(dev, 0) + n, noise)
                self._queue.extend([(dev, 0)] * min(due, MAX_TIMER_BACKLOG))
                self._timer_count[dev] = count

    def frame_done(self) -> None:
        """Count one frame; called by ``swapbuffers``.

        Ticks the timers once and delivers the next script step if it is due.

        Raises
        ------
        ScriptExhausted
            When ``max_frames`` is reached, or a delivered step is ``stop``.
        """
        self.frame += 1
        self._idle = 0
        if self.max_frames is not None and self.frame >= self.max_frames:
            raise ScriptExhausted(f"max_frames={self.max_frames} reached", self.frame, "max_frames")
        self.tick()
        self._deliver_due()

    # ------------------------------------------------------------------ queue
    def qenter(self, dev: int, val: int) -> None:
        """Enter ``(dev, val)`` into the queue whether or not ``dev`` is queued."""
        self._queue.append((operator.index(dev), _short(val)))

    def qreset(self) -> None:
        """Empty the queue (script steps not yet delivered are kept)."""
        self._queue.clear()

    def qtest(self) -> int:
        """Return the device at the head of the queue, or 0 if it is empty.

        Does not block.  On an empty queue, one due script step is delivered first.
        """
        if not self._queue:
            self._deliver_due()
        return self._queue[0][0] if self._queue else 0

    def qread(self) -> tuple[int, int]:
        """Remove and return the entry at the head of the queue as ``(dev, val)``.

        Blocks in the IRIS sense: see the module docstring for how time passes
        while the queue is empty.

        Raises
        ------
        ScriptExhausted
            When the queue is empty and the script has no steps left.
        """
        while not self._queue:
            step = self.source.peek()
            if step is None:
                raise ScriptExhausted(
                    f"qread: input script exhausted after {self.frame} frames", self.frame
                )
            if self._is_due(step):
                self._deliver(self.source.pop())
            elif self._idle < self.max_idle_ticks and self._timers_queued():
                self._idle += 1
                self.tick()
            else:
                self._deliver(self.source.pop())
        return self._queue.popleft()

    def getbutton(self, dev: int) -> int:
        """Return 1 if button ``dev`` is down, else 0 (0 for non-buttons)."""
        dev = operator.index(dev)
        return 1 if D.is_button(dev) and self._state.get(dev, 0) else 0

    def getvaluator(self, dev: int) -> int:
        """Return the current value of valuator ``dev`` (0 until it is set)."""
        return self._state.get(operator.index(dev), 0)

    @property
    def entries(self) -> list[tuple[int, int]]:
        """A copy of the queue's entries, head first."""
        return list(self._queue)

    def __len__(self) -> int:
        return len(self._queue)

    # --------------------------------------------------------------- internal
    def _timers_queued(self) -> bool:
        return any(dev in self._queued for dev in D.TIMERS)

    def _is_due(self, step: Step) -> bool:
        return self.frame >= step.after and self.frame >= self._last_delivery + step.wait

    def _deliver_due(self) -> None:
        step = self.source.peek()
        # A modal step (a script ``menu`` choice) waits for the call that reads it
        # (dopup); frames and qtest pass it by.  A blocking qread may still drop it.
        if step is not None and self._is_due(step) and not getattr(step, "modal", False):
            self._deliver(self.source.pop())

    def _deliver(self, step: Step) -> None:
        self._last_delivery = self.frame
        if step.resize is not None:
            where = f"{step.where}: " if step.where else ""
            if self.window_resizer is None:
                raise ValueError(f"{where}resize: no window to resize (no window open)")
            try:
                self.window_resizer(*step.resize)
            except ValueError as exc:
                raise ValueError(f"{where}{exc}") from None
        for dev, val in step.events:
            self.post(dev, val)
        if step.ticks:
            self.tick(step.ticks)
        if step.stop:
            where = f" ({step.where})" if step.where else ""
            raise ScriptExhausted(
                f"script stop{where} after {self.frame} frames", self.frame, "stop"
            )
