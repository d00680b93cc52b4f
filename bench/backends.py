"""Frame times of the same IRIS GL program on both backends, side by side.

    python bench/backends.py [--size WxH] [--rounds N] [--workloads A,B] [--csv FILE]
    python bench/backends.py --quick          # 160x128, 3 rounds: a smoke run

Workloads, each one frame of the shadows program's 'shadows' mode (vgxsim/shadow/
program.py) at subpixel(FALSE), as in the article:

* ``heidmann``: the Heidmann example (vgxsim/examples/heidmann1991.py: the default
  scene, silhouette edges, the article's stencil signs); ``heidmann_all_edges``:
  the same with every polygon's volume drawn (about twice the shadow faces);
* the shipped scenes of vgxsim/data as ``vgxsim shadows SCENE`` draws them
  (screen signs): ``cubes`` (the default scene read from its .scn file),
  ``balls``, ``textured_floor`` (a bilinear TV_MODULATE texture on every pass: on
  the OpenGL backend the software batch draws the textured floor, see
  docs/opengl_backend.md), ``dense`` (a torus of 51 200 triangles) and ``teapot``.

Each frame is ``DrawFrame(); swapbuffers()`` through vgxsim.gl: the front end, the
geometry pass and, on OpenGL, the upload of the planes, the GL drawing and the
readback of the planes (what a vgxsim.gl program pays).

Configurations, each in a fresh process (llvmpipe reads LP_NUM_THREADS and
GALLIUM_DRIVER once, at its first context): software with 1 and 2 render threads;
OpenGL on llvmpipe with LP_NUM_THREADS 1 and 2; OpenGL on softpipe.  Prints, as a
markdown table, the median frame time of each and its ratio to software with one
thread, then the OpenGL frames split into front end and flush.  Compare ratios from
one run: on a shared machine the absolute numbers are noisy.
"""

from __future__ import annotations

import argparse
import csv
import json
import os
import subprocess
import sys
import time

import numpy as np

CONFIGS = (
    ("software, 1 thread", "software", {"NUMBA_NUM_THREADS": "1"}, 1),
    ("software, 2 threads", "software", {"NUMBA_NUM_THREADS": "2"}, 2),
    ("opengl llvmpipe, 1 thread", "opengl", {"LP_NUM_THREADS": "1"}, 1),
    ("opengl llvmpipe, 2 threads", "opengl", {"LP_NUM_THREADS": "2"}, 2),
    ("opengl softpipe", "opengl", {"GALLIUM_DRIVER": "softpipe", "LP_NUM_THREADS": "1"}, 1),
)
SCENES = ("cubes", "balls", "textured_floor", "dense", "teapot")
WORKLOADS = ("heidmann", "heidmann_all_edges", *SCENES)


def make_program(name: str):
    """The Shadows program of one workload."""
    from vgxsim.shadow.api import load_scene
    from vgxsim.shadow.program import Shadows

    if name == "heidmann":
        return Shadows(edges="silhouette")
    if name == "heidmann_all_edges":
        return Shadows(edges="all")
    return Shadows(load_scene(name), signs="screen")


def _time_calls(spent: dict) -> None:
    """Add the seconds spent in the OpenGL batch's flush and the surface's upload
    and readback to ``spent`` (the OpenGL frame split)."""
    from vgxsim.backends.opengl.batch import OpenGLBatch
    from vgxsim.backends.opengl.surface import Surface

    def timed(cls, name, key):
        real = getattr(cls, name)

        def wrapper(self, *a, **k):
            t = time.perf_counter()
            try:
                return real(self, *a, **k)
            finally:
                spent[key] += time.perf_counter() - t
        setattr(cls, name, wrapper)

    timed(OpenGLBatch, "flush", "flush")
    timed(Surface, "begin", "upload")
    timed(Surface, "end", "readback")  # waits for GL to finish drawing


def worker(backend: str, threads: int, width: int, height: int, rounds: int,
           workloads: list[str]) -> dict:
    """Median frame seconds of each workload in this process."""
    from vgxsim import backends, gl
    from vgxsim import threads as vthreads

    backends.set_backend(backend)
    vthreads.set_threads(threads)
    out: dict = {}
    spent = {"flush": 0.0, "upload": 0.0, "readback": 0.0}
    if backend == "opengl":
        _time_calls(spent)
    for name in workloads:
        prog = make_program(name)
        gl.prefsize(width, height)
        gid = gl.winopen("bench")
        prog.setup()

        def frame(prog=prog):
            prog.DrawFrame()
            gl.swapbuffers()

        frame()  # compiles, creates the GL context
        frame()
        ts = []
        parts = {k: [] for k in spent}
        for _ in range(rounds):
            for k in spent:
                spent[k] = 0.0
            t = time.perf_counter()
            frame()
            ts.append(time.perf_counter() - t)
            for k, v in spent.items():
                parts[k].append(v)
        out[name] = float(np.median(ts))
        if backend == "opengl":
            out[name + "_parts"] = {k: float(np.median(v)) for k, v in parts.items()}
        prog.teardown()
        gl.winclose(gid)
    if backend == "opengl":
        from vgxsim.reference.mesa import mesa_renderer_string

        out["renderer"] = mesa_renderer_string()
    return out


