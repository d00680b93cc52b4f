"""IRIS GL window and configuration calls: winopen, gconfig, swapbuffers, viewport ...

Headless windows.  A window is a :class:`~vgxsim.pipeline.context.Context`; nothing is
shown on a display.  Window-manager requests that only matter on a screen
(``foreground``, ``noport``, ``noborder``, ``iconsize``, ``icontitle``, ``winmove``)
are validated and recorded but change no pixels.

Size.  ``winopen`` takes its size from ``prefsize``, else from ``prefposition``, else
from ``session.default_size`` (640x512; ``vgxsim run --size`` sets it), brought
within ``minsize``/``maxsize`` and to the ``keepaspect`` ratio, as a user sizing the
window with the mouse would be held to them.  The window constraints are used up by
``winopen`` (winconstraints(3G)): the next window starts unconstrained.  Sizes are
not limited to the 1280x1024 screen (``getgdesc(GD_XPMAX/GD_YPMAX)``), so large
headless renders are possible, up to :data:`MAX_WINDOW_SIZE` pixels a side (16384,
vgxsim's limit: one 16384x16384 plane of 32-bit words is already 1 GiB).  Larger
sizes raise GLValueError at ``prefsize``, ``prefposition``, ``winposition``,
``minsize`` and ``winopen``/``winconstraints`` (for a size made by
``keepaspect`` or ``vgxsim run --size``), before anything is allocated.

Reshaping.  ``vgxsim run --size WxH`` acts as a user who reshapes each new window to
WxH: a window whose program asked for another size (``prefsize``, ``prefposition``)
opens at that size, with its viewport and ortho2, and is reshaped at once
(:func:`_reshape`, as ``winposition`` reshapes): its planes take the new size, its
viewport and screen mask stay until the program calls ``reshapeviewport`` or
``viewport`` (or ``gconfig`` resets them), and it gets a REDRAW, as the window
manager sends one after a reshape.

Configuration.  A new window is in colour-map mode, single-buffered, with a 24-bit
z-buffer and no stencil or accumulation planes (the IRIS GL defaults; the VGX always
had its z planes).  ``RGBmode``, ``doublebuffer``, ``stensize``, ``acsize``
and ``zbsize`` only record a request; ``gconfig`` allocates the planes.  (The colour
map calls multimap/onemap/setmap/getmap live in :mod:`vgxsim.gl._color`.)

Frames.  Each window hands pictures of its screen to its frame sink (``ctx.sink``:
``session.sink_factory(gid)`` when ``vgxsim run`` set one, else None; library users
may set ``ctx.sink`` to any object with a ``write(rgba_bottom_up)`` method, e.g. a
:class:`vgxsim.sinks.MemorySink`).  A double-buffered window hands over its new front
buffer at every ``swapbuffers``.  A single-buffered window has no frame boundary --
what it draws is on the screen at once -- so its screen is handed over whenever it
has changed, checked at ``swapbuffers``, ``gflush``, ``finish``, ``winclose``, before
a ``qread`` waits on an empty queue, and at the end of a ``vgxsim run``.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from vgxsim import DEVICE, GL
from vgxsim.pipeline import layers
from vgxsim.pipeline.context import Context, replace_config
from vgxsim.state.planes import MAX_STENCIL_PLANES

from . import _events
from ._core import (
    GLTypeError,
    GLValueError,
    Window,
    as_int,
    check_token,
    current,
    describe,
    gl_function,
    session,
    window_of,
)
from ._drawmode import set_draw_buffer
from ._matrix import load_window_projection
from ._raster import register_call

__all__ = [
    "winopen", "winclose", "winset", "winget", "wintitle", "prefsize", "prefposition",
    "foreground", "keepaspect", "winconstraints", "noborder", "minsize", "maxsize",
    "iconsize", "icontitle", "winposition", "winmove", "noport",
    "RGBmode", "cmode", "doublebuffer", "singlebuffer", "stensize", "acsize", "zbsize",
    "gconfig", "swapbuffers", "gflush", "finish",
    "viewport", "reshapeviewport", "getviewport", "getsize", "getorigin", "scrmask",
    "getscrmask", "subpixel", "frontbuffer", "backbuffer", "readsource",
]

#: Largest window width and height in pixels (see the module docstring).
MAX_WINDOW_SIZE = 16384

ACBITS = (0, 16)  # acsize(3G) on the VGX: none or 16 bits per component (GD_BITS_ACBUF)
ZBITS = (0, 24)  # zbsize: none or the 24-bit z-buffer (GD_BITS_NORM_ZBUFFER)

# -- window constraints (prefsize & co), used up by the next winopen ---------------------
# They live in the session beside session.prefsize/prefposition.
def _pending_constraints() -> dict:
    return session.constraints


def _clear_constraints() -> None:
    session.prefsize = None
    session.prefposition = None
    session.constraints = {}


def _positive_pair(name: str, args: tuple) -> tuple[int, int]:
    if len(args) != 2:
        raise GLTypeError(f"{describe(name, args)}: expected 2 integers, got {len(args)}")
    x = as_int(name, args, "x", args[0])
    y = as_int(name, args, "y", args[1])
    if x <= 0 or y <= 0:
        raise GLValueError(f"{describe(name, args)}: sizes must be positive")
    return x, y


def _check_size(name: str, args: tuple, w: int, h: int) -> tuple[int, int]:
    """``(w, h)``, refused past MAX_WINDOW_SIZE before any plane is allocated."""
    if w > MAX_WINDOW_SIZE or h > MAX_WINDOW_SIZE:
        raise GLValueError(f"{describe(name, args)}: a window of {w}x{h} pixels is larger "
                           f"than vgxsim's limit of {MAX_WINDOW_SIZE}x{MAX_WINDOW_SIZE}")
    return w, h


def _rect(name: str, args: tuple, order: str = "x1x2y1y2") -> tuple[int, int, int, int]:
    """Four ints in the call's order, returned as (x1, x2, y1, y2), each range ordered."""
    if len(args) != 4:
        raise GLTypeError(f"{describe(name, args)}: expected 4 integers, got {len(args)}")
    names = ("x1", "x2", "y1", "y2") if order == "x1x2y1y2" else ("left", "right", "bottom",
                                                                  "top")
    v = [as_int(name, args, n, a) for n, a in zip(names, args, strict=True)]
    if v[0] > v[1] or v[2] > v[3]:
        raise GLValueError(f"{describe(name, args)}: {names[0]} must not exceed {names[1]} "
                           f"and {names[2]} must not exceed {names[3]}")
    return v[0], v[1], v[2], v[3]


