"""``vgxsim sweep CONFIG.toml``: a grid of scenes x render settings on the farm.

A config names the scenes and, per axis, the values of one keyword argument of
:func:`vgxsim.shadow.api.render`; the grid is their product, one task per point::

    [sweep]
    name = "small"
    output = "sweep-out"        # optional: a PNG per point, beside the report

    [grid]
    scene = ["cubes", "balls"]  # shipped names or .scn paths (relative to the config)
    size = [[64, 48], [128, 96]]
    mode = ["shadows", "objects"]
    subpixel = [false, true]
    soft = [0, 4]

    [fixed]                     # keyword arguments every point gets
    seed = 1991

Any keyword of ``api.render`` may be an axis (a new one, such as a technique, works as
soon as ``render`` takes it); an unknown one is refused before anything runs, naming
the config file and line.  The report (CSV and markdown) has one row per point: its
settings, where it ran, render and compile seconds, digests of the colour and depth
planes, and the error of a point that failed.
"""

from __future__ import annotations

import csv
import hashlib
import inspect
import itertools
import os
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from vgxsim.shadow import api

from .tasks import TaskResult, render_task

try:
    import tomllib
except ModuleNotFoundError:  # Python 3.10
    import tomli as tomllib

NOT_AXES = ("scene", "on_soft_frame")


class SweepConfigError(ValueError):
    """A sweep config that cannot be run; the message names the file and line."""


@dataclass(frozen=True)
class SweepConfig:
    """A parsed sweep config.

    Attributes
    ----------
    path : str
    name : str
    scenes : tuple of str
        As written (names or paths resolved against the config's folder).
    axes : dict of str to list
        Render keyword -> its values, in the file's order.
    fixed : dict of str to value
        Keywords every point gets.
    output : str or None
        Folder for a PNG per point (relative to the config's folder).
    """

    path: str
    name: str
    scenes: tuple[str, ...]
    axes: dict[str, list]
    fixed: dict[str, Any] = field(default_factory=dict)
    output: str | None = None


@dataclass(frozen=True)
class Point:
    """One grid point: a scene and the render keywords."""

    scene: str
    settings: dict[str, Any]


def _line_of(text: str, key: str) -> int:
    for n, line in enumerate(text.splitlines(), 1):
        if line.split("=")[0].strip() == key:
            return n
    return 0


def _value(key: str, value: Any) -> Any:
    if key == "size":
        return tuple(int(v) for v in value)
    return value


def load_config(path: str | os.PathLike) -> SweepConfig:
    """Read and check a sweep config.

    Raises
    ------
    SweepConfigError
        Unreadable TOML, no scenes, an axis that is not a list, or a key that is not a
        keyword of ``api.render`` -- naming the file and line.
    """
    path = os.fspath(path)
    try:
        with open(path, encoding="utf-8") as fh:
            text = fh.read()
        data = tomllib.loads(text)
    except OSError as exc:
        raise SweepConfigError(f"{path}: cannot read the sweep config: {exc}") from None
    except tomllib.TOMLDecodeError as exc:
        raise SweepConfigError(f"{path}: {exc}") from None
    head = data.get("sweep", {})
    grid = dict(data.get("grid", {}))
    fixed = dict(data.get("fixed", {}))
    known = set(inspect.signature(api.render).parameters) - set(NOT_AXES)
    scenes = grid.pop("scene", ["cubes"])
    if isinstance(scenes, str):
        scenes = [scenes]
    if not scenes:
        raise SweepConfigError(f"{path}:{_line_of(text, 'scene')}: grid.scene lists no scene")
    for table, entries in (("grid", grid), ("fixed", fixed)):
        for key, value in entries.items():
            where = f"{path}:{_line_of(text, key)}"
            if key not in known:
                raise SweepConfigError(f"{where}: {table}.{key} is not a keyword of "
                                       f"vgxsim.shadow.api.render (known: "
                                       f"{', '.join(sorted(known))})")
            if table == "grid" and (not isinstance(value, list) or not value):
                raise SweepConfigError(f"{where}: grid.{key} must be a non-empty list of "
                                       "values")
    axes = {k: [_value(k, v) for v in vals] for k, vals in grid.items()}
    fixed = {k: _value(k, v) for k, v in fixed.items()}
    base = os.path.dirname(os.path.abspath(path))
    output = head.get("output")
    return SweepConfig(path, str(head.get("name", os.path.splitext(os.path.basename(path))[0])),
                       tuple(str(s) for s in scenes), axes, fixed,
                       os.path.join(base, output) if output else None)


def grid_points(config: SweepConfig) -> list[Point]:
    """Every point of the grid: scenes outermost, then the axes in the file's order."""
    keys = list(config.axes)
    points = []
    for scene in config.scenes:
        for values in itertools.product(*(config.axes[k] for k in keys)):
            settings = dict(config.fixed)
            settings.update(zip(keys, values, strict=True))
            points.append(Point(scene, settings))
    return points


def resolve_scene(config: SweepConfig, name: str):
    """Load a grid scene: a shipped name, or a path relative to the config's folder."""
    candidate = os.path.join(os.path.dirname(os.path.abspath(config.path)), name)
    return api.load_scene(candidate if os.path.exists(candidate) else name)


@dataclass
class SweepRow:
    """One point's outcome (arrays are dropped after digests and images are made)."""

    point: Point
    result: TaskResult
    colour_sha256: str = ""
    depth_sha256: str = ""


@dataclass
class SweepReport:
    """A finished sweep: rows in grid order, warm-up seconds per worker."""

    config: SweepConfig
    executor: str
    rows: list[SweepRow]
    warm_up_s: dict[str, float]
    wall_s: float = 0.0

    @property
    def failed(self) -> list[SweepRow]:
        """Rows whose task failed."""
        return [r for r in self.rows if r.result.error is not None]


