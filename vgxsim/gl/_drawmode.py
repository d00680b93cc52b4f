"""drawmode, overlay, underlay and the older pop-up calls (pupmode, endpupmode,
pupcolor): drawing into the overlay, underlay and pop-up framebuffers; zdraw: the
z-buffer as a colour buffer of the normal framebuffer.

drawmode(3G) directs drawing, and the modes each framebuffer keeps for itself
(color, mapcolor, writemask and their getters, frontbuffer/backbuffer, readsource),
to one of NORMALDRAW, OVERDRAW, UNDERDRAW, PUPDRAW or CURSORDRAW; matrices,
linewidth and the other modes are shared (vgxsim.pipeline.layers).  The overlay,
underlay and pop-up planes are colour-index planes with their own colour maps:
``drawmode(OVERDRAW); mapcolor(1, 255, 0, 0); color(1); ...`` draws red over the
normal planes, ``color(0); clear()`` makes the overlay transparent again.  What the
monitor (and every recorded frame) shows follows underlay(3G)'s rule: a non-zero
pop-up pixel, else a non-zero overlay pixel, else the normal planes, except where
those are zero and underlay planes exist (vgxsim.state.layers.composite).

overlay(n) and underlay(n) ask for planes, granted at the next gconfig (0..4 each,
getgdesc(GD_BITS_OVER_SNG_CMODE) / GD_BITS_UNDR_SNG_CMODE; default 0).  The pop-up
framebuffer always has its 2 planes.  In CURSORDRAW only mapcolor and getmcolor do
anything (drawmode(3G)); no cursor is drawn headless, so what is drawn there is
never shown.  Drawing in the extra framebuffers is flat-shaded and ignores the
z-buffer, stencil, blending, alpha test and textures, which belong to the normal
framebuffer (vgxsim.state.registers, ``_layer_state``).
"""

from __future__ import annotations

from vgxsim import GL
from vgxsim.pipeline import layers
from vgxsim.pipeline.context import replace_config
from vgxsim.state import colormap
from vgxsim.state.layers import MAX_BITS

from ._core import (
    GLUsageError,
    GLValueError,
    as_int,
    check_token,
    current,
    describe,
    gl_function,
    window_of,
)

__all__ = ["drawmode", "overlay", "underlay", "pupmode", "endpupmode", "pupcolor", "zdraw"]

#: drawmode tokens -> the framebuffer's name in vgxsim.pipeline.layers.
FRAMEBUFFER_OF = {int(GL.NORMALDRAW): layers.NORMAL, int(GL.OVERDRAW): "overlay",
                  int(GL.UNDERDRAW): "underlay", int(GL.PUPDRAW): "popup",
                  int(GL.CURSORDRAW): "cursor"}


def select(name: str, args: tuple, mode: int) -> None:
    """Switch the current window to drawing mode ``mode`` (a drawmode token)."""
    ctx = current(name, args)
    if ctx.prim is not None:
        raise GLUsageError(f"{describe(name, args)}: a primitive is open (call its end* "
                           "first); the draw mode cannot change inside bgn*/end*")
    layers.select(ctx, FRAMEBUFFER_OF[mode])
    window_of(ctx).drawmode = mode


@gl_function(record=False)
def drawmode(mode: int) -> None:
    """Select the framebuffer drawing goes to (drawmode(3G)).

    Parameters
    ----------
    mode : int
        NORMALDRAW, OVERDRAW, UNDERDRAW, PUPDRAW or CURSORDRAW.

    Raises
    ------
    GLValueError
        For any other token (DUALDRAW, drawing two framebuffers at once, is not
        emulated).
    GLUsageError
        Inside bgn*/end*.
    """
    args = (mode,)
    m = check_token("drawmode", args, "mode", mode, FRAMEBUFFER_OF, "NORMALDRAW/OVERDRAW/")
    select("drawmode", args, m)


def _planes(name: str, which: str, planes) -> None:
    args = (planes,)
    n = as_int(name, args, "planes", planes)
    most = MAX_BITS[which]
    if not 0 <= n <= most:
        gd = "GD_BITS_OVER_SNG_CMODE" if which == "overlay" else "GD_BITS_UNDR_SNG_CMODE"
        raise GLValueError(f"{describe(name, args)}: planes must be 0..{most} "
                           f"(getgdesc({gd}) is {most})")
    replace_config(current(name, args), **{which: n})


@gl_function(record=False)
def overlay(planes: int) -> None:
    """Ask for ``planes`` overlay bitplanes (0..4); granted at gconfig (overlay(3G)).

    The overlay shows wherever its index is non-zero, over the normal planes.
    """
    _planes("overlay", "overlay", planes)


@gl_function(record=False)
def underlay(planes: int) -> None:
    """Ask for ``planes`` underlay bitplanes (0..4); granted at gconfig (underlay(3G)).

    The underlay shows wherever the normal planes hold zero.
    """
    _planes("underlay", "underlay", planes)


