"""IRIS GL input calls: the event queue (qdevice(3G), qread(3G), ...).

Thin wrappers over :class:`vgxsim.events.EventQueue`, held in ``session.queue`` and
created on first use (so a program may call ``qdevice`` before ``winopen``, as IRIS GL
allows).  ``vgxsim run`` puts a queue fed by the ``--events`` script there; library
users may do the same.  The queue's model (buttons, valuators, ``tie``, ``noise``,
timers ticking once per frame) is documented in :mod:`vgxsim.events.queue`.

Input focus.  ``winopen`` enters ``(REDRAW, gid)`` at once (the first redraw) and
makes INPUTCHANGE a queued device; the window manager then gives the new window the
input focus, which IRIS GL reports as ``(INPUTCHANGE, gid)``.  On a real workstation
that entry arrives a little after ``winopen`` returns, so a program that calls
``unqdevice(INPUTCHANGE)`` straight away (mclock does) never sees it.  vgxsim models
that delay: the INPUTCHANGE entry is made at the program's next queue read or frame,
if INPUTCHANGE is still queued then.

A blocking ``qread`` on an empty queue whose script is used up raises
:class:`vgxsim.events.ScriptExhausted`; ``vgxsim run`` treats that as the clean end of
the run.
"""

from __future__ import annotations

from vgxsim import DEVICE
from vgxsim.events import EventQueue

from ._core import GLValueError, as_int, describe, gl_function, session

__all__ = [
    "qdevice", "unqdevice", "qread", "qtest", "qenter", "qreset", "isqueued",
    "getvaluator", "getbutton", "tie", "noise", "blkqread",
]

def event_queue() -> EventQueue:
    """The session's event queue, created (with no scripted input) on first use."""
    if session.queue is None:
        session.queue = EventQueue()
    return session.queue


def window_opened(gid: int) -> None:
    """What ``winopen`` does to the queue: REDRAW now, INPUTCHANGE at the next read."""
    q = event_queue()
    q.window_opened(gid)
    if q.window_resizer is None:  # a script's (or the user's) resize reaches the windows
        from ._window import reshape_window

        q.window_resizer = reshape_window
    session.focus_pending = (q, gid)  # INPUTCHANGE at the next read of this queue


def _sync_focus(q: EventQueue) -> None:
    pending = session.focus_pending
    if pending is None or pending[0] is not q:
        return
    session.focus_pending = None
    gid = pending[1]
    if q.isqueued(DEVICE.INPUTCHANGE) and gid in session.windows:
        q.qenter(DEVICE.INPUTCHANGE, gid)


def frame_done() -> None:
    """Tell the queue one frame was drawn (swapbuffers): timers tick, script steps
    that wait for frames become due."""
    q = event_queue()
    _sync_focus(q)
    q.frame_done()


def _device(name: str, args: tuple, v, what: str = "device") -> int:
    # Device is an unsigned short in gl.h (irisgl_reference.md s.1 type conventions).
    dev = as_int(name, args, what, v)
    if not 0 <= dev <= 0xFFFF:
        raise GLValueError(f"{describe(name, args)}: {what} {dev} is not a device number "
                           "(0..65535)")
    return dev


@gl_function(record=False)
def qdevice(dev: int) -> None:
    """Queue the input of device ``dev`` (qdevice(3G))."""
    event_queue().qdevice(_device("qdevice", (dev,), dev))


@gl_function(record=False)
def unqdevice(dev: int) -> None:
    """Stop queuing ``dev``; entries already queued stay (unqdevice(3G))."""
    event_queue().unqdevice(_device("unqdevice", (dev,), dev))


@gl_function(record=False)
def isqueued(dev: int) -> int:
    """1 if ``dev`` is queued, else 0 (isqueued(3G))."""
    return event_queue().isqueued(_device("isqueued", (dev,), dev))


@gl_function(record=False)
def qread() -> tuple[int, int]:
    """Remove the entry at the head of the queue and return it as ``(dev, val)``.

    Blocks (qread(3G)) in the scripted sense of :meth:`EventQueue.qread`.  Before it
    waits on an empty queue, the screen of every single-buffered window is handed to
    its frame sink if it changed: IRIS GL flushes the graphics pipe before blocking,
    so that picture is what the user saw while the program waited.

    Raises
    ------
    vgxsim.events.ScriptExhausted
        When the queue is empty and the scripted input is used up (the end of a
        ``vgxsim run``).
    """
    q = event_queue()
    _sync_focus(q)
    if len(q) == 0:
        from ._window import present_windows

        present_windows()
    dev, val = q.qread()
    return int(dev), int(val)


@gl_function(record=False)
def blkqread(n: int) -> list[int]:
    """Read several entries at once (blkqread(3G)); not in CPython's binding.

    Blocks like :func:`qread` for the first entry, then takes whatever else is
    queued, up to ``n // 2`` entries.  Returns the C buffer as a flat list of shorts
    ``[dev, val, dev, val, ...]``; its length is the C return value.
    """
    args = (n,)
    count = as_int("blkqread", args, "n", n)
    if count < 2:
        raise GLValueError(f"{describe('blkqread', args)}: n must be at least 2 "
                           "(one device and one value per entry)")
    out = list(qread())
    q = event_queue()
    while len(out) + 2 <= count and q.qtest():
        out.extend(q.qread())
    return [int(v) for v in out]


@gl_function(record=False)
def qtest() -> int:
    """The device at the head of the queue, or 0 if it is empty; does not block
    (qtest(3G))."""
    q = event_queue()
    _sync_focus(q)
    return int(q.qtest())


@gl_function(record=False)
def qenter(dev: int, val: int) -> None:
    """Enter ``(dev, val)`` into the queue whatever the device (qenter(3G)); ``val``
    wraps to a C short."""
    args = (dev, val)
    d = _device("qenter", args, dev)
    v = as_int("qenter", args, "value", val)
    event_queue().qenter(d, v)


@gl_function(record=False)
def qreset() -> None:
    """Empty the queue (qreset(3G)); scripted input not yet delivered is kept."""
    event_queue().qreset()


@gl_function(record=False)
def getvaluator(dev: int) -> int:
    """Current value of valuator ``dev``, e.g. MOUSEX in screen pixels (getvaluator(3G))."""
    return int(event_queue().getvaluator(_device("getvaluator", (dev,), dev)))


@gl_function(record=False)
def getbutton(dev: int) -> int:
    """1 while button ``dev`` is down, else 0 (getbutton(3G))."""
    return int(event_queue().getbutton(_device("getbutton", (dev,), dev)))


@gl_function(record=False)
def tie(b: int, v1: int, v2: int) -> None:
    """After each queue entry of button ``b`` enter valuators ``v1`` and ``v2``
    (0 = none) (tie(3G))."""
    args = (b, v1, v2)
    devs = [_device("tie", args, x, w) for x, w in ((b, "button"), (v1, "valuator 1"),
                                                    (v2, "valuator 2"))]
    try:
        event_queue().tie(*devs)
    except ValueError as exc:
        raise GLValueError(f"{describe('tie', args)}: {exc}") from None


@gl_function(record=False)
def noise(dev: int, delta: int) -> None:
    """A valuator enters the queue only after moving ``delta`` units; a timer enters
    once every ``delta`` ticks (noise(3G))."""
    args = (dev, delta)
    d = _device("noise", args, dev)
    n = as_int("noise", args, "delta", delta)
    if n < 0:
        raise GLValueError(f"{describe('noise', args)}: delta must not be negative")
    event_queue().noise(d, n)
