"""Shared machinery of the IRIS GL layer: the current window, errors, arguments.

Every gl function validates its arguments here and raises a :class:`GLError`
subclass whose message names the call and its arguments, e.g.
``stensize(9): planes must be 0..8 (getgdesc(GD_BITS_STENCIL) is 8)``.  Nothing below
this layer ever sees a bad value.

Argument conventions follow CPython's historical IRIX ``gl`` module
(shared/reference/cpython_gl_module.md): short/long/Angle/Boolean arguments must be
Python ints (a float Angle is an error, as the binding's ``PyInt_Check`` made it),
Coord/float arguments take ints or floats, fixed-size arrays may be passed either as
one flat sequence or as separate arguments (``v3f((x, y, z))`` and ``v3f(x, y, z)``).
"""

from __future__ import annotations

import inspect
import math
import numbers
from collections.abc import Sequence
from dataclasses import dataclass, field
from weakref import WeakKeyDictionary

import numpy as np

from vgxsim import GL


class GLError(Exception):
    """Base class of every error the IRIS GL layer raises."""


class GLUsageError(GLError):
    """A call made in the wrong state (no window, vertex outside bgn/end, ...)."""


class GLValueError(GLError, ValueError):
    """A value out of range or an unknown token."""


class GLTypeError(GLError, TypeError):
    """An argument of the wrong Python type (e.g. a float Angle)."""


#: Marks a positional parameter the caller did not pass (the fast calls take
#: ``(x=_NO, y=_NO, z=_NO, /, *more, **kw)`` instead of ``*args``: no tuple is built).
_NO = object()


def given(slots: tuple, more: tuple) -> tuple:
    """The positional arguments a fast call ``f(a=_NO, b=_NO, /, *more)`` got (``slots``:
    its named parameters), as the tuple ``*args`` would have held, for its general
    path and its errors (the slots fill from the left, so the unpassed ones trail)."""
    return tuple(a for a in slots if a is not _NO) + more


def describe(name: str, args: tuple) -> str:
    """``name(arg, ...)`` with token names where the argument is a token."""
    parts = []
    for a in args:
        if isinstance(a, (list, tuple)) and len(a) > 6:
            parts.append(f"[{len(a)} values]")
        elif isinstance(a, np.ndarray):
            parts.append(f"<array {a.shape}>")
        else:
            parts.append(repr(a))
    return f"{name}({', '.join(parts)})"


@dataclass
class Window:
    """What IRIS GL keeps about a window that the pipeline never reads (winopen(3G),
    wintitle, icontitle, winposition/winmove, winconstraints): its gid, titles, the
    screen position of its lower-left corner, the constraints it was opened under,
    and the screen last handed to its frame sink (``"fresh"``: the planes as
    allocated; None: nothing yet, or a double-buffered window); and the window state
    only gl calls read: the drawmode(3G) token, the rectzoom(3G) factors and the
    texture(3G)/tevdef(3G) definitions and bindings (gl/_texture.py TextureUnit,
    made on first use)."""

    gid: int = 0
    title: str = ""
    icontitle: str = ""
    origin: tuple[int, int] = (0, 0)
    constraints: dict = field(default_factory=dict)
    shown: object = None
    drawmode: int = int(GL.NORMALDRAW)
    rectzoom: tuple[float, float] = (1.0, 1.0)
    texture: object = None


#: Fast path switch (issue 6: the common calls under 1 us).  True: the common calls
#: (v3f, n3f, c3f, cpack, bgn*/end*, stencil, lmbind, zwritemask, wmpack,
#: blendfunction, the matrix stack, callobj) find the window through
#: :attr:`_Session.imm` and take a valid path of a few plain-value checks; anything
#: else -- recording, a keyword, a wrong count
#: or type, an out-of-range value -- goes to the call's general path, which validates
#: and raises as it always did.  False: every call takes its general path (the planes
#: are the same either way, tests/gl/test_fast_calls.py).  Call
#: ``session.refresh()`` after changing it.
FAST_CALLS = True

