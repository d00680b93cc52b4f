"""``vgxsim shadows`` and ``vgxsim convert``: the command line over :mod:`.api`.

The original program was interactive (mouse trackball, pop-up menu); its
"command-line options ... designed primarily to allow for generation of specific
images from a shell script" (README) are what remains here, headless::

    vgxsim shadows [SCENE] [-o OUT] [--size WxH] [--mode objects|volumes|mask|shadows]
                   [--light N] [--soft [N|figure6]] [--soft-max N] [--seed N]
                   [--rotate AZ,EL] [--translate X,Y] [--dolly D] [--spin N] [--fps F]
                   [--subpixel on|off] [--edges silhouette|all] [--signs screen|article]
                   [--technique NAME] [--option KEY=VALUE ...]
                   [--scheduler ADDRESS | --local] [--workers N]
    vgxsim shadows [SCENE] --window [--record DIR|FILE] [--record-events FILE] [options]
    vgxsim shadows [SCENE] --events FILE [--record DIR|FILE] [options]
    vgxsim convert MESH OUT [-f] [--normals none|face|vertex]

``--window`` runs the original's interactive program (trackball, translate, dolly,
spin, the right-button menu of display modes and soft shadows;
``vgxsim/examples/shadows_interactive.py``) in a real window, starting in "Show Objects
Only" as the original did; ``--record-events`` writes the session's input, and
``--events FILE`` plays such a script to the same program headless (``--record`` the
frames of either).

SCENE is a ``.scn`` file or the name of a shipped scene (cubes, balls,
textured_floor, dense, teapot); without it, the three cubes.  Errors in a scene or
model name the file and line and exit with status 1; nothing is written then.
Outputs are written atomically.  ``--spin`` and ``--soft`` run as Dask tasks
(:mod:`vgxsim.farm`: an embedded LocalCluster, or ``--scheduler``; the same pixels);
``--local`` keeps them in this process, with the soft shadows' intermediate images.
"""

from __future__ import annotations

import argparse
import os
import sys
import warnings

STATUS_BAD_INPUT = 1


def _pair(text: str) -> tuple[float, float]:
    parts = text.replace(" ", "").split(",")
    try:
        a, b = (float(p) for p in parts)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected two numbers A,B, got {text!r}") from None
    return a, b


def _soft(text: str) -> int | str:
    from .api import SOFT_PRESETS

    if text in SOFT_PRESETS:
        return text
    try:
        n = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"expected a frame count or a preset ({', '.join(SOFT_PRESETS)}), got {text!r}"
        ) from None
    if n < 1:
        raise argparse.ArgumentTypeError(f"expected at least 1 frame, got {n}")
    return n


def _on_off(text: str) -> bool:
    if text.lower() not in ("on", "off"):
        raise argparse.ArgumentTypeError(f"expected on or off, got {text!r}")
    return text.lower() == "on"


