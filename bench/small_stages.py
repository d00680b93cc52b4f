"""Where the time of a 10-pixel triangle goes, stage by stage (issue 7, item 3).

    python bench/small_stages.py [--count N] [--area A] [--threads T] [--rounds R]
                                 [--tile-order PIXELS]

Draws bench/scenes.py small_triangles (Context.draw_arrays: one call of N triangles,
then a flush) and reports, per stage function, the median over ``rounds`` of the
process CPU time spent in it (cProfile's own time, so nested stages do not count
twice), in ns per triangle.  The stages are the functions of the array path:
as_homogeneous / transform_points / clip_triangles / project_snap (front end),
setup_triangles_states (kernels/setup.py), bin_primitives and gather_band_records
(binning), render_bands (the band kernel).  Process CPU time, not wall time: the
machine this runs on is usually shared, and CPU time is the steadier figure.
"""

from __future__ import annotations

import argparse
import cProfile
import os
import pstats
import sys
import time

import numba
import numpy as np

sys.path.insert(0, os.path.dirname(__file__))

import scenes  # noqa: E402

from vgxsim import threads  # noqa: E402


def stage_times(count: int, area: float, nthreads: int, rounds: int,
                tile_order: int = 0) -> dict:
    """Median CPU ns per triangle of each function of the run (and ``total``).

    Returns
    -------
    dict
        ``{function name: ns per triangle}``, plus ``"total"`` (the whole run).
    """
    threads.set_threads(nthreads)
    numba.set_num_threads(min(nthreads, numba.config.NUMBA_NUM_THREADS))
    run, n = scenes.small_triangles(count=count, area=area, tile_order=tile_order)
    run()  # compile and warm up
    samples: dict[str, list[float]] = {}
    for _ in range(rounds):
        prof = cProfile.Profile()
        c = time.process_time()
        prof.enable()
        run()
        prof.disable()
        samples.setdefault("total", []).append(time.process_time() - c)
        for (_file, _line, name), row in pstats.Stats(prof).stats.items():
            samples.setdefault(name, []).append(row[2])  # own time (tottime)
    return {k: float(np.median(v)) * 1e9 / n for k, v in samples.items()
            if len(v) == rounds}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--count", type=int, default=200_000)
    ap.add_argument("--area", type=float, default=10.0)
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--tile-order", type=int, default=0,
                    help="submit the triangles sorted by tiles of this many pixels")
    args = ap.parse_args()
    ns = stage_times(args.count, args.area, args.threads, args.rounds, args.tile_order)
    total = ns.pop("total")
    print(f"{args.count} triangles of {args.area} px, {args.threads} thread(s), "
          f"median of {args.rounds}: {total:.0f} ns/tri CPU = {1e3 / total:.2f} M tri/s")
    for name, v in sorted(ns.items(), key=lambda kv: -kv[1])[:14]:
        print(f"  {name:32s} {v:7.0f} ns/tri  {100 * v / total:5.1f} %")


if __name__ == "__main__":
    main()
