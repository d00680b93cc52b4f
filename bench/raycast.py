"""Speed of the exact ray-cast reference (issue 9): rays per second, 1 and 2 threads.

    python bench/raycast.py [--quick] [--rounds N] [--json FILE]

Scenes: the default three-cube scene at 1280 x 1024, the shipped dense scene
(vgxsim/data/scenes/dense.scn: a torus of 51,200 triangles over a floor, the
issue's 50 k-triangle scene), and 20 icospheres (5120 triangles each, 102 k
triangles with the floor) over a floor, two point lights.
Measured side by side in one run, medians of ``--rounds``:

* BVH build time, SAH against object-median splits, and primary-ray speed with each;
* primary rays (nearest hit over every pixel), shadow rays (first blocker, the
  ``counts=False`` path) and the whole :func:`vgxsim.shadow.raycast.raycast` frame
  (visible surface, counts along every segment, face crossings), on 1 and 2 worker
  threads;
* embreex (Embree 4, float32, one thread) on the same primary and shadow rays, when
  it is installed -- an optional speed anchor, not a dependency
  (``pip install vgxsim[raycast-bench]``).

The target (issue 9) is >= 5 M rays/s on two cores on the 50 k-triangle scene;
it is reported, never asserted.  The machine is shared: wall times are noisy, so
rays per CPU-second (``*_cpu_s``) are reported beside them.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import os
import time

import numpy as np
import trimesh

from vgxsim.kernels.raycast import closest_hits, shadow_segments
from vgxsim.shadow import (
    Camera,
    PointLight,
    Scene,
    SurfaceMaterial,
    default_scene,
    polyhedron_from_polygons,
)
from vgxsim.shadow.api import load_scene
from vgxsim.shadow.raycast import (
    homogeneous,
    light_position,
    no_window,
    pixel_rays,
    raycast,
    run_bands,
    scene_bvh,
    tile_order,
)
from vgxsim.shadow.scene import LightModel, make_grid_box


def spheres_scene(n: int = 20, subdivisions: int = 4) -> Scene:
    """``n`` icospheres of radius 0.6 in a 5-wide grid over a 14 x 14 floor."""
    mesh = trimesh.creation.icosphere(subdivisions=subdivisions, radius=0.6)
    ball = polyhedron_from_polygons(mesh.vertices, mesh.faces, "ball",
                                    SurfaceMaterial(diffuse=(0.8, 0.5, 0.3)))
    objs = [make_grid_box("floor", (14.0, 0.25, 14.0), (8, 1, 8),
                          position=(0.0, -0.125, 0.0), casts=False)]
    for i in range(n):
        x, z = (i % 5 - 2) * 1.6, (i // 5 - (n // 5 - 1) / 2) * 1.6
        y = 0.6 + 0.5 * (i % 3)
        objs.append(dataclasses.replace(ball, name=f"ball{i}",
                                        vertices=ball.vertices + np.array([x, y, z])))
    lights = (PointLight("red", (-3.5, 7.5, 1.5), (1.0, 0.3, 0.2)),
              PointLight("blue", (4.0, 6.5, 3.0), (0.3, 0.4, 1.0)))
    cam = Camera(fovy=450, near=1.0, far=40.0, eye=(2.5, 6.5, 9.5), target=(0.0, 0.6, 0.0))
    return Scene(objects=tuple(objs), lights=lights, lmodel=LightModel(), camera=cam)


CPU: dict[str, float] = {}  # CPU seconds of the last median() call (all threads)


def median(run, rounds: int) -> float:
    """Median wall seconds of ``rounds`` runs after a warm-up run; the median CPU
    seconds of the process (every thread) is left in ``CPU['s']``.  On a shared,
    loaded machine the wall time mostly measures the other jobs: rays per
    CPU-second is the figure that carries (for 2 threads, wall >= CPU / 2)."""
    run()  # compile / warm caches
    ts, cs = [], []
    for _ in range(rounds):
        t, c = time.perf_counter(), time.process_time()
        run()
        ts.append(time.perf_counter() - t)
        cs.append(time.process_time() - c)
    CPU["s"] = float(np.median(cs))
    return float(np.median(ts))


def measure(scene: Scene, w: int, h: int, rounds: int) -> dict:
    origin, direction = pixel_rays(scene, w, h)
    o = np.ascontiguousarray(origin.reshape(-1, 3))
    d = np.ascontiguousarray(direction.reshape(-1, 3))
    n = len(o)
    tris, tri_obj = scene.triangles()
    t4 = homogeneous(tris)
    res: dict = {"triangles": len(tris), "pixels": n}
    trees = {}
    for sah in (True, False):
        res[f"build_s_{'sah' if sah else 'median'}"] = median(
            lambda sah=sah: trees.__setitem__(sah, scene_bvh(t4, sah=sah)), rounds)
    idx = np.empty(n, np.int64)
    t = np.empty(n)
    win = no_window()
    order = tile_order(w, h)
    for sah in (True, False):
        for th in (1, 2):
            s = median(lambda th=th, sah=sah: run_bands(closest_hits, n, th, trees[sah], win, o,
                                                         d, 0.0, 1.0, order, (idx, t)), rounds)
            key = f"primary_{'sah' if sah else 'median'}_{th}t"
            res[f"{key}_Mrays_s"] = n / s / 1e6
            res[f"{key}_Mrays_cpu_s"] = n / CPU["s"] / 1e6
    hit = idx >= 0
    pts = np.ascontiguousarray(np.where(hit[:, None], o + np.where(hit, t, 0)[:, None] * d, 0))
    casts = np.array([ob.casts for ob in scene.objects])[tri_obj]
    ctree = scene_bvh(t4, casts)
    lights = np.array([light_position(li) for li in scene.lights])
    nl = len(lights)
    lw = np.zeros((nl, len(tris)), np.int64)
    outs = (np.zeros((n, nl), bool), np.zeros((n, nl), np.int64), np.zeros((n, nl), np.int64))
    nseg = int(hit.sum()) * nl
    for th in (1, 2):
        s = median(lambda th=th: run_bands(shadow_segments, n, th, ctree, tri_obj,
                                           len(scene.objects), lw, pts, idx, hit, lights,
                                           100.0, 1e-6, False, order, outs), rounds)
        res[f"shadow_{th}t_Mrays_s"] = nseg / s / 1e6
        res[f"shadow_{th}t_Mrays_cpu_s"] = nseg / CPU["s"] / 1e6
        f = median(lambda th=th: raycast(scene, w, h, threads=th), max(1, rounds // 2))
        res[f"frame_{th}t_s"] = f
        res[f"frame_{th}t_cpu_s"] = CPU["s"]
        # rays per frame: eye rays, the same rays again for the crossings, shadow rays
        res[f"frame_{th}t_Mrays_s"] = (2 * n + nseg) / f / 1e6
    res["shadowed_fraction"] = float(outs[0][hit].mean()) if hit.any() else 0.0
    res.update(embree(tris, casts, o, d, pts[hit], lights, rounds, n, nseg))
    return res


def embree(tris, casts, o, d, pts, lights, rounds: int, n: int, nseg: int) -> dict:
    """embreex on the same rays (float32), or nothing when it is not installed."""
    try:
        from embreex import rtcore_scene as rtcs
        from embreex.mesh_construction import TriangleMesh
    except ImportError:
        return {"embree": "not installed"}
    sc = rtcs.EmbreeScene()
    TriangleMesh(sc, tris.astype(np.float32))
    csc = rtcs.EmbreeScene()
    TriangleMesh(csc, tris[casts].astype(np.float32))
    o32, d32 = o.astype(np.float32), d.astype(np.float32)
    out = {"embree_primary_Mrays_s": n / median(lambda: sc.run(o32, d32, output=1),
                                                 rounds) / 1e6}
    out["embree_primary_Mrays_cpu_s"] = n / CPU["s"] / 1e6
    segs = []
    for lp in lights:
        to = (lp[:3] - pts).astype(np.float32)
        org = (pts + 1e-4 * to).astype(np.float32)  # float32 needs a real offset
        segs.append((org, to))

    def shadows():
        for org, to in segs:
            csc.run(org, to, query="OCCLUDED", dists=np.full(len(org), 0.999, np.float32))

    out["embree_shadow_Mrays_s"] = nseg / median(shadows, rounds) / 1e6
    out["embree_shadow_Mrays_cpu_s"] = nseg / CPU["s"] / 1e6
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="320 x 256, fewer rounds")
    ap.add_argument("--rounds", type=int, default=None)
    ap.add_argument("--json", help="write the figures to this file")
    ap.add_argument("--scenes", nargs="+",
                    choices=["three cubes", "dense torus", "20 icospheres"],
                    help="measure only these (default: all)")
    args = ap.parse_args(argv)
    w, h = (320, 256) if args.quick else (1280, 1024)
    rounds = args.rounds or (2 if args.quick else 3)
    results = {}
    scenes = {"three cubes": default_scene, "dense torus": lambda: load_scene("dense"),
              "20 icospheres": spheres_scene}
    load = [os.getloadavg()[0]]
    for name in args.scenes or scenes:
        results[name] = measure(scenes[name](), w, h, rounds)
    load.append(os.getloadavg()[0])
    for r in results.values():
        r["load_average_1min"] = f"{load[0]:.1f} -> {load[1]:.1f}"
    keys = sorted({k for r in results.values() for k in r})
    print(f"| {w} x {h} | " + " | ".join(results) + " |")
    print("|---" * (len(results) + 1) + "|")
    for k in keys:
        row = []
        for r in results.values():
            v = r.get(k, "")
            row.append(f"{v:.3g}" if isinstance(v, float) else str(v))
        print(f"| {k} | " + " | ".join(row) + " |")
    if args.json:
        with open(args.json, "w") as f:
            json.dump({"size": [w, h], "results": results}, f, indent=1)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
