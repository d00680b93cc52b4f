"""drawmode(3G): which GL framebuffer a window's drawing goes to, and what the monitor
shows of all four.

A window draws into one framebuffer at a time.  Selecting another one renders what
is queued, puts the modes drawmode(3G) keeps per framebuffer (current colour, colour
map, write mask, draw buffers, readsource, the planes and their command batch) into
the old framebuffer's :class:`~vgxsim.state.layers.PlaneSet` and takes the new one's
onto the window.  Everything downstream -- the command stream, the pipeline, the
fragment kernels -- then works as for any colour-index window: drawing into the
overlay is ordinary drawing into other planes, with the register snapshot restricted
to what those planes can do (vgxsim.state.registers, ``layer_mask``).  In NORMALDRAW
nothing of this runs, so drawing there is unchanged.

The extra framebuffers are always rendered by the software batch (their own
:class:`~vgxsim.batch.CommandBatch`): the OpenGL backend has no place for them, as it
has none for other states it cannot express.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from vgxsim.batch import CommandBatch
from vgxsim.state import colormap
from vgxsim.state.layers import (
    MAX_BITS,
    PlaneSet,
    composite,
    default_layer_map,
    layer_config,
    nonzero_colour,
)
from vgxsim.state.planes import Framebuffer, unpack_rgba

NORMAL = "normal"

#: Window attributes drawmode(3G) keeps once per framebuffer.
WINDOW_MODES = ("config", "fb", "_batch", "colormap", "multimap", "curmap", "colour",
                "colour_index", "readsource")
#: Raster registers it keeps once per framebuffer (writemask, frontbuffer, backbuffer).
REGISTER_MODES = ("wmpack", "frontbuffer", "backbuffer", "zdraw_back")


def configure(ctx) -> None:
    """gconfig for the extra framebuffers (the window has the normal framebuffer
    selected): overlay and underlay get the planes ``ctx.config`` asks for, cleared;
    the pop-up and cursor planes are allocated anew, at the window's size, when a
    drawmode next selects them; every colour map is kept (the maps are the
    monitor's, not the window's planes)."""
    old = ctx.plane_sets
    config = ctx.config
    sets = {NORMAL: PlaneSet(NORMAL)}
    view = replace(config, rgb=False, zbits=0, stencil=0, acbits=0)  # what calls see
    for name, most in MAX_BITS.items():
        bits = {"overlay": config.overlay, "underlay": config.underlay}.get(name, most)
        prev = old.get(name)
        cmap = prev.modes["colormap"] if prev is not None else None  # made at first use
        ps = PlaneSet(name, bits, modes=_fresh_modes(view, cmap))
        if bits and name in ("overlay", "underlay"):
            _allocate(ctx, ps)  # granted by this gconfig: the planes start cleared
        sets[name] = ps
    ctx.plane_sets = sets
    ctx.planes_selected = NORMAL


def _fresh_modes(view, cmap: np.ndarray | None) -> dict:
    return {"config": view,
            "fb": None, "_batch": None, "colormap": cmap, "multimap": False, "curmap": 0,
            "colour": colormap.index_rgba(0), "colour_index": 0, "readsource": 0,
            "wmpack": 0xFFFFFFFF, "frontbuffer": True, "backbuffer": False,
            "zdraw_back": None}


def _allocate(ctx, ps: PlaneSet) -> None:
    if ps.modes["colormap"] is None:
        ps.modes["colormap"] = default_layer_map(ps.name)
    ps.fb = Framebuffer(layer_config(ctx.config.width, ctx.config.height))
    ps.modes["fb"] = ps.fb
    ps.modes["_batch"] = CommandBatch(ps.fb)


def select(ctx, name: str) -> None:
    """Make framebuffer ``name`` ('normal', 'overlay', 'underlay', 'popup', 'cursor')
    the one the window draws into (drawmode(3G))."""
    if name == ctx.planes_selected:
        return
    ctx.flush()  # what is queued goes to the planes it was drawn for
    sets = ctx.plane_sets
    _store(ctx, sets[ctx.planes_selected])
    new = sets[name]
    if new.fb is None and name != NORMAL:
        _allocate(ctx, new)  # the pop-up and cursor planes, at first use
    for k in WINDOW_MODES:
        setattr(ctx, k, new.modes[k])
    ctx.raster.set(**{k: new.modes[k] for k in REGISTER_MODES},
                   layer_mask=None if name == NORMAL else new.mask)
    ctx.planes_selected = name
    ctx.stream.forget()  # the next vertex and bgn* record colour and state anew


def _store(ctx, ps: PlaneSet) -> None:
    ps.modes.update({k: getattr(ctx, k) for k in WINDOW_MODES})
    ps.modes.update({k: getattr(ctx.raster, k) for k in REGISTER_MODES})
    if ps.name == NORMAL:
        ps.fb = ctx.fb


def normal_modes(ctx) -> dict:
    """The normal framebuffer's per-framebuffer modes, wherever they are now."""
    if ctx.planes_selected == NORMAL:
        return {k: getattr(ctx, k) for k in WINDOW_MODES}
    return ctx.plane_sets[NORMAL].modes


