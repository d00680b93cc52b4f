"""IRIS GL inquiries: getgdesc, gversion, getgconfig and the mode getters.

``getgdesc`` describes the emulated machine -- an IRIS Power Series VGX with a
1280x1024 screen -- and works before ``winopen`` (getgdesc(3G): "inquiries about the
graphics hardware ... can be made at any time"); the 1991 shadow code calls
``stensize(getgdesc(GD_BITS_STENCIL))`` right after ``winopen``.  The other getters
describe the current window.

Sources for the answers are named per entry: [pstech] is SGI's Power Series technical
report s.3 (VGX frame buffer), [ref] is the project note irisgl_reference.md, [model]
is docs/numeric_model.md (what this emulator does).  Entries marked *assumed* have no
source; each says why its value was chosen.

Every answer is true of *vgxsim*, not only of the 1990 hardware: a program that asks
before it draws (``if getgdesc(GD_TEXTURE): texdef2d(...)``) must not be sent down a
path that then fails.  Features the VGX had but vgxsim does not emulate answer 0
(stereo, smoothing, textports, cursors).  Features whose calls live in other parts of
the gl layer (textures, clip planes, fog, zdraw, overlay planes, blink, NURBS) answer
through :data:`FEATURE_GDESC`: the VGX value once the call exists in :mod:`vgxsim.gl`,
0 before.  An inquiry that is no GD_* token answers -1 (getgdesc(3G): "returns -1 if
the inquiry is invalid"), so programs that print every token they know -- including
ones newer than vgxsim -- keep running.
"""

from __future__ import annotations

from vgxsim import GL
from vgxsim.state.layers import MAX_BITS
from vgxsim.state.planes import MAX_STENCIL_PLANES, ZMAX, ZMIN

from ._core import as_int, check_token, current, gl_function, window_of

__all__ = [
    "getgdesc", "getgconfig", "gversion", "getplanes", "getdisplaymode", "getbuffer",
    "getzbuffer", "getdrawmode", "GDESC", "FEATURE_GDESC",
]

