"""Soft shadows by jittered lights and the accumulation buffer (Heidmann 1991, Fig. 6).

The article: "Figure 6 was created from thirty-two separate images in only a few
seconds on the VGX hardware.  By drawing a shadowed scene several times, each time
moving the light source a small amount and accumulating the images in the soft
shadows, we achieve accurate soft shadows."  The README adds that lights are made
"jitterable" with a JITTER cube inside which each image picks a light position.

Each image here is one frame of :class:`vgxsim.shadow.program.Shadows` with every
light moved inside a cube of side ``jitter`` centred on its position (a
deterministic stratified pattern, so runs repeat), accumulated by
:func:`vgxsim.shadow.program.accumulate` (acbuf, 16-bit components).  ``vgxsim
shadows --soft`` uses the same accumulation with each light's own JITTER box.
"""

from __future__ import annotations

import argparse
import sys
import time

import numpy as np

from vgxsim.examples.heidmann1991 import _front_rgba
from vgxsim.gl import *
from vgxsim.shadow.program import Shadows, accumulate, jittered_lights
from vgxsim.shadow.scene import Scene, default_scene


def jitter_offsets(n: int, side: float) -> np.ndarray:
    """``n`` offsets inside a cube of side ``side``: a stratified, repeatable set.

    Returns
    -------
    ndarray, shape (n, 3), float64
    """
    k = int(np.ceil(n ** (1.0 / 3.0)))
    grid = np.stack(np.meshgrid(*(np.arange(k),) * 3, indexing="ij"), -1).reshape(-1, 3)
    rng = np.random.default_rng(1991)
    picks = grid[rng.permutation(len(grid))[:n]]
    return ((picks + rng.random((n, 3))) / k - 0.5) * side


def jittered_scene(scene: Scene, offset) -> Scene:
    """The scene with every light moved by ``offset`` (3 floats)."""
    return jittered_lights(scene, offset)


def render_soft(width: int = 640, height: int = 512, images: int = 32, jitter: float = 0.6,
                edges: str = "silhouette", scene: Scene | None = None) -> np.ndarray:
    """Accumulate ``images`` jittered shadow frames and return their average.

    Parameters
    ----------
    width, height : int
    images : int
        Frames accumulated (32 in the article's Figure 6).
    jitter : float
        Side of the cube each light moves in (world units; the scene is about 14
        units across).
    edges : {'silhouette', 'all'}
    scene : Scene, optional

    Returns
    -------
    ndarray, shape (height, width, 4), uint8
        RGBA, row 0 = bottom.
    """
    if images < 1:
        raise ValueError("images must be at least 1")
    base = scene if scene is not None else default_scene()
    prefsize(width, height)
    gid = winopen("soft shadows")
    prog = Shadows(base, edges=edges)
    try:
        prog.setup(accumulate=True)
        accumulate(prog, jitter_offsets(images, jitter))
        swapbuffers()
        return _front_rgba()
    finally:
        prog.teardown()
        winclose(gid)


def main(argv=None) -> int:
    """``python -m vgxsim.examples.soft_shadows [--out PNG] [--images N] [--size WxH]``"""
    from vgxsim.sinks.frames import write_png

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default="soft_shadows.png")
    ap.add_argument("--images", type=int, default=32)
    ap.add_argument("--jitter", type=float, default=0.6)
    ap.add_argument("--size", default="640x512")
    args = ap.parse_args(argv)
    w, h = (int(v) for v in args.size.lower().split("x"))
    t = time.perf_counter()
    img = render_soft(w, h, args.images, args.jitter)
    dt = time.perf_counter() - t
    write_png(args.out, img)
    print(f"wrote {args.out}: {args.images} images accumulated in {dt:.2f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