def display(ctx, ignore=frozenset()) -> np.ndarray:
    """(H, W, 4) uint8: what the monitor shows of the window (after a flush): the
    normal front buffer, colour-mapped in cmode, with the pop-up, overlay and
    underlay planes composited by underlay(3G)'s rule
    (:func:`vgxsim.state.layers.composite`), except those named in ``ignore``."""
    modes = normal_modes(ctx)
    config, front = modes["config"], modes["fb"].front
    if config.rgb:
        picture = unpack_rgba(front)
    else:
        picture = colormap.lookup(modes["colormap"], front, modes["multimap"],
                                  modes["curmap"])
    shown = {}
    for name in ("underlay", "overlay", "popup"):
        ps = ctx.plane_sets[name]
        if ps.bits and ps.fb is not None and name not in ignore:
            cmap = ctx.colormap if ctx.planes_selected == name else ps.modes["colormap"]
            shown[name] = (ps.fb.front, ps.bits, cmap)
    if not shown:
        return picture
    index_bits = 8 if modes["multimap"] else 12
    return composite(picture, nonzero_colour(front, config.rgb, index_bits), shown)


# -- zdraw(3G): the z-buffer as a colour buffer ---------------------------------------
def zdraw_targets(ctx) -> list[np.ndarray]:
    """The buffers drawing goes to under zdraw(TRUE), as uint32 planes: the z-buffer,
    then the colour buffers frontbuffer/backbuffer enable (zdraw(3G): "All
    combinations of values for backbuffer, frontbuffer, and zdraw are valid while the
    normal framebuffer is in double buffer mode.  While ... in single buffer mode,
    backbuffer is ignored, and frontbuffer can be disabled only while zdraw is
    enabled").  The normal framebuffer must be selected."""
    fb, rs = ctx.fb, ctx.raster
    out = [fb.z.view(np.uint32)]
    if fb.back is not None and rs.backbuffer:
        out.append(fb.back)
    if rs.frontbuffer:
        out.append(fb.front)
    return out


class ZDrawBatch(CommandBatch):
    """The software batch of zdraw(TRUE): after each flush the z-buffer keeps the low
    24 bits of what was drawn into it, as a signed 24-bit value like every z
    (GD_BITS_NORM_ZBUFFER 24: red, green and blue -- or a colour index -- survive,
    alpha does not).  Depth values already there are unchanged by this."""

    def flush(self) -> None:
        if self.nprims == 0:
            return
        super().flush()
        z = self.fb.z
        z[:] = ((z & 0xFFFFFF) ^ 0x800000) - 0x800000


def set_zdraw(ctx, on: bool) -> None:
    """Draw colours into the z-buffer too (on) or not (zdraw(3G)).

    The kernels write two colour buffers; with zdraw their first is the z-buffer and
    their second the colour buffer also enabled, through a software batch over a
    :meth:`~vgxsim.state.planes.Framebuffer.view` of the window's planes (the caller
    checks that at most one colour buffer is enabled).
    """
    ctx.flush()
    if ctx.zdraw_batch is None and not on:
        return
    if ctx.zdraw_batch is None:
        ctx.zdraw_batch = ctx._batch  # the window's own batch, back at zdraw(FALSE)
    if not on:
        ctx._batch, ctx.zdraw_batch = ctx.zdraw_batch, None
        ctx.raster.set(zdraw_back=None)
        ctx.stream.forget()
        return
    fb = ctx.fb
    targets = zdraw_targets(ctx)
    second = targets[1] if len(targets) > 1 else None
    view = Framebuffer.view(replace(fb.config, double=second is not None), targets[0],
                            second, fb.z, fb.stencil)
    ctx._batch = ZDrawBatch(view)
    ctx.raster.set(zdraw_back=second is not None)
    ctx.stream.forget()


def fresh_pixel(ctx) -> np.ndarray:
    """(4,) uint8: what the monitor shows of freshly allocated (all zero) planes --
    the normal planes' 0 (black, or index 0 through the normal map), or index 0
    through the underlay map where underlay planes exist (underlay(3G))."""
    under = ctx.plane_sets["underlay"]
    if under.bits:
        cmap = ctx.colormap if ctx.planes_selected == "underlay" else under.modes["colormap"]
        return np.array([*cmap[0], 255], np.uint8)
    modes = normal_modes(ctx)
    if modes["config"].rgb:
        return np.zeros(4, np.uint8)
    zero = np.zeros((1, 1), np.uint32)
    return colormap.lookup(modes["colormap"], zero, modes["multimap"], modes["curmap"])[0, 0]