#: VGX answer of every getgdesc inquiry, by gl.h name.
GDESC: dict[str, int] = {
    # The screen, not the largest window: headless windows may be up to
    # MAX_WINDOW_SIZE (16384) a side (gl/_window.py, docs/headless_runs.md).
    "GD_XPMAX": 1280,  # screen width in pixels, 1280x1024 standard [pstech]
    "GD_YPMAX": 1024,  # screen height in pixels [pstech]
    "GD_XMMAX": 340,  # assumed: screen width in mm of a 19-inch 1280x1024 monitor
    "GD_YMMAX": 272,  # assumed: screen height in mm (5:4 of GD_XMMAX)
    "GD_ZMIN": ZMIN,  # -0x800000, signed 24-bit z [ref 1.2] [model]
    "GD_ZMAX": ZMAX,  # 0x7FFFFF [ref 1.2] [model]
    "GD_BITS_NORM_SNG_RED": 8,  # 24-bit colour [pstech]
    "GD_BITS_NORM_SNG_GREEN": 8,  # [pstech]
    "GD_BITS_NORM_SNG_BLUE": 8,  # [pstech]
    "GD_BITS_NORM_DBL_RED": 8,  # 24-bit colour double-buffered [pstech]
    "GD_BITS_NORM_DBL_GREEN": 8,  # [pstech]
    "GD_BITS_NORM_DBL_BLUE": 8,  # [pstech]
    "GD_BITS_NORM_SNG_CMODE": 12,  # 4096-entry colour map (vgxsim.state.colormap)
    "GD_BITS_NORM_DBL_CMODE": 12,  # 24 bits per buffer hold a 12-bit index [pstech]
    "GD_BITS_NORM_SNG_MMAP": 8,  # assumed: multimap() splits the map into 256-entry maps
    "GD_BITS_NORM_DBL_MMAP": 8,  # assumed: as single-buffered
    "GD_BITS_NORM_ZBUFFER": 24,  # 24-bit z-buffer [pstech]
    "GD_BITS_OVER_SNG_CMODE": 0,  # VGX had 4 [pstech]; see FEATURE_GDESC (drawmode)
    "GD_BITS_UNDR_SNG_CMODE": 0,  # own 4 planes here (vgxsim.state.layers); FEATURE_GDESC
    "GD_BITS_PUP_SNG_CMODE": 0,  # 2 (PUP_CLEAR..PUP_WHITE); see FEATURE_GDESC (drawmode)
    "GD_BITS_NORM_SNG_ALPHA": 8,  # 8-bit alpha double-buffered [pstech]
    "GD_BITS_NORM_DBL_ALPHA": 8,  # [pstech]
    "GD_BITS_CURSOR": 0,  # headless: no cursor is drawn (defcursor is not emulated)
    "GD_OVERUNDER_SHARED": 0,  # overlay and underlay have separate planes (state/layers.py)
    "GD_BLEND": 1,  # pixel blending [pstech]
    "GD_CIFRACT": 0,  # assumed: colour indices are not interpolated fractionally here
    "GD_CROSSHAIR_CINDEX": 0,  # no cursor (see GD_BITS_CURSOR)
    "GD_DITHER": 0,  # assumed: the emulator never dithers (8 bits per component)
    "GD_LINESMOOTH_CMODE": 0,  # linesmooth is accepted, not modelled (gl/_raster.py)
    "GD_LINESMOOTH_RGB": 0,  # as GD_LINESMOOTH_CMODE
    "GD_LOGICOP": 1,  # logicop() supported [model s.6]
    "GD_NSCRNS": 1,  # one screen
    "GD_NURBS_ORDER": 0,  # see FEATURE_GDESC (nurbssurface)
    "GD_NBLINKS": 0,  # see FEATURE_GDESC (blink)
    "GD_NVERTEX_POLY": 256,  # assumed: Alice 4's POLY_MAX; the VGX figure is unknown [ref 1.8]
    "GD_PATSIZE_64": 0,  # assumed: 16x16 and 32x32 patterns only
    "GD_PNTSMOOTH_CMODE": 0,  # pntsmooth is accepted, not modelled
    "GD_PNTSMOOTH_RGB": 0,  # as GD_PNTSMOOTH_CMODE
    "GD_PUP_TO_OVERUNDER": 0,  # assumed: pop-up planes are separate
    "GD_READSOURCE": 1,  # readsource(SRC_FRONT/SRC_BACK) supported [ref 1.11]
    "GD_READSOURCE_ZBUFFER": 1,  # readsource(SRC_ZBUFFER) supported (lrectread of z)
    "GD_STEREO": 0,  # VGX had stereo [pstech]; stereo windows are not emulated
    "GD_SUBPIXEL_LINE": 1,  # subpixel positioning [pstech] [ref 2.2]
    "GD_SUBPIXEL_PNT": 1,  # [pstech]
    "GD_SUBPIXEL_POLY": 1,  # [pstech]
    "GD_TRIMCURVE_ORDER": 0,  # see FEATURE_GDESC (bgntrim)
    "GD_WSYS": 1,  # GD_WSYS_4S: the 4Sight window system of IRIX 1990
    "GD_ZDRAW_GEOM": 0,  # see FEATURE_GDESC (zdraw)
    "GD_ZDRAW_PIXELS": 0,  # see FEATURE_GDESC (zdraw)
    "GD_SCRNTYPE": 0,  # GD_SCRNTYPE_WM: a window-manager screen
    "GD_TEXTPORT": 0,  # headless: no textports (textport calls are not emulated)
    "GD_NMMAPS": 16,  # assumed: multimap() gives 16 maps (multimap(3G) "16 small maps")
    "GD_FRAMEGRABBER": 0,  # no Live Video Digitizer
    "GD_TIMERHZ": 60,  # TIMER0..3 tick once per 60 Hz frame (events queue model)
    "GD_DBBOX": 0,  # no dial-and-button box
    "GD_AFUNCTION": 1,  # afunction() alpha test [model s.6]
    "GD_ALPHA_OVERUNDER": 0,  # assumed: overlay planes have no alpha
    "GD_BITS_ACBUF": 16,  # 16 bits per component [ref 1.5] [model s.9]
    "GD_BITS_ACBUF_HW": 0,  # assumed: whether the VGX acbuf was hardware is unconfirmed
    "GD_BITS_STENCIL": MAX_STENCIL_PLANES,  # 8 stencil bitplanes [pstech]
    "GD_CLIPPLANES": 0,  # see FEATURE_GDESC (clipplane)
    "GD_FOGVERTEX": 0,  # see FEATURE_GDESC (fogvertex)
    "GD_LIGHTING_TWOSIDE": 1,  # two-sided lighting [pstech]
    "GD_POLYMODE": 0,  # polymode is recorded for getpolymode only; PYM_FILL is drawn
    "GD_POLYSMOOTH": 0,  # polysmooth is accepted, not modelled
    "GD_SCRBOX": 0,  # assumed: no screen bounding box hardware
    "GD_TEXTURE": 0,  # see FEATURE_GDESC (texdef2d)
    "GD_FOGPIXEL": 0,  # assumed: per-pixel fog is RealityEngine [ref 3]
    "GD_TEXTURE_PERSP": 0,  # see FEATURE_GDESC (texdef2d)
    "GD_MUXPIPES": 0,  # assumed: one graphics pipe
    # Post-IRIX-5 inquiries (GL.POST_IRIX5): RealityEngine-era features are absent.
    "GD_MULTISAMPLE": 0,  # RealityEngine [ref 3]
    "GD_TEXTURE_3D": 0,  # RealityEngine
    "GD_TEXTURE_LUT": 0,  # RealityEngine
    "GD_TEXTURE_SHARP": 0,  # RealityEngine
    "GD_TEXTURE_DETAIL": 0,  # RealityEngine
    "GD_STEREO_IN_WINDOW": 0,  # assumed: stereo is full-screen on VGX
    "GD_BLENDCOLOR": 0,  # BF_CA..BF_MCC are post-VGX [ref 1.3]
    "GD_LIGHTING_SPOTLIGHT": 1,  # spotlights [pstech]
    "GD_LIGHTING_ATT2": 1,  # assumed: ATTENUATION2 is emulated (vgxsim.lighting)
    "GD_AFUNCTION_MODES": 0xFF,  # assumed: bit n set for each supported AF_n (all eight)
}

