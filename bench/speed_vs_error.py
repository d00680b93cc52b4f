"""Speed against error for every shadow technique (issue 9, item 4).

    python bench/speed_vs_error.py [--quick] [--out DIR]

For every technique x resolution x subpixel mode (x shadow-map size) over the shipped
scenes and the hard cases: the median time per frame of the program's own loop
(``DrawFrame(); swapbuffers(); finish()`` in one window, after one untimed frame),
and the error against the ray cast of
:mod:`vgxsim.shadow.raycast` via :mod:`vgxsim.shadow.error`: misclassified pixels
interior / boundary, false lit / false shadow (summed over lights), and the stencil
count error histogram where the technique keeps counts.  Writes speed_vs_error.md,
.csv and .png (time against interior error, the Pareto front marked) to DIR.
The raster's work counters of the last frame (``CommandBatch.work()``: fragments,
tiles skipped, blocks covered, stencil writes) are added beside the times when the
batch keeps them (the shadow map's own window is not counted).
Timings on a shared 2-core machine are noisy: compare ratios within one run.
"""

from __future__ import annotations

import argparse
import csv
import os
import statistics
import time
import warnings

import numpy as np

from vgxsim.shadow import api
from vgxsim.shadow.error import count_error, shadow_error
from vgxsim.shadow.raycast import raycast
from vgxsim.shadow.techniques import TECHNIQUES
from vgxsim.shadow.techniques.hard_cases import HARD_CASES


def variants(quick: bool):
    """(technique, options, label): every technique, the shadow map at several
    resolutions, Roettger's start value and low-resolution mask."""
    for name in TECHNIQUES:
        if name == "shadowmap":
            for n in ((256, 1024) if quick else (256, 512, 1024, 2048)):
                yield name, {"size": n}, f"shadowmap{n}"
        elif name == "roettger":
            yield name, {}, name
            yield name, {"start": 64}, "roettger_start64"
            yield name, {"mask_scale": 2}, "roettger_half_mask"
        else:
            yield name, {}, name


def measure(scene, tech, opts, size, subpixel, repeats):
    """Median seconds per frame of the program's own loop (one window, display
    objects made once), the per-light lit masks (row 0 = bottom) and count planes of
    the last frame, and the raster's work counters for it when the batch keeps them."""
    from vgxsim.gl import TRUE, finish, prefsize, swapbuffers, winclose, winopen
    from vgxsim.gl import subpixel as gl_subpixel
    from vgxsim.gl._core import session
    from vgxsim.shadow.program import Shadows
    from vgxsim.shadow.techniques import make

    technique = make(tech, **opts)
    planes: dict[int, np.ndarray] = {}

    def hook(i: int) -> None:
        planes[i] = np.array(technique.read_mask(prog, i))

    prog = Shadows(scene, signs="screen", technique=technique, stencil_hook=hook)
    prefsize(*size)
    gid = winopen("speed_vs_error")
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            prog.setup()
            if subpixel:
                gl_subpixel(TRUE)
            prog.DrawFrame()
            swapbuffers()
            finish()
            batch = session.windows[session.current].batch
            times = []
            for _ in range(repeats):
                if hasattr(batch, "reset_counters"):
                    batch.reset_counters()
                t = time.perf_counter()
                prog.DrawFrame()
                swapbuffers()
                finish()
                times.append(time.perf_counter() - t)
            work = batch.work() if hasattr(batch, "work") else {}
        zero = technique.lit_value(prog)
    finally:
        prog.teardown()
        winclose(gid)
    counts = [planes[i].astype(np.int64) - zero for i in sorted(planes)]
    lit = [c == 0 for c in counts]
    return lit, counts, statistics.median(times), work


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="a small grid")
    ap.add_argument("--large", action="store_true",
                    help="the shipped scenes at 640x512 too (slow: an hour or more on 2 "
                         "busy cores)")
    ap.add_argument("--out", default="bench/out", help="output folder")
    ap.add_argument("--from-csv", metavar="CSV",
                    help="only rebuild the table and plot from an earlier run's CSV")
    ns = ap.parse_args()
    if ns.from_csv:
        report_from_csv(ns.from_csv, ns.out)
        return
    from tqdm import tqdm

    os.makedirs(ns.out, exist_ok=True)
    # (scene name, scene, sizes): the shipped scenes at larger sizes, the hard cases small
    if ns.quick:
        grid = [("cubes", api.load_scene(None), [(96, 80), (320, 256)])]
        grid += [(k, HARD_CASES[k](), [(96, 80)]) for k in ("eye_in_shadow", "open_box")]
        modes, repeats = [True], 1
    else:
        sizes = [(320, 256), (640, 512)] if ns.large else [(320, 256)]
        grid = [(n, api.load_scene(None if n == "cubes" else n), sizes)
                for n in ("cubes", "balls", "teapot")]
        grid += [(k, b(), [(96, 80)]) for k, b in HARD_CASES.items()]
        modes, repeats = [False, True], 3
    vs = list(variants(ns.quick))
    rows = []
    bar = tqdm(total=sum(len(g[2]) for g in grid) * len(modes) * len(vs), unit="frame",
               desc="speed vs error")
    for sname, sc, sizes in grid:
        for size in sizes:
            for sp in modes:
                ref = raycast(sc, *size, subpixel=sp)
                for tech, opts, label in vs:
                    bar.update(1)
                    try:
                        lit, counts, dt, work = measure(sc, tech, opts, size, sp, repeats)
                    except Exception as exc:  # a technique refusing a scene: a row
                        rows.append(dict(scene=sname, technique=label, size=f"{size[0]}x"
                                         f"{size[1]}", subpixel=sp, ms=float("nan"),
                                         note=type(exc).__name__))
                        continue
                    tot = dict(interior=0, boundary=0, false_lit=0, false_shadow=0)
                    hist: dict[int, int] = {}
                    for li in range(len(sc.lights)):
                        e = shadow_error(lit[li], ref, li)
                        for k in tot:
                            tot[k] += getattr(e, k)
                        if tech in ("heidmann", "finite"):
                            c = count_error(counts[li], ref.crossings[..., li], ref.hit)
                            for k, v in c.histogram.items():
                                hist[k] = hist.get(k, 0) + v
                    rows.append(dict(scene=sname, technique=label,
                                     size=f"{size[0]}x{size[1]}", subpixel=sp,
                                     ms=1000 * dt, **tot,
                                     count_hist=" ".join(f"{k}:{v}" for k, v in
                                                         sorted(hist.items()) if k),
                                     note="", **work))
    bar.close()
    keys = ["scene", "technique", "size", "subpixel", "ms", "interior", "boundary",
            "false_lit", "false_shadow", "count_hist", "note"]
    work_keys = sorted({k for r in rows for k in r} - set(keys))
    keys += work_keys
    with open(os.path.join(ns.out, "speed_vs_error.csv"), "w", newline="") as fh:
        w = csv.DictWriter(fh, keys)
        w.writeheader()
        for r in rows:
            w.writerow({k: r.get(k, "") for k in keys})
    write_report(rows, work_keys, ns.out)


