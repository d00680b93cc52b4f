"""The ``vgxsim`` command.

::

    vgxsim --version
    vgxsim run PROGRAM.py [--events FILE] [--frames DIR|FILE.gif|FILE.mp4] [--size WxH]
                          [--max-frames N] [--timeout SECONDS] [--fps F] [--overwrite]
                          [--backend software|opengl]
                          [--window [--record DIR|FILE] [--record-events FILE]]
                          [-- PROGRAM ARGS...]
    vgxsim compare PROGRAM.py [--events FILE] [--size WxH] [--max-frames N]
                              [--tolerance F] [--levels L] [--z-units U] [--diff DIR]
                              [-- PROGRAM ARGS...]
    vgxsim render [--out PATH] [--size WxH] [--mode objects|volumes|shadows]
                  [--edges all|silhouette] [--overwrite]
    vgxsim shadows [SCENE] [-o OUT] [options]    (see vgxsim.shadow.command)
    vgxsim convert MESH OUT.glo [-f]
    vgxsim sweep CONFIG.toml [--scheduler ADDRESS | --local]   (see vgxsim.farm.command)

``run`` executes an IRIS GL Python program headless (see :mod:`vgxsim.runner`), or
with ``--window`` in real windows (:mod:`vgxsim.window`, needs ``vgxsim[window]``);
everything after ``--`` is passed to the program.  ``render`` draws Heidmann's 1991
scene with :mod:`vgxsim.examples.heidmann1991` and writes one image (PNG, JPEG or
TIFF, by the file name).

Outputs are never replaced silently: an existing ``--out`` file, ``--frames`` video
file or folder of an earlier run's frames is refused (status 2, before anything
runs) unless ``--overwrite`` is given.

``compare`` runs a program on the software and the OpenGL backend with the same input
and reports, per frame, the differing pixels of colour, z and stencil (see
:mod:`vgxsim.backends.compare`); its exit status is 1 past the tolerance.
"""

from __future__ import annotations

import argparse
import os
import sys

import vgxsim

__all__ = ["main", "build_parser"]


def _size(text: str) -> tuple[int, int]:
    from vgxsim.runner import parse_size

    try:
        return parse_size(text)
    except ValueError as exc:
        raise argparse.ArgumentTypeError(str(exc)) from None


def _positive_int(text: str) -> int:
    try:
        n = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a positive integer, got {text!r}") from None
    if n <= 0:
        raise argparse.ArgumentTypeError(f"expected a positive integer, got {text!r}")
    return n


def _positive_seconds(text: str) -> float:
    try:
        t = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a number of seconds, got {text!r}") from None
    if not t > 0 or t == float("inf"):
        raise argparse.ArgumentTypeError(f"expected a positive number of seconds, got {text!r}")
    return t


_OVERWRITE_HELP = ("replace an existing output (file, or a folder's frames of an earlier "
                   "run); without it an existing output is refused and nothing runs")


def _fraction(text: str) -> float:
    try:
        f = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a number in [0, 1], got {text!r}") from None
    if not 0.0 <= f <= 1.0:
        raise argparse.ArgumentTypeError(f"expected a number in [0, 1], got {text!r}")
    return f


def _count(text: str) -> int:
    try:
        n = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected an integer >= 0, got {text!r}") from None
    if n < 0:
        raise argparse.ArgumentTypeError(f"expected an integer >= 0, got {text!r}")
    return n


def add_window_options(parser: argparse.ArgumentParser) -> None:
    """``--window``, ``--record`` and ``--record-events`` (vgxsim run and shadows)."""
    parser.add_argument("--window", action="store_true",
                        help="show each IRIS GL window as a real window and take input from "
                             "the mouse and keyboard (needs pip install 'vgxsim[window]')")
    parser.add_argument("--record", metavar="DIR_OR_FILE",
                        help="where frames go, as --frames (with --window: what the windows "
                             "showed)")
    parser.add_argument("--record-events", metavar="FILE",
                        help="with --window: write the input as an events script that "
                             "replays the session headless (--events FILE)")


def window_problem(ns: argparse.Namespace) -> str | None:
    """Why the window options of ``ns`` cannot run, or None."""
    if getattr(ns, "frames", None) is not None and ns.record is not None:
        return "give --frames or --record, not both"
    if not ns.window:
        if ns.record_events is not None:
            return "--record-events records a --window session"
        return None
    if getattr(ns, "events", None) is not None:
        return "--window takes its input from the user: give --events or --window"
    if ns.record_events is not None and os.path.lexists(ns.record_events) \
            and not getattr(ns, "overwrite", False):
        return f"{ns.record_events} exists; give --overwrite to replace it"
    from vgxsim.window import available

    return available()


