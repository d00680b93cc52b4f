"""Farm tasks: pure functions of (scene, settings, frame or sample index) -> arrays.

Every task builds its own window through :func:`vgxsim.shadow.api.render`, so a task
run on a Dask worker draws exactly what the same call draws in-process: the scene
arrives whole (scattered once per worker), the settings are plain keyword arguments
of ``api.render``, and nothing depends on which worker, thread or order ran it.

:func:`run_measured` wraps a task where it runs: wall time of the task, the worker's
name, the Numba compile time spent inside it (``numba:compile`` events; nonzero only
on a worker whose caches were not warmed), and any exception turned into a report
instead of a lost sweep.
"""

from __future__ import annotations

import contextlib
import os
import threading
import time
import traceback
import warnings
from collections.abc import Callable, Mapping
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from vgxsim.shadow import api
from vgxsim.shadow.program import jittered_lights, random_offsets
from vgxsim.shadow.scene import Scene

from .exact import accumulate_frames


@dataclass(frozen=True)
class Timing:
    """Where and how long one task ran.

    Attributes
    ----------
    worker : str
        The Dask worker's address, or ``"in-process"``.
    render_s : float
        Wall seconds of the task body.
    compile_s : float
        Seconds of Numba compilation (or cache loading) inside the task.
    pid : int
        Process id of the worker.
    cpu_s : float
        CPU seconds of the worker's process during the task: beside ``render_s`` it
        tells a slow task from one that waited for a core shared with other jobs.
    """

    worker: str
    render_s: float
    compile_s: float
    pid: int
    cpu_s: float = 0.0


@dataclass(frozen=True)
class TaskResult:
    """One task's outcome: ``value`` (arrays) or ``error`` (a traceback's text)."""

    index: int
    value: Any
    timing: Timing
    error: str | None = None


def worker_name() -> str:
    """The running Dask worker's address, or ``"in-process"`` outside a worker."""
    try:
        from distributed import get_worker

        return get_worker().address
    except (ImportError, ValueError):
        return "in-process"


_compile_lock = threading.Lock()
# IRIS GL keeps one current window per process (vgxsim.gl._core.session, like winset
# in the 1990 library), so two renders in one process must not interleave: workers
# that are threads of one process (LocalCluster(processes=False)) take turns here.
# Process workers have one task thread each and never wait.
_gl_lock = threading.Lock()


@contextlib.contextmanager
def numba_threads(n: int):
    """Numba threads of the calling thread for the block (``numba.set_num_threads`` is
    per thread), restored after, so an in-process run leaves its caller as it was."""
    import numba

    before = numba.get_num_threads()
    numba.set_num_threads(max(1, min(int(n), numba.config.NUMBA_NUM_THREADS)))
    try:
        yield
    finally:
        numba.set_num_threads(before)


def run_measured(index: int, fn: Callable, *args, threads: int = 1) -> TaskResult:
    """Run ``fn(*args)`` and time it where it runs.

    Parameters
    ----------
    index : int
        The task's position in its job list (results are put back in this order).
    fn : callable
        A task function of this module.
    *args
        Its arguments.
    threads : int
        Numba threads for this task.  ``numba.set_num_threads`` is per calling thread,
        so this pins the executor thread without touching other threads of the process.

    Returns
    -------
    TaskResult
        An exception inside ``fn`` becomes ``error`` (the sweep goes on); only a lost
        worker makes Dask re-run the task.
    """
    from numba.core import event

    spent = [0.0]

    def on_compile(seconds: float) -> None:
        with _compile_lock:
            spent[0] += seconds

    value, error = None, None
    with _gl_lock, numba_threads(threads), event.install_timer("numba:compile", on_compile):
        t0, c0 = time.perf_counter(), time.process_time()
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", api.ViewpointInShadowWarning)
                value = fn(*args)
        except Exception:  # reported with its job's scene and settings by the caller
            error = traceback.format_exc()
        elapsed, cpu = time.perf_counter() - t0, time.process_time() - c0
    timing = Timing(worker_name(), elapsed, spent[0], os.getpid(), cpu)
    return TaskResult(index, value, timing, error)


