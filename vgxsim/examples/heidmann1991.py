# ruff: noqa: E702  (the article writes "bgnpolygon(); . . ." on one line)
"""Heidmann 1991, "Real Shadows, Real Time": the article's code segment as Python.

The code segment printed in the article (shared/seeds/000_...txt, "Example Code
Segment for Drawing Accurate Shadows") is transcribed line for line in
:meth:`vgxsim.shadow.program.Shadows.draw_shadows` (the ``shadows`` program's
drawing class, shared with ``vgxsim shadows``), with syntax changes only and the article's comments kept
beside each line.  The parts the article elides ("...") are filled in from the
article's text and the README of its ``shadows`` program (shared/seeds/001_...txt):
the window set-up, the lmdef of materials, lights and light model, ``DrawObjects``,
the shadow-face vertices ``v3``, ``v4`` and the ``ingoing`` flag, and the drawing of
the face.  The scene is :func:`vgxsim.shadow.scene.default_scene` (three cubes over a
floor, a red and a blue point light).

Corrections to the printed text (all marked in the code):

* OCR damage: ``LIGHTO`` is ``LIGHT0``, ``Oxff`` is ``0xff``.
* ``zwritemask(0xfffffffff)`` and ``wmpack(0xfffffffff)`` have nine hex digits in the
  article; the masks are 32-bit ``unsigned long`` and written ``0xffffffff``.
* ``zclear (getgdesc (GD_ZMAX))``: IRIS GL's ``zclear`` takes no argument (pre-ANSI
  C passed and ignored it); vgxsim's ``zclear`` accepts and ignores one int for this
  very line, so it is transcribed as printed.  It writes GD_ZMAX anyway.
* ``stencil(...)`` before ``bgnpolygon`` lacks its ``;`` and the edge loop's closing
  brace is not printed; the stencil test is left on at the end of the segment, so
  the next frame's first pass would be masked by it -- ``stencil(FALSE, ...)`` and
  ``blendfunction(BF_ONE, BF_ZERO)`` are added after the light loop.

The z-buffer reset before the lit pass (``faithful``)
-----------------------------------------------------
The article resets the z-buffer before drawing the lit parts ("Reset the z-buffer
contents") and only then enables z writes ("Enable writing to the z- buffer").  If
that reset took effect, the lit pass would be depth-tested against far instead of
against the visible surfaces of the first pass: every object drawn at a pixel before
a nearer one would pass too and, with ``blendfunction(BF_ONE, BF_ONE)``, *add* its
diffuse and specular light there (the floor is drawn first, under every cube); and
the z values of pixels shadowed from the first light would stay at GD_ZMAX, so the
next light's shadow faces would count crossings behind the visible surface.  The
README describes the program as working: "the scene is drawn again using only the
Diffuse and Specular components ... so that calculated colors are added to the
colors in the frame buffer", which needs the lit pass depth-tested (ZF_LEQUAL, the
default) against the z of the first pass, with no reset.

But the reset does not take effect: ``zclear`` "honours zwritemask" (zclear(3G);
docs/numeric_model.md section 8), and the z write mask is still ``0x0`` from the
shadow-face pass when ``zclear`` runs.  So the article's code *is* the README's
program.  Three variants are provided:

* ``faithful=True``: the article verbatim, with ``zclear``;
* ``faithful=False`` (default): the same code without the ``zclear`` (the README's
  description, and what the article's code does);
* ``effective_zclear=True``: a what-if that enables z writes before the reset, so it
  takes effect.

Measured on the default scene, silhouette edges, subpixel(FALSE): ``faithful=True``
and ``faithful=False`` give identical images (0 pixels differ at 640 x 512, 320 x 256
and 160 x 128).  With ``effective_zclear=True``, 26,503 of 327,680 pixels differ at
640 x 512 (8,351 of them brighter: hidden surfaces added; the rest darker: the second
light's faces counted against far; up to 155 levels in one channel).

Accuracy against the ray cast
-----------------------------
Tests (tests/shadow/test_heidmann1991.py) read the stencil planes after each light's
shadow faces and compare "stencil == MYZERO" with the float64 ray cast
(:mod:`vgxsim.shadow.raycast`), leaving out pixels within one pixel of a boundary of
the ray-cast classification.  Measured at 640 x 512 (about 217,000 such pixels per
light): with ``subpixel(TRUE)`` no pixel is misclassified and ``stencil - MYZERO``
equals the exact signed crossing count everywhere; with the IRIS default
``subpixel(FALSE)``, which the article's code runs under, 4 (red light) and 10 (blue
light) pixels are wrongly in shadow.  In the cases examined the causes were vertex
snapping -- a caster corner landing exactly on a pixel centre, where only some of the
faces meeting there own it -- and the faces of a cube's bottom edges grazing the
floor it stands on, so that the depth test decides by rounding.  These are stray
pixels like those of the README's Bugs section, though not from the cause it
suspects (shared face edges are rasterized watertight here).  ``edges='all'`` and ``edges='silhouette'`` classify every pixel alike (the
all-edge count is twice the silhouette count behind these convex cubes).

Display modes (README): ``'objects'`` ("Show Objects Only": all material components,
all lights, no shadow work), ``'volumes'`` ("Show Volumes": the shadow faces of one
light drawn semi-transparent, silhouette edges as yellow lines -- solid where visible,
dotted where hidden, which is this module's reading of "solid or dotted"),
``'shadows'`` ("Show Shadows").  Edges (article): ``'all'`` projects "every single
edge of every polygon in the scene", ``'silhouette'`` only "the silhouette edges of an
object".

Library use: :func:`render`; as an IRIS GL program: ``python -m
vgxsim.examples.heidmann1991 --out shadows.png`` or under ``vgxsim run``.
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Callable, Sequence

import numpy as np

from vgxsim.DEVICE import ESCKEY, REDRAW
from vgxsim.gl import *
from vgxsim.shadow.program import (  # noqa: F401  (re-exported: the article's names)
    EDGES,
    LightSlot,
    Shadows,
    matl_diffspec,
    matl_emitambient,
    matl_full,
)
from vgxsim.shadow.scene import Scene

# Article: "take the simpler approach of using some positive number, such as 128, as
# the "zero" stencil value"; README: the constant STENZERO in shadows.c is 128.
# Shadows.config() picks it from getgdesc(GD_BITS_STENCIL), which is 128 on the
# VGX's 8 stencil planes.
MYZERO = 128

MODES = ("objects", "volumes", "shadows")


def _front_rgba() -> np.ndarray:
    """(H, W, 4) uint8 of the current window's front buffer, row 0 = bottom."""
    from vgxsim.gl._core import current

    return current("render").read_rgba("front")