def _string(name: str, args: tuple, what: str, v) -> str:
    if not isinstance(v, str):
        raise GLTypeError(f"{describe(name, args)}: {what} must be a str, not "
                          f"{type(v).__name__}")
    return v


def _initial_size() -> tuple[int, int]:
    c = _pending_constraints()
    if session.prefsize is not None:
        return session.prefsize
    if session.prefposition is not None:
        x1, x2, y1, y2 = session.prefposition
        return x2 - x1 + 1, y2 - y1 + 1
    w, h = session.default_size
    if "keepaspect" in c:  # keepaspect(3G): the user may only pick sizes of this ratio
        ax, ay = c["keepaspect"]
        h = max(1, round(w * ay / ax))
    lo = c.get("minsize", (1, 1))
    hi = c.get("maxsize", (1 << 30, 1 << 30))
    return min(max(w, lo[0]), hi[0]), min(max(h, lo[1]), hi[1])


# -- frames -----------------------------------------------------------------------------
def present(ctx: Context, force: bool = False) -> bool:
    """Hand the window's screen to its sink if it changed since the last frame.

    Parameters
    ----------
    ctx : Context
    force : bool
        Hand it over even if unchanged.

    Returns
    -------
    bool
        Whether a frame was produced (never without a sink: with nobody watching,
        the screen is not even computed).
    """
    if ctx.sink is None:
        return False
    img = ctx.display_rgba()
    rec = window_of(ctx)
    shown = rec.shown
    if isinstance(shown, str):  # "fresh": the planes as allocated (all zero)
        shown = np.broadcast_to(layers.fresh_pixel(ctx), img.shape)
    if not force and shown is not None and np.array_equal(img, shown):
        return False
    ctx.sink.write(img)
    ctx.frames += 1
    rec.shown = img
    return True