def build_parser() -> argparse.ArgumentParser:
    """The argument parser of the ``vgxsim`` command."""
    p = argparse.ArgumentParser(
        prog="vgxsim",
        description="Software emulation of the SGI IRIS GL / Power Series VGX pipeline.")
    p.add_argument("--version", action="version", version=f"vgxsim {vgxsim.__version__}")
    sub = p.add_subparsers(dest="command", metavar="COMMAND")

    run = sub.add_parser(
        "run", help="run an IRIS GL Python program headless",
        description="Run an IRIS GL Python program headless: `import gl, GL, DEVICE` "
                    "resolve to vgxsim for the run; arguments after `--` go to the program.")
    run.add_argument("program", help="the program file (PROGRAM.py)")
    run.add_argument("--events", metavar="FILE", help="event script standing in for the user")
    run.add_argument("--frames", metavar="DIR_OR_FILE",
                     help="where frames go: a directory (PNG files), a .gif or a .mp4; "
                          "written as they come, so a killed run keeps its frames")
    run.add_argument("--size", type=_size, metavar="WxH",
                     help="the size a user gives every window: windows opened without "
                          "prefsize open at it, the others are reshaped to it (REDRAW) "
                          "(default: none, 640x512 without prefsize; at most 16384x16384)")
    run.add_argument("--max-frames", type=_positive_int, metavar="N",
                     help="end the run after N frames")
    run.add_argument("--timeout", type=_positive_seconds, metavar="SECONDS",
                     help="end the run after SECONDS, whatever the program does (exit "
                          "status 0; SIGTERM gives 143, SIGINT 130); the frames so far "
                          "are kept and every sink completed")
    run.add_argument("--fps", type=float, default=30.0, help="video frame rate (default 30)")
    run.add_argument("--overwrite", action="store_true", help=_OVERWRITE_HELP)
    run.add_argument("--backend", choices=("software", "opengl"),
                     help="what draws: the software pipeline or OpenGL (default: "
                          "VGXSIM_BACKEND, else software)")
    add_window_options(run)

    cmp = sub.add_parser(
        "compare", help="run a program on both backends and compare its frames",
        description="Run an IRIS GL Python program on the software and the OpenGL backend "
                    "with the same scripted input; report per frame the pixels that "
                    "differ in colour, z and stencil, and the PSNR.  Exit status 1 when "
                    "a frame is past the tolerance.")
    cmp.add_argument("program", help="the program file (PROGRAM.py)")
    cmp.add_argument("--events", metavar="FILE", help="event script for both runs")
    cmp.add_argument("--size", type=_size, metavar="WxH",
                     help="size of windows opened without prefsize (default 640x512)")
    cmp.add_argument("--max-frames", type=_positive_int, metavar="N",
                     help="end each run after N frames")
    cmp.add_argument("--tolerance", type=_fraction, default=0.0, metavar="F",
                     help="fraction of a frame's pixels that may differ per plane "
                          "(default 0)")
    cmp.add_argument("--levels", type=_count, default=0, metavar="L",
                     help="colour differences up to L levels do not count (default 0)")
    cmp.add_argument("--z-units", type=_count, default=0, metavar="U",
                     help="z differences up to U units do not count (default 0)")
    cmp.add_argument("--diff", metavar="DIR",
                     help="write a difference image per frame (diff_0000.png ...)")

    render = sub.add_parser(
        "render", help="render Heidmann's 1991 shadow scene to an image",
        description="Render the scene of Heidmann's 1991 `shadows` program to one image.")
    render.add_argument("--out", default="heidmann1991.png", metavar="PATH",
                        help="output image, .png, .jpg or .tif (default heidmann1991.png)")
    render.add_argument("--size", type=_size, default=(640, 512), metavar="WxH",
                        help="image size (default 640x512)")
    render.add_argument("--mode", choices=("objects", "volumes", "shadows"),
                        default="shadows", help="display mode (default shadows)")
    render.add_argument("--edges", choices=("all", "silhouette"), default="silhouette",
                        help="shadow-volume edges (default silhouette)")
    render.add_argument("--overwrite", action="store_true", help=_OVERWRITE_HELP)

    from vgxsim.shadow.command import add_parsers  # shadows, convert

    add_parsers(sub, _size, _positive_int)
    from vgxsim.farm.command import add_sweep_parser

    add_sweep_parser(sub)
    return p