#: Answers that depend on a feature: GD name -> (the gl call that provides the feature,
#: the answer once it exists).  The values are the VGX's ([pstech] s.3: 4 overlay planes,
#: texture, fog; clipplane(3G): six planes) or, for NURBS orders, the highest order
#: vgxsim's own tessellator accepts (vgxsim.gl._nurbs.MAX_ORDER).
FEATURE_GDESC: dict[str, tuple[str, int]] = {
    "GD_TEXTURE": ("texdef2d", 1),
    "GD_TEXTURE_PERSP": ("texdef2d", 1),
    "GD_CLIPPLANES": ("clipplane", 6),
    "GD_FOGVERTEX": ("fogvertex", 1),
    "GD_ZDRAW_GEOM": ("zdraw", 1),
    "GD_ZDRAW_PIXELS": ("zdraw", 1),
    "GD_BITS_OVER_SNG_CMODE": ("drawmode", MAX_BITS["overlay"]),
    "GD_BITS_UNDR_SNG_CMODE": ("drawmode", MAX_BITS["underlay"]),
    "GD_BITS_PUP_SNG_CMODE": ("drawmode", MAX_BITS["popup"]),
    "GD_NBLINKS": ("blink", 20),
    "GD_NURBS_ORDER": ("nurbssurface", 8),
    "GD_TRIMCURVE_ORDER": ("bgntrim", 8),
}

#: GD_* names that are answers, not inquiries (GD_WSYS/GD_SCRNTYPE values, GD_NOLIMIT).
ANSWER_NAMES = frozenset(
    {"GD_NOLIMIT", "GD_WSYS_NONE", "GD_WSYS_4S", "GD_SCRNTYPE_WM", "GD_SCRNTYPE_NOWM"})

_BY_VALUE: dict[int, str] = {int(getattr(GL, n)): n for n in GDESC}

#: gversion() string: "GL4D" + the graphics type and a release number (gversion(3G)
#: gives 12-character strings such as "GL4DVGX-4.0"; the release is assumed).
VERSION = "GL4DVGX-4.0"


@gl_function(record=False)
def getgdesc(inquiry: int) -> int:
    """Answer a question about the graphics hardware (getgdesc(3G)).

    Works before ``winopen``.  The answers describe a VGX (see :data:`GDESC`).

    Parameters
    ----------
    inquiry : int
        A ``GD_*`` token.

    Returns
    -------
    int
        The answer; -1 for an int that is no GD_* inquiry (getgdesc(3G)).

    Raises
    ------
    GLTypeError
        If ``inquiry`` is not an int (the binding's ``PyInt_Check``).
    """
    args = (inquiry,)
    name = _BY_VALUE.get(as_int("getgdesc", args, "inquiry", inquiry))
    if name is None:
        return -1
    feature = FEATURE_GDESC.get(name)
    if feature is not None:
        return feature[1] if _implemented(feature[0]) else 0
    return GDESC[name]


def _implemented(call: str) -> bool:
    """Whether ``vgxsim.gl`` exports the IRIS GL call ``call``."""
    import vgxsim.gl  # the package, complete by the time a program can call getgdesc

    return callable(getattr(vgxsim.gl, call, None))


@gl_function(record=False)
def gversion() -> str:
    """The graphics library version string (gversion(3G); a ``str`` as in CPython's
    binding), e.g. ``'GL4DVGX-4.0'``."""
    return VERSION