def render_task(scene: Scene, settings: Mapping[str, Any]) -> dict[str, np.ndarray]:
    """One ``api.render(scene, **settings)``.

    Returns
    -------
    dict
        ``colour`` (H, W, 4) uint8 and ``depth`` (H, W) int32, row 0 = top.
    """
    frame = api.render(scene, **settings)
    return {"colour": frame.colour, "depth": frame.depth}


def spin_frame_camera(scene: Scene, k: int, frames: int) -> Scene:
    """``scene`` seen from frame ``k`` of a spin of ``frames`` (as api.render_spin)."""
    return replace(scene, camera=api.orbit(scene.camera, rotate=(360.0 * k / frames, 0.0)))


def spin_task(scene: Scene, k: int, frames: int, settings: Mapping[str, Any]) -> np.ndarray:
    """Frame ``k`` of ``api.render_spin(scene, frames, **settings)``: (H, W, 4) uint8."""
    return api.render(spin_frame_camera(scene, k, frames), **settings).colour


@dataclass(frozen=True)
class Partial:
    """Soft-shadow samples ``start .. stop - 1`` summed in accumulation units.

    Attributes
    ----------
    start, stop : int
    acc : ndarray, shape (H, W, 4), int16
        The accumulation buffer after those samples (acbuf's units: colour 0..255).
    depth : ndarray, shape (H, W), int32, or None
        The z planes of the last sample of the whole run (only in the chunk that holds
        it): ``api.render(soft=N)`` returns the z buffer its last frame left.
    stencil_zero : int
    """

    start: int
    stop: int
    acc: np.ndarray
    depth: np.ndarray | None
    stencil_zero: int


def soft_chunk_task(scene: Scene, start: int, stop: int, total: int,
                    settings: Mapping[str, Any]) -> Partial:
    """Samples ``start .. stop - 1`` of an ``N = total`` soft shadow.

    Sample ``k`` is one hard-shadow frame with the lights moved by row ``k`` of
    ``random_offsets(scene, total, seed)`` -- the frame :func:`~vgxsim.shadow.program.
    accumulate` draws as its ``k``-th -- accumulated like acbuf (AC_CLEAR_ACCUMULATE,
    then AC_ACCUMULATE, value 1.0) by the project's acbuf kernel.
    """
    kw = dict(settings)
    seed = kw.pop("seed", 1991)
    kw.pop("soft", None)
    kw.pop("on_soft_frame", None)
    offsets = random_offsets(scene, total, seed)[start:stop]
    colours, last = [], None
    for off in offsets:
        last = api.render(jittered_lights(scene, off), soft=0, **kw)
        colours.append(last.colour)
    acc = accumulate_frames(colours)
    depth = last.depth if stop == total else None
    return Partial(start, stop, acc, depth, last.stencil_zero)


def warm_up(settings_list: list[Mapping[str, Any]], threads: int = 1) -> float:
    """Render a tiny default scene once per distinct setting so every kernel the run
    will use is compiled (or loaded from Numba's cache) before anything is timed.

    Returns
    -------
    float
        Seconds spent.
    """
    t0 = time.perf_counter()
    seen = set()
    with _gl_lock, numba_threads(threads), warnings.catch_warnings():
        warnings.simplefilter("ignore", api.ViewpointInShadowWarning)
        for s in settings_list:
            kw = {k: v for k, v in s.items() if k not in ("size", "soft", "on_soft_frame")}
            soft = 1 if s.get("soft") else 0
            key = repr(sorted(kw.items())) + str(soft)
            if key in seen:
                continue
            seen.add(key)
            try:
                frame = api.render(None, size=(16, 12), soft=soft, **kw)
            except Exception:  # a bad setting: its own task reports it with its point
                continue
            accumulate_frames([frame.colour])
    return time.perf_counter() - t0
