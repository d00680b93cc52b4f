# ruff: noqa: E702  (the article writes "bgnpolygon(); . . ." on one line)
"""The ``shadows`` program of Heidmann 1991: its drawing code, as IRIS GL calls.

:class:`Shadows` holds the program's state (scene, lmdef indices, display options)
and draws one frame in each of the README's display modes:

* ``'objects'`` -- "Show Objects Only": every material component, every light, no
  shadow calculation;
* ``'volumes'`` -- "Show Volumes": the shadow volume faces "projected away from one
  of the light sources as semi-transparent surfaces", and the silhouette edges "as
  solid or dotted yellow lines" (solid where visible, dotted where hidden: this
  module's reading of "solid or dotted");
* ``'mask'`` -- "Show Mask": the stencil counts in colour, "clear where no shadow
  volume faces cover the scene, magenta at the pixels where you go out of shadow
  exactly as many times as you go into it, blue at the pixels where you have gone
  into shadow once more than you have gone out, and blue-green where you have gone
  in two times more".  As the README says of the original, this mode counts "the
  times gone in and the times gone out, not just the running total": the top half
  of the stencil planes counts the ins, the bottom half the outs
  (:meth:`Shadows.draw_mask`, :func:`mask_fields`), so it can overflow as the
  original's could;
* ``'shadows'`` -- "Show Shadows": the article's code segment, transcribed line for
  line in :meth:`Shadows.draw_shadows` (see :mod:`vgxsim.examples.heidmann1991` for
  the corrections to the printed text and the ``faithful`` z reset).

The stencil "zero" is ``1 << (getgdesc(GD_BITS_STENCIL) - 1)`` (128 with the VGX's 8
planes), the README's "more robust approach [that] would use getgdesc
(GD_BITS_STENCIL) to pick a zero value" instead of the hard-wired STENZERO.

Objects are drawn from display objects (``makeobj`` once per object, ``callobj``
per pass; the same polygons as immediate mode, ``display_objects=False``).  Soft
shadows (article, Figure 6; README: "the positions of the light sources can be
jittered and several images accumulated") are :func:`accumulate`.
"""

from __future__ import annotations

import sys
from collections.abc import Callable, Iterable
from dataclasses import dataclass, replace

import numpy as np

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

# Material parts DrawObjects() takes (article: DrawObjects (matl_emitambient)).
matl_full = MATL_FULL
matl_emitambient = MATL_EMITAMBIENT
matl_diffspec = MATL_DIFFSPEC

MODES = ("objects", "volumes", "mask", "shadows")

# README: "all textures are mapped onto the x-z plane in object space using the
# texgen command.  The mapping is specified by the arrays tex_sparams and
# tex_tparams in "shadows.c"."  Their values are not in the README; these give one
# repeat of the image per 4 units of x and of z (our choice).  Objects here are
# placed before drawing, so their "object space" is the scene's.
tex_sparams = (0.25, 0.0, 0.0, 0.0)
tex_tparams = (0.0, 0.0, 0.25, 0.0)
TEXTURE_PROPS = (TX_MINFILTER, TX_BILINEAR, TX_MAGFILTER, TX_BILINEAR, TX_WRAP, TX_REPEAT,
                 TX_NULL)
EDGES = ("silhouette", "all")
SIGNS = ("article", "screen")

# README "Show Mask" colours, packed ABGR (cpack)
MASK_MAGENTA = 0xFFFF00FF   # in == out
MASK_BLUE = 0xFFFF0000      # one more in than out
MASK_BLUEGREEN = 0xFFFFFF00  # two more in than out
SILHOUETTE_YELLOW = 0xFF00FFFF


