# ruff: noqa: E702  (bgnpolygon(); v4f(...); endpolygon() on one line, as the article)
"""The strategy a shadow technique plugs into :class:`vgxsim.shadow.program.Shadows`.

Shadows stays the one drawing engine: it owns the window set-up, the lmdef indices,
the display objects, ``DrawObjects`` and the display modes.  With a technique set,
its ``'shadows'`` mode calls :meth:`Technique.draw_shadows`, whose default is the
frame of Heidmann's code segment -- ambient pass, then per light: mark the shadow,
read it (``stencil_hook``), add the light where it is not shadowed -- with the
marking (:meth:`Technique.mark`) left to each technique.  The stencil "zero" is the
engine's ``MYZERO`` (from getgdesc(GD_BITS_STENCIL)).

Shadow faces are drawn with their stencil operation chosen by the facing the
rasterizer sees (``backface``/``frontface`` culling, the engine's ``signs='screen'``),
so a face that a snapped vertex turns over counts with the sign of the pixels it
covers.
"""

from __future__ import annotations

import hashlib
from collections.abc import Callable, Iterable

import numpy as np

from vgxsim.gl import (
    BF_ONE,
    BF_ZERO,
    FALSE,
    GD_BITS_STENCIL,
    GD_ZMAX,
    LIGHT0,
    MPROJECTION,
    MVIEWING,
    SF_ALWAYS,
    SF_EQUAL,
    ST_DECR,
    ST_INCR,
    ST_KEEP,
    TRUE,
    ZF_LEQUAL,
    ZF_LESS,
    backface,
    bgnpolygon,
    blendfunction,
    callobj,
    closeobj,
    czclear,
    delobj,
    endpolygon,
    frontface,
    genobj,
    getgdesc,
    getsize,
    lmbind,
    loadmatrix,
    makeobj,
    mmode,
    read_pixels,
    sclear,
    stencil,
    v4f,
    wmpack,
    zfunction,
    zwritemask,
)
from vgxsim.shadow.scene import MATL_DIFFSPEC, MATL_EMITAMBIENT, Polyhedron

from .volumes import infinite_projection, light4


class TechniqueError(ValueError):
    """A technique cannot draw this scene or configuration (the message says why)."""


def draw_polygons4(polys: Iterable[np.ndarray]) -> None:
    """``bgnpolygon(); v4f(...) ...; endpolygon()`` for each (K, 4) homogeneous polygon."""
    for poly in polys:
        bgnpolygon()
        for v in poly:
            v4f(v)
        endpolygon()


def draw_by_facing(polys: np.ndarray, front_op: int, back_op: int, *, zfail: bool = False,
                   times: np.ndarray | None = None,
                   draw: Callable[[np.ndarray], None] = draw_polygons4) -> None:
    """Draw polygons twice with culling: front-facing ones (as the rasterizer sees
    them) with ``front_op``, back-facing ones with ``back_op``.

    Parameters
    ----------
    polys : ndarray, shape (N, K, 4)
    front_op, back_op : int
        ST_INCR, ST_DECR or ST_KEEP.
    zfail : bool
        False: the op applies where the z test passes (z-pass); True: where it fails
        (z-fail; stencil(3G)'s ``pass`` argument), under ``zfunction(ZF_LESS)`` so
        that a cap lying exactly on the visible surface (the caster's own
        light-facing polygons, drawn again from the same vertices: bit-identical
        depths, shadow_literature.md H7) counts as behind it.
    times : ndarray, shape (N,), int, optional
        Draw polygon n ``times[n]`` times (Bergeron's multiplicity).
    draw : callable
        How the polygons are sent (immediate mode, or :class:`VolumeCache`).
    """
    if times is not None and len(polys):
        polys = np.repeat(polys, np.asarray(times, np.int64), axis=0)
    if zfail:
        zfunction(ZF_LESS)
    for cull, op in ((backface, front_op), (frontface, back_op)):
        if op == ST_KEEP:
            continue
        cull(TRUE)
        if zfail:
            stencil(TRUE, 0, SF_ALWAYS, 0xff, ST_KEEP, op, ST_KEEP)
        else:
            stencil(TRUE, 0, SF_ALWAYS, 0xff, ST_KEEP, ST_KEEP, op)
        draw(polys)
        cull(FALSE)
    if zfail:
        zfunction(ZF_LEQUAL)


