"""Heidmann's 1991 claims, and Kolivand and Sunar's Table 1, beside our numbers
(issue 9, item 5).

    python bench/heidmann_claims.py [--quick] [--claims-only] [--out FILE.md]

* "Real shadows, real time": frames per second of the default scene (three cubes,
  two lights) with hard shadows at 1280 x 1024, for the 1991 code and each stencil
  technique.  Two figures: the steady frame loop of the program (window set up once;
  ``DrawFrame(); swapbuffers(); finish()`` timed, as the interactive program ran)
  and one ``api.render`` call (window open, draw, readback, close).
* Figure 6: "created from thirty-two separate images" -- 32 jittered frames
  accumulated in acbuf at 1280 x 1024, seconds (median of several), wall and process
  CPU, beside the shared ambient pass switched off (``share_ambient=False``).
* The shadows program's volume cache (``cache_volumes``: each light's shadow faces and
  their display object kept while the light stays) on and off, the two frame loops
  and the two figure-6 runs alternating, so the ratio is measured side by side.
* Kolivand-Sunar Table 1 ("Compare FPS"): frames per second without shadows
  (``mode='objects'``) and with each technique, on a torus and on a sphere over a
  floor; and their silhouette edge set beside edge adjacency (same edges, tested),
  milliseconds per light.

Medians of several runs on a shared 2-core machine: noisy; compare ratios within a
run, and read them with the load average printed beside them.  ``--claims-only``
measures the first three parts only.  Targets (issue 9): >= 60 frames/s hard
shadows at 1280 x 1024, z-fail <= 1.3x z-pass, 32-image soft shadow <= 0.6 s.
None is asserted anywhere.
"""

from __future__ import annotations

import argparse
import os
import statistics
import time
import warnings

import numpy as np

from vgxsim.shadow import api
from vgxsim.shadow.program import Shadows
from vgxsim.shadow.techniques import make
from vgxsim.shadow.techniques.volumes import (
    light4,
    silhouettes_by_adjacency,
    silhouettes_by_toggle,
)

STENCIL_TECHNIQUES = ("heidmann", "zfail", "auto", "zpplus", "counting", "finite",
                      "roettger", "shadowmap")


def median(fn, repeats: int) -> float:
    fn()  # warm: compiles, caches display objects
    ts = []
    for _ in range(repeats):
        t = time.perf_counter()
        fn()
        ts.append(time.perf_counter() - t)
    return statistics.median(ts)


def frame_loop(scene, size, technique, repeats: int, mode: str = "shadows") -> float:
    """Median seconds per frame of the program's own loop in one open window."""
    return frame_loops(scene, size, [dict(technique=technique, mode=mode)], repeats)[0]


def frame_loops(scene, size, configs: list[dict], repeats: int,
                clock=time.perf_counter) -> list[float]:
    """Median seconds per frame of the program's loop for each configuration
    (``Shadows`` keywords; ``technique`` a name), one window each, the
    configurations' frames alternating round by round.  ``clock``: wall time, or
    ``time.thread_time`` for the CPU time of the calling thread alone (the front end
    and the program's own Python; the raster runs in other threads), which a
    loaded machine disturbs much less."""
    from vgxsim.gl import finish, prefsize, swapbuffers, winclose, winopen, winset

    opened = []
    try:
        for cfg in configs:
            cfg = dict(cfg)
            name = cfg.pop("technique", None)
            cfg.setdefault("signs", "screen")
            prog = Shadows(scene, technique=make(name) if name else None, **cfg)
            prefsize(*size)
            opened.append((winopen("claims"), prog))
            prog.setup()
        times: list[list[float]] = [[] for _ in configs]
        for r in range(repeats + 1):  # round 0 warms up (compiles, display objects)
            for k, (gid, prog) in enumerate(opened):
                winset(gid)
                t = clock()
                prog.DrawFrame()
                swapbuffers()
                finish()
                if r:
                    times[k].append(clock() - t)
        return [statistics.median(ts) for ts in times]
    finally:
        for gid, prog in opened:
            winset(gid)
            prog.teardown()
            winclose(gid)


def load_average() -> str:
    return " ".join(f"{v:.2f}" for v in os.getloadavg())


