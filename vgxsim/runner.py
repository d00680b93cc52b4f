"""Run an IRIS GL Python program headless: the engine behind ``vgxsim run``.

A program written for CPython's historical IRIX binding does ``import gl, GL, DEVICE``
(or ``from gl import *``, and ``import fm`` for the Font Manager).  For the length of
the run those names are aliases of :mod:`vgxsim.gl`, :mod:`vgxsim.GL`,
:mod:`vgxsim.DEVICE` and :mod:`vgxsim.fm` in ``sys.modules``;
the previous entries (usually none) are put back afterwards.  The program runs as
``__main__`` with ``sys.argv = [program, *args]`` and its folder first on
``sys.path``, as ``python program.py`` would run it.  stdin, stdout and stderr are
the process's own.

Input comes from an event script (:mod:`vgxsim.events.script`) through the session's
event queue; frames go to sinks made by :class:`FrameRecorder` (one per window).
With ``window`` (``vgxsim run --window``) the same seams carry a real session: the
queue is fed by the user's input, each window's sink shows its frames in an SDL window
before the recorder gets them, and ``dopup`` draws its menu (:mod:`vgxsim.window`,
imported only then).

Exit status, as the program's own: ``sys.exit(n)`` gives ``n``; falling off the end
gives 0; an uncaught exception prints its traceback and gives 1; the end of the
scripted input (:class:`~vgxsim.events.ScriptExhausted`) is a clean end -- a note on
stderr and status 0 -- because a headless program waiting for input that can never
come has nothing left to do.

Runs that end.  ``max_frames`` ends the run at that many frames (swapbuffers, or a
single-buffered frame at gflush/finish); ``timeout`` seconds end it whatever the
program does -- looping without ever swapping, polling ``qtest``, sleeping.  SIGTERM
and SIGINT end it the same way.  The end always comes in the program's own code,
between two IRIS GL calls, never inside vgxsim (a signal that arrives inside a call
waits, a few milliseconds at a time, until the call returns), so no frame is ever
half written.  Then, as at any end, each window's screen goes to its sink if it has
changed (a single-buffered program's last picture; a window that produced no frame
yet produces one) and every sink is closed, so the files are complete.  A note on
stderr says why the run ended and how many frames were written.  Status: 0 for
``max_frames`` and ``timeout`` (limits the caller chose), 130 for SIGINT and 143 for
SIGTERM (128 + the signal number, as a shell reports a killed program).

Frames never lost.  Every sink tries its target before the program starts (see
:mod:`vgxsim.sinks`).  A frame that cannot be written ends the run at once with a
message naming the file and status 1 (the program cannot catch it with ``except
Exception``); so does a sink that cannot be completed at the end.
"""

from __future__ import annotations

import glob
import os
import runpy
import signal
import sys
import threading
import traceback
from contextlib import contextmanager
from os import PathLike

from vgxsim.events import EventQueue, EventSource, ScriptExhausted, load_script
from vgxsim.gl._core import GLError
from vgxsim.gl._window import MAX_WINDOW_SIZE
from vgxsim.sinks import FrameSink, PNGSequenceSink, SinkError, VideoSink, open_sink

__all__ = ["FrameRecorder", "run_program", "parse_size", "gl_modules", "RunEnded"]


def parse_size(text: str) -> tuple[int, int]:
    """Parse ``'WxH'`` (e.g. ``'640x512'``) into positive ints.

    Raises
    ------
    ValueError
        If the text is not two positive integers joined by ``x``, or a side is past
        the window limit (:data:`vgxsim.gl._window.MAX_WINDOW_SIZE`, 16384).
    """
    parts = text.lower().split("x")
    if len(parts) != 2 or not all(p.strip().isdigit() for p in parts):
        raise ValueError(f"size must look like WIDTHxHEIGHT (e.g. 640x512), got {text!r}")
    w, h = int(parts[0]), int(parts[1])
    if w <= 0 or h <= 0:
        raise ValueError(f"size must be positive, got {text!r}")
    if w > MAX_WINDOW_SIZE or h > MAX_WINDOW_SIZE:
        raise ValueError(f"size {text!r} is larger than the largest window, "
                         f"{MAX_WINDOW_SIZE}x{MAX_WINDOW_SIZE}")
    return w, h


