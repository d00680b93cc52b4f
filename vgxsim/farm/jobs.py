"""Soft shadows and spins as farm jobs, put back together exactly.

::

    from vgxsim.farm import DaskExecutor, soft_shadows, spin
    with DaskExecutor(n_workers=2) as ex:
        frame = soft_shadows(ex, scene, 32, size=(320, 256))   # == api.render(soft=32)
        frames = spin(ex, scene, 24, size=(320, 256))           # == api.render_spin
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

from vgxsim.shadow import api
from vgxsim.shadow.scene import Scene, default_scene
from vgxsim.shadow.viewpoint import eye_in_shadow

from .exact import reduce_partials, resolve
from .tasks import TaskResult, soft_chunk_task, spin_task


class FarmTaskError(RuntimeError):
    """A farm task failed; the message names the job and carries its traceback."""


def collect(results, jobs_described: Sequence[str]) -> list[TaskResult]:
    """All results in job order; raise :class:`FarmTaskError` naming the first failure."""
    out: list[TaskResult | None] = [None] * len(jobs_described)
    for r in results:
        out[r.index] = r
    for r in out:
        if r.error is not None:
            raise FarmTaskError(f"{jobs_described[r.index]} failed on {r.timing.worker}:\n"
                                f"{r.error}")
    return out  # type: ignore[return-value]


def sample_chunks(frames: int, chunks: int) -> list[tuple[int, int]]:
    """``frames`` samples cut into ``chunks`` contiguous ranges ``(start, stop)``."""
    chunks = max(1, min(int(chunks), frames))
    edges = np.linspace(0, frames, chunks + 1).round().astype(int)
    return [(int(a), int(b)) for a, b in zip(edges[:-1], edges[1:], strict=True) if b > a]


def soft_shadows(executor, scene: Scene | None, frames: int, *, chunks: int | None = None,
                 **settings: Any) -> api.Frame:
    """``api.render(scene, soft=frames, **settings)`` with the samples spread over the
    executor's workers (bit-identical: :mod:`vgxsim.farm.exact`).

    Parameters
    ----------
    executor : LocalExecutor or DaskExecutor
    scene : Scene, optional
    frames : int
        Samples (jittered frames), at least 1.
    chunks : int, optional
        Tasks to cut the samples into (default: two per worker, so a slow worker
        does not hold the last one alone).
    **settings
        Keyword arguments of :func:`vgxsim.shadow.api.render` (not ``soft``).

    Returns
    -------
    vgxsim.shadow.api.Frame
        ``stencil`` is empty, as for any soft-shadow render.
    """
    if frames < 1:
        raise ValueError(f"soft_shadows: frames must be >= 1, not {frames}")
    scene = scene if scene is not None else default_scene()
    ranges = sample_chunks(frames, chunks or 2 * len(executor.workers))
    shipped = executor.put(scene)
    jobs = [(soft_chunk_task, shipped, a, b, frames, settings) for a, b in ranges]
    names = [f"soft-shadow samples {a}..{b - 1} of {frames} (settings {settings})"
             for a, b in ranges]
    results = collect(executor.map(jobs, desc="soft shadows"), names)
    partials = [r.value for r in results]
    colour = resolve(reduce_partials(partials, frames), frames)
    last = partials[-1]
    h, w = colour.shape[:2]
    notes = tuple(f"the viewpoint is inside the shadow of light {e.light} ({e.light_name}) "
                  f"cast by {e.caster}" for e in eye_in_shadow(scene))
    return api.Frame(colour, last.depth, np.zeros((0, h, w), np.uint8), last.stencil_zero,
                     notes)


def spin(executor, scene: Scene | None, frames: int, **settings: Any) -> list[np.ndarray]:
    """``api.render_spin(scene, frames, **settings)``, one task per frame.

    Returns
    -------
    list of ndarray, each (H, W, 4) uint8, row 0 = top, in frame order
    """
    if frames < 1:
        raise ValueError(f"spin: frames must be >= 1, not {frames}")
    scene = scene if scene is not None else default_scene()
    shipped = executor.put(scene)
    jobs = [(spin_task, shipped, k, frames, settings) for k in range(frames)]
    names = [f"spin frame {k} of {frames} (settings {settings})" for k in range(frames)]
    return [r.value for r in collect(executor.map(jobs, desc="spin"), names)]