def present_windows(final: bool = False) -> None:
    """Hand every single-buffered window's changed screen to its sink.

    With ``final`` (the end of a run) a window that never produced a frame produces
    one now, whatever its buffering, so every window leaves a picture.
    """
    for ctx in list(session.windows.values()):
        if final and ctx.frames == 0:
            present(ctx, force=True)
        elif not ctx.config.double:
            present(ctx)


def _baseline(ctx: Context) -> None:
    # Freshly allocated planes are what the screen shows before any drawing; only
    # changes from here make frames of a single-buffered window.
    # Computed lazily in present(): fresh planes are all zero, so the screen shows
    # index/colour 0 everywhere, and a window nobody watches costs nothing here.
    window_of(ctx).shown = "fresh" if not ctx.config.double else None


# -- opening and closing ----------------------------------------------------------------
@gl_function(record=False)
def winopen(name: str) -> int:
    """Open a window and make it current (winopen(3G)).

    Parameters
    ----------
    name : str
        The window title.

    Returns
    -------
    int
        The window's gid (1, 2, ...).

    Notes
    -----
    The window starts in cmode, single-buffered, 24-bit z, no stencil (see the module
    docstring for its size).  The event queue gets ``(REDRAW, gid)`` and, at the next
    read, ``(INPUTCHANGE, gid)`` (see :mod:`vgxsim.gl._events`).
    """
    args = (name,)
    title = _string("winopen", args, "name", name)
    w, h = _initial_size()
    _check_size("winopen", args, w, h)
    origin = session.prefposition[0::2] if session.prefposition is not None else (0, 0)
    c = dict(_pending_constraints())
    _clear_constraints()
    ctx = Context(w, h, rgb=False, double=False, stencil=0, zbits=24, acbits=0)
    load_window_projection(ctx)  # MSINGLE with ortho2(-0.5, w-0.5, -0.5, h-0.5), greset(3G)
    gid = session.next_gid
    session.next_gid += 1
    session.window_records[ctx] = Window(gid, title, title, (int(origin[0]),
                                                            int(origin[1])), c)
    session.windows[gid] = ctx
    session.current = gid
    if session.sink_factory is not None:
        ctx.sink = session.sink_factory(gid)
    _baseline(ctx)
    _events.window_opened(gid)
    if session.reshape_size is not None and session.reshape_size != (w, h):
        _check_size("winopen", args, *session.reshape_size)
        _reshape(ctx, *session.reshape_size)
    return gid



def _window(name: str, args: tuple, gid) -> Context:
    g = as_int(name, args, "gid", gid)
    if g not in session.windows:
        raise GLValueError(f"{describe(name, args)}: no open window has gid {g}")
    return session.windows[g]


@gl_function(record=False)
def winclose(gid: int) -> None:
    """Close window ``gid`` (winclose(3G)).

    Its last screen goes to its sink first (if single-buffered and changed).  If it
    was the current window there is no current window until ``winset``/``winopen``.
    """
    args = (gid,)
    ctx = _window("winclose", args, gid)
    ctx.flush()
    if not ctx.config.double:
        present(ctx)
    g = as_int("winclose", args, "gid", gid)
    del session.windows[g]
    session.window_records.pop(ctx, None)
    if session.current == g:
        session.current = None


@gl_function(record=False)
def winset(gid: int) -> None:
    """Make window ``gid`` the current window (winset(3G))."""
    _window("winset", (gid,), gid)
    session.current = as_int("winset", (gid,), "gid", gid)