# getgconfig(3G): what gconfig granted the current window.
_GC = {
    "GC_BITS_CMODE": lambda c: 0 if c.rgb else GDESC["GD_BITS_NORM_SNG_CMODE"],
    "GC_BITS_RED": lambda c: 8 if c.rgb else 0,
    "GC_BITS_GREEN": lambda c: 8 if c.rgb else 0,
    "GC_BITS_BLUE": lambda c: 8 if c.rgb else 0,
    "GC_BITS_ALPHA": lambda c: 8 if c.rgb else 0,
    "GC_BITS_ZBUFFER": lambda c: c.zbits,
    "GC_ZMIN": lambda c: ZMIN if c.zbits else 0,
    "GC_ZMAX": lambda c: ZMAX if c.zbits else 0,
    "GC_BITS_STENCIL": lambda c: c.stencil,
    "GC_BITS_ACBUF": lambda c: c.acbits,
    "GC_MS_SAMPLES": lambda c: 0,  # no multisampling on the VGX
    "GC_BITS_MS_ZBUFFER": lambda c: 0,
    "GC_MS_ZMIN": lambda c: 0,
    "GC_MS_ZMAX": lambda c: 0,
    "GC_BITS_MS_STENCIL": lambda c: 0,
    "GC_STEREO": lambda c: 0,  # stereo windows are not emulated
    "GC_DOUBLE": lambda c: int(c.double),
}
_GC_BY_VALUE = {int(getattr(GL, n)): n for n in _GC}


@gl_function(record=False)
def getgconfig(buffer: int) -> int:
    """What the last ``gconfig`` granted the current window (getgconfig(3G)).

    Parameters
    ----------
    buffer : int
        A ``GC_*`` token, e.g. ``GC_BITS_STENCIL``.

    Returns
    -------
    int
        The granted size; pending (not yet configured) requests do not count.
    """
    args = (buffer,)
    tok = check_token("getgconfig", args, "buffer", buffer, _GC_BY_VALUE, "GC_")
    ctx = current("getgconfig", args)
    return int(_GC[_GC_BY_VALUE[tok]](ctx.config))


def _drawmode(ctx) -> int:
    return int(window_of(ctx).drawmode)


@gl_function(record=False)
def getplanes() -> int:
    """Bitplanes available for drawing in the current mode (getplanes(3G)).

    RGB mode: 24 (8 per component); colour-map mode: 12, or 8 in multimap mode; in
    OVERDRAW, UNDERDRAW and PUPDRAW the planes that framebuffer was granted
    (overlay(3G), underlay(3G); 2 pop-up planes), in CURSORDRAW 0.
    """
    ctx = current("getplanes")
    if _drawmode(ctx) != GL.NORMALDRAW:
        return ctx.plane_sets[ctx.planes_selected].bits
    if ctx.config.rgb:
        return 24
    if ctx.multimap:
        return GDESC["GD_BITS_NORM_SNG_MMAP"]
    return GDESC["GD_BITS_NORM_SNG_CMODE"]


@gl_function(record=False)
def getdisplaymode() -> int:
    """The configured display mode (getdisplaymode(3G)): DMRGB, DMRGBDOUBLE, DMSINGLE
    (colour map, single-buffered) or DMDOUBLE."""
    c = current("getdisplaymode").config
    if c.rgb:
        return GL.DMRGBDOUBLE if c.double else GL.DMRGB
    return GL.DMDOUBLE if c.double else GL.DMSINGLE


@gl_function(record=False)
def getbuffer() -> int:
    """Which buffers drawing goes to (getbuffer(3G)): BCKBUFFER | FRNTBUFFER bits,
    plus DRAWZBUFFER while ``zdraw(TRUE)`` is in effect.

    Single-buffered windows answer FRNTBUFFER (their one buffer).
    """
    ctx = current("getbuffer")
    rs = ctx.raster
    if ctx.config.double:
        bits = (GL.FRNTBUFFER if rs.frontbuffer else 0) | (GL.BCKBUFFER if rs.backbuffer else 0)
    else:
        bits = int(GL.FRNTBUFFER)
    if ctx.zdraw_batch is not None:
        bits |= GL.DRAWZBUFFER
    return int(bits)


@gl_function(record=False)
def getzbuffer() -> int:
    """1 if z-buffering is enabled (``zbuffer(TRUE)``), else 0 (getzbuffer(3G))."""
    return int(bool(current("getzbuffer").raster.zbuffer))


@gl_function(record=False)
def getdrawmode() -> int:
    """The current draw mode (getdrawmode(3G)); NORMALDRAW unless ``drawmode`` set
    another."""
    return _drawmode(current("getdrawmode"))

