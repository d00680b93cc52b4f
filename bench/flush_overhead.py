"""Per-flush Python overhead of the fill workloads, one CommandBatch switch A/B.

For each workload of bench/scenes.py, alternates the switch off/on for ``rounds``
rounds and prints medians of: the calling thread's CPU time per flush (the serial
Python share: queueing, flush preparation, handing out bands), the process CPU time
and the wall time, at 1 and 2 render threads, and the 2-thread wall speed-up.

Usage: python bench/flush_overhead.py [switch[,switch...]] [rounds]
(default band_workers,cache_tables 9; several switches are set together)
"""

from __future__ import annotations

import statistics
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

import scenes  # noqa: E402

from vgxsim import threads  # noqa: E402
from vgxsim.batch import CommandBatch  # noqa: E402

WORKLOADS = ("zstencil_fill", "zstencil_hidden_fill", "colour_blend_fill", "lit_equal_fill")


def measure(run, reps: int) -> tuple[float, float, float]:
    """Medians over ``reps`` calls of (thread CPU, process CPU, wall) in ms."""
    tt, pt, wt = [], [], []
    for _ in range(reps):
        t0, p0, w0 = time.thread_time(), time.process_time(), time.perf_counter()
        run()
        tt.append(time.thread_time() - t0)
        pt.append(time.process_time() - p0)
        wt.append(time.perf_counter() - w0)
    return tuple(1e3 * statistics.median(v) for v in (tt, pt, wt))


def main(argv: list[str]) -> None:
    switches = (argv[1] if len(argv) > 1 else "band_workers,cache_tables").split(",")
    rounds = int(argv[2]) if len(argv) > 2 else 9
    defaults = {s: getattr(CommandBatch, s) for s in switches}
    for name in WORKLOADS:
        run, _ = getattr(scenes, name)()
        for n in (1, 2):
            threads.set_threads(n)
            run()
        res = {(on, n): [] for on in (False, True) for n in (1, 2)}
        for _ in range(rounds):
            for on in (False, True):
                for s in switches:
                    setattr(CommandBatch, s, on)
                for n in (1, 2):
                    threads.set_threads(n)
                    res[(on, n)].append(measure(run, 5))
        for s, v in defaults.items():
            setattr(CommandBatch, s, v)
        threads.set_threads(None)
        for on in (False, True):
            med = {n: [statistics.median(r[i] for r in res[(on, n)]) for i in range(3)]
                   for n in (1, 2)}
            print(f"{name:22s} {'+'.join(switches)}={int(on)}  "
                  f"1thr: main {med[1][0]:.3f} wall {med[1][2]:.3f}  "
                  f"2thr: main {med[2][0]:.3f} cpu {med[2][1]:.3f} wall {med[2][2]:.3f}  "
                  f"speed-up {med[1][2] / med[2][2]:.2f}x")


if __name__ == "__main__":
    main(sys.argv)