def torus_and_sphere():
    import trimesh

    torus = trimesh.creation.torus(major_radius=1.0, minor_radius=0.35,
                                   major_sections=48, minor_sections=24)
    torus.apply_translation([-1.4, 1.2, 0.0])
    sphere = trimesh.creation.icosphere(subdivisions=3, radius=0.8)
    sphere.apply_translation([1.5, 1.3, 0.3])
    return {"torus": api.scene_from_meshes([torus]),
            "sphere": api.scene_from_meshes([sphere])}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--out", help="also write the tables to this markdown file")
    ap.add_argument("--claims-only", action="store_true",
                    help="the real-time table, figure 6 and the cache comparison only")
    ns = ap.parse_args()
    warnings.simplefilter("ignore")
    repeats = 3 if ns.quick else 7
    big = (1280, 1024)
    lines = [f"Load average at the start: {load_average()}", "",
             "## Heidmann 1991: real time, default scene, two lights, 1280x1024", "",
             "| technique | frame loop ms | frames/s | api.render ms | vs 1991 loop |",
             "|---|---|---|---|---|"]
    sc = api.load_scene(None)
    base = None
    for tech in (None,) + STENCIL_TECHNIQUES:
        loop = frame_loop(sc, big, tech, repeats)
        one = median(lambda t=tech: api.render(sc, size=big, technique=t), max(1, repeats // 2))
        base = base or loop
        lines.append(f"| {tech or '1991 code'} | {1000 * loop:.0f} | {1 / loop:.1f} | "
                     f"{1000 * one:.0f} | {loop / base:.2f} |")
    frames = 8 if ns.quick else 32
    soft_runs = 3 if ns.quick else 5
    # Default options, volume cache off, shared ambient pass off: alternating, wall
    # and process CPU time (every thread: the band threads render).
    soft_opts = {"default": {}, "cache off": dict(cache_volumes=False),
                 "ambient not shared": dict(share_ambient=False)}
    soft_wall: dict[str, list[float]] = {k: [] for k in soft_opts}
    soft_cpu: dict[str, list[float]] = {k: [] for k in soft_opts}
    api.render(sc, size=big, soft=2)  # warm
    for _ in range(soft_runs):
        for key, opts in soft_opts.items():
            t, c = time.perf_counter(), time.process_time()
            api.render(sc, size=big, soft=frames, **opts)
            soft_wall[key].append(time.perf_counter() - t)
            soft_cpu[key].append(time.process_time() - c)
    wall = {k: statistics.median(v) for k, v in soft_wall.items()}
    cpu_s = {k: statistics.median(v) for k, v in soft_cpu.items()}
    soft = wall["default"]
    lines += ["", f"## Figure 6: {frames} jittered images accumulated, 1280x1024", "",
              f"{frames} frames: median {soft:.2f} s of {soft_runs}, process CPU "
              f"{cpu_s['default']:.2f} s ({soft / frames * 1000:.0f} ms per frame"
              + (f"; 32 frames would take about {soft / frames * 32:.2f} s)" if frames != 32
                 else ")") + "; target <= 0.6 s", "",
              "| options | wall s | process CPU s | CPU vs default |", "|---|---|---|---|"]
    for key in soft_opts:
        lines.append(f"| {key} | {wall[key]:.2f} | {cpu_s[key]:.2f} | "
                     f"{cpu_s[key] / cpu_s['default']:.2f} |")
    configs = [dict(cache_volumes=True), dict(cache_volumes=False),
               dict(cache_volumes=True, signs="article"),
               dict(cache_volumes=False, signs="article")]
    loops = frame_loops(sc, big, configs, repeats)
    cpu = frame_loops(sc, big, configs, repeats, clock=time.thread_time)
    soft_off = wall["cache off"]
    lines += ["", "## The volume cache on and off (1991 code, 1280x1024, alternating)", "",
              "| measure | cache on | cache off | on / off |", "|---|---|---|---|"]
    for name, v in (("frame loop ms", loops), ("main-thread CPU ms per frame", cpu)):
        for signs, a in (("screen", 0), ("article", 2)):
            lines.append(f"| {name}, {signs} signs | {1000 * v[a]:.1f} | "
                         f"{1000 * v[a + 1]:.1f} | {v[a] / v[a + 1]:.2f} |")
    lines += [f"| figure 6 s ({frames} frames) | {soft:.2f} | {soft_off:.2f} | "
              f"{soft / soft_off:.2f} |",
              "", f"Load average at the end of these: {load_average()}"]
    if ns.claims_only:
        _emit(lines, ns.out)
        return
    ks_size = (320, 256) if ns.quick else (640, 512)
    lines += ["", f"## Kolivand-Sunar Table 1 style: frames/s at {ks_size[0]}x{ks_size[1]}",
              "", "| scene | no shadows | " + " | ".join(STENCIL_TECHNIQUES) + " |",
              "|---|" + "---|" * (len(STENCIL_TECHNIQUES) + 1)]
    for name, scene in torus_and_sphere().items():
        row = [f"{1 / frame_loop(scene, ks_size, None, repeats, mode='objects'):.1f}"]
        for tech in STENCIL_TECHNIQUES:
            row.append(f"{1 / frame_loop(scene, ks_size, tech, repeats):.1f}")
        lines.append(f"| {name} | " + " | ".join(row) + " |")
    lines += ["", "## Silhouette detection: edge adjacency vs the Kolivand-Sunar edge set",
              "", "| scene | polygons | adjacency ms | toggle set ms | ratio |",
              "|---|---|---|---|---|"]

    tests = {"cubes": api.load_scene(None), **torus_and_sphere(),
             "teapot": api.load_scene("teapot"), "dense": api.load_scene("dense")}
    for name, scene in tests.items():
        lt = light4(scene.lights[0])
        polys = sum(len(m.polygons) for m in scene.casters)
        adj = median(lambda sc=scene, lt=lt: [silhouettes_by_adjacency(m, lt) for m in sc.casters],
                     repeats)
        tog = median(lambda sc=scene, lt=lt: [silhouettes_by_toggle(m, lt) for m in sc.casters],
                     repeats)
        lines.append(f"| {name} | {polys} | {1000 * adj:.2f} | {1000 * tog:.2f} | "
                     f"{tog / adj:.1f} |")
    lines += ["", f"Load average at the end: {load_average()}"]
    _emit(lines, ns.out)
    _ = np


def _emit(lines: list[str], out: str | None) -> None:
    text = "\n".join(lines)
    print(text)
    if out:
        with open(out, "w") as fh:
            fh.write(text + "\n")


if __name__ == "__main__":
    main()