def add_parsers(sub, size_type, positive_int) -> None:
    """Add the ``shadows`` and ``convert`` subcommands to the ``vgxsim`` parser."""
    from .api import SOFT_MAX_DEFAULT
    from .program import EDGES, MODES, SIGNS

    sh = sub.add_parser(
        "shadows", help="Heidmann's shadows program: render a .scn scene to an image",
        description="Render a scene of Heidmann's 1991 `shadows` program (stencil shadow "
                    "volumes) to a PNG, or a spin to a GIF/MP4.  SCENE: a .scn file or a "
                    "shipped scene name (cubes, balls, textured_floor, dense, teapot); "
                    "default: three cubes and a red and a blue light.")
    sh.add_argument("scene", nargs="?", metavar="SCENE", help="scene file or shipped name")
    sh.add_argument("-o", "--output", metavar="PATH",
                    help="output image (default shadows.png; with --spin spin.gif)")
    sh.add_argument("--size", type=size_type, default=(640, 512), metavar="WxH",
                    help="image size (default 640x512)")
    sh.add_argument("--mode", choices=MODES, default=None,
                    help="display mode (README: Show Objects Only / Volumes / Mask / "
                         "Shadows; default shadows, interactive: objects)")
    sh.add_argument("--light", type=int, default=0, metavar="N",
                    help="the light whose volumes and mask are shown (default 0)")
    sh.add_argument("--soft", type=_soft, nargs="?", const="max", default=None,
                    metavar="N|figure6",
                    help="soft shadows: jitter the JITTER lights and accumulate N frames "
                         "(no N: --soft-max; figure6: the article's 32)")
    sh.add_argument("--soft-max", type=positive_int, default=SOFT_MAX_DEFAULT, metavar="N",
                    help=f"most frames soft shadows accumulate (default {SOFT_MAX_DEFAULT}); "
                         "intermediate results are written after 1, 2, 4, 8, ... frames")
    sh.add_argument("--seed", type=int, default=1991, help="jitter random seed (default 1991)")
    sh.add_argument("--rotate", type=_pair, default=(0.0, 0.0), metavar="AZ,EL",
                    help="turn the view: degrees of azimuth and elevation (trackball); "
                         "negative first: --rotate=-30,10")
    sh.add_argument("--translate", type=_pair, default=(0.0, 0.0), metavar="X,Y",
                    help="shift the view right and up, in scene units")
    sh.add_argument("--dolly", type=float, default=0.0, metavar="D",
                    help="track into (D > 0) or out of the scene, in scene units")
    sh.add_argument("--spin", type=positive_int, metavar="N",
                    help="a full turn in N frames, written as .gif or .mp4 (-o)")
    sh.add_argument("--fps", type=float, default=15.0, help="spin frame rate (default 15)")
    sh.add_argument("--subpixel", type=_on_off, default=False, metavar="on|off",
                    help="subpixel(TRUE): keep sub-pixel vertex positions (IRIS default off: "
                         "vertices snap to pixel centres)")
    sh.add_argument("--edges", choices=EDGES, default="silhouette",
                    help="shadow faces from silhouette edges or every edge")
    sh.add_argument("--signs", choices=SIGNS, default="screen",
                    help="INCR/DECR per face from the rasterizer's facing (screen, default) "
                         "or the article's 3-D test (article)")
    from .techniques import TECHNIQUES

    sh.add_argument("--technique", choices=tuple(TECHNIQUES), default=None,
                    help="a shadow technique since 1991 for the shadows mode (default: the "
                         "1991 code as printed)")
    sh.add_argument("--option", action="append", default=[], metavar="KEY=VALUE",
                    help="an option of the technique, e.g. --option size=1024 (numbers, "
                         "true/false and none are converted)")
    sh.add_argument("--no-cache", action="store_true",
                    help="rebuild model adjacency instead of using the cache")
    sh.add_argument("--overwrite", action="store_true",
                    help="replace an existing output file or earlier recording (without "
                         "it, one is refused before anything is drawn)")
    from vgxsim.farm.command import add_scheduler_options

    add_scheduler_options(sh)  # where --spin frames and --soft samples run
    from vgxsim.cli import add_window_options

    add_window_options(sh)
    sh.add_argument("--events", metavar="FILE",
                    help="run the interactive program headless with this events script "
                         "(e.g. one written by --record-events)")
    sh.add_argument("--timeout", type=float, default=None, metavar="SECONDS",
                    help="with --window or --events: end the session after SECONDS")

    cv = sub.add_parser(
        "convert", help="convert a mesh (OBJ, STL, PLY, OFF, GLB, .glo) to .glo or a cache",
        description="Convert a mesh that trimesh reads (or a .glo) to .glo / .glo.gz, or "
                    "to a standalone adjacency cache (.npz): the roles of the original "
                    "bintoglo and glotopdat.")
    cv.add_argument("mesh", metavar="MESH")
    cv.add_argument("out", metavar="OUT", help="output .glo, .glo.gz or .npz")
    cv.add_argument("-f", "--flip", action="store_true",
                    help="reverse every polygon's vertex order (README's -f)")
    cv.add_argument("--normals", choices=("none", "face", "vertex"), default="none",
                    help="normals to store in the .glo (default none: one per polygon, "
                         "computed when drawn)")
    cv.add_argument("--overwrite", action="store_true",
                    help="replace an existing OUT (without it, one is refused)")


def _progress(total: int):
    from tqdm import tqdm

    # disable=None: a bar only when stderr is a terminal
    return tqdm(total=total, desc="soft shadows", unit="frame", disable=None, file=sys.stderr)