#: Replay switch (issue 6: callobj and the frame's front end), in effect where
#: :data:`FAST_CALLS` is.  True: callobj replays an object of stencil calls and small
#: closed chunks from a prepared block while the caller's state is the block's key
#: (gl/_objects.py ReplayBlock; under another matrix, rebased: REBASE_REPLAYS),
#: splices a one-chunk object inline -- also where a parent object calls it
#: (gl/_objects.py _walk) -- and draw-state
#: records and lmbind(LIGHTn)'s eye-space light entries are kept from one flush to
#: the next (StateTable.intern_kept).  False: those calls take the FAST_CALLS paths
#: they took before (the planes are the same either way, tests/stream/
#: test_fast_calls.py).  Read at each call: no refresh needed.
REPLAY_OBJECTS = True


class _Windows(dict):
    """The session's windows by gid: a dict that tells its session when it changes,
    so the session's cached current window (:attr:`_Session.imm`) never goes stale,
    whoever installs or removes a window (winopen, winclose, tests)."""

    __slots__ = ("_changed",)

    def __init__(self, changed, *args):
        super().__init__(*args)
        self._changed = changed

    def __setitem__(self, key, value):
        super().__setitem__(key, value)
        self._changed()

    def __delitem__(self, key):
        super().__delitem__(key)
        self._changed()

    def pop(self, *args):
        out = super().pop(*args)
        self._changed()
        return out

    def popitem(self):
        out = super().popitem()
        self._changed()
        return out

    def clear(self):
        super().clear()
        self._changed()

    def update(self, *args, **kwargs):
        super().update(*args, **kwargs)
        self._changed()

    def setdefault(self, key, default=None):
        out = super().setdefault(key, default)
        self._changed()
        return out


class _Session:
    """Process-wide IRIS GL state: windows, the current one, window preferences.

    The one owner of the gl layer's process state: :meth:`reset` clears all of it
    (no gl or events module keeps state of its own).

    ``imm`` is the current window's Context while calls execute in immediate mode
    (a window is current, no display object is being recorded and
    :data:`FAST_CALLS` is on), else None: the common calls read this one attribute
    instead of ``recording``, ``windows`` and ``current``.  Assigning ``current``,
    ``recording`` or ``windows``, or changing ``windows``, recomputes it.
    """

    def __init__(self):
        self.imm = None
        self._current: int | None = None
        self._recording = None
        self._windows = _Windows(self.refresh)
        self.reset()

    def refresh(self) -> None:
        """Recompute :attr:`imm` (see the class docstring)."""
        self.imm = (self._windows.get(self._current)
                    if FAST_CALLS and self._recording is None else None)

    @property
    def current(self) -> int | None:
        """The gid of the current window (winset(3G)), or None."""
        return self._current

    @current.setter
    def current(self, gid: int | None) -> None:
        self._current = gid
        self.refresh()

    @property
    def recording(self):
        """What recordable calls append (call, args) to while makeobj is open: the
        object's recorder (gl/_objects.py), or None in immediate mode."""
        return self._recording

    @recording.setter
    def recording(self, recorder) -> None:
        self._recording = recorder
        self.refresh()

    @property
    def windows(self) -> dict[int, object]:
        """The open windows' Contexts by gid."""
        return self._windows

    @windows.setter
    def windows(self, windows: dict) -> None:
        self._windows = _Windows(self.refresh, windows)
        self.refresh()

    def reset(self) -> None:
        self.windows = {}
        self.current = None
        self.next_gid = 1
        self.prefsize: tuple[int, int] | None = None
        self.prefposition: tuple[int, int, int, int] | None = None
        self.default_size = (640, 512)  # winopen without prefsize (vgxsim run --size)
        # vgxsim run --size: the size a user reshapes every new window to (None: none).
        self.reshape_size: tuple[int, int] | None = None
        self.queue = None  # vgxsim.events.EventQueue, created lazily
        self.sink_factory = None  # callable(gid) -> sink, set by `vgxsim run`
        self.objects: dict[int, object] = {}  # display objects (gl/_objects.py), by name
        self.next_object = 1  # where genobj starts looking
        self.open_object: int | None = None  # makeobj in progress
        self.recording = None
        self.topics: dict[str, object] = {}  # per-topic state, see topic_state()
        # cpack's colours by packed word (gl/_color.py cpack): one RGBA tuple per
        # distinct word, so a repeated cpack leaves the current colour the same object
        # and the stream sends no new SYNC; bounded, emptied when full.
        self.packed: dict[int, tuple] = {}
        # The Window record of each Context (window_of()); weak, so a Context installed
        # without winopen (tests, library users) takes its record with it.
        self.window_records: WeakKeyDictionary = WeakKeyDictionary()
        # Constraints (keepaspect, minsize, maxsize, iconsize, noborder) for the next
        # winopen or winconstraints, which use them up (winconstraints(3G)).
        self.constraints: dict = {}
        # (queue, gid): the window whose INPUTCHANGE entry the next read delivers.
        self.focus_pending: tuple | None = None


