"""Where the time of a 10-pixel triangle goes, stage by stage (issue 7, item 3).

    python bench/small_stages.py [--count N] [--area A] [--threads T] [--rounds R]
                                 [--tile-order PIXELS] [--ab SWITCH]

Draws bench/scenes.py small_triangles (Context.draw_arrays: one call of N triangles,
then a flush) and reports, per stage function, the median over ``rounds`` of the
process CPU time spent in it (cProfile's own time, so nested stages do not count
twice), in ns per triangle.  The stages are the functions of the array path:
as_homogeneous / transform_points / clip_triangles / project_snap, or front_vertices
(front end), setup_triangles_states (kernels/setup.py; setup_triangles_borrowed with
CommandBatch.borrow_arrays; setup_triangles_slots(_borrowed) where band_slots places
the records, after kernels/band_order.py band_slots), bin_primitives, scatter_records
and gather_band_records (binning; none of them for one tall band, CommandBatch.tall_bands,
whose choice reads mean_rows), render_bands (the band kernel; render_bands_borrowed
likewise).  Process
CPU time, not wall time: the machine this runs on is usually shared, and CPU time is
the steadier figure.
``--ab SWITCH`` runs each round twice, with the switch SWITCH (a CommandBatch
attribute, or a dotted module constant such as vgxsim.geometry.pipeline.FUSED_FRONT) on and
then off (alternating, so load drifts hit both alike), and reports both, with the
median wall time of a round beside the CPU time.
"""

from __future__ import annotations

import argparse
import cProfile
import importlib
import os
import pstats
import sys
import time

import numba
import numpy as np

sys.path.insert(0, os.path.dirname(__file__))

import scenes  # noqa: E402

from vgxsim import threads  # noqa: E402
from vgxsim.batch import CommandBatch  # noqa: E402


def _switch_owner(switch: str | None):
    """Where a switch lives: ``name`` is a CommandBatch attribute, ``pkg.mod.NAME`` a
    module constant (vgxsim.geometry.pipeline.FUSED_FRONT)."""
    if switch is None or "." not in switch:
        return CommandBatch, switch
    mod, _, attr = switch.rpartition(".")
    return importlib.import_module(mod), attr


def stage_times(count: int, area: float, nthreads: int, rounds: int,
                tile_order: int = 0, switch: str | None = None) -> dict:
    """Median CPU ns per triangle of each function of the run (and ``total``,
    ``wall``), per setting of ``switch`` (a CommandBatch class attribute: on, off,
    alternating round by round; None: the defaults only).

    Returns
    -------
    dict
        ``{setting: {function name: ns per triangle}}``, plus ``"total"`` (the whole
        run's CPU time) and ``"wall"``; setting is True/False, or None.
    """
    threads.set_threads(nthreads)
    numba.set_num_threads(min(nthreads, numba.config.NUMBA_NUM_THREADS))
    run, n = scenes.small_triangles(count=count, area=area, tile_order=tile_order)
    settings = [None] if switch is None else [True, False]
    owner, attr = _switch_owner(switch)
    keep = None if switch is None else getattr(owner, attr)
    samples: dict = {s: {} for s in settings}
    try:
        for r in range(rounds + 1):
            for setting in settings:
                if switch is not None:
                    setattr(owner, attr, setting)
                if r == 0:
                    run()  # compile and warm up
                    continue
                prof = cProfile.Profile(time.process_time)
                c, w = time.process_time(), time.perf_counter()
                prof.enable()
                run()
                prof.disable()
                got = samples[setting]
                got.setdefault("wall", []).append(time.perf_counter() - w)
                got.setdefault("total", []).append(time.process_time() - c)
                for (_file, _line, name), row in pstats.Stats(prof).stats.items():
                    got.setdefault(name, []).append(row[2])  # own time (tottime)
    finally:
        if switch is not None:
            setattr(owner, attr, keep)
    return {s: {k: float(np.median(v)) * 1e9 / n for k, v in got.items()
                if len(v) == rounds} for s, got in samples.items()}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--count", type=int, default=200_000)
    ap.add_argument("--area", type=float, default=10.0)
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--tile-order", type=int, default=0,
                    help="submit the triangles sorted by tiles of this many pixels")
    ap.add_argument("--ab", metavar="SWITCH", default=None,
                    help="a CommandBatch switch to run on and off, alternating")
    args = ap.parse_args()
    runs = stage_times(args.count, args.area, args.threads, args.rounds, args.tile_order,
                       args.ab)
    for setting, ns in runs.items():
        total = ns.pop("total")
        wall = ns.pop("wall")
        label = "" if setting is None else f", {args.ab}={'on' if setting else 'off'}"
        print(f"{args.count} triangles of {args.area} px, {args.threads} thread(s){label}, "
              f"median of {args.rounds}: {total:.0f} ns/tri CPU = {1e3 / total:.2f} M tri/s"
              f" (wall {wall:.0f} ns/tri = {1e3 / wall:.2f} M tri/s)")
        for name, v in sorted(ns.items(), key=lambda kv: -kv[1])[:14]:
            print(f"  {name:32s} {v:7.0f} ns/tri  {100 * v / total:5.1f} %")


if __name__ == "__main__":
    main()