def write_report(rows: list[dict], work_keys: list[str], out: str) -> None:
    """The markdown table (a summary per technique, then every row) and the plot.

    Summary per technique: the summed median frame times over the grid, the rows
    with no interior error ("exact rows"), and interior / boundary totals.  The
    Pareto front is over (summed time, rows not exact): no other technique is both
    faster and exact on more rows.
    """
    agg: dict[str, list[float]] = {}
    for r in rows:
        ms = float(r["ms"]) if r["ms"] not in ("", None) else float("nan")
        a = agg.setdefault(r["technique"], [0.0, 0, 0, 0.0, 0.0])
        a[2] += 1
        if ms == ms:
            a[0] += ms
            a[1] += int(int(r.get("interior", 0) or 0) == 0)
            a[3] += int(r.get("interior", 0) or 0)
            a[4] += int(r.get("boundary", 0) or 0)
    front = {t for t, v in agg.items()
             if not any(o[0] <= v[0] and o[2] - o[1] <= v[2] - v[1]
                        and (o[0], o[1]) != (v[0], v[1]) for o in agg.values())}
    with open(os.path.join(out, "speed_vs_error.md"), "w") as fh:
        fh.write("| technique | summed ms | exact rows | interior total | boundary total "
                 "| Pareto |\n|---|---|---|---|---|---|\n")
        for t, (ms, ok, n, er, bd) in sorted(agg.items(), key=lambda kv: kv[1][0]):
            fh.write(f"| {t} | {ms:.0f} | {ok}/{n} | {er:.0f} | {bd:.0f} | "
                     f"{'*' if t in front else ''} |\n")
        cols = ["scene", "technique", "size", "subpixel", "ms", "interior", "boundary",
                "false_lit", "false_shadow", "count_hist", *work_keys, "note"]
        fh.write("\n| " + " | ".join(cols) + " |\n|" + "---|" * len(cols) + "\n")
        for r in rows:
            fh.write("| " + " | ".join(str(r.get(k, "")) if k != "ms" or r["ms"] in ("", None)
                                       else f"{float(r['ms']):.1f}" for k in cols) + " |\n")
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(8, 5))
    for t, (ms, ok, n, _, _) in agg.items():
        ax.scatter(ms, n - ok, marker="*" if t in front else "o", s=120 if t in front else 50)
        ax.annotate(t, (ms, n - ok), fontsize=8)
    ax.set_xlabel("summed median time per frame over the grid (ms)")
    ax.set_ylabel("rows with interior misclassified pixels")
    ax.set_title("speed vs error (stars: Pareto front)")
    fig.savefig(os.path.join(out, "speed_vs_error.png"), dpi=100)
    print(open(os.path.join(out, "speed_vs_error.md")).read().split("\n\n")[0])


def report_from_csv(path: str, out: str) -> None:
    """Rebuild the markdown and the plot from a CSV this script wrote."""
    with open(path, newline="") as fh:
        rows = list(csv.DictReader(fh))
    base = {"scene", "technique", "size", "subpixel", "ms", "interior", "boundary",
            "false_lit", "false_shadow", "count_hist", "note"}
    work_keys = [k for k in rows[0] if k not in base] if rows else []
    write_report(rows, work_keys, out)


if __name__ == "__main__":
    main()