session = _Session()


def topic_state(key: str, factory):
    """The session's state object for one topic of the gl layer (popup menus, pick
    mode, fonts, curve bases, ...), made by ``factory()`` on first use and dropped by
    ``session.reset()``, so each topic module keeps its state without a field here."""
    state = session.topics.get(key)
    if state is None:
        state = session.topics[key] = factory()
    return state


def window_of(ctx) -> Window:
    """The :class:`Window` record of a window's Context (a default one, at the screen
    origin, for a Context installed without winopen)."""
    rec = session.window_records.get(ctx)
    if rec is None:
        rec = session.window_records[ctx] = Window()
    return rec


def current(name: str, args: tuple = ()):
    """The current window's Context; GLUsageError before winopen."""
    if session._current is None:
        raise GLUsageError(f"{describe(name, args)}: no window is open (call winopen first)")
    return session._windows[session._current]


#: The integers any IRIS GL argument can hold: a 32-bit ``long`` or ``unsigned long``
#: (the largest C integer type of the 1990 API, irisgl_reference.md s.1).  Anything
#: outside is refused, so no count or coordinate past 32 bits reaches a size
#: computation.
INT_MIN, INT_MAX = -(1 << 31), (1 << 32) - 1


def as_int(name: str, args: tuple, what: str, v, *, wrap: bool = False) -> int:
    """An integer argument (short, long, Angle, Boolean, Device, token).

    Ints outside ``INT_MIN..INT_MAX`` (32-bit signed or unsigned ``long``) raise
    GLValueError.  ``wrap=True`` is for ``unsigned long`` masks and colours, where C
    reduces any integer modulo 2**32 (the 1991 article's ``zwritemask(0xfffffffff)``):
    the result is that residue, 0..2**32-1, and never refused.
    """
    if type(v) is int:  # the common case, without the ABC checks below (~1 us)
        if wrap:
            return v & INT_MAX
        if INT_MIN <= v <= INT_MAX:
            return v
    if isinstance(v, (bool, np.bool_)):
        return int(v)
    if isinstance(v, (numbers.Integral, np.integer)):
        iv = int(v)
        if wrap:
            return iv & INT_MAX
        if not INT_MIN <= iv <= INT_MAX:
            raise GLValueError(f"{describe(name, args)}: {what} {iv} does not fit in 32 "
                               "bits (an IRIS GL long is -2**31..2**32-1)")
        return iv
    raise GLTypeError(f"{describe(name, args)}: {what} must be an int, not "
                      f"{type(v).__name__} (IRIS GL takes an integer here)")