class RunEnded(BaseException):
    """The run is ended from outside the program: a signal, the timeout, or a frame
    that could not be written.

    A BaseException, like :class:`SystemExit`, so the program's ``except Exception``
    cannot swallow it.

    Attributes
    ----------
    reason : str
        ``"timeout"``, ``"SIGINT"``, ``"SIGTERM"`` or ``"sink"``.
    status : int
        The exit status the run ends with.
    error : SinkError or None
        The write failure, for ``"sink"``.
    """

    def __init__(self, reason: str, status: int, error: SinkError | None = None):
        super().__init__(reason)
        self.reason = reason
        self.status = status
        self.error = error


class _RecordedSink:
    """A window's sink as the recorder hands it out: a write failure ends the run
    (RunEnded), and a failed sink takes no more frames."""

    def __init__(self, recorder: FrameRecorder, sink: FrameSink):
        self.recorder = recorder
        self.sink = sink
        self.failed = False

    def write(self, image) -> None:
        if self.failed:
            return
        try:
            self.sink.write(image)
        except SinkError as exc:
            self.failed = True
            self.recorder.errors.append(exc)
            raise RunEnded("sink", 1, exc) from exc


class FrameRecorder:
    """Makes each window's frame sink from one ``--frames`` specification.

    Window 1 gets exactly what :func:`vgxsim.sinks.open_sink` makes of the spec (a
    PNG directory ``frame_0000.png`` ..., or a ``.gif``/``.mp4`` file).  Further
    windows get their own: ``win<gid>_frame_0000.png`` in the same directory, or
    ``<name>_win<gid>.gif``.  With no spec, windows get no sink.

    The first sink is made at once, so a bad target fails before the program starts;
    an earlier run's output (frames in the folder, the video file or its
    ``_win<gid>`` siblings) is refused then, or with ``overwrite`` removed then, so
    two runs' frames are never mixed.

    Parameters
    ----------
    spec : str, path-like, FrameSink or None
        Where frames go.
    fps : float
        Frame rate of video files.
    overwrite : bool
        Replace an earlier run's output instead of refusing it.

    Attributes
    ----------
    errors : list of SinkError
        Write failures so far.
    """

    def __init__(self, spec: str | PathLike | FrameSink | None, fps: float = 30,
                 overwrite: bool = False):
        self.spec = spec
        self.fps = fps
        self.overwrite = overwrite
        self.sinks: dict[int, FrameSink] = {}
        self.errors: list[SinkError] = []
        self._handed: dict[int, _RecordedSink] = {}
        self._first = None if spec is None else open_sink(spec, fps=fps, overwrite=overwrite)
        if isinstance(self._first, VideoSink):
            self._clear_window_videos(self._first.path)

    def _clear_window_videos(self, path: str) -> None:
        stem, suffix = os.path.splitext(path)
        earlier = sorted(glob.glob(f"{glob.escape(stem)}_win[0-9]*{glob.escape(suffix)}"))
        if earlier and not self.overwrite:
            raise SinkError(f"{earlier[0]} exists (a window of an earlier run); give "
                            "--overwrite (overwrite=True) to replace it")
        for p in earlier:
            try:
                os.unlink(p)
            except OSError as exc:
                raise SinkError(f"cannot delete the earlier {p}: {exc}") from exc

    def __call__(self, gid: int) -> _RecordedSink | None:
        """The sink of window ``gid`` (the ``session.sink_factory`` interface)."""
        if self.spec is None:
            return None
        if gid in self._handed:
            return self._handed[gid]
        if not self.sinks:
            sink = self._first
        elif isinstance(self.spec, FrameSink):
            sink = None  # a ready sink serves the first window only
        else:
            first = next(iter(self.sinks.values()))
            # the first sink already checked for (and cleared) earlier output
            if isinstance(first, VideoSink):
                stem, suffix = os.path.splitext(first.path)
                sink = VideoSink(f"{stem}_win{gid}{suffix}", fps=self.fps, overwrite=True)
            else:
                sink = PNGSequenceSink(first.directory, f"win{gid}_frame_", overwrite=True)
        if sink is None:
            return None
        self.sinks[gid] = sink
        self._handed[gid] = _RecordedSink(self, sink)
        return self._handed[gid]

    @property
    def frames(self) -> int:
        """Frames written to every sink so far."""
        return sum(sink.count for sink in self.sinks.values())

    def close(self) -> None:
        """Finish every sink (video files are completed here); failures are added to
        :attr:`errors`, and every sink is closed whatever the others do."""
        sinks = list(self.sinks.values())
        if self._first is not None and not self.sinks:
            sinks.append(self._first)
        for sink in sinks:
            try:
                sink.close()
            except SinkError as exc:
                self.errors.append(exc)


