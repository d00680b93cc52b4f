"""A CommandBatch switch on and off, alternating, on the fill workloads.

    python bench/fill_ab.py SWITCH[,SWITCH...] [--rounds N] [--threads T] [--only NAME ...]

(several switches: all on against all off)

Workloads: the full-screen z+stencil pass, lit pass and lit pass at zfunction(ZF_EQUAL)
over a depth pass of bench/scenes.py (one run
queues and flushes the whole batch; units: fragments a rasterizer without work
skipping would test), the Heidmann 1991 frame at 1280 x 1024 through the IRIS GL
API, and the dense scene (bench/dense_scene.py, raster only).  Each round runs a
workload once with the switch on and once off (the order alternating round to
round); quoted are medians of the process CPU time spent in CommandBatch.flush
(all threads; on a shared machine the steadier figure), after one warm-up round
each.  The work counters of one run with each setting are printed beside.
"""

from __future__ import annotations

import argparse
import os
import sys

import numba
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import dense_scene  # noqa: E402
import scenes  # noqa: E402

from vgxsim.batch import CommandBatch  # noqa: E402


def _heidmann():
    from vgxsim.examples import heidmann1991

    def run():
        heidmann1991.render(1280, 1024, mode="shadows", edges="silhouette")

    return run, None


def _dense():
    passes, _, _ = dense_scene.build()
    run, batch = dense_scene.vgxsim_frame(passes)
    run.batch = batch
    return run, None


WORKLOADS = {
    "zstencil_fill": lambda: scenes.zstencil_fill(),
    "colour_blend_fill": lambda: scenes.colour_blend_fill(),
    "lit_equal_fill": lambda: scenes.lit_equal_fill(),
    "heidmann_frame": _heidmann,
    "dense_scene": _dense,
}


def _set(names, on: bool) -> None:
    for sw in names:
        setattr(CommandBatch, sw, on)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("switch", help="CommandBatch class attributes (bool), comma-separated")
    ap.add_argument("--rounds", type=int, default=9)
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--only", nargs="*", default=list(WORKLOADS))
    args = ap.parse_args(argv)
    names = args.switch.split(",")
    for sw in names:
        if not isinstance(getattr(CommandBatch, sw, None), bool):
            ap.error(f"CommandBatch has no switch {sw!r}")
    numba.set_num_threads(min(args.threads, numba.config.NUMBA_NUM_THREADS))
    keep = {sw: getattr(CommandBatch, sw) for sw in names}
    print(f"CommandBatch.{'+'.join(names)} on / off, {args.rounds} alternating rounds, "
          f"{args.threads} thread(s), medians of flush CPU time (ms)")
    with dense_scene.flush_cpu_time() as spent:
        try:
            for name in args.only:
                run, units = WORKLOADS[name]()
                samples = {True: [], False: []}
                for r in range(args.rounds + 1):
                    for on in ((True, False) if r % 2 else (False, True)):
                        _set(names, on)
                        spent[0] = 0.0
                        run()
                        if r:
                            samples[on].append(spent[0])
                on_ms = float(np.median(samples[True])) * 1e3
                off_ms = float(np.median(samples[False])) * 1e3
                line = (f"{name:20s} on {on_ms:9.2f}  off {off_ms:9.2f}  "
                        f"off/on {off_ms / on_ms:5.2f}x")
                if isinstance(units, int):
                    line += (f"  ({units / on_ms / 1e6:.2f} / {units / off_ms / 1e6:.2f} "
                             "G frag/s)")
                batch = getattr(run, "batch", None)
                if batch is not None:
                    for on in (True, False):
                        _set(names, on)
                        batch.reset_counters()
                        run()
                        line += f"\n    {'on ' if on else 'off'} {batch.work()}"
                print(line, flush=True)
        finally:
            for sw, v in keep.items():
                setattr(CommandBatch, sw, v)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