def run_interactive(ns: argparse.Namespace) -> int:
    """``vgxsim shadows --window`` / ``--events``: the interactive program through the
    runner (on screen, or headless from a script)."""
    from vgxsim.cli import window_problem
    from vgxsim.events import ScriptError
    from vgxsim.runner import run_program
    from vgxsim.sinks import SinkError

    prog = "vgxsim shadows"
    problem = window_problem(ns)
    if problem is not None:
        print(f"{prog}: {problem}", file=sys.stderr)
        return 2
    if ns.events is not None and not os.path.isfile(ns.events):
        print(f"{prog}: no such event script: {ns.events}", file=sys.stderr)
        return 2
    here = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    program = os.path.join(here, "examples", "shadows_interactive.py")
    args = [*([ns.scene] if ns.scene else []), "--mode", ns.mode or "objects",
            "--seed", str(ns.seed), "--edges", ns.edges, "--signs", ns.signs,
            "--soft-max", str(ns.soft_max if ns.soft in (None, "max") else
                              min(ns.soft_max, api_frames(ns.soft)))]
    if ns.soft is not None:
        args.append("--soft")
    try:
        return run_program(program, args, events=ns.events, frames=ns.record, size=ns.size,
                           timeout=ns.timeout, overwrite=ns.overwrite, window=ns.window,
                           record_events=ns.record_events)
    except ScriptError as exc:
        print(f"{prog}: bad event script: {exc}", file=sys.stderr)
        return 2
    except (SinkError, ImportError, ValueError) as exc:
        print(f"{prog}: cannot record: {exc}", file=sys.stderr)
        return 2


def api_frames(soft) -> int:
    from .api import _frames_for

    return _frames_for(soft)


def _technique_options(items: list[str]) -> dict:
    """``KEY=VALUE`` strings to keyword options (int, float, bool, None or str)."""
    out: dict = {}
    for item in items:
        key, sep, text = item.partition("=")
        if not sep or not key:
            raise ValueError(f"expected KEY=VALUE, got {item!r}")
        low = text.lower()
        value: object = text
        if low in ("true", "false"):
            value = low == "true"
        elif low == "none":
            value = None
        else:
            for conv in (int, float):
                try:
                    value = conv(text)
                    break
                except ValueError:
                    pass
        out[key] = value
    return out