def stencil_zero(bits: int) -> int:
    """The stencil value that stands for a count of zero: the middle of the range,
    so the count may go below zero (article: "using some positive number, such as
    128, as the "zero" stencil value")."""
    return 1 << (bits - 1) if bits > 0 else 0


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
    scene : Scene, optional
        Default: :func:`vgxsim.shadow.scene.default_scene`.
    mode : {'objects', 'volumes', 'mask', 'shadows'}
    edges : {'silhouette', 'all'}
    light : int
        The light whose volumes the 'volumes' and 'mask' modes show.
    faithful : bool
        True: the article's ``zclear`` before the lit pass; False: the README's
        program (no z reset).  See :mod:`vgxsim.examples.heidmann1991`.
    stencil_hook : callable, optional
        Called as ``stencil_hook(i)`` after the shadow faces of light ``i`` are drawn
        and before its lit pass (not part of the 1991 code: lets tests and the
        library read the stencil planes).
    effective_zclear : bool
        A what-if, not the article: enable z writes *before* the z reset so that it
        takes effect.
    display_objects : bool
        Draw objects from display objects (True) or in immediate mode (False); both
        issue the same polygons.
    cache_volumes : bool
        Not the article: keep each light's shadow faces, and in the 'shadows' mode a
        display object holding their drawing, until the light, the casters, the
        extrusion length, the edge set or the eye (for ``signs='article'``) change
        (True); or compute and draw them in immediate mode every frame (False).  Both
        issue the same polygons and stencil calls (tested).  The article computes the
        faces "for every polygon edge" each frame; with static lights and objects
        nothing of them changes between frames.
    technique : vgxsim.shadow.techniques.Technique, optional
        Not the article: a later shadow technique that draws the 'shadows' mode
        through this engine (:mod:`vgxsim.shadow.techniques`); None: the 1991 code.
    signs : {'article', 'screen'}
        How a shadow face's stencil op is chosen.  'article': from the 3-D test
        ``ingoing`` (article: "front-facing polygons will be going into shadow"),
        one ``stencil()`` per face as printed.  'screen': from the facing the
        rasterizer itself sees -- all faces drawn with ``backface(TRUE)`` and
        ST_INCR, then with ``frontface(TRUE)`` and ST_DECR.  With vertices snapped to
        pixel centres (``subpixel(FALSE)``) a nearly edge-on face can turn over on
        screen; its 3-D sign then disagrees with the pixels it covers and leaves a
        line of stray pixels along it (measured on the shipped ball, torus and teapot
        scenes).  Screen signs remove them: a cause of the README's "stray pixels"
        bug beyond the one it suspects.
    """

    def __init__(self, scene: Scene | None = None, mode: str = "shadows",
                 edges: str = "silhouette", faithful: bool = False,
                 stencil_hook: Callable[[int], None] | None = None,
                 effective_zclear: bool = False, *, light: int = 0,
                 display_objects: bool = True, signs: str = "article", technique=None,
                 cache_volumes: bool = True):
        if mode not in MODES:
            raise ValueError(f"mode must be one of {MODES}, not {mode!r}")
        if edges not in EDGES:
            raise ValueError(f"edges must be one of {EDGES}, not {edges!r}")
        if signs not in SIGNS:
            raise ValueError(f"signs must be one of {SIGNS}, not {signs!r}")
        self.signs = signs
        self.technique = technique
        self.scene = scene if scene is not None else default_scene()
        if not 0 <= light < len(self.scene.lights):
            raise ValueError(f"light must be 0..{len(self.scene.lights) - 1}, not {light}")
        self.mode = mode
        self.edges = edges
        self.light_index = light
        self.faithful = faithful
        self.stencil_hook = stencil_hook
        self.effective_zclear = effective_zclear
        self.display_objects = display_objects
        self.light: list[LightSlot] = []
        self.nLights = 0
        self.matl: list[tuple[int, int, int]] = []  # per object: lmdef index per part
        self.MYZERO = 128  # set from getgdesc(GD_BITS_STENCIL) by config()
        self.stencil_bits = 8
        self._geometry: dict[int, int] = {}  # id(object) -> display object
        self.cache_volumes = cache_volumes
        # per light index: (key, faces, ingoing) and (key, display object of the faces)
        self._volumes: dict[int, tuple] = {}
        self._face_objects: dict[int, tuple] = {}
        self.texture: list[int] = []  # per object: texdef2d index, 0 for none
        # accumulate()'s shared ambient pass: keep the colour after it, or restore it
        self.keep_ambient = False
        self.ambient_image: bytes | None = None

    # -- set-up (elided in the article: "/* Set up. */ . . .") -------------------------
    def config(self, accumulate: bool = False) -> None:
        """Frame-buffer configuration: the article's first lines, after RGBmode and
        doublebuffer on the window just opened (``acsize(16)`` too for soft
        shadows)."""
        if self.technique is not None and self.technique.config(self, accumulate):
            return                                    # (the technique configured the planes)
        RGBmode()
        doublebuffer()
        if getgdesc(GD_BITS_STENCIL) == 0:            # /* This requires stencil hardware. */
            sys.exit(1)
        stensize(getgdesc(GD_BITS_STENCIL))           # /* Use all the stencil bitplanes. */
        if accumulate:
            acsize(16)  # Haeberli and Akeley: 16 bits per component leave room for 64 x 255
        gconfig()
        zbuffer(TRUE)                                 # /* z comparison always active. */
        # README, Bugs: "A more robust approach would use getgdesc(GD_BITS_STENCIL) to
        # pick a zero value" -- instead of STENZERO = 128.
        self.stencil_bits = getgdesc(GD_BITS_STENCIL)
        self.MYZERO = stencil_zero(self.stencil_bits)

    def define_lighting(self) -> None:
        """lmdef the light model (README's theLModel), the lights and, per object,
        its full, emitted+ambient and diffuse+specular materials."""
        sc = self.scene
        lmdef(DEFLMODEL, 1, sc.lmodel.props())
        self.define_lights()
        self.matl = []
        for k, obj in enumerate(sc.objects):
            idx = tuple(3 * k + 1 + part for part in (matl_full, matl_emitambient,
                                                      matl_diffspec))
            for part, index in zip((matl_full, matl_emitambient, matl_diffspec), idx,
                                   strict=True):
                lmdef(DEFMATERIAL, index, obj.material.props(part))
            self.matl.append(idx)

    def define_lights(self) -> None:
        """lmdef the scene's lights only (what a jittered frame of soft shadows
        changes; the light model and materials stay defined)."""
        self.light = []
        for i, lt in enumerate(self.scene.lights):
            lmdef(DEFLIGHT, i + 1, lt.props())
            self.light.append(LightSlot(i + 1, lt.position, lt.colour))
        self.nLights = len(self.light)

    def define_textures(self) -> None:
        """texdef2d each object's TEXTURE image, one TV_MODULATE environment and the
        README's texgen mapping onto the x-z plane (tex_sparams, tex_tparams).
        Modulating every pass's colour by the texture textures their sum too."""
        from vgxsim.formats.sgi import read_rgb

        self.texture = []
        for k, obj in enumerate(self.scene.objects):
            if obj.texture is None:
                self.texture.append(0)
                continue
            image = read_rgb(obj.texture)[::-1]  # texdef2d's row 0 is the bottom row
            h, w, nc = image.shape
            texdef2d(k + 1, nc, w, h, image, len(TEXTURE_PROPS), TEXTURE_PROPS)
            self.texture.append(k + 1)
        if any(self.texture):
            tevdef(1, 2, (TV_MODULATE, TV_NULL))
            texgen(TX_S, TG_LINEAR, tex_sparams)
            texgen(TX_T, TG_LINEAR, tex_tparams)
            texgen(TX_S, TG_ON, None)
            texgen(TX_T, TG_ON, None)

    def viewing(self) -> None:
        """README: WINDOW gives near and far (and the frustum height at near), LOOKAT
        the look-from and look-to points.  The lights are bound later under this
        matrix, so lmbind takes their positions to eye space."""
        cam = self.scene.camera
        w, h = getsize()
        reshapeviewport()
        mmode(MVIEWING)
        if cam.near_height is not None:
            window(*cam.frustum(w / h))
        else:
            perspective(cam.fovy, w / h, cam.near, cam.far)
        loadmatrix(np.eye(4).reshape(-1).tolist())
        lookat(*cam.eye, *cam.target, cam.twist)
        lmbind(LMODEL, 1)
        if self.technique is not None:               # e.g. an infinite far plane (z-fail)
            self.technique.after_viewing(self)

    def setup(self, accumulate: bool = False) -> None:
        """Everything before the first frame, on the current window."""
        self.config(accumulate)
        self.define_lighting()
        self.define_textures()
        self.viewing()

    def teardown(self) -> None:
        """Delete the display objects this program made."""
        for obj in self._geometry.values():
            delobj(obj)
        self._geometry.clear()
        for _, obj in self._face_objects.values():
            delobj(obj)
        self._face_objects.clear()
        self._volumes.clear()
        if self.technique is not None:
            self.technique.teardown(self)

    # -- drawing ---------------------------------------------------------------------
    def draw_polygons(self, obj) -> None:
        """One object's polygons (README: the .glo format "represents objects as a
        series of gl bgnpolygon/v3f/endpolygon calls"), with a normal per face or,
        where the model has them, per vertex."""
        # Python lists: a call per vertex is the front end's cost, numpy scalars add to it
        verts = obj.vertices.tolist()
        polys = obj.polygons.tolist()
        if obj.vertex_normals is None:
            normals = obj.normals.tolist()
            for f, poly in enumerate(polys):
                bgnpolygon()
                n3f(normals[f])
                for vi in poly:
                    v3f(verts[vi])
                endpolygon()
        else:
            vn = obj.vertex_normals.tolist()
            for poly in polys:
                bgnpolygon()
                for vi in poly:
                    n3f(vn[vi]); v3f(verts[vi])
                endpolygon()

    def _object(self, obj) -> int:
        key = id(obj)
        if key not in self._geometry:
            name = genobj()
            makeobj(name)
            self.draw_polygons(obj)
            closeobj()
            self._geometry[key] = name
        return self._geometry[key]

    def DrawObjects(self, matl: int) -> None:
        """Draw every object with the given material part bound (article:
        ``DrawObjects (matl_emitambient)``)."""
        for k, obj in enumerate(self.scene.objects):
            lmbind(MATERIAL, self.matl[k][matl])
            tex = self.texture[k] if k < len(self.texture) else 0
            if tex:
                texbind(TX_TEXTURE_0, tex)
                tevbind(TV_ENV0, 1)
            if self.display_objects:
                callobj(self._object(obj))
            else:
                self.draw_polygons(obj)
            if tex:
                texbind(TX_TEXTURE_0, 0)
        lmbind(MATERIAL, 0)

    def _volume_key(self, i: int) -> tuple:
        """What light ``i``'s shadow faces depend on.  The casters are compared by
        identity (scenes and meshes are immutable) and kept alive by the key, so an
        id cannot be reused while it is cached."""
        sc = self.scene
        return (self.edges, sc.casters, tuple(sc.lights[i].position), sc.volume_length,
                tuple(sc.camera.eye))

    def volume_faces(self, i: int) -> tuple[np.ndarray, np.ndarray]:
        """The article's ``v3= . . . ; v4= . . . ; ingoing= . . . ;`` for every edge of
        light ``i``: (nEdges, 4, 3) faces v1, v2, v3, v4 and (nEdges,) ingoing.

        Kept per light while its :meth:`_volume_key` stays the same
        (``cache_volumes``); the arrays are shared, not to be written."""
        if not self.cache_volumes:
            return shadow_faces(self.scene, i, self.edges)
        key = self._volume_key(i)
        hit = self._volumes.get(i)
        if hit is None or hit[0] != key:
            faces, ingoing = shadow_faces(self.scene, i, self.edges)
            faces.flags.writeable = ingoing.flags.writeable = False
            hit = self._volumes[i] = (key, faces, ingoing)
        return hit[1], hit[2]

    def _face_key(self, i: int) -> tuple:
        return (self._volume_key(i), self.signs)

    def _drop_face_object(self, i: int) -> None:
        old = self._face_objects.pop(i, None)
        if old is not None:
            delobj(old[1])

    def _screen_face_object(self, i: int, faces: np.ndarray) -> int | None:
        """``signs='screen'``: the display object holding :meth:`draw_quads` of light
        ``i``'s faces, made again (the old one deleted) when the faces' key changes --
        one object per light, so jittered lights do not pile objects up; None
        without ``cache_volumes``."""
        if not self.cache_volumes:
            return None
        name, key = self._current_face_object(i)
        if name is not None:
            return name
        name = genobj()
        makeobj(name)
        self.draw_quads(faces)
        closeobj()
        self._face_objects[i] = (key, name)
        return name

    def _open_face_object(self, i: int) -> int | None:
        """``signs='article'``: None when the edge loop is to run -- immediate (no
        ``cache_volumes``) or into a display object opened here; else the object
        that already holds the loop's calls for light ``i``'s current faces."""
        if not self.cache_volumes:
            return None
        name, key = self._current_face_object(i)
        if name is not None:
            return name
        name = genobj()
        makeobj(name)
        self._face_objects[i] = (key, name)
        return None

    def _current_face_object(self, i: int) -> tuple[int | None, tuple]:
        """(object, key): the display object that holds light ``i``'s faces for the
        current key, or None for it after deleting an object made for another key."""
        key = self._face_key(i)
        hit = self._face_objects.get(i)
        if hit is not None and hit[0] == key:
            return hit[1], key
        self._drop_face_object(i)
        return None, key

    def _close_face_object(self, i: int, recorded: int | None) -> None:
        """After the edge loop: close the object it was recorded into and draw it, or
        draw the one it was recorded into before."""
        if not self.cache_volumes:
            return
        if recorded is None:
            closeobj()
            recorded = self._face_objects[i][1]
        callobj(recorded)

    def draw_faces_by_facing(self, faces: np.ndarray, ops: tuple[int, int] = (ST_INCR, ST_DECR),
                             obj: int | None = None) -> None:
        """Draw shadow faces twice with culling: the front-facing ones (as the raster
        sees them) with ``ops[0]``, the back-facing ones with ``ops[1]``; from the
        display object ``obj`` (holding :meth:`draw_quads` of ``faces``) if given."""
        for cull, op in ((backface, ops[0]), (frontface, ops[1])):
            cull(TRUE)
            stencil(TRUE, 0, SF_ALWAYS, 0xff, ST_KEEP, ST_KEEP, op)
            if obj is not None:
                callobj(obj)
            else:
                self.draw_quads(faces)
            cull(FALSE)

    @staticmethod
    def draw_quads(faces: np.ndarray) -> None:
        """One polygon per shadow face, (N, 4, 3) v1 .. v4."""
        for quad in faces.tolist():  # Python floats: numpy scalars cost the front end more
            bgnpolygon(); v3f(quad[0]); v3f(quad[1]); v3f(quad[2]); v3f(quad[3]); endpolygon()

    def draw_shadows(self) -> None:
        """The article's code segment ("Show Shadows")."""
        if self.technique is not None:                # (not in the article: a later
            self.technique.draw_shadows(self)         #  technique, same engine)
            return
        nLights, light, DrawObjects = self.nLights, self.light, self.DrawObjects
        MYZERO = self.MYZERO                          # (the article's constant; see config)
        # /* Draw scene w/ ambient light, setting z-buffer. */
        if self.ambient_image is None:                # (not in the article: see accumulate)
            for i in range(nLights):                  # /* Turn on all the lights for */
                lmbind(LIGHT0+i, light[i].index)      # /* ambient light value calculation. */
            zwritemask(0xffffffff)                    # /* We do want to set z values, */
            czclear(0x00000000, getgdesc(GD_ZMAX))    # /* using the full z range. */
            blendfunction(BF_ONE, BF_ZERO)            # /* No alpha blending. */
            DrawObjects(matl_emitambient)             # /* Draw all objects using only ambient */
                                                      # /* and emitted material components. */
            for i in range(nLights):                  # /* Turn off all the lights when done. */
                lmbind(LIGHT0+i, 0)
            if self.keep_ambient:                     # (not in the article: accumulate()'s
                w, h = getsize()                      #  first frame keeps the picture...)
                self.ambient_image = lrectread(0, 0, w - 1, h - 1)
        else:                                         # (...and its later frames put it back;
            w, h = getsize()                          #  z is still the first pass's)
            lrectwrite(0, 0, w - 1, h - 1, self.ambient_image)
        # /* Accumulate effects of each light in the scene in turn. */
        for i in range(nLights):
            # /* Draw faces of shadow volumes, setting stencil planes. */
            lmbind(LIGHT0, light[i].index)            # /* Turn on just this light. */  (LIGHTO in print)
            sclear(MYZERO)                            # /* Reset the stencil values to "zero" */
            zwritemask(0x0)                           # /* We aren't changing any z values */
            wmpack(0x0)                               # /* or any color values. */
            faces, ingoing_flags = self.volume_faces(i)
            if self.signs == "screen":                # (not in the article: see ``signs``)
                self.draw_faces_by_facing(faces, obj=self._screen_face_object(i, faces))
            recorded = self._open_face_object(i) if self.signs == "article" else None
            nEdges = len(faces) if self.signs == "article" and recorded is None else 0
            if nEdges:                                # (Python floats: cheaper calls)
                faces, ingoing_flags = faces.tolist(), ingoing_flags.tolist()
            for iEdge in range(nEdges):               # /* For each edge in the scene, */
                v1, v2, v3, v4 = faces[iEdge]; ingoing = ingoing_flags[iEdge]  # /* project shadow face from this edge. */
                stencil(TRUE, 0, SF_ALWAYS, 0xff,     # /* Write stencil unconditionally, */
                        ST_KEEP, ST_KEEP,             # /* do nothing if zbuffer test fails, */
                        ST_INCR if ingoing else ST_DECR)  # /* otherwise, add or subtract one. */
                bgnpolygon(); v3f(v1); v3f(v2); v3f(v3); v3f(v4); endpolygon()  # /* Draw the shadow volume face. */
            if self.signs == "article":               # (not in the article: the loop's calls
                self._close_face_object(i, recorded)  #  recorded once, replayed per frame)
            if self.stencil_hook is not None:         # (not in the article: lets tests
                self.stencil_hook(i)                  #  read the stencil planes)
            # /* Add highlights for this light, constrained by stencil mask to unshadowed areas. */
            if self.effective_zclear:                 # (what-if, not the article: unmask z so
                zwritemask(0xffffffff)                #  that the reset below takes effect)
            if self.faithful or self.effective_zclear:
                zclear(getgdesc(GD_ZMAX))             # /* Reset the z-buffer contents. */  (zclear takes no argument)
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

    def draw_silhouettes(self, i: int) -> None:
        """Yellow silhouette edges of every caster for light ``i``: solid where the
        z-buffer shows them, dotted where hidden."""
        lt = self.light[i]
        blendfunction(BF_ONE, BF_ZERO)
        zwritemask(0x0)
        cpack(SILHOUETTE_YELLOW)
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

    def draw_volumes(self) -> None:
        """README "Show Volumes": the shadow faces "projected away from one of the
        light sources as semi-transparent surfaces", and the silhouette edges "as
        solid or dotted yellow lines"."""
        self.draw_objects()
        i = self.light_index
        lt = self.light[i]
        faces, _ = self.volume_faces(i)
        zwritemask(0x0)
        blendfunction(BF_SA, BF_MSA)
        c4f((*lt.colour, 0.3))
        for quad in faces:
            bgnpolygon(); v3f(quad[0]); v3f(quad[1]); v3f(quad[2]); v3f(quad[3]); endpolygon()
        self.draw_silhouettes(i)

    def draw_mask(self) -> None:
        """README "Show Mask": one light's shadow faces counted in the stencil, ins and
        outs apart, and shown in the README's colours (module docstring).

        The stencil's top half counts the faces crossed going into shadow, the bottom
        half those going out (:func:`mask_fields`).  ST_INCR adds 1 to the whole
        value, so the ins are counted with the bottom half all ones and only the top
        half writable (the carry lands there), then the bottom half is cleared and
        counts the outs.  Overflow (README: "parts of the mask may be displayed
        incorrectly or clear due to stencil overflow"): the ins stop at 15 (ST_INCR
        clamps at 255); the outs wrap to 0 after 15 (the carry is masked off), except
        when the ins are at 15 too, where they stop.  A pixel is painted where ins -
        outs is 0 (magenta, ins > 0), 1 (blue) or 2 (blue-green); no face, or more
        outs than ins, or three more ins, leaves the objects' image (clear)."""
        self.draw_objects()
        i = self.light_index
        shift, low = mask_fields(self.stencil_bits)
        faces, ingoing = self.volume_faces(i)
        zwritemask(0x0)
        wmpack(0x0)
        swritemask(0xffffffff)
        sclear(low)                                   # ins 0, the outs' half all ones
        for ins, field in ((True, low << shift), (False, low)):
            swritemask(field)
            if not ins:
                sclear(0)                             # outs 0, the ins kept
            stencil(TRUE, 0, SF_ALWAYS, 0xff, ST_KEEP, ST_KEEP, ST_INCR)
            chosen = faces[ingoing == ins]
            if self.signs == "screen":                # in: front-facing as drawn
                cull = backface if ins else frontface
                cull(TRUE)
                chosen = faces
            for quad in chosen:
                bgnpolygon(); v3f(quad[0]); v3f(quad[1]); v3f(quad[2]); v3f(quad[3]); endpolygon()
            if self.signs == "screen":
                cull(FALSE)
        if self.stencil_hook is not None:
            self.stencil_hook(i)
        swritemask(0xffffffff)
        wmpack(0xffffffff)
        colours = (MASK_MAGENTA, MASK_BLUE, MASK_BLUEGREEN)
        self._paint_stencil(((outs + d) << shift | outs, colours[d])
                            for outs in range(low + 1) for d in range(3)
                            if outs + d <= low and outs + d > 0)
        self.draw_silhouettes(i)

    def _paint_stencil(self, values: Iterable[tuple[int, int]]) -> None:
        """Fill the window with a colour where the stencil equals each value."""
        w, h = getsize()
        zbuffer(FALSE)
        pushmatrix()
        ortho2(-0.5, w - 0.5, -0.5, h - 0.5)
        loadmatrix(np.eye(4).reshape(-1).tolist())
        blendfunction(BF_ONE, BF_ZERO)
        for value, colour in values:
            stencil(TRUE, value, SF_EQUAL, 0xff, ST_KEEP, ST_KEEP, ST_KEEP)
            cpack(colour)
            rectf(0, 0, w - 1, h - 1)
        stencil(FALSE, 0, SF_ALWAYS, 0xff, ST_KEEP, ST_KEEP, ST_KEEP)
        popmatrix()
        self.viewing()
        zbuffer(TRUE)

    def DrawFrame(self) -> None:
        """Draw one frame in the current display mode (README: "The main drawing
        routine is DrawFrame(), which uses a select statement")."""
        if self.mode == "shadows":
            self.draw_shadows()
        elif self.mode == "volumes":
            self.draw_volumes()
        elif self.mode == "mask":
            self.draw_mask()
        else:
            self.draw_objects()