@gl_function(record=False)
def winget() -> int:
    """The current window's gid (winget(3G)); -1 when no window is current."""
    return session.current if session.current is not None else -1


@gl_function(record=False)
def wintitle(name: str) -> None:
    """Set the current window's title (wintitle(3G))."""
    args = (name,)
    window_of(current("wintitle", args)).title = _string("wintitle", args, "name", name)


@gl_function(record=False)
def icontitle(name: str) -> None:
    """Set the title of the current window's icon (icontitle(3G)); no icon is shown
    headless."""
    args = (name,)
    window_of(current("icontitle", args)).icontitle = _string("icontitle", args, "name", name)


@gl_function(record=False)
def iconsize(x: int, y: int) -> None:
    """Icon size for the next window (iconsize(3G)); recorded, no effect headless."""
    _pending_constraints()["iconsize"] = _positive_pair("iconsize", (x, y))


@gl_function(record=False)
def prefsize(x: int, y: int) -> None:
    """Size, in pixels, of the next window (or of the current one at
    ``winconstraints``) (prefsize(3G))."""
    args = (x, y)
    session.prefsize = _check_size("prefsize", args, *_positive_pair("prefsize", args))
    session.prefposition = None


@gl_function(record=False)
def prefposition(x1: int, x2: int, y1: int, y2: int) -> None:
    """Screen rectangle of the next window, inclusive bounds (prefposition(3G))."""
    args = (x1, x2, y1, y2)
    r = _rect("prefposition", args)
    _check_size("prefposition", args, r[1] - r[0] + 1, r[3] - r[2] + 1)
    session.prefposition = r
    session.prefsize = None


@gl_function(record=False)
def keepaspect(x: int, y: int) -> None:
    """Width:height ratio of the next window (keepaspect(3G))."""
    _pending_constraints()["keepaspect"] = _positive_pair("keepaspect", (x, y))


@gl_function(record=False)
def minsize(x: int, y: int) -> None:
    """Smallest size of the next window (minsize(3G))."""
    args = (x, y)
    _pending_constraints()["minsize"] = _check_size("minsize", args,
                                                    *_positive_pair("minsize", args))


@gl_function(record=False)
def maxsize(x: int, y: int) -> None:
    """Largest size of the next window (maxsize(3G))."""
    _pending_constraints()["maxsize"] = _positive_pair("maxsize", (x, y))


@gl_function(record=False)
def noborder() -> None:
    """Open the next window without a border (noborder(3G)); no effect headless."""
    _pending_constraints()["noborder"] = True


@gl_function(record=False)
def foreground() -> None:
    """Keep the program in the foreground at winopen (foreground(3G)); headless runs
    never fork, so this has no effect."""


@gl_function(record=False)
def noport() -> None:
    """Ask for no window at the next winopen (noport(3G)); accepted with no effect:
    a headless window costs nothing on a screen."""


def _reshape(ctx: Context, w: int, h: int, gid: int | None = None) -> bool:
    """Give the window a new size: planes are reallocated (their contents are lost, as
    after a reshape on the workstation) and REDRAW is entered (for ``gid``, default
    the current window, which ``ctx`` then is).  The viewport and draw buffers are
    kept: IRIS GL programs call reshapeviewport on REDRAW."""
    if (w, h) == (ctx.width, ctx.height):
        return False
    keep = {k: getattr(ctx.raster, k) for k in ("viewport", "scrmask", "frontbuffer",
                                               "backbuffer", "swritemask")}
    ctx.pending = replace(ctx.pending, width=w, height=h)
    ctx.configure(replace(ctx.config, width=w, height=h))
    ctx.raster.set(**keep)
    _baseline(ctx)
    _events.event_queue().qenter(DEVICE.REDRAW, session.current if gid is None else gid)
    return True