def run_shadows(ns: argparse.Namespace) -> int:
    """Carry out ``vgxsim shadows``; returns the exit status."""
    from dataclasses import replace

    if ns.window or ns.events is not None or ns.record_events is not None:
        return run_interactive(ns)
    if ns.record is not None:
        print("vgxsim shadows: --record records a --window or --events session (-o names "
              "the headless image)", file=sys.stderr)
        return 2
    ns.mode = ns.mode or "shadows"

    from vgxsim.formats import FormatError

    from . import api

    prog = "vgxsim shadows"
    out = ns.output or ("spin.gif" if ns.spin else "shadows.png")
    if ns.spin and not out.lower().endswith((".gif", ".mp4")):
        print(f"{prog}: --spin writes an animation: -o must end in .gif or .mp4, not {out!r}",
              file=sys.stderr)
        return 2
    if not ns.spin and out.lower().endswith((".gif", ".mp4")):
        print(f"{prog}: {out!r} is an animation file: add --spin N", file=sys.stderr)
        return 2
    folder = os.path.dirname(os.path.abspath(out))
    if not os.path.isdir(folder):
        print(f"{prog}: the output folder {folder} does not exist", file=sys.stderr)
        return 2
    problem = _output_problem(out, ns.overwrite)
    if problem:
        print(f"{prog}: {problem}", file=sys.stderr)
        return 2
    # With an empty Numba cache: the band kernel compiles here while the helper of
    # vgxsim/coldstart.py compiles the geometry kernels, the scene's edge adjacency
    # among them (which would otherwise compile first, alone, in this process).
    from vgxsim import coldstart
    from vgxsim.batch import CommandBatch

    coldstart.prepare(CommandBatch)
    try:
        scene = api.load_scene(ns.scene, use_cache=not ns.no_cache)
    except FormatError as exc:
        print(f"{prog}: {exc}", file=sys.stderr)
        return STATUS_BAD_INPUT
    if not 0 <= ns.light < len(scene.lights):
        print(f"{prog}: --light {ns.light}: the scene has lights 0..{len(scene.lights) - 1}",
              file=sys.stderr)
        return 2
    cam = api.orbit(scene.camera, ns.rotate, ns.translate, ns.dolly)
    scene = replace(scene, camera=cam)
    soft = 0
    if ns.soft is not None:
        soft = ns.soft_max if ns.soft == "max" else api._frames_for(ns.soft)
        soft = min(soft, ns.soft_max)
        if not any(lt.jitterable for lt in scene.lights):
            print(f"{prog}: note: no light of this scene has JITTER, so soft shadows look "
                  "hard", file=sys.stderr)
    try:
        options = _technique_options(ns.option)
    except ValueError as exc:
        print(f"{prog}: --option: {exc}", file=sys.stderr)
        return 2
    kw = dict(mode=ns.mode, size=ns.size, light=ns.light, seed=ns.seed, edges=ns.edges,
              subpixel=ns.subpixel, signs=ns.signs)
    if ns.technique is not None:
        from .techniques import TechniqueError, make

        try:
            make(ns.technique, **options)
        except TechniqueError as exc:
            print(f"{prog}: --technique {ns.technique}: {exc}", file=sys.stderr)
            return 2
        kw.update(technique=ns.technique, technique_options=options)
    farmed = bool(ns.spin or soft) and not ns.local
    try:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always", api.ViewpointInShadowWarning)
            if farmed:  # vgxsim.farm: the same arrays, computed as Dask tasks
                from vgxsim.farm.command import run_farmed_shadows

                result = run_farmed_shadows(ns, scene, soft, kw)
            if ns.spin:
                frames = result if farmed else api.render_spin(scene, ns.spin, soft=soft,
                                                               **kw)
                api.write_animation(out, frames, ns.fps)
                what = f"{ns.spin} frames"
            else:
                bar = _progress(soft) if soft and not farmed else None
                checkpoints = {1 << k for k in range(16)}

                def intermediate(n: int, colour) -> None:
                    if bar is not None:
                        bar.update(1)
                    if n in checkpoints and n < soft:  # README: "intermediate results"
                        api.write_image(out, colour)

                try:
                    frame = result if farmed else api.render(
                        scene, soft=soft, on_soft_frame=intermediate if soft else None, **kw)
                finally:
                    if bar is not None:
                        bar.close()
                api.write_image(out, frame.colour)
                what = f"{soft} soft-shadow frames" if soft else f"mode {ns.mode}"
    except (OSError, ImportError, ValueError) as exc:
        # e.g. a read-only folder, or .mp4 without imageio-ffmpeg: nothing half-written
        print(f"{prog}: cannot write {out}: {exc}", file=sys.stderr)
        return STATUS_BAD_INPUT
    for w in caught:
        if issubclass(w.category, api.ViewpointInShadowWarning):
            print(f"{prog}: warning: {w.message}", file=sys.stderr)
    width, height = ns.size
    print(f"wrote {out} ({width}x{height}, {what}, {len(scene.objects)} objects, "
          f"{len(scene.lights)} lights)")
    return 0


def _output_problem(path: str, overwrite: bool) -> str | None:
    """Why ``path`` cannot be written (the rule of every vgxsim output: an existing
    file is replaced only with --overwrite; the target is tried before any work),
    or None."""
    from vgxsim.sinks import SinkError
    from vgxsim.sinks.images import check_writable_file

    try:
        check_writable_file(path, overwrite)
    except SinkError as exc:
        return str(exc).replace("(overwrite=True) ", "")
    return None


def run_convert(ns: argparse.Namespace) -> int:
    """Carry out ``vgxsim convert``; returns the exit status."""
    from vgxsim.formats import FormatError
    from vgxsim.formats.convert import convert

    problem = _output_problem(ns.out, ns.overwrite)
    if problem:
        print(f"vgxsim convert: {problem}", file=sys.stderr)
        return 2
    try:
        model = convert(ns.mesh, ns.out, flip=ns.flip, normals=ns.normals)
    except FormatError as exc:
        print(f"vgxsim convert: {exc}", file=sys.stderr)
        return STATUS_BAD_INPUT
    print(f"wrote {ns.out} ({len(model.vertices)} vertices, {len(model.poly_start) - 1} "
          f"polygons{', reversed' if ns.flip else ''})")
    return 0