# --------------------------------------------------------------------------------------
# Soft shadows: jittered lights, accumulated in acbuf
# --------------------------------------------------------------------------------------
def mask_fields(stencil_bits: int) -> tuple[int, int]:
    """The "Show Mask" stencil layout: (shift, field mask).  The ins are ``(value >>
    shift) & field`` and the outs ``value & field``: the top and bottom halves of the
    planes (4 bits each with the VGX's 8).

    Parameters
    ----------
    stencil_bits : int
        getgdesc(GD_BITS_STENCIL), at least 2.
    """
    shift = stencil_bits // 2
    return shift, (1 << shift) - 1


def random_offsets(scene: Scene, frames: int, seed: int = 1991) -> np.ndarray:
    """Per frame and light, a random offset inside the light's JITTER box.

    README: JITTER gives "the dimensions of a cube within which the light is given a
    random position"; lights without JITTER stay put.

    Returns
    -------
    ndarray, shape (frames, L, 3), float64
    """
    rng = np.random.default_rng(seed)
    box = np.array([lt.jitter for lt in scene.lights], np.float64)
    return (rng.random((frames, len(scene.lights), 3)) - 0.5) * box


def jittered_lights(scene: Scene, offsets: np.ndarray) -> Scene:
    """``scene`` with light ``i`` moved by ``offsets[i]`` ((L, 3) or one (3,))."""
    off = np.broadcast_to(np.asarray(offsets, np.float64), (len(scene.lights), 3))
    lights = tuple(replace(lt, position=tuple(float(p + o) for p, o in
                                              zip(lt.position, d, strict=True)))
                   for lt, d in zip(scene.lights, off, strict=True))
    return replace(scene, lights=lights)


