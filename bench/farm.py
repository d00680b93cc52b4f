"""Farm throughput against the number of Dask workers on this machine (issue 13).

    python bench/farm.py [--workers 1,2,3] [--rounds N] [--size WxH] [--soft N] [--json FILE]

Measured side by side in one run: the same sweep grid (two scenes x mode x subpixel,
plus soft-shadow points) in-process and on embedded LocalClusters of 1, 2, 3 process
workers (one Numba thread each, warmed before timing), medians of ``--rounds`` wall
times of the whole grid; then a ``--soft``-sample soft shadow on each.  Also checked
in the same run: every executor's colour and depth digests equal the in-process ones
(bit-identical), and the soft shadow equals ``api.render(soft=N)``.

Target (issue 13): 2 workers >= 1.8x one worker.  Reported, never asserted; the
machine is shared by other jobs, so the numbers are noisy.
"""

from __future__ import annotations

import argparse
import json
import statistics
import tempfile
import time
import warnings

import numpy as np

from vgxsim.farm import DaskExecutor, LocalExecutor, soft_shadows
from vgxsim.farm.sweep import load_config, run_sweep
from vgxsim.shadow import api

GRID = """
[sweep]
name = "bench"
[grid]
scene = ["cubes", "balls"]
size = [[{w}, {h}]]
mode = ["shadows", "objects", "volumes"]
subpixel = [false, true]
soft = [0, 2]
"""


def measure(ex, config, scene, soft: int, size, rounds: int) -> dict:
    walls, digests = [], None
    for _ in range(rounds):
        report = run_sweep(config, ex)  # wall_s: first task submitted to last result,
        walls.append(report.wall_s)     # after the warm-up
        got = [(r.colour_sha256, r.depth_sha256) for r in report.rows]
        assert not report.failed, report.failed[0].result.error
        digests = got if digests is None else digests
        assert got == digests, "a repeat differed"
    t0 = time.perf_counter()
    frame = soft_shadows(ex, scene, soft, size=size)
    soft_s = time.perf_counter() - t0
    task_s = [r.result.timing.render_s for r in report.rows]
    cpu_s = [r.result.timing.cpu_s for r in report.rows]
    return {"executor": ex.name, "points": len(report.rows),
            "sweep_wall_s": statistics.median(walls), "sweep_walls": walls,
            "task_s_median": statistics.median(task_s), "task_s_sum": sum(task_s),
            "task_cpu_s_median": statistics.median(cpu_s),
            "soft_wall_s": soft_s,
            "digests": digests, "soft_colour": frame.colour, "soft_depth": frame.depth}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--workers", default="1,2,3")
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--size", default="96x80")
    ap.add_argument("--soft", type=int, default=32)
    ap.add_argument("--json", metavar="FILE")
    ns = ap.parse_args()
    w, h = (int(v) for v in ns.size.split("x"))
    counts = [int(v) for v in ns.workers.split(",")]
    with tempfile.NamedTemporaryFile("w", suffix=".toml", delete=False) as fh:
        fh.write(GRID.format(w=w, h=h))
    config = load_config(fh.name)
    scene = api.load_scene("cubes")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", api.ViewpointInShadowWarning)
        ref_soft = api.render(scene, soft=ns.soft, size=(w, h))
    runs = []
    with LocalExecutor() as ex:
        runs.append(measure(ex, config, scene, ns.soft, (w, h), ns.rounds))
    for n in counts:
        with DaskExecutor(n_workers=n, processes=True) as ex:
            runs.append(measure(ex, config, scene, ns.soft, (w, h), ns.rounds))
    base = runs[0]
    one = next((r for r in runs if r["executor"].endswith("(1 processes)")), None)
    print(f"grid {base['points']} points at {w}x{h}, soft {ns.soft} samples, "
          f"median of {ns.rounds} rounds")
    print("| executor | sweep wall s | points/s | vs 1 worker | median task s | median task "
          "CPU s | task s summed | soft wall s | identical |")
    print("|---|---|---|---|---|---|---|---|---|")
    out = []
    for r in runs:
        same = (r["digests"] == base["digests"]
                and np.array_equal(r["soft_colour"], ref_soft.colour)
                and np.array_equal(r["soft_depth"], ref_soft.depth))
        speed = f"{one['sweep_wall_s'] / r['sweep_wall_s']:.2f}x" if one else "-"
        print(f"| {r['executor']} | {r['sweep_wall_s']:.2f} | "
              f"{r['points'] / r['sweep_wall_s']:.2f} | {speed} | {r['task_s_median']:.3f} | "
              f"{r['task_cpu_s_median']:.3f} | "
              f"{r['task_s_sum']:.2f} | {r['soft_wall_s']:.2f} | "
              f"{same} |")
        out.append({k: v for k, v in r.items() if k not in ("soft_colour", "soft_depth")}
                   | {"identical": same})
    if ns.json:
        with open(ns.json, "w") as fh:
            json.dump(out, fh, indent=1)


if __name__ == "__main__":
    main()