def render(width: int = 640, height: int = 512, mode: str = "shadows",
           edges: str = "silhouette", faithful: bool = False, *,
           scene: Scene | None = None, subpixel_mode: bool = False,
           stencil_hook: Callable[[int], None] | None = None,
           effective_zclear: bool = False) -> np.ndarray:
    """Render one frame of the ``shadows`` program in a window of its own.

    Opens a window of the given size, draws one frame, swaps, reads the front buffer
    and closes the window (the previously current window, if any, is current again).

    Parameters
    ----------
    width, height : int
    mode : {'shadows', 'objects', 'volumes'}
    edges : {'silhouette', 'all'}
    faithful : bool
        The article's ``zclear`` before the lit pass (see the module docstring).
    scene : Scene, optional
        Default: :func:`vgxsim.shadow.scene.default_scene`.
    subpixel_mode : bool
        ``subpixel(TRUE)`` before drawing (the IRIS default, and the article's, is
        FALSE: vertices snap to pixel centres).
    stencil_hook : callable, optional
        ``stencil_hook(i)`` after light ``i``'s shadow faces (see :class:`Shadows`).
    effective_zclear : bool
        What-if: make the article's z reset take effect (see :class:`Shadows`).

    Returns
    -------
    ndarray, shape (height, width, 4), uint8
        RGBA, row 0 = bottom.
    """
    from vgxsim.gl._core import session

    if mode not in MODES:
        raise ValueError(f"mode must be one of {MODES}, not {mode!r}")
    previous = session.current
    prog = Shadows(scene, mode=mode, edges=edges, faithful=faithful,
                   stencil_hook=stencil_hook, effective_zclear=effective_zclear)
    prefsize(width, height)
    gid = winopen("shadows")
    try:
        prog.setup()
        if subpixel_mode:
            subpixel(TRUE)
        prog.DrawFrame()
        swapbuffers()
        image = _front_rgba()
    finally:
        prog.teardown()
        winclose(gid)
        if previous is not None and previous in session.windows:
            winset(previous)
    return image


def main(argv: Sequence[str] | None = None) -> int:
    """Run as an IRIS GL program: draw a frame, swap, then read events until ESCKEY
    or until the (scripted) events run out.

    Parameters
    ----------
    argv : sequence of str, optional
        ``--out PNG``, ``--size WxH``, ``--mode``, ``--edges``, ``--faithful``.

    Returns
    -------
    int
        Exit status.
    """
    from vgxsim.events.queue import ScriptExhausted
    from vgxsim.sinks.frames import write_png

    ap = argparse.ArgumentParser(prog="heidmann1991", description=__doc__.split("\n")[0])
    ap.add_argument("--out", help="write the first frame to this PNG file")
    ap.add_argument("--size", help="window size WxH (default: 640x512 or vgxsim run's)")
    ap.add_argument("--mode", choices=MODES, default="shadows")
    ap.add_argument("--edges", choices=EDGES, default="silhouette")
    ap.add_argument("--faithful", action="store_true",
                    help="the article's zclear before the lit pass")
    args = ap.parse_args(argv)
    if args.size:
        w, h = (int(v) for v in args.size.lower().split("x"))
        prefsize(w, h)
    prog = Shadows(mode=args.mode, edges=args.edges, faithful=args.faithful)
    winopen("shadows")
    prog.setup()
    qdevice(ESCKEY)
    prog.DrawFrame()
    swapbuffers()
    drawn = getsize()
    if args.out:
        write_png(args.out, _front_rgba())
    try:
        while True:
            dev, val = qread()
            if dev == ESCKEY:
                break
            if dev == REDRAW and getsize() != drawn:
                prog.viewing()
                prog.DrawFrame()
                swapbuffers()
                drawn = getsize()
    except ScriptExhausted:
        pass
    return 0


if __name__ == "__main__":
    sys.exit(main())