class _RunStopper:
    """Ends the run on SIGTERM, SIGINT or the timeout alarm, in the program's code.

    The handler raises :class:`RunEnded` only when the interrupted Python frame and
    every frame between it and :func:`run_program` are outside vgxsim (the program,
    the standard library, other packages it calls).  Inside vgxsim -- a flush, a
    frame being written -- it notes the request and looks again every 5 ms, so the
    exception lands right after the IRIS GL call returns.  Signal handlers can only
    be set in the main thread; elsewhere the stopper does nothing (no timeout, the
    default signal behaviour).
    """

    _STATUS = {"timeout": 0, "SIGINT": 128 + signal.SIGINT, "SIGTERM": 128 + signal.SIGTERM}
    RETRY_S = 0.005

    def __init__(self, timeout: float | None, program: str):
        self.timeout = timeout
        self.pending: str | None = None
        self.armed = False
        self._saved: dict = {}
        self._dirs = _vgxsim_dirs()
        # programs shipped inside vgxsim (vgxsim/examples) are programs, not vgxsim
        examples = os.path.join(os.path.dirname(os.path.abspath(__file__)), "examples")
        self._programs = (os.path.abspath(program), examples + os.sep)

    def __enter__(self):
        if threading.current_thread() is not threading.main_thread():
            return self
        for sig in (signal.SIGTERM, signal.SIGINT, signal.SIGALRM):
            self._saved[sig] = signal.signal(sig, self._handler)
        if self.timeout is not None:
            signal.setitimer(signal.ITIMER_REAL, self.timeout)
        return self

    def __exit__(self, *exc_info) -> None:
        if self._saved:
            signal.setitimer(signal.ITIMER_REAL, 0)
            for sig, handler in self._saved.items():
                signal.signal(sig, handler)

    def _handler(self, signum, frame) -> None:
        if self.pending is None:
            self.pending = "timeout" if signum == signal.SIGALRM else signal.Signals(
                signum).name
        if not self.armed:
            return  # the program has ended: the runner finishes the sinks anyway
        if self._in_vgxsim(frame):
            signal.setitimer(signal.ITIMER_REAL, self.RETRY_S)
            return
        reason = self.pending
        raise RunEnded(reason, self._STATUS[reason])

    def _in_vgxsim(self, frame) -> bool:
        while frame is not None and frame.f_code is not run_program.__code__:
            name = os.path.abspath(frame.f_code.co_filename)
            if name.startswith(self._dirs) and not name.startswith(self._programs):
                return True
            frame = frame.f_back
        return False

    @property
    def status(self) -> int:
        return self._STATUS.get(self.pending, 0)

    def raise_pending(self) -> None:
        """End the run now if a signal or the timeout asked for it (called by vgxsim
        code that waits for the user, where the handler itself only takes a note)."""
        if self.pending is not None and self.armed:
            raise RunEnded(self.pending, self._STATUS[self.pending])


def _vgxsim_dirs() -> tuple[str, ...]:
    """Folders whose code the stopper never interrupts: vgxsim and its kernels."""
    import importlib.util

    dirs = [os.path.dirname(os.path.abspath(__file__))]
    spec = importlib.util.find_spec("vgxsim.kernels")
    if spec is not None and spec.submodule_search_locations:
        dirs.extend(os.path.abspath(d) for d in spec.submodule_search_locations)
    return tuple(d + os.sep for d in dirs)


