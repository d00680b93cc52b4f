"""Frame times of the same IRIS GL program on both backends, side by side.

    python bench/backends.py [--size WxH] [--rounds N]

Workloads: the Heidmann example (vgxsim/examples/heidmann1991.py: the shadows
program's default scene, silhouette edges, subpixel(FALSE) as in the article) and
the same scene with every polygon's volume drawn (``edges='all'``, about twice
the shadow faces).  Each frame is ``DrawFrame(); swapbuffers()`` through vgxsim.gl:
the front end, the geometry pass and, on OpenGL, the upload of the planes, the GL
drawing and the readback of the planes (what a vgxsim.gl program pays).

Configurations, each in a fresh process (llvmpipe reads LP_NUM_THREADS and
GALLIUM_DRIVER once, at its first context): software with 1 and 2 render threads;
OpenGL on llvmpipe with LP_NUM_THREADS 1 and 2; OpenGL on softpipe.  Prints the
median frame time of each and its ratio to software with one thread.  The machine
is shared, so the numbers are noisy: compare ratios from one run.
"""

from __future__ import annotations

import argparse
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
WORKLOADS = ("heidmann", "heidmann_all_edges")


def worker(backend: str, threads: int, width: int, height: int, rounds: int) -> dict:
    """Median frame seconds of each workload in this process."""
    from vgxsim import backends, gl
    from vgxsim import threads as vthreads
    from vgxsim.examples.heidmann1991 import Shadows

    backends.set_backend(backend)
    vthreads.set_threads(threads)
    out: dict = {}
    spent = {"flush": 0.0, "upload": 0.0, "readback": 0.0}
    if backend == "opengl":
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
    for name in WORKLOADS:
        prog = Shadows(edges="all" if name.endswith("all_edges") else "silhouette")
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
        gl.winclose(gid)
    if backend == "opengl":
        from vgxsim.reference.mesa import mesa_renderer_string

        out["renderer"] = mesa_renderer_string()
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--size", default="640x512")
    ap.add_argument("--rounds", type=int, default=7)
    ap.add_argument("--worker", nargs=2, metavar=("BACKEND", "THREADS"), help=argparse.SUPPRESS)
    ns = ap.parse_args(argv)
    w, h = (int(v) for v in ns.size.lower().split("x"))
    if ns.worker:
        print(json.dumps(worker(ns.worker[0], int(ns.worker[1]), w, h, ns.rounds)))
        return 0
    results = {}
    for label, backend, env, threads in CONFIGS:
        proc = subprocess.run(
            [sys.executable, __file__, "--worker", backend, str(threads), "--size", ns.size,
             "--rounds", str(ns.rounds)],
            env={**os.environ, **env}, capture_output=True, text=True)
        if proc.returncode != 0:
            print(f"{label}: failed\n{proc.stderr[-2000:]}", file=sys.stderr)
            continue
        results[label] = json.loads(proc.stdout.strip().splitlines()[-1])
    base = results.get(CONFIGS[0][0])
    print(f"frame times at {w}x{h}, median of {ns.rounds} (ms; ratio to software, 1 thread)")
    print(f"{'configuration':28s}" + "".join(f"{n:>26s}" for n in WORKLOADS) + "  renderer")
    for label, res in results.items():
        cells = ""
        for n in WORKLOADS:
            ratio = "" if base is None else f" ({res[n] / base[n]:.2f}x)"
            cells += f"{res[n] * 1e3:17.1f}{ratio:>9s}"
        print(f"{label:28s}{cells}  {res.get('renderer', '')}")
    print("OpenGL frame split (ms, medians): flush = upload + GL drawing + readback")
    for label, res in results.items():
        for n in WORKLOADS:
            parts = res.get(n + "_parts")
            if parts:
                print(f"  {label:28s} {n:20s} flush {parts['flush'] * 1e3:6.1f}  upload "
                      f"{parts['upload'] * 1e3:5.1f}  draw+readback "
                      f"{parts['readback'] * 1e3:6.1f}  front end "
                      f"{(res[n] - parts['flush']) * 1e3:6.1f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