def as_angle(name: str, args: tuple, v) -> int:
    """An Angle: an int in tenths of a degree (a float is an error, as in IRIS GL)."""
    if type(v) is int:
        return v
    if isinstance(v, (numbers.Integral, np.integer)) and not isinstance(v, bool):
        return int(v)
    raise GLTypeError(f"{describe(name, args)}: Angle must be an int in tenths of a "
                      f"degree, not {type(v).__name__} {v!r} (use rot() for float degrees)")


def as_float(name: str, args: tuple, what: str, v) -> float:
    if type(v) is float:
        return v
    if isinstance(v, (numbers.Real, np.floating, np.integer)) and not isinstance(v, bool):
        return float(v)
    if isinstance(v, bool):
        return float(v)
    raise GLTypeError(f"{describe(name, args)}: {what} must be a number, not "
                      f"{type(v).__name__}")


def as_axis(name: str, args: tuple, v) -> str:
    if isinstance(v, str) and len(v) == 1 and v.lower() in "xyz":
        return v.lower()
    raise GLValueError(f"{describe(name, args)}: axis must be 'x', 'y' or 'z'")


def flat_numbers(name: str, args: tuple, n: int | None, integer: bool = False) -> list:
    """Fixed-size array arguments: ``f(x, y, z)`` or ``f((x, y, z))``.

    ``n`` is the required count (None: any count).  Integer arrays reject floats
    (the historical binding read them with PyInt_Check).
    """
    seq = args
    if len(args) == 1 and isinstance(args[0], (Sequence, np.ndarray)) and not isinstance(
            args[0], str):
        seq = tuple(np.asarray(args[0]).reshape(-1).tolist()) if isinstance(
            args[0], np.ndarray) else tuple(args[0])
    if n is not None and len(seq) != n:
        raise GLTypeError(f"{describe(name, args)}: expected {n} numbers, got {len(seq)}")
    # Fast path: plain Python floats/ints (the common case in immediate mode).
    if not integer and all(type(v) is float or type(v) is int for v in seq):
        return [float(v) for v in seq]
    out = []
    for i, v in enumerate(seq):
        if integer:
            out.append(as_int(name, args, f"element {i}", v))
        else:
            out.append(as_float(name, args, f"element {i}", v))
    return out


def as_array(name: str, args: tuple, what: str, v, dtype=None) -> np.ndarray:
    """``np.asarray(v, dtype)`` of an array argument; ragged nesting, strings where
    numbers belong and other values numpy cannot convert raise GLTypeError naming the
    call (numpy's own ValueError/TypeError would not)."""
    try:
        return np.asarray(v) if dtype is None else np.asarray(v, dtype=dtype)
    except (TypeError, ValueError, OverflowError):
        raise GLTypeError(f"{describe(name, args)}: {what} must be numbers, as a flat "
                          "sequence or rows of equal length") from None


def check_token(name: str, args: tuple, what: str, v, allowed, family: str = "") -> int:
    """An int token that must be one of ``allowed``."""
    iv = as_int(name, args, what, v)
    if iv not in allowed:
        fam = f" ({family}*)" if family else ""
        raise GLValueError(f"{describe(name, args)}: {what} {iv} is not a valid token{fam}")
    return iv


def _arity(func) -> tuple[int, int | float, tuple]:
    """(fewest, most positional arguments, annotation of each) of a gl call's body."""
    sig = inspect.signature(func)
    lo, hi, kinds = 0, 0, []
    for p in sig.parameters.values():
        if p.kind is p.VAR_POSITIONAL:
            return lo, math.inf, tuple(kinds)
        if p.kind in (p.POSITIONAL_ONLY, p.POSITIONAL_OR_KEYWORD):
            hi += 1
            if p.default is p.empty:
                lo += 1
            kinds.append(p.annotation if isinstance(p.annotation, str) else
                         getattr(p.annotation, "__name__", ""))
    return lo, hi, tuple(kinds)


def _count(n: float) -> str:
    return f"{n} argument{'s' if n != 1 else ''}"