class VolumeCache:
    """Volume geometry kept in display objects from one frame to the next.

    The 1991 program sends its shadow faces in immediate mode every frame; here each
    array of polygons becomes a display object (``makeobj`` ... ``closeobj``) the first
    time it is drawn and is replayed with ``callobj`` while the same geometry comes
    again (same light, same casters: the key is a digest of the vertex bytes, so a
    moved light or object makes a new one).  Objects not drawn during a frame are
    deleted after it.  Same polygons, same order: the planes are identical with the
    cache off (tested), only the time differs (immediate-mode calls cost about
    100 microseconds per polygon here, a replay about 1).
    """

    def __init__(self):
        self.objects: dict[bytes, int] = {}
        self.used: set[bytes] = set()

    def draw(self, polys: np.ndarray) -> None:
        polys = np.ascontiguousarray(polys, np.float64)
        key = hashlib.blake2b(polys.tobytes() + repr(polys.shape).encode(),
                              digest_size=16).digest()
        name = self.objects.get(key)
        if name is None:
            name = genobj()
            makeobj(name)
            draw_polygons4(polys)
            closeobj()
            self.objects[key] = name
        self.used.add(key)
        callobj(name)

    def end_frame(self) -> None:
        """Delete the objects this frame did not use."""
        for key in [k for k in self.objects if k not in self.used]:
            delobj(self.objects.pop(key))
        self.used = set()

    def clear(self) -> None:
        for name in self.objects.values():
            delobj(name)
        self.objects.clear()
        self.used = set()