def ambient_pass_shareable(prog: Shadows) -> bool:
    """Whether the jittered frames of :func:`accumulate` may share the first frame's
    ambient pass.

    The pass's colour is emission + ambient terms, and a light's ambient term depends
    on where the light is only through attenuation and a spot cone (lmdef(3G)); with
    neither, moving the lights leaves every pixel of it as it was.  Its z is the
    nearest surface at each pixel, and no later pass of the frame changes it (the
    shadow faces are drawn with ``zwritemask(0x0)``; the lit passes draw the same
    polygons under ZF_LEQUAL, so a z they write equals the one there), so the next
    frame starts on the right z without a clear.  Only the 1991 code's 'shadows'
    mode, without the z-reset variants.
    """
    sc = prog.scene
    return (prog.mode == "shadows" and prog.technique is None and not prog.faithful
            and not prog.effective_zclear and tuple(sc.lmodel.attenuation) == (1.0, 0.0)
            and all(lt.spot is None or lt.spot[1] >= 180.0 for lt in sc.lights))


def accumulate(prog: Shadows, offsets: np.ndarray,
               on_frame: Callable[[int], None] | None = None,
               share_ambient: bool = True) -> None:
    """Draw one jittered frame per row of ``offsets`` and leave their average in the
    colour buffer (article, Figure 6: "drawing a shadowed scene several times, each
    time moving the light source a small amount and accumulating the images").

    ``acbuf(AC_CLEAR_ACCUMULATE, 1.0)`` for the first frame, ``AC_ACCUMULATE`` for the
    rest and ``acbuf(AC_RETURN, 1.0 / n)`` after frame ``n`` -- the idiom of Haeberli
    and Akeley's accumulation buffer.  The window must have been configured with
    ``prog.setup(accumulate=True)``.

    Parameters
    ----------
    prog : Shadows
    offsets : ndarray, shape (N, L, 3) or (N, 3)
        Light offsets per frame.
    on_frame : callable, optional
        ``on_frame(n)`` after the average of the first ``n`` frames was returned to
        the back buffer (the README's "intermediate results will be displayed").
    share_ambient : bool
        Not the article: where :func:`ambient_pass_shareable` allows it, draw the
        ambient pass for the first frame only, keep its picture (``lrectread``) and
        put it back (``lrectwrite``) instead of clearing and drawing it again; the
        same pixels (tested), one pass fewer per jittered frame (``lrectwrite``
        replaces the whole colour buffer, so the running averages ``on_frame`` has
        ``AC_RETURN`` write there between frames are gone too).  False: every frame
        draws the whole code segment.
    """
    base = prog.scene
    share = share_ambient and ambient_pass_shareable(prog)
    try:
        for k, off in enumerate(offsets):
            prog.scene = jittered_lights(base, off)
            prog.define_lights()  # lmdef the moved lights; lmbind transforms them
            prog.keep_ambient = share and k == 0
            prog.DrawFrame()
            acbuf(AC_CLEAR_ACCUMULATE if k == 0 else AC_ACCUMULATE, 1.0)
            if on_frame is not None:
                acbuf(AC_RETURN, 1.0 / (k + 1))
                on_frame(k + 1)
        acbuf(AC_RETURN, 1.0 / len(offsets))
    finally:
        prog.scene = base
        prog.keep_ambient = False
        prog.ambient_image = None