def bind_error(call, args: tuple, kwargs: dict) -> GLTypeError:
    """The GLTypeError for arguments a call cannot bind (keywords, wrong count)."""
    name = call.__name__
    shown = describe(name, args)
    if kwargs:
        shown = shown[:-1] + (", " if args else "") + ", ".join(
            f"{k}={v!r}" for k, v in kwargs.items()) + ")"
        return GLTypeError(f"{shown}: IRIS GL calls take positional arguments only (the C "
                           f"call has no keyword {', '.join(map(repr, kwargs))})")
    lo, hi = call.gl_arity
    want = _count(lo) if lo == hi else f"{lo} to {_count(hi)}"
    return GLTypeError(f"{shown}: expected {want}, got {len(args)}")


def record_or_refuse(call, args: tuple, kwargs: dict):
    """Slow path of a self-binding call (``gl_function(binds=...)``): refuse keywords
    and a wrong argument count, else record into the open display object."""
    lo, hi = getattr(call, "gl_arity", (0, math.inf))
    if kwargs or not lo <= len(args) <= hi:
        raise bind_error(call, args, kwargs)
    return session.recording.append((call, args))


def check_types(call, args: tuple) -> None:
    """Type-check arguments against the call's annotations (int: an integer, float:
    a number), as the call itself would, without executing it (display objects
    validate calls when they are recorded)."""
    for i, (kind, v) in enumerate(zip(call.gl_types, args, strict=False)):
        if kind == "int" and not isinstance(v, (numbers.Integral, np.integer)):
            raise GLTypeError(f"{describe(call.__name__, args)}: argument {i + 1} must be "
                              f"an int, not {type(v).__name__}")
        if kind == "float" and (not isinstance(v, (numbers.Real, np.floating, np.integer))):
            raise GLTypeError(f"{describe(call.__name__, args)}: argument {i + 1} must be "
                              f"a number, not {type(v).__name__}")


def gl_function(record: bool = True, binds: tuple | None = None):
    """Decorate an IRIS GL call: bind its arguments in one place.

    The binder is built from the body's signature: keyword arguments (C has none)
    and a wrong argument count raise :class:`GLTypeError` naming the call and the
    arguments it got; bodies taking ``*args`` check their own counts.  With
    ``record=True`` the call is stored in the open display object while ``makeobj``
    is in effect (IRIS GL compiles drawing and state commands into the object
    instead of executing them); queries and window calls use ``record=False``.
    The valid path allocates nothing beyond what the body does.

    ``binds=(lo, hi, types)``: the body binds itself, for the calls an immediate-mode
    program makes per vertex or per primitive (v3f, bgnpolygon, stencil, ...), where
    the binder's extra call frame was a third of the cost.  Such a body takes
    ``(*args, **kwargs)`` and starts with ``if kwargs or session.recording is not None
    or <its count is wrong>: return record_or_refuse(call, args, kwargs)``;
    ``lo``/``hi`` (the argument counts) and ``types`` (``"int"``/``"float"`` per
    argument, as annotations give them) are what the generic binder would have read
    from a signature, so the errors and the display-object checks are the same.
    """

    def wrap(func):
        if binds is not None:
            func.gl_record = record
            func.gl_arity = (binds[0], binds[1])
            func.gl_types = tuple(binds[2])
            func.__wrapped__ = func
            return func
        lo, hi, kinds = _arity(func)

        def call(*args, **kwargs):
            if kwargs or not lo <= len(args) <= hi:
                raise bind_error(call, args, kwargs)
            if record and session._recording is not None:
                return session._recording.append((call, args))
            return func(*args)

        call.__name__ = func.__name__
        call.__qualname__ = func.__qualname__
        call.__doc__ = func.__doc__
        call.__wrapped__ = func
        call.gl_record = record
        call.gl_arity = (lo, hi)
        call.gl_types = kinds
        return call

    return wrap