def digest(a: np.ndarray) -> str:
    """sha256 of an array's bytes, its shape and dtype (equal digests: equal planes)."""
    h = hashlib.sha256(f"{a.shape}{a.dtype}".encode())
    h.update(np.ascontiguousarray(a).tobytes())
    return h.hexdigest()


def point_label(point: Point) -> str:
    """A short, file-name-safe label of a point."""
    parts = [point.scene]
    for k, v in point.settings.items():
        v = "x".join(str(x) for x in v) if isinstance(v, tuple) else v
        parts.append(f"{k}-{v}")
    return "_".join(str(p) for p in parts).replace(os.sep, "-").replace(" ", "")


def run_sweep(config: SweepConfig, executor, keep: bool = False,
              on_row=None) -> SweepReport:
    """Run every grid point on ``executor``.

    Scenes are loaded here and shipped once each (``executor.put``); the workers are
    warmed with every distinct setting before the first timed task.

    Parameters
    ----------
    config : SweepConfig
    executor : LocalExecutor or DaskExecutor
    keep : bool
        Keep the colour and depth arrays in each row's ``result.value`` (tests).
    on_row : callable, optional
        ``on_row(row)`` as each point arrives (images are written through this).

    Returns
    -------
    SweepReport
        Failed points are rows with ``result.error`` set; the sweep does not stop.
    """
    import time

    points = grid_points(config)
    scenes = {name: executor.put(resolve_scene(config, name)) for name in config.scenes}
    warm = executor.warm_up([p.settings for p in points])
    jobs = [(render_task, scenes[p.scene], p.settings) for p in points]
    rows: list[SweepRow | None] = [None] * len(points)
    t0 = time.perf_counter()
    for result in executor.map(jobs, desc=f"sweep {config.name}"):
        row = SweepRow(points[result.index], result)
        if result.error is None:
            row.colour_sha256 = digest(result.value["colour"])
            row.depth_sha256 = digest(result.value["depth"])
        if on_row is not None:
            on_row(row)
        if not keep and result.error is None:
            row.result = TaskResult(result.index, None, result.timing)
        rows[result.index] = row
    return SweepReport(config, executor.name, rows, warm,  # type: ignore[arg-type]
                       time.perf_counter() - t0)


def _columns(report: SweepReport) -> list[str]:
    return (["index", "scene", *report.config.axes] +
            ["worker", "render_s", "cpu_s", "compile_s", "colour_sha256", "depth_sha256",
             "error"])


def _cells(report: SweepReport, row: SweepRow) -> list[Any]:
    t = row.result.timing
    axes = [row.point.settings[k] for k in report.config.axes]
    axes = ["x".join(map(str, v)) if isinstance(v, tuple) else v for v in axes]
    err = row.result.error.strip().splitlines()[-1] if row.result.error else ""
    return [row.result.index, row.point.scene, *axes, t.worker, f"{t.render_s:.4f}",
            f"{t.cpu_s:.4f}", f"{t.compile_s:.4f}", row.colour_sha256[:16],
            row.depth_sha256[:16], err]


def write_csv(report: SweepReport, path: str | os.PathLike) -> None:
    """One row per point (digests shortened to 16 hex digits)."""
    with open(path, "w", newline="", encoding="utf-8") as fh:
        out = csv.writer(fh)
        out.writerow(_columns(report))
        for row in report.rows:
            out.writerow(_cells(report, row))


def markdown(report: SweepReport) -> str:
    """The report as markdown: summary, warm-up per worker, a table of points and the
    full traceback of every failed point."""
    ok = [r for r in report.rows if r.result.error is None]
    per_worker: dict[str, list[float]] = {}
    for r in ok:
        per_worker.setdefault(r.result.timing.worker, []).append(r.result.timing.render_s)
    lines = [f"# Sweep {report.config.name}", "",
             f"{len(report.rows)} points on {report.executor}; {len(report.failed)} failed; "
             f"wall {report.wall_s:.2f} s after warm-up "
             f"({sum(t for v in per_worker.values() for t in v):.2f} s of task time).", "",
             "| worker | warm-up s | tasks | median render s |", "|---|---|---|---|"]
    for w in sorted(set(report.warm_up_s) | set(per_worker)):
        times = per_worker.get(w, [])
        med = f"{float(np.median(times)):.4f}" if times else "-"
        warm = report.warm_up_s.get(w)
        lines.append(f"| {w} | {'-' if warm is None else f'{warm:.2f}'} | {len(times)} | {med} |")
    cols = _columns(report)
    lines += ["", "| " + " | ".join(cols) + " |", "|" + "---|" * len(cols)]
    for row in report.rows:
        lines.append("| " + " | ".join(str(c) for c in _cells(report, row)) + " |")
    for row in report.failed:
        lines += ["", f"## Point {row.result.index} failed: scene {row.point.scene}, "
                      f"settings {row.point.settings}", "", "```", row.result.error.rstrip(),
                  "```"]
    return "\n".join(lines) + "\n"


def write_markdown(report: SweepReport, path: str | os.PathLike) -> None:
    """Write :func:`markdown` to ``path``."""
    with open(path, "w", encoding="utf-8") as fh:
        fh.write(markdown(report))


def example_config() -> str:
    """The text of the shipped example config (axes that exist in api.render today)."""
    here = os.path.dirname(__file__)
    with open(os.path.join(here, "example.toml"), encoding="utf-8") as fh:
        return fh.read()


def points_table(points: Sequence[Point]) -> list[Mapping[str, Any]]:
    """Points as plain dicts (scene plus settings), e.g. for printing a dry run."""
    return [{"scene": p.scene, **p.settings} for p in points]