def _run(ns: argparse.Namespace, program_args: list[str]) -> int:
    from vgxsim.events import ScriptError
    from vgxsim.runner import run_program
    from vgxsim.sinks import SinkError

    if not os.path.isfile(ns.program):
        print(f"vgxsim run: no such program file: {ns.program}", file=sys.stderr)
        return 2
    if ns.events is not None and not os.path.isfile(ns.events):
        print(f"vgxsim run: no such event script: {ns.events}", file=sys.stderr)
        return 2
    if ns.backend == "opengl":
        from vgxsim.backends.opengl.surface import available

        if not available():
            print("vgxsim run: the opengl backend needs PyOpenGL and libOSMesa "
                  "(pip install 'vgxsim[opengl]'; apt install libosmesa6)", file=sys.stderr)
            return 2
    problem = window_problem(ns)
    if problem is not None:
        print(f"vgxsim run: {problem}", file=sys.stderr)
        return 2
    try:
        return run_program(ns.program, program_args, events=ns.events,
                           frames=ns.frames if ns.record is None else ns.record,
                           size=ns.size, max_frames=ns.max_frames, timeout=ns.timeout,
                           fps=ns.fps, overwrite=ns.overwrite, backend=ns.backend,
                           window=ns.window, record_events=ns.record_events)
    except ScriptError as exc:
        print(f"vgxsim run: bad event script: {exc}", file=sys.stderr)
        return 2
    except (SinkError, ImportError, ValueError) as exc:
        print(f"vgxsim run: cannot record frames: {exc}", file=sys.stderr)
        return 2
    except OSError as exc:  # the events file could not be read
        print(f"vgxsim run: cannot read the event script {ns.events}: {exc}",
              file=sys.stderr)
        return 2


def _compare(ns: argparse.Namespace, program_args: list[str]) -> int:
    from vgxsim.backends import BackendError
    from vgxsim.backends.compare import compare_program
    from vgxsim.events import ScriptError

    if not os.path.isfile(ns.program):
        print(f"vgxsim compare: no such program file: {ns.program}", file=sys.stderr)
        return 2
    if ns.events is not None and not os.path.isfile(ns.events):
        print(f"vgxsim compare: no such event script: {ns.events}", file=sys.stderr)
        return 2
    try:
        return compare_program(ns.program, program_args, events=ns.events, size=ns.size,
                               max_frames=ns.max_frames, levels=ns.levels,
                               z_units=ns.z_units, tolerance=ns.tolerance, diff_dir=ns.diff)
    except ScriptError as exc:
        print(f"vgxsim compare: bad event script: {exc}", file=sys.stderr)
        return 2
    except BackendError as exc:
        print(f"vgxsim compare: {exc}", file=sys.stderr)
        return 2


def _render(ns: argparse.Namespace) -> int:
    from vgxsim.sinks import SinkError, to_top_down, write_image
    from vgxsim.sinks.images import image_format

    try:  # a bad name or an existing file fails before the render, not after it
        image_format(ns.out)
        if os.path.lexists(ns.out) and not ns.overwrite:
            raise SinkError(f"{ns.out} exists; give --overwrite to replace it")
    except SinkError as exc:
        print(f"vgxsim render: {exc}", file=sys.stderr)
        return 2

    try:
        from vgxsim.examples import heidmann1991
    except ModuleNotFoundError as exc:
        if exc.name not in ("vgxsim.examples.heidmann1991", "vgxsim.examples"):
            raise
        print("vgxsim render: the example module vgxsim.examples.heidmann1991 is not "
              "available in this installation, so there is nothing to render",
              file=sys.stderr)
        return 1
    w, h = ns.size
    image = heidmann1991.render(w, h, ns.mode, ns.edges)
    try:
        write_image(ns.out, to_top_down(image, alpha=False), overwrite=ns.overwrite)
    except SinkError as exc:
        print(f"vgxsim render: {exc}", file=sys.stderr)
        return 1
    print(f"wrote {ns.out} ({w}x{h}, mode {ns.mode}, edges {ns.edges})")
    return 0


def main(argv: list[str] | None = None) -> int:
    """Entry point of the ``vgxsim`` console script.

    Parameters
    ----------
    argv : list of str, optional
        Arguments without the program name (default ``sys.argv[1:]``).

    Returns
    -------
    int
        Exit status.
    """
    argv = list(sys.argv[1:] if argv is None else argv)
    program_args: list[str] = []
    if "--" in argv:  # everything after the first "--" belongs to the program
        i = argv.index("--")
        argv, program_args = argv[:i], argv[i + 1:]
    parser = build_parser()
    ns = parser.parse_args(argv)
    if ns.command == "run":
        return _run(ns, program_args)
    if ns.command == "compare":
        return _compare(ns, program_args)
    if ns.command == "render":
        if program_args:
            parser.error("render takes no arguments after --")
        return _render(ns)
    if ns.command in ("shadows", "convert"):
        from vgxsim.shadow.command import run_convert, run_shadows

        if program_args:
            parser.error(f"{ns.command} takes no arguments after --")
        return run_shadows(ns) if ns.command == "shadows" else run_convert(ns)
    if ns.command == "sweep":
        from vgxsim.farm.command import run_sweep_command

        return run_sweep_command(ns)
    parser.print_help(sys.stderr)
    return 2


if __name__ == "__main__":
    sys.exit(main())