@gl_function(record=False)
def pupmode() -> None:
    """Draw into the pop-up planes: the older form of ``drawmode(PUPDRAW)``
    (pupmode(3G), which drawmode replaced)."""
    select("pupmode", (), int(GL.PUPDRAW))


@gl_function(record=False)
def endpupmode() -> None:
    """Back to the normal planes after :func:`pupmode` (endpupmode(3G)):
    ``drawmode(NORMALDRAW)``."""
    select("endpupmode", (), int(GL.NORMALDRAW))


@gl_function()
def pupcolor(clr: int) -> None:
    """The current colour of the pop-up planes, 0..3 (pupcolor(3G): PUP_CLEAR,
    PUP_COLOR, PUP_BLACK, PUP_WHITE), whichever framebuffer is being drawn."""
    args = (clr,)
    ctx = current("pupcolor", args)
    c = as_int("pupcolor", args, "clr", clr)
    top = (1 << MAX_BITS["popup"]) - 1
    if not 0 <= c <= top:
        raise GLValueError(f"{describe('pupcolor', args)}: clr must be 0..{top} "
                           "(PUP_CLEAR..PUP_WHITE)")
    if ctx.planes_selected == "popup":
        ctx.colour_index = c
        ctx.colour = colormap.index_rgba(c)
        ctx.last_sent = "colour"
    else:
        modes = ctx.plane_sets["popup"].modes
        modes["colour_index"] = c
        modes["colour"] = colormap.index_rgba(c)


# -- zdraw ------------------------------------------------------------------------------
@gl_function()
def zdraw(b: int) -> None:
    """Draw colours into the z-buffer too (zdraw(3G)).

    "When zbuffer is FALSE ... it is possible to treat the z-buffer as a third color
    bitplane buffer": with ``zdraw(TRUE)`` lines, polygons, clears and the pixel
    writes (lrectwrite, rectcopy) store their colour words -- the index in colour-map
    mode -- in the z-buffer, besides the colour buffers frontbuffer/backbuffer
    enable; readsource(SRC_ZBUFFER) reads them back (lrectread, rectcopy).  The
    z-buffer has 24 bits (GD_BITS_NORM_ZBUFFER): it keeps red, green and blue (or the
    index) as a signed 24-bit z, so alpha is lost and a word whose blue byte is 128 or
    more reads back with 0xFF above it (vgxsim.pipeline.layers.ZDrawBatch).  No depth
    test is made meanwhile ("you must turn z-buffer mode off"; vgxsim ignores
    zbuffer(TRUE) while zdraw is on, where IRIS GL leaves it undefined).  gconfig
    resets it to FALSE.

    Raises
    ------
    GLUsageError
        Without a z-buffer; in a draw mode other than NORMALDRAW ("zdraw should not
        be called while drawing to the overlay, underlay, or pop-up framebuffers");
        or when the z-buffer and both colour buffers would be drawn at once (vgxsim's
        fragment kernels write two buffers: use frontbuffer or backbuffer alone).
    """
    args = (b,)
    ctx = current("zdraw", args)
    on = bool(as_int("zdraw", args, "b", b))
    if on:
        check_zdraw("zdraw", args, ctx, ctx.raster.frontbuffer, ctx.raster.backbuffer)
    layers.set_zdraw(ctx, on)


def check_zdraw(name: str, args: tuple, ctx, front: bool, back: bool) -> None:
    """GLUsageError unless zdraw can draw with these frontbuffer/backbuffer values."""
    if ctx.planes_selected != layers.NORMAL:
        raise GLUsageError(f"{describe(name, args)}: zdraw works in NORMALDRAW only (only "
                           "the normal framebuffer has a z-buffer, zdraw(3G))")
    if ctx.fb.z is None:
        raise GLUsageError(f"{describe(name, args)}: the window has no z-buffer "
                           "(zbsize(0) was configured)")
    if ctx.fb.back is not None and front and back:
        raise GLUsageError(f"{describe(name, args)}: zdraw with both frontbuffer and "
                           "backbuffer is three colour buffers; vgxsim draws at most two "
                           "at once (the z-buffer and one of them)")



def set_draw_buffer(name: str, args: tuple, ctx, **change) -> None:
    """frontbuffer/backbuffer: store the register; under zdraw, check the new
    combination first and then draw through the new choice of buffers."""
    if ctx.zdraw_batch is None:
        ctx.raster.set(**change)
        return
    new = {"frontbuffer": ctx.raster.frontbuffer, "backbuffer": ctx.raster.backbuffer,
           **change}
    check_zdraw(name, args, ctx, new["frontbuffer"], new["backbuffer"])
    ctx.flush()  # what is queued is drawn with the buffers it was queued for
    ctx.raster.set(**change)
    layers.set_zdraw(ctx, True)