class Technique:
    """Base strategy: Heidmann's frame with the shadow marking left open.

    Subclasses set :attr:`name`, implement :meth:`mark` and may override any hook.

    Attributes
    ----------
    name : str
        Registry name (``api.render(..., technique=name)``).
    infinite_far : bool
        Replace the camera's projection by :func:`.volumes.infinite_projection`
        (z-fail and anything drawing w = 0 vertices).
    exact : bool
        Whether the technique is meant to match the reference everywhere away from
        shadow boundaries (hard cases document where it does not).
    """

    name = "base"
    infinite_far = False
    exact = True
    cache = True  # keep volume geometry in display objects (VolumeCache); a switch
    _volume_cache: VolumeCache | None = None

    # -- engine hooks -------------------------------------------------------------------
    def config(self, prog, accumulate: bool) -> bool:
        """Configure the frame buffer and return True, or return False to leave it to
        the engine (all stencil planes, the default)."""
        return False  # the engine configures all stencil planes

    def after_viewing(self, prog) -> None:
        """Called at the end of :meth:`Shadows.viewing`: the projection may be swapped."""
        if self.infinite_far:
            w, h = getsize()
            mmode(MPROJECTION)
            loadmatrix(infinite_projection(prog.scene.camera, w / h).reshape(-1).tolist())
            mmode(MVIEWING)

    def before_frame(self, prog) -> None:
        """Called once per frame before the first pass (shadow maps render here)."""

    def first_pass(self, prog) -> None:
        """The article's first pass: every light on, ambient and emitted parts, z set."""
        for i in range(prog.nLights):
            lmbind(LIGHT0 + i, prog.light[i].index)
        zwritemask(0xffffffff)
        czclear(0x00000000, getgdesc(GD_ZMAX))
        blendfunction(BF_ONE, BF_ZERO)
        prog.DrawObjects(MATL_EMITAMBIENT)
        for i in range(prog.nLights):
            lmbind(LIGHT0 + i, 0)

    def mark(self, prog, i: int) -> None:
        """Mark light ``i``'s shadow (for stencil techniques: stencil != MYZERO)."""
        raise NotImplementedError

    def lit_pass(self, prog, i: int) -> None:
        """Add light ``i`` where its shadow is not marked (the article's last lines)."""
        zwritemask(0xffffffff)
        wmpack(0xffffffff)
        blendfunction(BF_ONE, BF_ONE)
        stencil(TRUE, prog.MYZERO, SF_EQUAL, 0xff, ST_KEEP, ST_KEEP, ST_KEEP)
        prog.DrawObjects(MATL_DIFFSPEC)

    def finish(self, prog) -> None:
        """After the last light: leave stencil and blending off."""
        stencil(FALSE, 0, SF_ALWAYS, 0xff, ST_KEEP, ST_KEEP, ST_KEEP)
        blendfunction(BF_ONE, BF_ZERO)

    def teardown(self, prog) -> None:
        """Delete the display objects the technique made (the engine's teardown)."""
        if self._volume_cache is not None:
            self._volume_cache.clear()

    def draw_shadows(self, prog) -> None:
        """One 'shadows' frame: Heidmann's segment with this technique's marking."""
        self.before_frame(prog)
        self.first_pass(prog)
        for i in range(prog.nLights):
            lmbind(LIGHT0, prog.light[i].index)
            self.mark(prog, i)
            if prog.stencil_hook is not None:
                prog.stencil_hook(i)
            self.lit_pass(prog, i)
            lmbind(LIGHT0, 0)
        self.finish(prog)
        if self._volume_cache is not None:
            self._volume_cache.end_frame()

    # -- reading the result -------------------------------------------------------------
    def read_mask(self, prog, i: int) -> np.ndarray:
        """(H, W) uint8 plane, row 0 = bottom, equal to :meth:`lit_value` where lit;
        read while the engine's ``stencil_hook`` runs."""
        return read_pixels("back", "stencil")

    def lit_value(self, prog) -> int:
        """The value :meth:`read_mask` holds where the pixel is lit."""
        return prog.MYZERO

    # -- helpers ------------------------------------------------------------------------
    def draw_polygons(self, polys: np.ndarray) -> None:
        """Send (N, K, 4) homogeneous polygons, through the cache when it is on."""
        if not self.cache:
            draw_polygons4(polys)
            return
        if self._volume_cache is None:
            self._volume_cache = VolumeCache()
        self._volume_cache.draw(polys)

    def draw_by_facing(self, polys: np.ndarray, front_op: int, back_op: int, *,
                       zfail: bool = False, times: np.ndarray | None = None) -> None:
        """:func:`draw_by_facing` through :meth:`draw_polygons`."""
        draw_by_facing(polys, front_op, back_op, zfail=zfail, times=times,
                       draw=self.draw_polygons)

    def start_stencil(self, prog) -> None:
        """The article's "Reset the stencil values to zero ... We aren't changing any z
        values or any color values"."""
        sclear(prog.MYZERO)
        zwritemask(0x0)
        wmpack(0x0)

    def light(self, prog, i: int) -> np.ndarray:
        """(4,) homogeneous position of light ``i`` (w = 0: directional)."""
        return light4(prog.scene.lights[i])

    def casters(self, prog, light: np.ndarray, length) -> list[Polyhedron]:
        """Casters to draw volumes for (all, or culled when ``self.cull``)."""
        return casters_in_view(prog, light, length, getattr(self, "cull", False))

    def stencil_bits(self) -> int:
        return getgdesc(GD_BITS_STENCIL)

    @staticmethod
    def open_casters(casters: Iterable[Polyhedron]) -> list[str]:
        """Names of casters that are not closed 2-manifolds."""
        return [c.name for c in casters if not c.is_closed]


# ST_INCR / ST_DECR pairs, named for readability at the call sites
ZPASS_OPS = (ST_INCR, ST_DECR)   # front faces go into shadow, back faces out
ZFAIL_OPS = (ST_DECR, ST_INCR)   # behind the surface: back faces in, front faces out


def casters_in_view(prog, light: np.ndarray, length, cull: bool) -> list[Polyhedron]:
    """The scene's casters, less (``cull``) those whose volume misses the frustum."""
    from .volumes import frustum_planes, volume_culled

    casters = list(prog.scene.casters)
    if not cull:
        return casters
    w, h = getsize()
    planes = frustum_planes(prog.scene, w / h, infinite=prog.technique.infinite_far)
    return [m for m in casters if not volume_culled(m, light, planes)]