@contextmanager
def gl_modules():
    """Make ``gl``, ``GL``, ``DEVICE`` and ``fm`` importable as the vgxsim modules, then restore
    ``sys.modules`` as it was."""
    import vgxsim.DEVICE
    import vgxsim.fm
    import vgxsim.GL
    import vgxsim.gl

    # fm: the Font Manager module of the same binding (vgxsim.fm).
    aliases = {"gl": vgxsim.gl, "GL": vgxsim.GL, "DEVICE": vgxsim.DEVICE, "fm": vgxsim.fm}
    saved = {name: sys.modules.get(name) for name in aliases}
    sys.modules.update(aliases)
    try:
        yield
    finally:
        for name, mod in saved.items():
            if mod is None:
                sys.modules.pop(name, None)
            else:
                sys.modules[name] = mod


def _exit_code(exc: SystemExit) -> int:
    """The status ``python`` itself would exit with for this SystemExit."""
    code = exc.code
    if code is None:
        return 0
    if isinstance(code, int):
        return code
    print(code, file=sys.stderr)
    return 1


def _report_gl_error(exc: BaseException, path: str) -> None:
    """Print a GLError as ``traceback`` would, keeping only frames outside vgxsim."""
    pkg = os.path.dirname(os.path.abspath(__file__))
    frames = [f for f in traceback.extract_tb(exc.__traceback__)
              if not os.path.abspath(f.filename).startswith(pkg)
              and not f.filename.startswith("<frozen")]
    print("Traceback (most recent call last):", file=sys.stderr)
    print("".join(traceback.format_list(frames)), end="", file=sys.stderr)
    print(f"{type(exc).__name__}: {exc}", file=sys.stderr)


