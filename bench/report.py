"""Print the core benchmark table (issue 2, deliverable 9).

    python bench/report.py [--quick] [--no-mesa] [--json FILE]

Everything is measured side by side in one run and medians are quoted:
* fill rates of the z+stencil (shadow-volume) pass and of the colour+blend (lit)
  pass, each beside a loop that only touches the same memory (the ratio is the
  figure that carries across machines);
* 10-pixel triangles per second through the array path (transform, clip, snap,
  setup, bin, raster), and split into front end and raster with the fused front end
  (kernels/front.py) on and off, alternating;
* thread scaling 1 -> 2 (numba.set_num_threads);
* Mesa llvmpipe on the same workloads with LP_NUM_THREADS = 1 and 2, each in its own
  process (llvmpipe reads the variable once);
* cold start (empty Numba cache) and warm start to the first image, in fresh
  processes;
* the Heidmann 1991 shadow frame, when the example is installed;
* a dense shadow scene (bench/dense_scene.py: 20 spheres over a floor, two lights,
  about 42 k triangles) through the library path, beside Mesa llvmpipe;
* the work counters (CommandBatch.work()) of each workload, and the time of the
  shadow frames with exact work skipping switched off, measured beside;
* the 10-pixel triangles and the dense scene with the raster switches (spans stepped
  row to row, records copied into band order, int32 packing, the small-triangle path,
  the block update) on and off, alternating.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import time

import numba
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

import dense_scene  # noqa: E402
import scenes  # noqa: E402
import startup  # noqa: E402

from vgxsim.batch import CommandBatch  # noqa: E402


def median_time(run, rounds: int) -> float:
    run()
    ts = []
    for _ in range(rounds):
        t = time.perf_counter()
        run()
        ts.append(time.perf_counter() - t)
    return float(np.median(ts))


def set_skipping(on: bool) -> None:
    """Exact work skipping on every batch (kernels/tiles.py switches)."""
    CommandBatch.skip_tiles = on
    CommandBatch.cover_blocks = on
    CommandBatch.tight_tiles = on


def vgxsim_rates(rounds: int) -> tuple[dict, dict]:
    out = {}
    work = {}
    for threads in (1, 2):
        numba.set_num_threads(min(threads, numba.config.NUMBA_NUM_THREADS))
        for name in ("zstencil_fill", "zstencil_hidden_fill", "colour_blend_fill",
                     "small_triangles", "touch_zstencil_run", "touch_colour_run"):
            run, units = getattr(scenes, name)()
            out[(name, threads)] = (median_time(run, rounds), units)
            batch = getattr(run, "batch", None)
            if batch is not None and threads == 1:
                batch.reset_counters()
                run()
                work[name] = batch.work()
    numba.set_num_threads(numba.config.NUMBA_NUM_THREADS)
    return out, work


def small_triangle_split(rounds: int) -> dict:
    """The 10-pixel triangles (bench/scenes.py small_triangles) split into front end
    (transform, clip, project, snap, set-up: the time outside CommandBatch.flush) and
    raster (inside it), with the fused front end (kernels/front.py) on and off,
    alternating round by round on 1 and 2 threads.  Process CPU time (all threads)
    beside wall time: on a shared machine the CPU time is the steadier figure.

    Returns {(threads, fused): {"wall", "cpu", "front_cpu", "raster_cpu"}} in s.
    """
    from vgxsim.geometry import pipeline as geometry

    out: dict = {}
    keep = geometry.FUSED_FRONT
    flush_timer = dense_scene.flush_cpu_time()
    spent = flush_timer.__enter__()
    try:
        for threads in (1, 2):
            numba.set_num_threads(min(threads, numba.config.NUMBA_NUM_THREADS))
            run, _units = scenes.small_triangles()
            samples: dict = {}
            for r in range(rounds + 1):
                for fused in (True, False):
                    geometry.FUSED_FRONT = fused
                    spent[0] = 0.0
                    c, w = time.process_time(), time.perf_counter()
                    run()
                    row = (time.perf_counter() - w, time.process_time() - c, spent[0])
                    if r:  # the first round compiles and warms up
                        samples.setdefault(fused, []).append(row)
            for fused, rows in samples.items():
                a = np.array(rows)
                out[(threads, fused)] = {
                    "wall": float(np.median(a[:, 0])), "cpu": float(np.median(a[:, 1])),
                    "front_cpu": float(np.median(a[:, 1] - a[:, 2])),
                    "raster_cpu": float(np.median(a[:, 2]))}
    finally:
        flush_timer.__exit__(None, None, None)
        geometry.FUSED_FRONT = keep
        numba.set_num_threads(numba.config.NUMBA_NUM_THREADS)
    return out


RASTER_SWITCHES = ("step_spans", "band_records", "vector_pack", "small_path",
                   "block_update", "lit_spans", "lit_lanes", "fill_spans", "zpass_spans",
                   "prefetch_planes",
                   "borrow_arrays")  # CommandBatch, issue 7


def raster_switches(rounds: int) -> dict:
    """The 10-pixel triangles and the dense scene with the raster switches
    (``RASTER_SWITCHES``: spans stepped row to row, records copied into band order,
    int32 conversions in the lit and z+stencil loops, the small-triangle path, the
    block update of z-passed tiles, the out-of-line lit span loop; bench/fill_ab.py
    A/Bs one switch, or a few, at a time)
    all on and all off, alternating round by round on 1 and 2 threads: wall time and
    the process CPU time spent in CommandBatch.flush (the raster).

    Returns {(workload, threads, on): {"wall", "raster_cpu"}} in s.
    """
    passes, _, _ = dense_scene.build()
    runs = {"small_triangles": scenes.small_triangles()[0],
            "dense_scene": dense_scene.vgxsim_frame(passes)[0]}
    out: dict = {}
    flush_timer = dense_scene.flush_cpu_time()
    spent = flush_timer.__enter__()
    try:
        for threads in (1, 2):
            numba.set_num_threads(min(threads, numba.config.NUMBA_NUM_THREADS))
            for name, run in runs.items():
                samples: dict = {True: [], False: []}
                for r in range(rounds + 1):
                    for on in (True, False):
                        for sw in RASTER_SWITCHES:
                            setattr(CommandBatch, sw, on)
                        spent[0] = 0.0
                        w = time.perf_counter()
                        run()
                        if r:
                            samples[on].append((time.perf_counter() - w, spent[0]))
                for on, rows in samples.items():
                    a = np.array(rows)
                    out[(name, threads, on)] = {"wall": float(np.median(a[:, 0])),
                                                "raster_cpu": float(np.median(a[:, 1]))}
    finally:
        flush_timer.__exit__(None, None, None)
        for sw in RASTER_SWITCHES:
            setattr(CommandBatch, sw, True)
        numba.set_num_threads(numba.config.NUMBA_NUM_THREADS)
    return out


def dense_rates(rounds: int, mesa: bool) -> dict:
    """The dense scene on vgxsim (1 and 2 threads, skipping on and off) and Mesa."""
    passes, ntri, nvol = dense_scene.build()
    run, batch = dense_scene.vgxsim_frame(passes)
    out = {"triangles": ntri, "volume_triangles": nvol}
    for threads in (1, 2):
        numba.set_num_threads(min(threads, numba.config.NUMBA_NUM_THREADS))
        for on in (True, False):
            set_skipping(on)
            out[f"vgxsim{threads}" + ("" if on else "_noskip")] = median_time(run, rounds)
    set_skipping(True)
    numba.set_num_threads(numba.config.NUMBA_NUM_THREADS)
    batch.reset_counters()
    run()
    out["work"] = batch.work()
    if mesa:
        for threads in (1, 2):
            proc = subprocess.run([sys.executable, os.path.join(HERE, "dense_scene.py"),
                                   str(threads)], capture_output=True, text=True)
            try:
                out[f"mesa{threads}"] = json.loads(proc.stdout.strip().splitlines()[-1])["frame"]
            except (IndexError, KeyError, json.JSONDecodeError):
                out[f"mesa{threads}"] = None
    return out


def mesa_rates() -> dict:
    out = {}
    env = dict(os.environ, PYTHONPATH=HERE + os.pathsep + os.environ.get("PYTHONPATH", ""))
    for threads in (1, 2):
        proc = subprocess.run([sys.executable, os.path.join(HERE, "mesa_worker.py"),
                               str(threads)], capture_output=True, text=True, env=env)
        try:
            data = json.loads(proc.stdout.strip().splitlines()[-1])
        except (IndexError, json.JSONDecodeError):
            data = {"error": proc.stderr.strip()[-300:]}
        out[threads] = data
    return out


def heidmann_frame(rounds: int) -> dict | None:
    try:
        from vgxsim.examples import heidmann1991
        from vgxsim.gl._core import current
    except ImportError:
        return None
    out = {}
    work = {}

    def hook(i):
        ctx = current("bench")
        ctx.flush()
        work.update(ctx.batch.work())

    def frame(**kw):
        return heidmann1991.render(1280, 1024, mode="shadows", edges="silhouette", **kw)

    for threads in (1, 2):
        numba.set_num_threads(min(threads, numba.config.NUMBA_NUM_THREADS))
        for on in (True, False):
            set_skipping(on)
            out[threads if on else f"{threads}_noskip"] = median_time(frame, rounds)
    set_skipping(True)
    numba.set_num_threads(numba.config.NUMBA_NUM_THREADS)
    frame(stencil_hook=hook)
    out["work"] = dict(work)
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="3 rounds instead of 7")
    ap.add_argument("--no-mesa", action="store_true")
    ap.add_argument("--json", help="also write the raw numbers here")
    args = ap.parse_args(argv)
    rounds = 3 if args.quick else 7
    rates, work = vgxsim_rates(rounds)
    split = small_triangle_split(rounds)
    switched = raster_switches(rounds)
    mesa = {} if args.no_mesa else mesa_rates()
    cold_run, warm_runs = startup.start_times()
    cold, warm = cold_run[0], warm_runs[0][0]
    frame = heidmann_frame(rounds)
    dense = dense_rates(rounds, not args.no_mesa)

    def rate(name, threads):
        t, units = rates[(name, threads)]
        return units / t

    print(f"vgxsim benchmark (medians of {rounds}; 1280x1024; machine: {os.cpu_count()} CPUs)")
    print()
    hdr = f"{'workload':28s} {'1 thread':>12s} {'2 threads':>12s} {'scaling':>8s}"
    hdr += f" {'touch ratio':>12s} {'Mesa 1T':>12s} {'Mesa 2T':>12s} {'vs Mesa 2T':>10s}"
    print(hdr)
    touch = {"zstencil_fill": "touch_zstencil_run", "zstencil_hidden_fill": "touch_zstencil_run",
             "colour_blend_fill": "touch_colour_run"}
    units = {"zstencil_fill": "Mfrag/s", "zstencil_hidden_fill": "Mfrag/s",
             "colour_blend_fill": "Mfrag/s", "small_triangles": "Mtri/s"}
    raw = {"vgxsim": {f"{k[0]}@{k[1]}": v for k, v in rates.items()}, "mesa": mesa}
    for name in ("zstencil_fill", "zstencil_hidden_fill", "colour_blend_fill",
                 "small_triangles"):
        r1, r2 = rate(name, 1) / 1e6, rate(name, 2) / 1e6
        ratio = f"{rate(name, 1) / rate(touch[name], 1):.3f}" if name in touch else "-"
        m1 = m2 = vs = "-"
        if 1 in mesa and name in mesa[1]:
            t, u = mesa[1][name]
            m1 = f"{u / t / 1e6:.1f}"
        if 2 in mesa and name in mesa[2]:
            t, u = mesa[2][name]
            m2 = f"{u / t / 1e6:.1f}"
            vs = f"{r2 / (u / t / 1e6):.2f}x"
        print(f"{name + ' (' + units[name] + ')':28s} {r1:12.1f} {r2:12.1f} {r2 / r1:7.2f}x"
              f" {ratio:>12s} {m1:>12s} {m2:>12s} {vs:>10s}")
    print("\n10-pixel triangles, 200 k per run, fused front end (kernels/front.py) on/off, "
          "alternating (ms; CPU = process time of all threads):")
    print(f"{'threads':>8s} {'fused':>6s} {'wall':>8s} {'CPU':>8s} {'front CPU':>10s} "
          f"{'raster CPU':>11s} {'Mtri/s wall':>12s}")
    for (threads, fused), v in sorted(split.items()):
        print(f"{threads:8d} {'on' if fused else 'off':>6s} {v['wall'] * 1e3:8.1f} "
              f"{v['cpu'] * 1e3:8.1f} {v['front_cpu'] * 1e3:10.1f} "
              f"{v['raster_cpu'] * 1e3:11.1f} {0.2 / v['wall']:12.2f}")
    raw["small_triangle_split"] = {f"{t}@{'fused' if f else 'unfused'}": v
                                   for (t, f), v in split.items()}
    print(f"\nraster switches ({', '.join(RASTER_SWITCHES)}) all on / all off, alternating "
          "(ms; raster CPU = process time in flush):")
    print(f"{'workload':18s} {'threads':>8s} {'wall on':>9s} {'wall off':>9s} "
          f"{'raster CPU on':>14s} {'raster CPU off':>15s} {'off/on':>7s}")
    for name in ("small_triangles", "dense_scene"):
        for threads in (1, 2):
            on, off = switched[(name, threads, True)], switched[(name, threads, False)]
            print(f"{name:18s} {threads:8d} {on['wall'] * 1e3:9.1f} {off['wall'] * 1e3:9.1f} "
                  f"{on['raster_cpu'] * 1e3:14.1f} {off['raster_cpu'] * 1e3:15.1f} "
                  f"{off['raster_cpu'] / max(on['raster_cpu'], 1e-9):6.2f}x")
    raw["raster_switches"] = {f"{n}@{t}@{'on' if o else 'off'}": v
                              for (n, t, o), v in switched.items()}
    if mesa.get(1, {}).get("renderer"):
        print(f"\nMesa renderer: {mesa[1]['renderer']}")
    elif mesa:
        print(f"\nMesa: {mesa.get(1, {}).get('error', 'unavailable')}")
    print(f"\ncold start to first image (empty Numba cache): {cold:.2f} s")
    print(f"warm start to first image: {warm:.2f} s")
    if frame:
        print(f"\nHeidmann 1991 shadow frame 1280x1024 (through the IRIS GL API): "
              f"{frame[1] * 1e3:.1f} ms on 1 thread, {frame[2] * 1e3:.1f} ms on 2 threads; "
              f"work skipping off: {frame['1_noskip'] * 1e3:.1f} / "
              f"{frame['2_noskip'] * 1e3:.1f} ms")
        raw["heidmann_frame"] = frame
        work["heidmann_frame"] = frame["work"]
    d = dense
    mesa_txt = ""
    if d.get("mesa1") and d.get("mesa2"):
        mesa_txt = (f"; Mesa {d['mesa1'] * 1e3:.1f} / {d['mesa2'] * 1e3:.1f} ms "
                    f"(vgxsim/Mesa time at 2 threads {d['vgxsim2'] / d['mesa2']:.2f})")
    print(f"\ndense scene ({d['triangles']} scene + {d['volume_triangles']} volume triangles, "
          f"two lights, raster only): vgxsim {d['vgxsim1'] * 1e3:.1f} / "
          f"{d['vgxsim2'] * 1e3:.1f} ms on 1 / 2 threads (skipping off: "
          f"{d['vgxsim1_noskip'] * 1e3:.1f} / {d['vgxsim2_noskip'] * 1e3:.1f} ms){mesa_txt}")
    work["dense_scene"] = d["work"]
    raw["dense_scene"] = d
    print("\nwork counters (one frame / one run, CommandBatch.work()):")
    names = list(next(iter(work.values())).keys())
    print(f"{'workload':24s}" + "".join(f" {n:>15s}" for n in names))
    for wl, counts in work.items():
        print(f"{wl:24s}" + "".join(f" {counts[n]:15d}" for n in names))
    raw["work"] = work
    raw["start"] = {"cold": cold, "warm": warm}
    if args.json:
        with open(args.json, "w") as f:
            json.dump(raw, f, indent=1, default=str)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