def reshape_window(gid: int, width: int, height: int) -> None:
    """The user reshaped window ``gid`` (0: the current one) to ``width`` x ``height``,
    its lower-left corner kept: new planes and ``(REDRAW, gid)`` (:func:`_reshape`).
    The event queue's ``window_resizer`` (a window session's resize, a script's
    ``resize`` statement).

    Raises
    ------
    GLValueError
        No open window has that gid, or the size is past vgxsim's limit.
    """
    g = gid or session.current
    args = (gid, width, height)
    ctx = session.windows.get(g)
    if ctx is None:
        raise GLValueError(f"resize {width} {height} {gid}: no open window has gid {g}")
    _check_size("resize", args, width, height)
    _reshape(ctx, width, height, g)


@gl_function(record=False)
def winconstraints() -> None:
    """Apply prefsize/prefposition (and the other constraints) to the current window
    (winconstraints(3G)), then reset them.  A new size reshapes the window."""
    ctx = current("winconstraints")
    if session.prefsize is not None or session.prefposition is not None:
        if session.prefposition is not None:
            x1, x2, y1, y2 = session.prefposition
            window_of(ctx).origin = (x1, y1)
        w, h = _initial_size()
        _check_size("winconstraints", (), w, h)
        _reshape(ctx, w, h)
    window_of(ctx).constraints = dict(_pending_constraints())
    _clear_constraints()


@gl_function(record=False)
def winposition(x1: int, x2: int, y1: int, y2: int) -> None:
    """Move and reshape the current window to a screen rectangle (winposition(3G))."""
    args = (x1, x2, y1, y2)
    r = _rect("winposition", args)
    _check_size("winposition", args, r[1] - r[0] + 1, r[3] - r[2] + 1)
    ctx = current("winposition", args)
    window_of(ctx).origin = (r[0], r[2])
    _reshape(ctx, r[1] - r[0] + 1, r[3] - r[2] + 1)


@gl_function(record=False)
def winmove(orgx: int, orgy: int) -> None:
    """Move the current window's lower-left corner to a screen position (winmove(3G));
    only ``getorigin`` sees it."""
    args = (orgx, orgy)
    x = as_int("winmove", args, "orgx", orgx)
    y = as_int("winmove", args, "orgy", orgy)
    window_of(current("winmove", args)).origin = (x, y)


# -- configuration requests -------------------------------------------------------------
@gl_function(record=False)
def RGBmode() -> None:  # noqa: N802  (IRIS GL name)
    """Ask for RGB mode; takes effect at gconfig (RGBmode(3G))."""
    replace_config(current("RGBmode"), rgb=True)


@gl_function(record=False)
def cmode() -> None:
    """Ask for colour-map mode (the default); takes effect at gconfig (cmode(3G))."""
    replace_config(current("cmode"), rgb=False)


@gl_function(record=False)
def doublebuffer() -> None:
    """Ask for front and back buffers; takes effect at gconfig (doublebuffer(3G))."""
    replace_config(current("doublebuffer"), double=True)


@gl_function(record=False)
def singlebuffer() -> None:
    """Ask for one colour buffer (the default); takes effect at gconfig."""
    replace_config(current("singlebuffer"), double=False)


@gl_function(record=False)
def stensize(planes: int) -> None:
    """Ask for ``planes`` stencil bitplanes, 0..8; takes effect at gconfig (stensize(3G))."""
    args = (planes,)
    n = as_int("stensize", args, "planes", planes)
    if not 0 <= n <= MAX_STENCIL_PLANES:
        raise GLValueError(f"{describe('stensize', args)}: planes must be "
                           f"0..{MAX_STENCIL_PLANES} (getgdesc(GD_BITS_STENCIL) is "
                           f"{MAX_STENCIL_PLANES})")
    replace_config(current("stensize", args), stencil=n)


@gl_function(record=False)
def acsize(planes: int) -> None:
    """Ask for an accumulation buffer of ``planes`` bits per component; takes effect at
    gconfig (acsize(3G)).

    The VGX offers none (0) or 16 signed bits per component (getgdesc(GD_BITS_ACBUF)),
    so only 0 and 16 are accepted.
    """
    args = (planes,)
    n = as_int("acsize", args, "planes", planes)
    if n not in ACBITS:
        raise GLValueError(f"{describe('acsize', args)}: planes must be 0 or 16 "
                           "(getgdesc(GD_BITS_ACBUF) is 16)")
    replace_config(current("acsize", args), acbits=n)


