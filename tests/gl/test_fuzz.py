"""Hostile call sequences (issue 11 item 5): random sequences of every public
vgxsim.gl call with random argument kinds raise only GLError subclasses.

Every call that :mod:`vgxsim.gl` exports with a ``gl_record`` attribute (the calls the
binder of ``vgxsim/gl/_core.py`` wraps) is drawn, with argument counts around its
arity (and sometimes keywords the C call never had), each argument one of many kinds:
small ints, GL tokens, 32-bit edge values, 2**63, floats, NaN, +-inf, huge and tiny
numbers, None, strings, bytes, nested lists and tuples, numpy scalars and arrays.
The only exception besides the GLError family is
:class:`vgxsim.events.ScriptExhausted`, which ``qread``/``blkqread``/``dopup`` raise
by design when the (empty) input script has ended; nothing is skipped, since no
vgxsim.gl call blocks (a headless qread ends the run instead) or exits the process.
After each sequence the planes must still read back (``read_pixels``, ``lrectread``).

Two bounds keep a run short and its memory small: windows are 16 x 12 by default
and the window size limit is lowered to 64 pixels a side while fuzzing (a random
``prefsize`` may not allocate GiBs; the real limit has its own tests), and each call
runs under a wall-clock alarm so that a hang is reported, not waited for.

The suite runs a few hundred calls; ``VGXSIM_FUZZ_EXAMPLES=N`` runs N sequences.
``python bench/fuzz_campaign.py --calls 100000`` runs a long campaign with the same
generator and counts every exception outside the family instead of stopping.
"""

from __future__ import annotations

import math
import os
import random
import signal
import traceback
from collections import Counter
from contextlib import contextmanager

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from vgxsim import GL, gl
from vgxsim.events import ScriptExhausted
from vgxsim.gl import _core, _window

#: Every public call the binder wraps.
CALLS = tuple(sorted(
    (name, getattr(gl, name)) for name in dir(gl)
    if not name.startswith("_") and hasattr(getattr(gl, name), "gl_record")))

#: Allowed outcomes besides returning: the GLError family, and the documented end of a
#: scripted run (qread and friends on an empty script).
ALLOWED = (gl.GLError, ScriptExhausted)

_TOKENS = tuple(sorted({v for k, v in vars(GL).items()
                        if k.isupper() and isinstance(v, int) and not isinstance(v, bool)}))

_SCALARS = (
    0, 1, -1, 2, 3, 4, 7, 8, 16, 255, 256, 1000, -1000, 0xFFFFFFFF, 0x7FFFFFFF,
    -(1 << 31), 1 << 31, 1 << 32, 1 << 63, -(1 << 63), 10 ** 30, True, False,
    0.0, 0.5, -0.5, 1.5, 3.0, -2.25, 1e-300, 5e-324, 1e17, 1e300, -1e300,
    math.nan, math.inf, -math.inf,
    None, "", "x", "hello", "X", b"abc", bytearray(b"\0" * 4), object(), complex(1, 2),
    np.int64(3), np.int32(-2), np.uint64(1 << 63), np.float32(1.5), np.float64(math.nan),
    np.bool_(True),
)


def _array(rng: random.Random):
    shape = rng.choice(((), (0,), (1,), (2,), (3,), (4,), (16,), (4, 4), (2, 3), (3, 3, 1)))
    dtype = rng.choice((np.float64, np.float32, np.int32, np.int64, np.uint8, np.bool_))
    a = np.asarray(rng.choice((0.0, 1.0, -3.0, 2.5, 1e30, math.nan, math.inf, 1 << 40)))
    with np.errstate(all="ignore"):
        return np.full(shape, a).astype(dtype)


def random_value(rng: random.Random, depth: int = 0):
    """One argument of a random kind."""
    r = rng.random()
    if r < 0.25:
        return rng.choice(_TOKENS)
    if r < 0.55:
        return rng.choice(_SCALARS)
    if r < 0.65:
        return rng.uniform(-100.0, 100.0) if rng.random() < 0.5 else rng.randint(-50, 700)
    if r < 0.75:
        return _array(rng)
    if depth < 2:
        n = rng.choice((0, 1, 2, 3, 3, 4, 4, 6, 16, 17))
        seq = [random_value(rng, depth + 1) if rng.random() < 0.3 else
               rng.choice((0.5, 1, 2.0, 0, GL.LMNULL, 3)) for _ in range(n)]
        return tuple(seq) if rng.random() < 0.5 else seq
    return rng.choice(_SCALARS)


