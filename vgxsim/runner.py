"""Run an IRIS GL Python program headless: the engine behind ``vgxsim run``.

A program written for CPython's historical IRIX binding does ``import gl, GL, DEVICE``
(or ``from gl import *``).  For the length of the run those three names are aliases
of :mod:`vgxsim.gl`, :mod:`vgxsim.GL` and :mod:`vgxsim.DEVICE` in ``sys.modules``;
the previous entries (usually none) are put back afterwards.  The program runs as
``__main__`` with ``sys.argv = [program, *args]`` and its folder first on
``sys.path``, as ``python program.py`` would run it.  stdin, stdout and stderr are
the process's own.

Input comes from an event script (:mod:`vgxsim.events.script`) through the session's
event queue; frames go to sinks made by :class:`FrameRecorder` (one per window).

Exit status, as the program's own: ``sys.exit(n)`` gives ``n``; falling off the end
gives 0; an uncaught exception prints its traceback and gives 1; the end of the
scripted input (:class:`~vgxsim.events.ScriptExhausted`) is a clean end -- a note on
stderr and status 0 -- because a headless program waiting for input that can never
come has nothing left to do.
"""

from __future__ import annotations

import os
import runpy
import sys
import traceback
from contextlib import contextmanager
from os import PathLike

from vgxsim.events import EventQueue, EventSource, ScriptExhausted, load_script
from vgxsim.gl._core import GLError
from vgxsim.sinks import FrameSink, PNGSequenceSink, VideoSink, open_sink

__all__ = ["FrameRecorder", "run_program", "parse_size", "gl_modules"]


def parse_size(text: str) -> tuple[int, int]:
    """Parse ``'WxH'`` (e.g. ``'640x512'``) into positive ints.

    Raises
    ------
    ValueError
        If the text is not two positive integers joined by ``x``.
    """
    parts = text.lower().split("x")
    if len(parts) != 2 or not all(p.strip().isdigit() for p in parts):
        raise ValueError(f"size must look like WIDTHxHEIGHT (e.g. 640x512), got {text!r}")
    w, h = int(parts[0]), int(parts[1])
    if w <= 0 or h <= 0:
        raise ValueError(f"size must be positive, got {text!r}")
    return w, h


class FrameRecorder:
    """Makes each window's frame sink from one ``--frames`` specification.

    Window 1 gets exactly what :func:`vgxsim.sinks.open_sink` makes of the spec (a
    PNG directory ``frame_0000.png`` ..., or a ``.gif``/``.mp4`` file).  Further
    windows get their own: ``win<gid>_frame_0000.png`` in the same directory, or
    ``<name>_win<gid>.gif``.  With no spec, windows get no sink.

    Parameters
    ----------
    spec : str, path-like, FrameSink or None
        Where frames go.
    fps : float
        Frame rate of video files.
    """

    def __init__(self, spec: str | PathLike | FrameSink | None, fps: float = 30):
        self.spec = spec
        self.fps = fps
        self.sinks: dict[int, FrameSink] = {}
        # The first window's sink is made now, so a bad spec (out.png, .mp4 without
        # imageio-ffmpeg) fails before the program starts, not inside its winopen.
        self._first = None if spec is None else open_sink(spec, fps=fps)

    def __call__(self, gid: int) -> FrameSink | None:
        """The sink of window ``gid`` (the ``session.sink_factory`` interface)."""
        if self.spec is None:
            return None
        if gid in self.sinks:
            return self.sinks[gid]
        if not self.sinks:
            sink = self._first
        elif isinstance(self.spec, FrameSink):
            sink = None  # a ready sink serves the first window only
        else:
            first = next(iter(self.sinks.values()))
            if isinstance(first, VideoSink):
                stem, suffix = os.path.splitext(first.path)
                sink = VideoSink(f"{stem}_win{gid}{suffix}", fps=self.fps)
            else:
                sink = PNGSequenceSink(first.directory, f"win{gid}_frame_")
        if sink is not None:
            self.sinks[gid] = sink
        return sink

    def close(self) -> None:
        """Finish every sink (video files are completed here)."""
        for sink in self.sinks.values():
            sink.close()
        if self._first is not None and not self.sinks:
            self._first.close()


@contextmanager
def gl_modules():
    """Make ``gl``, ``GL`` and ``DEVICE`` importable as the vgxsim modules, then restore
    ``sys.modules`` as it was."""
    import vgxsim.DEVICE
    import vgxsim.GL
    import vgxsim.gl

    aliases = {"gl": vgxsim.gl, "GL": vgxsim.GL, "DEVICE": vgxsim.DEVICE}
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
    fps: float = 30,
    backend: str | None = None,
    sink_factory=None,
) -> int:
    """Run an IRIS GL Python program headless and return its exit status.

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
        Size of windows opened without ``prefsize``/``prefposition`` (default 640x512).
    max_frames : int, optional
        End the run after this many frames (for programs that never wait for input).
    fps : float
        Frame rate of video output.
    backend : {'software', 'opengl'}, optional
        The backend for the run's windows (default: ``VGXSIM_BACKEND``, else
        software; see :mod:`vgxsim.backends`).
    sink_factory : callable, optional
        ``sink_factory(gid)`` gives window ``gid``'s sink instead of ``frames``
        (``vgxsim compare`` captures frames with their z and stencil planes).

    Returns
    -------
    int
        The exit status (see the module docstring).

    Notes
    -----
    The process-wide gl session (:data:`vgxsim.gl._core.session`) is reset before
    and after the run: windows a caller had open are gone afterwards.
    """
    from vgxsim import backends
    from vgxsim.gl._core import session
    from vgxsim.gl._window import present_windows

    path = os.fspath(program)
    source = events if isinstance(events, EventSource) or events is None else load_script(
        events)
    recorder = FrameRecorder(frames, fps=fps)
    session.reset()
    if size is not None:
        session.default_size = (int(size[0]), int(size[1]))
    session.queue = EventQueue(source, max_frames=max_frames)
    session.sink_factory = recorder if sink_factory is None else sink_factory
    saved_backend = backends.set_backend(backend) if backend is not None else None
    saved_argv, saved_path = sys.argv, list(sys.path)
    sys.argv = [path, *map(str, args)]
    sys.path.insert(0, os.path.dirname(os.path.abspath(path)))
    status = 0
    try:
        with gl_modules():
            try:
                runpy.run_path(path, run_name="__main__")
            except SystemExit as exc:
                status = _exit_code(exc)
            except ScriptExhausted as exc:
                print(f"vgxsim run: {exc}; the run ends here (exit status 0)",
                      file=sys.stderr)
            except KeyboardInterrupt:
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
            except Exception:
                traceback.print_exc()
                status = status or 1
    finally:
        sys.argv = saved_argv
        sys.path[:] = saved_path
        try:
            recorder.close()
        finally:
            session.reset()
            if backend is not None:
                backends.set_backend(saved_backend)
    return status
