"""Serial Python share of a flush at 2 render threads, band_workers+cache_tables A/B.

The calling thread's CPU time per queue-and-flush minus the kernel time it spends
itself drawing bands (with ``band_workers`` it is one of the band loops): what no
thread count can split (Amdahl's serial fraction).  9 alternating rounds of 5
flushes per workload, medians, in ms.

Usage: python bench/flush_serial.py
"""

from __future__ import annotations

import statistics
import sys
import threading
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

import scenes  # noqa: E402

from vgxsim import threads  # noqa: E402
from vgxsim.batch import CommandBatch  # noqa: E402

SWITCHES = ("band_workers", "cache_tables")


def main() -> None:
    caller = threading.get_ident()
    kernel = [0.0]
    real = threads.run_each

    def run_each(n, fn, items):
        def timed(item):
            if threading.get_ident() != caller:
                return fn(item)
            t = time.thread_time()
            fn(item)
            kernel[0] += time.thread_time() - t
        real(n, timed, items)

    threads.run_each = run_each
    threads.set_threads(2)
    defaults = {s: getattr(CommandBatch, s) for s in SWITCHES}
    try:
        for name in ("zstencil_fill", "zstencil_hidden_fill", "colour_blend_fill",
                     "lit_equal_fill"):
            run, _ = getattr(scenes, name)()
            run()
            res: dict = {False: [], True: []}
            for _ in range(9):
                for on in (False, True):
                    for s in SWITCHES:
                        setattr(CommandBatch, s, on)
                    run()
                    for _ in range(5):
                        kernel[0] = 0.0
                        t = time.thread_time()
                        run()
                        res[on].append(1e3 * (time.thread_time() - t - kernel[0]))
            print(f"{name:22s} serial CPU per flush: off {statistics.median(res[False]):.3f}"
                  f"  on {statistics.median(res[True]):.3f} ms")
    finally:
        threads.run_each = real
        threads.set_threads(None)
        for s, v in defaults.items():
            setattr(CommandBatch, s, v)


if __name__ == "__main__":
    main()