def random_call(rng: random.Random):
    """``(name, call, args, kwargs)`` for one random call."""
    name, call = rng.choice(CALLS)
    # Hand-written fast calls (vertices, normals, bgn/end) take *args and check them.
    lo, hi = getattr(call, "gl_arity", (0, math.inf))
    top = lo + 8 if hi == math.inf else hi
    if rng.random() < 0.75:
        n = rng.randint(lo, int(top))
    else:
        n = rng.randint(0, int(top) + 2)
    args = tuple(random_value(rng) for _ in range(n))
    kwargs = {}
    if rng.random() < 0.03:
        kwargs = {rng.choice(("x", "mode", "enable", "name")): random_value(rng)}
    return name, call, args, kwargs


class Hang(BaseException):
    """A call ran past its alarm."""


@contextmanager
def alarm(seconds: float):
    """Raise :class:`Hang` in the main thread after ``seconds`` (no-op where SIGALRM
    is missing)."""
    if not hasattr(signal, "setitimer"):
        yield
        return

    def ring(signum, frame):
        raise Hang(f"no return after {seconds} s")

    old = signal.signal(signal.SIGALRM, ring)
    signal.setitimer(signal.ITIMER_REAL, seconds)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, old)


@contextmanager
def fuzz_limits(max_side: int = 64):
    """The bounded world of a fuzz run: a lowered window size limit and small default
    windows; the session is reset before and after."""
    saved = _window.MAX_WINDOW_SIZE
    _window.MAX_WINDOW_SIZE = max_side
    _core.session.reset()
    _core.session.default_size = (16, 12)
    try:
        yield
    finally:
        _window.MAX_WINDOW_SIZE = saved
        _core.session.reset()


def open_window(rng: random.Random) -> None:
    """A fresh session with one window in a random configuration."""
    _core.session.reset()
    _core.session.default_size = (16, 12)
    gl.winopen("fuzz")
    if rng.random() < 0.6:
        gl.RGBmode()
    if rng.random() < 0.5:
        gl.doublebuffer()
    if rng.random() < 0.6:
        gl.stensize(rng.choice((1, 4, 8)))
    if rng.random() < 0.3:
        gl.acsize(16)
    gl.gconfig()


def check_readable() -> None:
    """The planes read back: read_pixels and lrectread answer with the window's size."""
    if _core.session.current is None:
        return
    if _core.session.recording is not None:
        gl.closeobj()
    w, h = gl.getsize()
    img = gl.read_pixels()
    assert img.shape == (h, w, 4)
    if gl.getdisplaymode() in (GL.DMRGB, GL.DMRGBDOUBLE):
        words = gl.lrectread(0, 0, w - 1, h - 1)
        assert len(words) == 4 * w * h


def run_sequence(rng: random.Random, n_calls: int, *, per_call_s: float = 60.0,
                 failures: Counter | None = None, examples: dict | None = None) -> int:
    """Open a window and make ``n_calls`` random calls; return the calls made.

    With ``failures`` None the first exception outside :data:`ALLOWED` is raised
    (with the call in its message); else each is counted in ``failures`` under
    ``(call name, exception type)`` and one example of each kept in ``examples``.
    """
    open_window(rng)
    made = 0
    for _ in range(n_calls):
        name, call, args, kwargs = random_call(rng)
        made += 1
        try:
            with alarm(per_call_s):
                call(*args, **kwargs)
        except ALLOWED:
            pass
        except (Exception, Hang) as exc:  # noqa: BLE001  (the point of the test)
            shown = _core.describe(name, args)
            if failures is None:
                raise AssertionError(f"{shown} raised {type(exc).__name__}: {exc}") from exc
            key = (name, type(exc).__name__)
            failures[key] += 1
            if examples is not None and key not in examples:
                examples[key] = f"{shown[:300]}: {exc!s:.300}\n" + "".join(
                    traceback.format_exception(exc)[-4:])
    try:
        with alarm(per_call_s):
            check_readable()
    except (Exception, Hang) as exc:  # noqa: BLE001
        if failures is None:
            raise AssertionError(f"planes unreadable: {type(exc).__name__}: {exc}") from exc
        failures[("<readback>", type(exc).__name__)] += 1
        if examples is not None:
            examples.setdefault(("<readback>", type(exc).__name__),
                                "".join(traceback.format_exception(exc)[-4:]))
    return made


