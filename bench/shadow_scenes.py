"""Render time of each shipped scene through `vgxsim.shadow.api.render` (median of 5
after a warm-up frame; one window per frame, so display objects are rebuilt each time,
as in one `vgxsim shadows` run).

    python bench/shadow_scenes.py [WIDTHxHEIGHT] [--soft N]
"""

from __future__ import annotations

import sys
import time

import numpy as np

from vgxsim.data import SCENES
from vgxsim.shadow.api import load_scene, render


def main(argv):
    size = next((a for a in argv if "x" in a and a[0].isdigit()), "640x512")
    soft = int(argv[argv.index("--soft") + 1]) if "--soft" in argv else 0
    w, h = (int(v) for v in size.split("x"))
    print(f"{w}x{h}, soft {soft}: median of 5 frames (noisy shared 2-core machine)")
    for name in SCENES:
        scene = load_scene(name)
        tris = sum(len(o.triangles) for o in scene.objects)
        render(scene, size=(w, h), soft=soft)
        times = []
        for _ in range(5):
            t = time.perf_counter()
            render(scene, size=(w, h), soft=soft)
            times.append(time.perf_counter() - t)
        print(f"{name:15s} {tris:7d} triangles  {1000 * float(np.median(times)):8.1f} ms",
              flush=True)


if __name__ == "__main__":
    main(sys.argv[1:])