def run_program(
    program: str | PathLike,
    args: list[str] | tuple[str, ...] = (),
    *,
    events: str | PathLike | EventSource | None = None,
    frames: str | PathLike | FrameSink | None = None,
    size: tuple[int, int] | None = None,
    max_frames: int | None = None,
    timeout: float | None = None,
    fps: float = 30,
    overwrite: bool = False,
    backend: str | None = None,
    sink_factory=None,
    window=None,
    record_events: str | PathLike | None = None,
) -> int:
    """Run an IRIS GL Python program headless (or in real windows) and return its exit
    status.

    Parameters
    ----------
    program : str or path-like
        The program file.
    args : sequence of str
        Its command-line arguments (``sys.argv[1:]``).
    events : str, path-like, EventSource or None
        Scripted input (an event-script file, or a ready source); None gives an
        empty queue, so the first blocking ``qread`` on an empty queue ends the run.
    frames : str, path-like, FrameSink or None
        Where frames go (see :class:`FrameRecorder`); None records nothing.
    size : (int, int), optional
        The size a user gives every window (default: none; windows opened without
        ``prefsize``/``prefposition`` are 640x512): such windows open at it, the
        others are reshaped to it at once and get REDRAW (gl/_window.py).
    max_frames : int, optional
        End the run after this many frames (for programs that never wait for input).
    timeout : float, optional
        End the run after this many seconds, whatever the program is doing.
    fps : float
        Frame rate of video output.
    overwrite : bool
        Replace an earlier run's output (video file, PNG frames) instead of refusing.
    backend : {'software', 'opengl'}, optional
        The backend for the run's windows (default: ``VGXSIM_BACKEND``, else
        software; see :mod:`vgxsim.backends`).
    sink_factory : callable, optional
        ``sink_factory(gid)`` gives window ``gid``'s sink instead of ``frames``
        (``vgxsim compare`` captures frames with their z and stencil planes).
    window : bool or WindowBackend, optional
        True: each IRIS GL window is a real window, input comes from the user
        (:mod:`vgxsim.window`, needs pygame-ce); ``frames`` then records what the
        windows showed.  A ready :class:`vgxsim.window.backend.WindowBackend` is used
        as it is (tests feed it synthesized input).  Not with ``events``.
    record_events : str or path-like, optional
        With ``window``: write the user's input as an events script that replays the
        session headless (``events=``).

    Returns
    -------
    int
        The exit status (see the module docstring).

    Raises
    ------
    SinkError, ValueError, ImportError
        Before the program starts, when ``frames`` cannot be written.
    ScriptError, OSError
        Before the program starts, when ``events`` cannot be read.

    Notes
    -----
    The process-wide gl session (:data:`vgxsim.gl._core.session`) is reset before
    and after the run: windows a caller had open are gone afterwards.
    """
    from vgxsim import backends
    from vgxsim.gl._core import session
    from vgxsim.gl._window import present_windows

    path = os.fspath(program)
    if timeout is not None and not timeout > 0:
        raise ValueError(f"timeout must be a positive number of seconds, got {timeout}")
    if window and events is not None:
        raise ValueError("a window run takes its input from the user: give events or "
                         "window, not both")
    if record_events is not None and not window:
        raise ValueError("record_events records a window session: give window=True")
    source = events if isinstance(events, EventSource) or events is None else load_script(
        events)
    recorder = FrameRecorder(frames, fps=fps, overwrite=overwrite)
    shown = None  # the real windows (vgxsim.window) of a --window run
    if window:  # imported only here: headless runs never load pygame
        from vgxsim.window.backend import WindowBackend

        shown = window if isinstance(window, WindowBackend) else WindowBackend(
            record_events, overwrite=overwrite, max_frames=max_frames)
    session.reset()
    if size is not None:
        session.default_size = (int(size[0]), int(size[1]))
        session.reshape_size = session.default_size  # prefsize'd windows are reshaped
    if shown is None:
        session.queue = EventQueue(source, max_frames=max_frames)
        session.sink_factory = recorder if sink_factory is None else sink_factory
    else:
        shown.install(session, recorder)
    saved_backend = backends.set_backend(backend) if backend is not None else None
    saved_argv, saved_path = sys.argv, list(sys.path)
    sys.argv = [path, *map(str, args)]
    sys.path.insert(0, os.path.dirname(os.path.abspath(path)))
    status = 0
    ended = None  # why the run was ended from outside, for the note
    stopper = _RunStopper(timeout, path)
    if shown is not None:  # a qread waiting for the user lets signals end the run
        shown.check_stop = stopper.raise_pending
    try:
        with stopper, gl_modules():
            try:
                stopper.armed = True
                try:
                    runpy.run_path(path, run_name="__main__")
                finally:
                    stopper.armed = False
            except SystemExit as exc:
                status = _exit_code(exc)
            except ScriptExhausted as exc:
                print(f"vgxsim run: {exc}; the run ends here (exit status 0)",
                      file=sys.stderr)
            except RunEnded as exc:
                ended = exc
                status = exc.status
            except KeyboardInterrupt:  # outside the main thread: no stopper
                status = 130
            except GLError as exc:
                # IRIS GL misuse: the program's own frames (file and line), then one
                # line naming the call -- not vgxsim's internals.
                _report_gl_error(exc, path)
                status = 1
            except Exception:  # the program's own error: report it as python would
                traceback.print_exc()
                status = 1
            try:
                present_windows(final=True)
            except RunEnded:
                status = 1  # a sink failed: reported below
            except Exception:
                traceback.print_exc()
                status = status or 1
            recorder.close()
            if ended is None and stopper.pending is not None:
                # a signal during the last frames: the run was ending anyway
                status = status or stopper.status
    finally:
        sys.argv = saved_argv
        sys.path[:] = saved_path
        try:
            recorder.close()
        finally:
            if shown is not None:
                shown.close()
            session.reset()
            if backend is not None:
                backends.set_backend(saved_backend)
    if recorder.errors:
        for exc in recorder.errors:
            print(f"vgxsim run: {exc}", file=sys.stderr)
        return status if status not in (0, 130, 143) else 1
    if ended is not None:
        what = {"timeout": f"the timeout of {timeout} s passed",
                "SIGINT": "SIGINT (interrupted)", "SIGTERM": "SIGTERM"}[ended.reason]
        n = recorder.frames
        print(f"vgxsim run: {what}; the run ends here after {n} frame{'s' * (n != 1)}, "
              f"every sink complete (exit status {status})", file=sys.stderr)
    return status
