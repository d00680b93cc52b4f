# ruff: noqa: E702  (the article writes "bgnpolygon(); . . ." on one line)
"""Heidmann 1991, "Real Shadows, Real Time": the article's code segment as Python.

The code segment printed in the article (shared/seeds/000_...txt, "Example Code
Segment for Drawing Accurate Shadows") is transcribed line for line in
:meth:`Shadows.draw_shadows`, with syntax changes only and the article's comments kept
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
from dataclasses import dataclass

import numpy as np

from vgxsim.DEVICE import ESCKEY, REDRAW
from vgxsim.gl import *
from vgxsim.shadow.scene import (
    MATL_DIFFSPEC,
    MATL_EMITAMBIENT,
    MATL_FULL,
    Scene,
    default_scene,
    shadow_faces,
    silhouette_edges,
)

# Article: "take the simpler approach of using some positive number, such as 128, as
# the "zero" stencil value"; README: the constant STENZERO in shadows.c is 128.
MYZERO = 128

# Material parts DrawObjects() takes (article: DrawObjects (matl_emitambient)).
matl_full = MATL_FULL
matl_emitambient = MATL_EMITAMBIENT
matl_diffspec = MATL_DIFFSPEC

MODES = ("objects", "volumes", "shadows")
EDGES = ("silhouette", "all")


@dataclass
class LightSlot:
    """One scene light: ``light[i].index`` of the article is its lmdef index."""

    index: int
    position: tuple[float, float, float]
    colour: tuple[float, float, float]


class Shadows:
    """The ``shadows`` program's state: scene, lmdef indices and display options.

    Parameters
    ----------
    scene : Scene
    mode : {'objects', 'volumes', 'shadows'}
    edges : {'silhouette', 'all'}
    faithful : bool
        True: the article's ``zclear`` before the lit pass; False: the README's
        program (no z reset).  See the module docstring.
    stencil_hook : callable, optional
        Called as ``stencil_hook(i)`` after the shadow faces of light ``i`` are drawn
        and before its lit pass (not part of the 1991 code: lets tests read the
        stencil planes).
    effective_zclear : bool
        A what-if, not the article: enable z writes *before* the z reset so that it
        takes effect (see the module docstring).
    """

    def __init__(self, scene: Scene | None = None, mode: str = "shadows",
                 edges: str = "silhouette", faithful: bool = False,
                 stencil_hook: Callable[[int], None] | None = None,
                 effective_zclear: bool = False):
        if mode not in MODES:
            raise ValueError(f"mode must be one of {MODES}, not {mode!r}")
        if edges not in EDGES:
            raise ValueError(f"edges must be one of {EDGES}, not {edges!r}")
        self.scene = scene if scene is not None else default_scene()
        self.mode = mode
        self.edges = edges
        self.faithful = faithful
        self.stencil_hook = stencil_hook
        self.effective_zclear = effective_zclear
        self.light: list[LightSlot] = []
        self.nLights = 0
        self.matl: list[tuple[int, int, int]] = []  # per object: lmdef index per part

    # -- set-up (elided in the article: "/* Set up. */ . . .") -------------------------
    def config(self) -> None:
        """Frame-buffer configuration: the article's first lines, after RGBmode and
        doublebuffer on the window just opened."""
        RGBmode()
        doublebuffer()
        if getgdesc(GD_BITS_STENCIL) == 0:            # /* This requires stencil hardware. */
            sys.exit(1)
        stensize(getgdesc(GD_BITS_STENCIL))           # /* Use all the stencil bitplanes. */
        gconfig()
        zbuffer(TRUE)                                 # /* z comparison always active. */

    def define_lighting(self) -> None:
        """lmdef the light model (README's theLModel), the lights and, per object,
        its full, emitted+ambient and diffuse+specular materials."""
        sc = self.scene
        lmdef(DEFLMODEL, 1, sc.lmodel.props())
        self.light = []
        for i, lt in enumerate(sc.lights):
            lmdef(DEFLIGHT, i + 1, lt.props())
            self.light.append(LightSlot(i + 1, lt.position, lt.colour))
        self.nLights = len(self.light)
        self.matl = []
        for k, obj in enumerate(sc.objects):
            idx = tuple(3 * k + 1 + part for part in (matl_full, matl_emitambient,
                                                      matl_diffspec))
            for part, index in zip((matl_full, matl_emitambient, matl_diffspec), idx,
                                   strict=True):
                lmdef(DEFMATERIAL, index, obj.material.props(part))
            self.matl.append(idx)

    def viewing(self) -> None:
        """README: WINDOW gives near and far, LOOKAT the look-from and look-to
        points.  The lights are bound later under this matrix, so lmbind takes their
        positions to eye space."""
        cam = self.scene.camera
        w, h = getsize()
        reshapeviewport()
        mmode(MVIEWING)
        perspective(cam.fovy, w / h, cam.near, cam.far)
        loadmatrix(np.eye(4).reshape(-1).tolist())
        lookat(*cam.eye, *cam.target, cam.twist)
        lmbind(LMODEL, 1)

    def setup(self) -> None:
        """Everything before the first frame, on the current window."""
        self.config()
        self.define_lighting()
        self.viewing()

    # -- drawing ---------------------------------------------------------------------
    def DrawObjects(self, matl: int) -> None:
        """Draw every object with the given material part bound (README: the .glo
        format "represents objects as a series of gl bgnpolygon/v3f/endpolygon
        calls", here with one normal per face)."""
        for k, obj in enumerate(self.scene.objects):
            lmbind(MATERIAL, self.matl[k][matl])
            for f, poly in enumerate(obj.polygons):
                bgnpolygon()
                n3f(obj.normals[f])
                for vi in poly:
                    v3f(obj.vertices[vi])
                endpolygon()
        lmbind(MATERIAL, 0)

    def volume_faces(self, i: int) -> tuple[np.ndarray, np.ndarray]:
        """The article's ``v3= . . . ; v4= . . . ; ingoing= . . . ;`` for every edge of
        light ``i``: (nEdges, 4, 3) faces v1, v2, v3, v4 and (nEdges,) ingoing."""
        return shadow_faces(self.scene, i, self.edges)

    def draw_shadows(self) -> None:
        """The article's code segment ("Show Shadows")."""
        nLights, light, DrawObjects = self.nLights, self.light, self.DrawObjects
        # /* Draw scene w/ ambient light, setting z-buffer. */
        for i in range(nLights):                      # /* Turn on all the lights for */
            lmbind(LIGHT0+i, light[i].index)          # /* ambient light value calculation. */
        zwritemask(0xffffffff)                        # /* We do want to set z values, */
        czclear(0x00000000, getgdesc(GD_ZMAX))        # /* using the full z range. */
        blendfunction(BF_ONE, BF_ZERO)                # /* No alpha blending. */
        DrawObjects(matl_emitambient)                 # /* Draw all objects using only ambient */
                                                      # /* and emitted material components. */
        for i in range(nLights):                      # /* Turn off all the lights when done. */
            lmbind(LIGHT0+i, 0)
        # /* Accumulate effects of each light in the scene in turn. */
        for i in range(nLights):
            # /* Draw faces of shadow volumes, setting stencil planes. */
            lmbind(LIGHT0, light[i].index)            # /* Turn on just this light. */  (LIGHTO in print)
            sclear(MYZERO)                            # /* Reset the stencil values to "zero" */
            zwritemask(0x0)                           # /* We aren't changing any z values */
            wmpack(0x0)                               # /* or any color values. */
            faces, ingoing_flags = self.volume_faces(i)
            nEdges = len(faces)
            for iEdge in range(nEdges):               # /* For each edge in the scene, */
                v1, v2, v3, v4 = faces[iEdge]; ingoing = ingoing_flags[iEdge]  # /* project shadow face from this edge. */
                stencil(TRUE, 0, SF_ALWAYS, 0xff,     # /* Write stencil unconditionally, */
                        ST_KEEP, ST_KEEP,             # /* do nothing if zbuffer test fails, */
                        ST_INCR if ingoing else ST_DECR)  # /* otherwise, add or subtract one. */
                bgnpolygon(); v3f(v1); v3f(v2); v3f(v3); v3f(v4); endpolygon()  # /* Draw the shadow volume face. */
            if self.stencil_hook is not None:         # (not in the article: lets tests
                self.stencil_hook(i)                  #  read the stencil planes)
            # /* Add highlights for this light, constrained by stencil mask to unshadowed areas. */
            if self.effective_zclear:                 # (what-if, not the article: unmask z so
                zwritemask(0xffffffff)                #  that the reset below takes effect)
            if self.faithful or self.effective_zclear:
                zclear(getgdesc(GD_ZMAX))             # /* Reset the z-buffer contents. */  (zclear takes no argument; see docstring)
            zwritemask(0xffffffff)                    # /* Enable writing to the z- buffer and */  (printed: 0xfffffffff)
            wmpack(0xffffffff)                        # /* the color planes. Set up to add */  (printed: 0xfffffffff)
            blendfunction(BF_ONE, BF_ONE)             # /* highlight color to existing values. */
            stencil(TRUE, MYZERO, SF_EQUAL, 0xff,     # /* Constrain drawing to ''zero'' areas */  (printed: Oxff)
                    ST_KEEP, ST_KEEP, ST_KEEP)        # /* of stencil. Don't change stencil. */
            DrawObjects(matl_diffspec)                # /* Draw lit part of object material. */
            lmbind(LIGHT0, 0)                         # /* Leave this light off for next pass. */  (LIGHTO in print)
        # (after the segment: leave stencil and blending off for the next frame)
        stencil(FALSE, 0, SF_ALWAYS, 0xff, ST_KEEP, ST_KEEP, ST_KEEP)
        blendfunction(BF_ONE, BF_ZERO)

    def draw_objects(self) -> None:
        """README "Show Objects Only": one pass, every material component, all
        lights, no shadow calculations."""
        for i in range(self.nLights):
            lmbind(LIGHT0+i, self.light[i].index)
        zwritemask(0xffffffff)
        wmpack(0xffffffff)
        blendfunction(BF_ONE, BF_ZERO)
        czclear(self.scene.background, getgdesc(GD_ZMAX))
        self.DrawObjects(matl_full)
        for i in range(self.nLights):
            lmbind(LIGHT0+i, 0)

    def draw_volumes(self) -> None:
        """README "Show Volumes": the shadow faces "projected away from one of the
        light sources as semi-transparent surfaces", and the silhouette edges "as
        solid or dotted yellow lines"."""
        self.draw_objects()
        lt = self.light[0]
        faces, _ = shadow_faces(self.scene, 0, self.edges)
        zwritemask(0x0)
        blendfunction(BF_SA, BF_MSA)
        c4f((*lt.colour, 0.3))
        for quad in faces:
            bgnpolygon(); v3f(quad[0]); v3f(quad[1]); v3f(quad[2]); v3f(quad[3]); endpolygon()
        blendfunction(BF_ONE, BF_ZERO)
        cpack(0xff00ffff)  # yellow (packed ABGR)
        deflinestyle(1, 0x3333)
        for zf, style in ((ZF_LEQUAL, 0), (ZF_GREATER, 1)):  # visible solid, hidden dotted
            zfunction(zf)
            setlinestyle(style)
            for obj in self.scene.casters:
                for v1, v2 in silhouette_edges(obj, lt.position):
                    bgnline(); v3f(v1); v3f(v2); endline()
        setlinestyle(0)
        zfunction(ZF_LEQUAL)
        zwritemask(0xffffffff)

    def DrawFrame(self) -> None:
        """Draw one frame in the current display mode (README: "The main drawing
        routine is DrawFrame(), which uses a select statement")."""
        if self.mode == "shadows":
            self.draw_shadows()
        elif self.mode == "volumes":
            self.draw_volumes()
        else:
            self.draw_objects()


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