@gl_function(record=False)
def zbsize(planes: int) -> None:
    """Ask for ``planes`` z bits, 0 or 24; takes effect at gconfig (zbsize(3G))."""
    args = (planes,)
    n = as_int("zbsize", args, "planes", planes)
    if n not in ZBITS:
        raise GLValueError(f"{describe('zbsize', args)}: planes must be 0 or 24 "
                           "(getgdesc(GD_BITS_NORM_ZBUFFER) is 24)")
    replace_config(current("zbsize", args), zbits=n)


@gl_function(record=False)
def gconfig() -> None:
    """Allocate the planes the pending requests ask for (gconfig(3G)).

    The new planes start cleared.  zwritemask and the colour write mask are reset to
    all ones (zwritemask(3G), RGBwritemask(3G): "initialized ... when gconfig is
    called"), swritemask to all stencil planes, and the draw buffer to the back buffer
    of a double-buffered window.
    """
    ctx = current("gconfig")
    ctx.configure(ctx.pending)
    ctx.raster.set(zwritemask=0xFFFFFFFF, wmpack=0xFFFFFFFF)
    _baseline(ctx)


# -- frames -----------------------------------------------------------------------------
@gl_function(record=False)
def swapbuffers() -> None:
    """Show the back buffer (swapbuffers(3G)) and end a frame.

    Double-buffered: render what is queued, exchange the buffers and hand the new
    front buffer to the frame sink.  Single-buffered: IRIS GL ignores swapbuffers;
    here nothing is exchanged, but the screen goes to the sink if it changed.  In both
    modes the event queue counts a frame (timers tick, scripted input waiting for
    frames becomes due).
    """
    ctx = current("swapbuffers")
    if ctx.config.double:
        ctx.swap()
    else:
        present(ctx)
    _events.frame_done()


def _flush_frame(name: str) -> None:
    if session.current is None:
        return  # nothing to flush before winopen
    ctx = current(name)
    ctx.flush()
    if not ctx.config.double:
        present(ctx)
        _events.frame_done()


@gl_function(record=False)
def gflush() -> None:
    """Render everything queued (gflush(3G)).

    Single-buffered windows have no swapbuffers, so gflush ends their frame: the screen
    goes to the sink if it changed and the event queue counts a frame.
    """
    _flush_frame("gflush")


@gl_function(record=False)
def finish() -> None:
    """Render everything queued and wait for it (finish(3G)); as :func:`gflush`."""
    _flush_frame("finish")


# -- viewport and screen mask -----------------------------------------------------------
@gl_function(record=True)
def viewport(left: int, right: int, bottom: int, top: int) -> None:
    """Map normalized coordinates onto the window rectangle (inclusive bounds)
    (viewport(3G)); also sets the screen mask to the same rectangle (scrmask(3G):
    "When viewport is called, the screen mask is set to match")."""
    args = (left, right, bottom, top)
    r = _rect("viewport", args, "lrbt")
    vp = (r[0], r[1], r[2], r[3])
    current("viewport", args).raster.set(viewport=vp, scrmask=vp)


@gl_function(record=True)
def reshapeviewport() -> None:
    """Set the viewport (and screen mask) to the whole current window
    (reshapeviewport(3G))."""
    ctx = current("reshapeviewport")
    vp = (0, ctx.width - 1, 0, ctx.height - 1)
    ctx.raster.set(viewport=vp, scrmask=vp)


@gl_function(record=False)
def getviewport() -> tuple[int, int, int, int]:
    """The viewport as ``(left, right, bottom, top)`` (getviewport(3G))."""
    return tuple(int(v) for v in current("getviewport").raster.viewport)