EXAMPLES = int(os.environ.get("VGXSIM_FUZZ_EXAMPLES", "25"))


def test_every_public_call_is_drawn():
    # The generator covers the whole API: every export the binder wraps, with nothing
    # skipped (a missing gl_record would hide a call from the fuzz).
    assert len(CALLS) > 300
    names = {n for n, _ in CALLS}
    assert {"winopen", "stencil", "lrectread", "callobj", "qread", "v3f"} <= names


@settings(max_examples=EXAMPLES, deadline=None, derandomize=os.environ.get(
    "VGXSIM_FUZZ_EXAMPLES") is None, suppress_health_check=list(HealthCheck))
@given(rng=st.randoms(use_true_random=False), n=st.integers(1, 30))
def test_random_calls_raise_only_gl_errors(rng, n):
    with fuzz_limits():
        run_sequence(rng, n)


@pytest.mark.parametrize("seed", range(3))
def test_fixed_seed_sequences(seed):
    # Three fixed campaigns of 100 calls each: the same calls on every run.
    with fuzz_limits():
        run_sequence(random.Random(seed), 100)


# Calls the campaign (bench/fuzz_campaign.py) found raising something other than a
# GLError, each fixed where the gl layer checks that argument.  Window: 16 x 12 RGB,
# double-buffered, 8 stencil planes.
REGRESSIONS = [
    # curves: ragged or non-numeric rows reached np.asarray (ValueError, TypeError)
    ("crv", ([[0, 0, 0], [1, 1], [2, 2, 2], [3, 3, 3]],), gl.GLTypeError),
    ("crv", ([[0, 0, 0], [1, "x", 1], [2, 2, 2], [3, 3, 3]],), gl.GLTypeError),
    ("rcrv", (np.zeros(2), np.zeros(0)), gl.GLTypeError),
    ("crvn", (), gl.GLTypeError),  # no geometry: IndexError
    ("rcrvn", (), gl.GLTypeError),
    ("crvn", (1, 2, 3), gl.GLTypeError),
    ("patch", ([[0] * 4, [1] * 3, [2] * 4, [3] * 4], [0] * 16, [0] * 16), gl.GLTypeError),
    ("rpatch", ([[0, 1], 2], [0] * 16, [0] * 16, [0] * 16), gl.GLTypeError),
    ("nurbscurve", ([[0, 1], 2], [[0, 0, 0]] * 4, 4, GL.N_XYZ), gl.GLTypeError),
    ("lrectwrite", (0, 0, 1, 0, [[1, 2], [3]]), gl.GLTypeError),
    # curveit: a 32-bit iteration count ran for hours (its count is a short)
    ("curveit", (1 << 31,), gl.GLValueError),
    ("curveit", (0x8000,), gl.GLValueError),
    # stencil: an array as `enable` was tested for truth before its type
    ("stencil", (np.zeros(4), 0, GL.SF_ALWAYS, 0xFF, GL.ST_KEEP, GL.ST_KEEP, GL.ST_KEEP),
     gl.GLTypeError),
]


@pytest.fixture
def rgb_window(fresh_session):
    _core.session.default_size = (16, 12)
    gl.winopen("regression")
    gl.RGBmode()
    gl.doublebuffer()
    gl.stensize(8)
    gl.gconfig()


@pytest.mark.parametrize("name, args, error", REGRESSIONS,
                         ids=[f"{n}-{i}" for i, (n, _, _) in enumerate(REGRESSIONS)])
def test_found_by_the_campaign(rgb_window, name, args, error):
    with pytest.raises(error, match=rf"^{name}\("):
        getattr(gl, name)(*args)
    check_readable()
