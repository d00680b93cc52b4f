"""Command-line side of the farm: ``vgxsim sweep`` and the ``--scheduler`` / ``--local``
options that ``vgxsim shadows --spin/--soft`` share.

::

    vgxsim sweep CONFIG.toml [--report PREFIX] [--scheduler ADDRESS | --local]
                 [--workers N] [--dry-run]
    vgxsim sweep --example            # print a config to start from

Exit status: 0 when every point rendered, 1 when some failed (the report says which,
with their scene and settings), 2 for a bad config or options.
"""

from __future__ import annotations

import argparse
import os
import sys

STATUS_FAILED_POINTS = 1
STATUS_USAGE = 2


def add_scheduler_options(parser: argparse.ArgumentParser) -> None:
    """``--scheduler``, ``--local`` and ``--workers`` (sweep, shadows --spin/--soft)."""
    where = parser.add_mutually_exclusive_group()
    where.add_argument("--scheduler", metavar="ADDRESS",
                       help="Dask scheduler to run on (tcp://host:8786); default: an "
                            "embedded LocalCluster, one single-threaded worker per core")
    where.add_argument("--local", action="store_true",
                       help="run in this process, without Dask")
    parser.add_argument("--workers", type=int, metavar="N",
                        help="workers of the embedded LocalCluster (default: one per core)")


def executor_for(ns: argparse.Namespace, prog: str, progress: bool = True):
    """The executor the options ask for; without Dask installed, in-process with a note
    (an explicit --scheduler without Dask is an error)."""
    from .executor import DaskExecutor, LocalExecutor

    if ns.local:
        return LocalExecutor(progress=progress)
    try:
        import distributed  # noqa: F401
    except ImportError:
        if ns.scheduler:
            raise SystemExit(f"{prog}: --scheduler needs Dask: pip install 'vgxsim[dask]'"
                             ) from None
        print(f"{prog}: note: Dask is not installed, running in-process "
              "(pip install 'vgxsim[dask]' for a cluster)", file=sys.stderr)
        return LocalExecutor(progress=progress)
    return DaskExecutor(ns.scheduler, n_workers=ns.workers, progress=progress)


def add_sweep_parser(sub) -> None:
    """Add the ``sweep`` subcommand to the ``vgxsim`` parser."""
    sw = sub.add_parser(
        "sweep", help="render a grid of scenes x settings on a Dask cluster, with a report",
        description="Render every point of a grid (scenes x keyword arguments of "
                    "vgxsim.shadow.api.render) as farm tasks and write a report "
                    "(CSV and markdown: settings, worker, render and compile seconds, "
                    "digests of the planes, failures).")
    sw.add_argument("config", nargs="?", metavar="CONFIG.toml")
    sw.add_argument("--report", metavar="PREFIX",
                    help="write PREFIX.csv and PREFIX.md (default: CONFIG's name + "
                         "'-report', beside it)")
    sw.add_argument("--dry-run", action="store_true", help="list the points, render nothing")
    sw.add_argument("--example", action="store_true", help="print an example config")
    add_scheduler_options(sw)


def run_sweep_command(ns: argparse.Namespace) -> int:
    """Carry out ``vgxsim sweep``; returns the exit status."""
    from . import sweep

    prog = "vgxsim sweep"
    if ns.example:
        sys.stdout.write(sweep.example_config())
        return 0
    if ns.config is None:
        print(f"{prog}: give a CONFIG.toml (or --example)", file=sys.stderr)
        return STATUS_USAGE
    try:
        config = sweep.load_config(ns.config)
        points = sweep.grid_points(config)
        if ns.dry_run:
            for row in sweep.points_table(points):
                print(row)
            return 0
        for name in config.scenes:  # bad scene files fail before a cluster starts
            sweep.resolve_scene(config, name)
    except sweep.SweepConfigError as exc:
        print(f"{prog}: {exc}", file=sys.stderr)
        return STATUS_USAGE
    except Exception as exc:  # a scene file's FormatError names the file and line
        from vgxsim.formats import FormatError

        if not isinstance(exc, FormatError):
            raise
        print(f"{prog}: {exc}", file=sys.stderr)
        return STATUS_USAGE
    prefix = ns.report or os.path.splitext(config.path)[0] + "-report"
    if config.output:
        os.makedirs(config.output, exist_ok=True)

    def save(row) -> None:
        if config.output and row.result.error is None:
            from vgxsim.shadow.api import write_image

            label = sweep.point_label(row.point)
            write_image(os.path.join(config.output, f"{row.result.index:04d}_{label}.png"),
                        row.result.value["colour"])

    with executor_for(ns, prog) as ex:
        report = sweep.run_sweep(config, ex, on_row=save)
    sweep.write_csv(report, prefix + ".csv")
    sweep.write_markdown(report, prefix + ".md")
    print(f"{prog}: {len(report.rows)} points on {report.executor} in {report.wall_s:.2f} s, "
          f"{len(report.failed)} failed; wrote {prefix}.csv and {prefix}.md")
    for row in report.failed:
        last = row.result.error.strip().splitlines()[-1]
        print(f"{prog}: point {row.result.index} failed (scene {row.point.scene}, settings "
              f"{row.point.settings}): {last}", file=sys.stderr)
    return STATUS_FAILED_POINTS if report.failed else 0


def run_farmed_shadows(ns: argparse.Namespace, scene, soft: int, kw: dict):
    """``vgxsim shadows --spin N`` or ``--soft N`` as farm tasks (not ``--local``).

    Returns
    -------
    list of ndarray (``--spin``) or vgxsim.shadow.api.Frame (``--soft``)
        The same arrays as ``api.render_spin`` / ``api.render`` in-process.
    """
    import warnings

    from vgxsim.shadow import api

    from .jobs import soft_shadows, spin

    with executor_for(ns, "vgxsim shadows") as ex:
        if ns.spin:
            return spin(ex, scene, ns.spin, soft=soft, **kw)
        frame = soft_shadows(ex, scene, soft, **kw)
    for note in frame.warnings:
        warnings.warn(note, api.ViewpointInShadowWarning, stacklevel=2)
    return frame