def table(results: dict, workloads: list[str]) -> list[str]:
    """Markdown rows: per configuration and workload the median frame time in ms
    and the ratio to the first configuration's."""
    base = results.get(CONFIGS[0][0])
    head = "| configuration | " + " | ".join(workloads) + " |"
    rows = [head, "|" + "---|" * (len(workloads) + 1)]
    for label, res in results.items():
        cells = []
        for n in workloads:
            ratio = "" if base is None else f" ({res[n] / base[n]:.2f}×)"
            cells.append(f"{res[n] * 1e3:.1f}{ratio}")
        rows.append(f"| {label} | " + " | ".join(cells) + " |")
    return rows


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--size", default=None, help="window WxH (default 640x512)")
    ap.add_argument("--rounds", type=int, default=None, help="timed frames (default 5)")
    ap.add_argument("--workloads", default=",".join(WORKLOADS),
                    help="comma-separated subset of " + ", ".join(WORKLOADS))
    ap.add_argument("--quick", action="store_true",
                    help="160x128 and 3 rounds unless given: a smoke run, not a measurement")
    ap.add_argument("--csv", metavar="FILE", help="also write the medians as CSV")
    ap.add_argument("--worker", nargs=2, metavar=("BACKEND", "THREADS"), help=argparse.SUPPRESS)
    ns = ap.parse_args(argv)
    size = ns.size or ("160x128" if ns.quick else "640x512")
    rounds = ns.rounds or (3 if ns.quick else 5)
    workloads = [w for w in ns.workloads.split(",") if w]
    unknown = sorted(set(workloads) - set(WORKLOADS))
    if unknown:
        ap.error(f"unknown workloads {', '.join(unknown)} (known: {', '.join(WORKLOADS)})")
    w, h = (int(v) for v in size.lower().split("x"))
    if ns.worker:
        print(json.dumps(worker(ns.worker[0], int(ns.worker[1]), w, h, rounds, workloads)))
        return 0
    results = {}
    for label, backend, env, threads in CONFIGS:
        t0 = time.perf_counter()
        proc = subprocess.run(
            [sys.executable, __file__, "--worker", backend, str(threads), "--size", size,
             "--rounds", str(rounds), "--workloads", ",".join(workloads)],
            env={**os.environ, **env}, capture_output=True, text=True)
        if proc.returncode != 0:
            print(f"{label}: failed\n{proc.stderr[-2000:]}", file=sys.stderr)
            continue
        results[label] = json.loads(proc.stdout.strip().splitlines()[-1])
        print(f"  ({label}: {time.perf_counter() - t0:.0f} s)", file=sys.stderr, flush=True)
    renderers = sorted({r["renderer"] for r in results.values() if "renderer" in r})
    print(f"Frame times at {w}x{h}, median of {rounds} (ms; ratio to software, 1 thread); "
          f"load average {os.getloadavg()[0]:.1f}; OpenGL: {'; '.join(renderers)}")
    print()
    print("\n".join(table(results, workloads)))
    print()
    print("OpenGL frames (ms, medians): front end and geometry = frame - flush; "
          "flush = upload + GL drawing and readback + software-batch runs")
    print()
    print("| configuration | workload | frame | front end | flush | upload | draw+readback |")
    print("|---|---|---|---|---|---|---|")
    for label, res in results.items():
        for n in workloads:
            parts = res.get(n + "_parts")
            if parts:
                print(f"| {label} | {n} | {res[n] * 1e3:.1f} | "
                      f"{(res[n] - parts['flush']) * 1e3:.1f} | {parts['flush'] * 1e3:.1f} | "
                      f"{parts['upload'] * 1e3:.1f} | {parts['readback'] * 1e3:.1f} |")
    if ns.csv:
        with open(ns.csv, "w", newline="") as f:
            out = csv.writer(f)
            out.writerow(["configuration", "workload", "width", "height", "rounds",
                          "median_ms", "ratio_to_software_1", "flush_ms"])
            base = results.get(CONFIGS[0][0])
            for label, res in results.items():
                for n in workloads:
                    parts = res.get(n + "_parts") or {}
                    out.writerow([label, n, w, h, rounds, f"{res[n] * 1e3:.3f}",
                                  "" if base is None else f"{res[n] / base[n]:.4f}",
                                  f"{parts['flush'] * 1e3:.3f}" if parts else ""])
    return 0


if __name__ == "__main__":
    sys.exit(main())