@gl_function(record=False)
def getsize() -> tuple[int, int]:
    """The current window's size ``(width, height)`` in pixels (getsize(3G))."""
    ctx = current("getsize")
    return int(ctx.width), int(ctx.height)


@gl_function(record=False)
def getorigin() -> tuple[int, int]:
    """Screen position of the window's lower-left corner (getorigin(3G)); (0, 0)
    unless prefposition/winposition/winmove placed it."""
    origin = window_of(current("getorigin")).origin
    return int(origin[0]), int(origin[1])


@gl_function(record=True)
def scrmask(left: int, right: int, bottom: int, top: int) -> None:
    """Restrict drawing to a window rectangle, inclusive (scrmask(3G)).

    As the manual says, left > right or bottom > top write-protects every pixel.
    """
    args = (left, right, bottom, top)
    names = ("left", "right", "bottom", "top")
    v = tuple(as_int("scrmask", args, n, a) for n, a in zip(names, args, strict=True))
    current("scrmask", args).raster.set(scrmask=v)


@gl_function(record=False)
def getscrmask() -> tuple[int, int, int, int]:
    """The screen mask as ``(left, right, bottom, top)`` (getscrmask(3G))."""
    return tuple(int(v) for v in current("getscrmask").raster.scrmask)


# -- buffers ----------------------------------------------------------------------------
@gl_function(record=True)
def subpixel(b: int) -> None:
    """Keep sub-pixel vertex positions (TRUE) or snap to pixel centres (FALSE, the
    default) (subpixel(3G))."""
    args = (b,)
    v = as_int("subpixel", args, "b", b)
    current("subpixel", args).raster.set(subpixel=bool(v))


def _in_zdraw(ctx) -> bool:
    """zdraw(3G) mode: a change of buffers is checked against the z-buffer drawing
    and the queue drawn first (set_draw_buffer), the validated body's business."""
    return ctx.zdraw_batch is not None


@register_call("frontbuffer", boolean=True, record=True, general_when=_in_zdraw)
def frontbuffer(b: int) -> None:
    """frontbuffer(b): draw into the front buffer too (frontbuffer(3G)); only
    double-buffered windows have a choice."""
    args = (b,)
    v = as_int("frontbuffer", args, "b", b)
    set_draw_buffer("frontbuffer", args, current("frontbuffer", args), frontbuffer=bool(v))


@register_call("backbuffer", boolean=True, record=True, general_when=_in_zdraw)
def backbuffer(b: int) -> None:
    """backbuffer(b): draw into the back buffer (backbuffer(3G)); the default when
    double-buffered."""
    args = (b,)
    v = as_int("backbuffer", args, "b", b)
    set_draw_buffer("backbuffer", args, current("backbuffer", args), backbuffer=bool(v))


_SOURCES = (GL.SRC_AUTO, GL.SRC_FRONT, GL.SRC_BACK, GL.SRC_ZBUFFER, GL.SRC_PUP,
            GL.SRC_OVER, GL.SRC_UNDER)


@gl_function(record=True)
def readsource(src: int) -> None:
    """Choose what lrectread, readRGB, rectcopy and acbuf read (readsource(3G)).

    SRC_AUTO (the default) reads the back buffer of a double-buffered window and the
    front buffer otherwise; SRC_FRONT, SRC_BACK; SRC_ZBUFFER makes lrectread return
    z values; SRC_PUP, SRC_OVER and SRC_UNDER read the colour indices of the pop-up,
    overlay and underlay planes (drawmode(3G); 0 where they have none).  The frame
    grabber is not emulated (GD_FRAMEGRABBER 0) and raises GLValueError.
    """
    args = (src,)
    s = as_int("readsource", args, "src", src)
    if s == GL.SRC_FRAMEGRABBER:
        raise GLValueError(f"{describe('readsource', args)}: there is no frame grabber "
                           "(getgdesc(GD_FRAMEGRABBER) is 0)")
    s = check_token("readsource", args, "src", s, _SOURCES, "SRC_")
    current("readsource", args).readsource = s
