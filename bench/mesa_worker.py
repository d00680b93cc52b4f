"""Time the bench workloads on Mesa llvmpipe (OSMesa) in a fresh process.

llvmpipe reads LP_NUM_THREADS once, when its first context is created, so each
thread count needs its own process: ``python bench/mesa_worker.py THREADS``
prints one JSON object of median seconds per workload.
"""

from __future__ import annotations

import json
import sys
import time

import numpy as np


def main() -> None:
    threads = int(sys.argv[1])
    from vgxsim.reference import mesa

    mesa.set_threads(threads)
    if not mesa.mesa_available():
        print(json.dumps({"error": "OSMesa/PyOpenGL not available"}))
        return
    import scenes

    from vgxsim.state.raster import RasterState

    w, h = scenes.W, scenes.H
    peer = mesa.MesaPeer(w, h)
    out = {"renderer": mesa.mesa_renderer_string(), "threads": threads}
    clear = ("clear", {"color", "z", "stencil"}, {"color": 0, "z": 0x7FFFFF, "stencil": 0},
             RasterState(scissor=(0, w - 1, 0, h - 1), draw_front=True))

    def timed(arrays, state, n=5):
        ts = []
        for _ in range(n):
            peer.render([clear])
            peer.finish()
            t = time.perf_counter()
            peer.draw_arrays(arrays, state)
            peer.finish()
            ts.append(time.perf_counter() - t)
        return float(np.median(ts))

    layers = 20
    xw, yw, zw, tris = scenes.fullscreen_quads(layers)
    pos = np.stack([xw, yw, zw], axis=1)[tris.reshape(-1)]
    rs = RasterState(scissor=(0, w - 1, 0, h - 1), zbuffer=True, stencil=True, sfunc=7,
                     szpass=3, wmpack=0, zwritemask=0, draw_front=True)
    arr = peer.upload_arrays(pos, (1, 1, 1, 1))
    out["zstencil_fill"] = [timed(arr, rs), layers * w * h]
    arr.delete()
    layers = 5
    xw, yw, zw, tris = scenes.fullscreen_quads(layers)
    pos = np.stack([xw, yw, zw], axis=1)[tris.reshape(-1)]
    col = np.random.default_rng(1).random((pos.shape[0], 4))
    rs = RasterState(scissor=(0, w - 1, 0, h - 1), zbuffer=True, stencil=True, sfunc=2,
                     blend_sf=1, blend_df=1, draw_front=True)
    arr = peer.upload_arrays(pos, col)
    out["colour_blend_fill"] = [timed(arr, rs), layers * w * h]
    arr.delete()
    count, area = 200_000, 10.0
    rng = np.random.default_rng(0)
    side = np.sqrt(2.0 * area)
    centre = rng.uniform([0, 0], [w, h], size=(count, 2))
    pts = (centre[:, None, :] + rng.uniform(-side / 2, side / 2, (count, 3, 2))).reshape(-1, 2)
    pos = np.concatenate([pts, rng.uniform(-1000, 1000, (pts.shape[0], 1))], axis=1)
    rs = RasterState(scissor=(0, w - 1, 0, h - 1), zbuffer=True, draw_front=True)
    arr = peer.upload_arrays(pos, rng.random((pos.shape[0], 4)))
    out["small_triangles"] = [timed(arr, rs), count]
    arr.delete()
    print(json.dumps(out))


if __name__ == "__main__":
    main()
