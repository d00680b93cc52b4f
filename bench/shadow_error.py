"""Shadow error of `vgxsim shadows` against the exact ray cast, per shipped scene.

    python bench/shadow_error.py [WIDTHxHEIGHT] [scene ...]

For each scene, subpixel off (the IRIS default) and on, and the two ways of choosing a
shadow face's stencil op (signs 'article' and 'screen'): the pixels whose stencil
classification (lit = stencil holds its zero) disagrees with the ray cast, counted
over all visible pixels and over those farther than one pixel from a boundary of the
ray-cast classification.  Also the render time of one frame (median of 3, after a
warm-up), on this shared 2-core machine: noisy.
"""

from __future__ import annotations

import sys
import time

import numpy as np

from vgxsim.shadow.api import load_scene, render
from vgxsim.shadow.error import near_boundary
from vgxsim.shadow.raycast import raycast


def away_from_boundaries(classes: np.ndarray) -> np.ndarray:
    """True where the 3 x 3 neighbourhood has one class (boundaries dilated by 1 px):
    the complement of the error metric's boundary band (vgxsim/shadow/error.py)."""
    return ~near_boundary(classes)


def errors(scene, w, h, ref, **kw):
    frame = render(scene, size=(w, h), **kw)
    out = []
    for i in range(len(scene.lights)):
        lit = ref.lit[::-1, :, i]
        hit = ref.hit[::-1]
        classes = np.where(hit, lit.astype(int), -1)
        interior = away_from_boundaries(classes) & hit
        bad = hit & (frame.lit[i] != lit)
        out.append((int(bad.sum()), int((bad & interior).sum())))
    return out


def main(argv):
    import re

    sizes = [a for a in argv if re.fullmatch(r"\d+x\d+", a)]
    size = sizes[0] if sizes else "320x256"
    names = [a for a in argv if a not in sizes] or ["cubes", "balls", "textured_floor",
                                                  "teapot", "dense"]
    w, h = (int(v) for v in size.split("x"))
    print(f"{w}x{h}: misclassified pixels per light (all visible / > 1 px from a boundary)")
    for name in names:
        scene = load_scene(name)
        times = []
        render(scene, size=(w, h))
        for _ in range(3):
            t = time.perf_counter()
            render(scene, size=(w, h))
            times.append(time.perf_counter() - t)
        t = time.perf_counter()
        ref = raycast(scene, w, h)
        tr = time.perf_counter() - t
        row = [f"{name:15s} frame {1000 * float(np.median(times)):7.1f} ms  (ray cast {tr:.1f} s)"]
        for sub in (False, True):
            for signs in ("article", "screen"):
                e = errors(scene, w, h, ref, subpixel=sub, signs=signs)
                row.append(f"  subpixel {'on ' if sub else 'off'} signs {signs:7s}: "
                           + ", ".join(f"{a}/{b}" for a, b in e))
        print("\n".join(row), flush=True)


if __name__ == "__main__":
    main(sys.argv[1:])
