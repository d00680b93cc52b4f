"""The Heidmann 1991 shadow frame on vgxsim and on Mesa llvmpipe, same scene and algorithm.

    python bench/heidmann_mesa.py [--size 1280x1024] [--reps 5] [--threads 1 2] [--json FILE]

vgxsim renders one frame of :mod:`vgxsim.examples.heidmann1991` while
:func:`vgxsim.reference.recorder.record_window_triangles` captures every clear and
every triangle after clipping and projection, in IRIS window coordinates, with its
state.  The recording is uploaded once to a :class:`vgxsim.reference.mesa.MesaPeer`
and replayed there: the clears and one ``glDrawArrays`` per run of equal state,
then ``glFinish``.  So Mesa gets the same primitives, the same per-face stencil
operations and the same pass structure as vgxsim, without the IRIS GL front end.

Timed (median of ``--reps``), for each thread count, each in a fresh process
(llvmpipe reads LP_NUM_THREADS once):

* ``vgxsim render``: the whole ``render(W, H)`` call -- window open, lighting set-up,
  the IRIS GL calls, transform, lighting, clipping, rasterization, swap, readback of
  the front buffer, window close;
* ``vgxsim replay``: the recorded window-space commands queued on a CommandBatch and
  flushed (snap, triangle set-up, binning, rasterization): the part of vgxsim that
  corresponds to what Mesa is given;
* ``Mesa replay``: the recorded commands on llvmpipe (uploaded beforehand).

Agreement: pixels of Mesa's colour buffer differing from vgxsim's image by more
than one level in some channel, and stencil pixels differing from vgxsim's final
stencil planes.  Differences come from llvmpipe's float32 depth interpolation
where a shadow face and the visible surface are within a few units of 2**-24 of
each other (the depth test goes the other way, and so the shadow does).
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import time

import numpy as np


def median_time(fn, reps: int) -> float:
    """Median wall time of ``reps`` calls of ``fn`` (after one untimed call)."""
    fn()
    ts = []
    for _ in range(reps):
        t = time.perf_counter()
        fn()
        ts.append(time.perf_counter() - t)
    return float(np.median(ts))


def worker(threads: int, width: int, height: int, reps: int) -> dict:
    """Measure one thread count in this process (LP_NUM_THREADS is set here first)."""
    import numba

    from vgxsim import threads as vthreads
    from vgxsim.reference import mesa

    mesa.set_threads(threads)  # before any OSMesa context exists
    numba.set_num_threads(min(threads, numba.config.NUMBA_NUM_THREADS))
    vthreads.set_threads(None)  # follow numba.get_num_threads()

    from vgxsim.batch import CommandBatch
    from vgxsim.examples import heidmann1991 as h91
    from vgxsim.gl._core import current
    from vgxsim.reference.recorder import MesaReplay, record_window_triangles
    from vgxsim.state.planes import Framebuffer, PlaneConfig

    out: dict = {"threads": threads, "vgxsim_threads": vthreads.get_threads(),
                 "size": [width, height]}
    stencils: dict[int, np.ndarray] = {}

    def hook(i: int) -> None:  # the final stencil is the last light's volume pass
        ctx = current("heidmann_mesa")
        ctx.flush()
        stencils[i] = ctx.fb.stencil.copy()

    h91.render(64, 48)  # compile / load the kernels before anything is measured
    with record_window_triangles() as rec:
        image = h91.render(width, height, stencil_hook=hook)
    final_stencil = stencils[max(stencils)]
    runs = rec.runs()
    out.update(triangles=rec.n_triangles, clears=rec.n_clears,
               state_runs=sum(1 for r in runs if not hasattr(r, "planes")),
               skipped_fragment_runs=rec.skipped_fragment_runs)

    out["vgxsim_render_s"] = median_time(lambda: h91.render(width, height), reps)

    fb = Framebuffer(PlaneConfig(width, height, stencil=8))
    batch = CommandBatch(fb)

    def vgx_replay() -> None:
        rec.replay(batch, runs)
        batch.flush()

    out["vgxsim_replay_s"] = median_time(vgx_replay, reps)
    packed = image.view("<u4")[..., 0]
    out["vgxsim_replay_identical"] = bool((fb.front == packed).all()
                                          and (fb.stencil == final_stencil).all())

    if not mesa.mesa_available():
        out["mesa_error"] = "OSMesa/PyOpenGL not available"
        return out
    peer = mesa.MesaPeer(width, height)
    out["renderer"] = mesa.mesa_renderer_string()
    out["mesa_version"] = mesa.mesa_version_string()
    replay = MesaReplay(peer, rec)

    def mesa_replay() -> None:
        replay.run()
        replay.finish()

    out["mesa_replay_s"] = median_time(mesa_replay, reps)
    colour = peer.color().view(np.uint8).reshape(height, width, 4).astype(np.int16)
    diff = np.abs(colour - image.astype(np.int16)).max(axis=-1)
    out["colour_pixels_over_1"] = int((diff > 1).sum())
    out["colour_pixels_over_0"] = int((diff > 0).sum())
    out["colour_max_diff"] = int(diff.max())
    out["stencil_pixels_differ"] = int((peer.stencil() != final_stencil).sum())
    out["pixels"] = width * height
    replay.delete()
    peer.close()
    return out


def run_worker(threads: int, args: argparse.Namespace) -> dict:
    """Run :func:`worker` in a fresh Python process and return its JSON result."""
    env = dict(os.environ)
    env["LP_NUM_THREADS"] = str(threads)
    env.setdefault("NUMBA_CACHE_DIR", "/tmp/nbcache")
    cmd = [sys.executable, os.path.abspath(__file__), "--worker", str(threads),
           "--size", f"{args.width}x{args.height}", "--reps", str(args.reps)]
    res = subprocess.run(cmd, env=env, capture_output=True, text=True)
    if res.returncode != 0:
        return {"threads": threads, "error": res.stderr.strip().splitlines()[-1:]}
    return json.loads(res.stdout.strip().splitlines()[-1])


def table(results: list[dict]) -> str:
    """Format the per-thread results as a text table."""
    lines = []
    first = next((r for r in results if "triangles" in r), None)
    if first is not None:
        w, h = first["size"]
        lines.append(f"Heidmann 1991 frame, {w}x{h}: {first['triangles']} triangles after "
                     f"clipping, {first['clears']} clears, {first['state_runs']} state runs")
        if "renderer" in first:
            lines.append(f"Mesa: {first['mesa_version']}, {first['renderer']}")
    lines.append(f"{'threads':>7} {'vgxsim render':>14} {'vgxsim replay':>14} "
                 f"{'Mesa replay':>12} {'replay ratio':>13} {'render ratio':>13}")
    for r in results:
        if "error" in r:
            lines.append(f"{r['threads']:>7}  error: {r['error']}")
            continue
        vr, vp = r["vgxsim_render_s"], r["vgxsim_replay_s"]
        m = r.get("mesa_replay_s")
        ms = f"{1e3 * m:9.1f} ms" if m else f"{'n/a':>12}"
        rr = f"{vp / m:12.2f}x" if m else f"{'':>13}"
        rn = f"{vr / m:12.2f}x" if m else f"{'':>13}"
        lines.append(f"{r['threads']:>7} {1e3 * vr:11.1f} ms {1e3 * vp:11.1f} ms {ms} {rr} {rn}")
    lines.append("ratio = vgxsim time / Mesa time (above 1: Mesa is faster)")
    for r in results:
        if "colour_pixels_over_1" in r:
            lines.append(
                f"threads {r['threads']}: colour differs by > 1 level at "
                f"{r['colour_pixels_over_1']} of {r['pixels']} pixels (any difference: "
                f"{r['colour_pixels_over_0']}, max {r['colour_max_diff']}); stencil differs "
                f"at {r['stencil_pixels_differ']}; vgxsim replay identical to render: "
                f"{r['vgxsim_replay_identical']}")
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    """Command-line entry point.

    Parameters
    ----------
    argv : list of str, optional
        Arguments (default: ``sys.argv[1:]``).

    Returns
    -------
    int
        Exit status.
    """
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--size", default="1280x1024", help="window WxH (default 1280x1024)")
    ap.add_argument("--reps", type=int, default=5, help="timed repetitions (median)")
    ap.add_argument("--threads", type=int, nargs="+", default=[1, 2])
    ap.add_argument("--json", help="also write the results to this file")
    ap.add_argument("--worker", type=int, help=argparse.SUPPRESS)
    args = ap.parse_args(argv)
    args.width, args.height = (int(v) for v in args.size.lower().split("x"))
    if args.worker is not None:
        print(json.dumps(worker(args.worker, args.width, args.height, args.reps)))
        return 0
    results = [run_worker(t, args) for t in args.threads]
    print(table(results))
    if args.json:
        with open(args.json, "w") as f:
            json.dump(results, f, indent=2)
    return 0


if __name__ == "__main__":
    sys.exit(main())
