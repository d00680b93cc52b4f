"""Fragment-stage registers: setters only store and mark dirty.

The snapshot handed to the batch (:class:`~vgxsim.state.raster.RasterState`) is
rebuilt at most once per change, when the next primitive is queued -- not on every
setter call -- following Mesa's softpipe pattern of one ``update_derived``.
"""

from __future__ import annotations

from dataclasses import replace
from typing import NamedTuple

from .raster import BF_ONE, BF_ZERO, CMP_ALWAYS, CULL_BACK, CULL_FRONT, FLAT, RasterState

#: Switch: clear_state() hands back the clear state made for the current snapshot
#: (False: a new one every clear; the planes are the same, tests/stream/
#: test_fast_calls.py).
KEEP_CLEAR_STATE = True


class StencilRegister(NamedTuple):
    """The arguments of the last stencil(3G) call, by name."""

    enable: bool = False
    ref: int = 0
    func: int = 7  # SF_ALWAYS
    mask: int = 0xFF
    fail: int = 0  # ST_KEEP
    pass_: int = 0  # stencil passed, z failed
    zpass: int = 0


class RasterRegisters:
    """The IRIS GL registers that decide what happens to a fragment."""

    def __init__(self, width: int, height: int, double: bool):
        self.width = width
        self.height = height
        self.double = double
        self.zbuffer = False
        self.zfunc = 3  # ZF_LEQUAL, the default (zfunction(3G))
        self.zwritemask = 0xFFFFFFFF
        self.stencil = StencilRegister()
        self.swritemask = 0xFF
        self.blend = (1, 0)  # BF_ONE, BF_ZERO
        self.logicop = 3  # LO_SRC
        self.wmpack = 0xFFFFFFFF
        self.afunction = (0, 7)  # (ref, AF_ALWAYS)
        self.shademodel = 1  # GOURAUD
        self.subpixel = False
        self.backface = False
        self.frontface = False
        self.frontbuffer = not double
        self.backbuffer = double
        self.viewport = (0, width - 1, 0, height - 1)
        self.scrmask = (0, width - 1, 0, height - 1)
        self.linewidth = 1
        self.linestyle = 0xFFFF
        self.lsrepeat = 1
        self.pntsize = 1
        self.texture = 0  # texture binding id (vgxsim.state.textures); 0: off
        # drawmode(3G): None while the normal planes are drawn; otherwise the index
        # planes of the overlay, underlay or pop-up framebuffer selected (their mask),
        # and snapshots carry what those framebuffers can do (see _layer_state).
        self.layer_mask: int | None = None
        # zdraw(3G): None, or whether the kernels' second colour buffer is drawn while
        # the z-buffer is the first (vgxsim.pipeline.layers.zdraw_planes).
        self.zdraw_back: bool | None = None
        self._snapshot: RasterState | None = None
        # Snapshots by register values: a program that alternates between a few
        # states (the 1991 shadow faces: stencil INCR, DECR, INCR, ...) gets the
        # same RasterState objects back, which the command stream compares by
        # identity.
        self._memo: dict[tuple, RasterState] = {}
        # stencil(3G)'s fast path: the StencilRegister of each valid argument tuple.
        self.stencil_memo: dict[tuple, StencilRegister] = {}
        # clear_state()'s clear states by snapshot: id -> (snapshot, clear state).
        self._clear_kept: dict[int, tuple] = {}

    def set(self, **values) -> None:
        """Store register values and mark the snapshot dirty."""
        for k, v in values.items():
            if not hasattr(self, k):
                raise AttributeError(k)
            setattr(self, k, v)
        self._snapshot = None

    def raster_rect(self) -> tuple[int, int, int, int]:
        """Viewport and screenmask and the window, intersected (inclusive)."""
        vl, vr, vb, vt = self.viewport
        sl, sr, sb, st = self.scrmask
        return (max(vl, sl, 0), min(vr, sr, self.width - 1),
                max(vb, sb, 0), min(vt, st, self.height - 1))

    def _key(self) -> tuple:
        return (self.zbuffer, self.zfunc, self.zwritemask, self.stencil, self.swritemask,
                self.blend, self.logicop, self.wmpack, self.afunction, self.shademodel,
                self.subpixel, self.backface, self.frontface, self.frontbuffer,
                self.backbuffer, self.viewport, self.scrmask, self.linewidth,
                self.linestyle, self.lsrepeat, self.pntsize, self.texture, self.layer_mask,
                self.zdraw_back)

    def snapshot(self) -> RasterState:
        """The current RasterState (cached until a register changes; one object per
        distinct set of register values)."""
        if self._snapshot is None:
            key = self._key()
            hit = self._memo.get(key)
            if hit is not None:
                self._snapshot = hit
                return hit
            en, ref, func, mask, fail, pas, zpass = self.stencil
            cull = (CULL_BACK if self.backface else 0) | (CULL_FRONT if self.frontface else 0)
            if self.double:
                front, back = self.frontbuffer, self.backbuffer
            else:
                front, back = True, False
            self._snapshot = RasterState(
                zbuffer=self.zbuffer, zfunc=self.zfunc, zwritemask=self.zwritemask & 0xFFFFFFFF,
                stencil=en, sref=ref, sfunc=func, smask=mask, sfail=fail, spass=pas,
                szpass=zpass, swritemask=self.swritemask,
                blend_sf=self.blend[0], blend_df=self.blend[1], logicop=self.logicop,
                wmpack=self.wmpack & 0xFFFFFFFF, afunc=self.afunction[1],
                aref=self.afunction[0], shademodel=self.shademodel, subpixel=self.subpixel,
                cull=cull, draw_front=front, draw_back=back, scissor=self.raster_rect(),
                linewidth=self.linewidth, linestyle=self.linestyle, lsrepeat=self.lsrepeat,
                pntsize=self.pntsize, texture=self.texture,
            )
            if self.layer_mask is not None:
                self._snapshot = _layer_state(self._snapshot, self.layer_mask)
            if self.zdraw_back is not None:
                # zdraw(3G): the z-buffer is a colour buffer, so no depth test ("you
                # must turn z-buffer mode off"); the kernels' front buffer is the
                # z-buffer and their back buffer the one colour buffer also drawn.
                self._snapshot = replace(self._snapshot, zbuffer=False, draw_front=True,
                                         draw_back=self.zdraw_back)
            if len(self._memo) > 4096:
                self._memo.clear()
            self._memo[key] = self._snapshot
        return self._snapshot

    def clear_state(self) -> RasterState:
        """Snapshot for clears: only the rectangle, masks and draw buffers matter.

        With :data:`KEEP_CLEAR_STATE` the one made for a snapshot is handed back
        for that snapshot again (``replace`` of a RasterState costs about 10 us, and
        the 1991 frame clears three times, under the same registers every frame)."""
        snap = self.snapshot()
        kept = self._clear_kept.get(id(snap))
        if kept is not None and kept[0] is snap and KEEP_CLEAR_STATE:
            return kept[1]
        cs = replace(snap, zbuffer=False, stencil=False, blend_sf=1, blend_df=0,
                     logicop=3, afunc=7, cull=0, texture=0)
        if len(self._clear_kept) >= 64:
            self._clear_kept.clear()
        self._clear_kept[id(snap)] = (snap, cs)
        return cs


def _layer_state(rs: RasterState, mask: int) -> RasterState:
    """A snapshot as the overlay, underlay and pop-up planes take it (drawmode(3G)).

    Those framebuffers are single colour-index buffers (vgxsim.state.layers): the
    write mask keeps only their planes, FLAT is "the only available shading model"
    there (overlay(3G), underlay(3G)); z-buffering, stencil, blending, the alpha test
    and texturing belong to the normal framebuffer (its z and stencil planes, its RGBA
    colours), so they are off.  logicop stays: it works on indices (XOR rubber bands
    drawn in the overlay are the classic use).  The fragment kernels see an ordinary
    state record; NORMALDRAW snapshots never come here.
    """
    return replace(rs, zbuffer=False, stencil=False, blend_sf=BF_ONE, blend_df=BF_ZERO,
                   afunc=CMP_ALWAYS, shademodel=FLAT, texture=0, draw_front=True,
                   draw_back=False,
                   wmpack=rs.wmpack & mask)
