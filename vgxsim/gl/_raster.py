"""IRIS GL raster-state calls: z-buffer, stencil, masks, blending, faces, lines, clears.

Each call validates its arguments (tokens against their gl.h family, ranges from the
manual pages) and stores into ``ctx.raster`` (:class:`RasterRegisters`); what the
registers mean per fragment is docs/numeric_model.md section 6.  Masks typed
``unsigned long`` in C are taken modulo 2**32 as the C conversion does, so the 1991
article's ``zwritemask(0xfffffffff)`` (nine f's) means all ones.

Accepted but not modelled (stored for the queries only): line/point/polygon
smoothing (linesmooth, pntsmooth, polysmooth), dither, polymode other than PYM_FILL
(polygons are still filled), glcompat modes other than GLC_ZRANGEMAP.
"""

from __future__ import annotations

import math

from vgxsim import GL
from vgxsim.pipeline.context import CLEAR_COLOUR, CLEAR_STENCIL, CLEAR_Z
from vgxsim.state.planes import ZMAX, ZMIN
from vgxsim.state.registers import StencilRegister
from vgxsim.tokens import Token

from . import _core
from ._color import packed_colour
from ._core import (
    _NO,
    INT_MAX,
    INT_MIN,
    GLUsageError,
    GLValueError,
    as_float,
    as_int,
    check_token,
    current,
    describe,
    given,
    gl_function,
    record_or_refuse,
    session,
)

__all__ = [
    "zbuffer", "zfunction", "zwritemask", "zclear", "czclear", "lsetdepth", "setdepth",
    "stencil", "sclear", "swritemask", "wmpack", "RGBwritemask", "blendfunction",
    "afunction", "logicop", "backface", "frontface", "getbackface", "shademodel", "getsm",
    "linewidth", "linewidthf", "getlwidth", "deflinestyle", "setlinestyle", "getlstyle",
    "lsrepeat", "getlsrepeat", "resetls", "getresetls", "lsbackup", "getlsbackup",
    "linesmooth", "pntsmooth",
    "polysmooth", "pntsize",
    "pntsizef", "polymode", "getpolymode", "dither", "glcompat", "clear",
]

_U32 = 0xFFFFFFFF
_CMP = range(8)  # ZF_*, SF_*, AF_*: NEVER 0 .. ALWAYS 7
_STOPS = range(6)  # ST_KEEP 0 .. ST_INVERT 5
_SHORT_MAX = 0x7FFF


def _u32(name: str, args: tuple, what: str, v) -> int:
    """An ``unsigned long`` argument: any int, reduced modulo 2**32 like C."""
    return as_int(name, args, what, v, wrap=True)


def _in_range(name: str, args: tuple, what: str, v, lo: int, hi: int, why: str = "") -> int:
    iv = as_int(name, args, what, v)
    if not lo <= iv <= hi:
        extra = f" ({why})" if why else ""
        raise GLValueError(f"{describe(name, args)}: {what} {iv} is outside {lo}..{hi}{extra}")
    return iv


def register_call(attr: str, lo: int = INT_MIN, hi: int = INT_MAX, *, boolean: bool = False,
                  wrap: bool = False, record: bool = False, general_when=None):
    """Give a one-int register call's validated body a valid path (FAST_CALLS), as
    zwritemask's: an int (or GL token) in ``lo..hi`` is stored in ``RasterRegisters.<attr>`` --
    ``v != 0`` with ``boolean``; with ``wrap`` any int, reduced modulo 2**32 -- and the
    snapshot marked dirty, which is what the body's ``regs.set(attr=...)`` does for
    such a value; anything else (recording, keywords, a wrong count or type, a value
    out of range, or a window for which ``general_when(ctx)`` is true) runs the body,
    which validates and raises as before.  ``record``: display objects record the
    call (gl_function's ``record``)."""

    def deco(body):
        name = body.__name__

        def general(*args, **kwargs) -> None:
            if kwargs or session.recording is not None or len(args) != 1:
                return record_or_refuse(call, args, kwargs)
            body(*args)

        def call(v=_NO, /, *more, **kw) -> None:
            ctx = session.imm
            t = type(v)
            if ctx is None or kw or more or (t is not int and t is not Token):
                return general(*given((v,), more), **kw)
            if t is Token:
                v = int(v)  # (a GL token: stored as the plain int as_int gives)
            if not (wrap or lo <= v <= hi) or (general_when is not None
                                               and general_when(ctx)):
                return general(v, *more)
            regs = ctx.raster
            setattr(regs, attr, v & _U32 if wrap else (v != 0) if boolean else v)
            regs._snapshot = None

        call.__name__ = call.__qualname__ = name
        call.__doc__ = body.__doc__
        return gl_function(record=record, binds=(1, 1, ("int",)))(call)

    return deco


# -- z-buffer ----------------------------------------------------------------------
@register_call("zbuffer", boolean=True)
def zbuffer(b: int) -> None:
    """Enable (any non-zero) or disable the z test and z writes (zbuffer(3G))."""
    ctx = current("zbuffer", (b,))
    ctx.raster.set(zbuffer=as_int("zbuffer", (b,), "b", b) != 0)


@register_call("zfunc", 0, 7)
def zfunction(func: int) -> None:
    """Comparison of incoming against stored z, ZF_NEVER..ZF_ALWAYS; ZF_LEQUAL is the
    default (zfunction(3G))."""
    args = (func,)
    ctx = current("zfunction", args)
    ctx.raster.set(zfunc=check_token("zfunction", args, "func", func, _CMP, "ZF_"))


def _general_zwritemask(*args, **kwargs) -> None:
    if kwargs or session.recording is not None or len(args) != 1:
        return record_or_refuse(zwritemask, args, kwargs)
    ctx = current("zwritemask", args)
    regs = ctx.raster
    regs.zwritemask = _u32("zwritemask", args, "mask", args[0])
    regs._snapshot = None


@gl_function(binds=(1, 1, ("int",)))
def zwritemask(mask=_NO, /, *more, **kw) -> None:
    """zwritemask(mask): which z bits are written (zwritemask(3G)); 0 keeps z while
    still testing it."""
    ctx = session.imm
    if ctx is None or kw or more or type(mask) is not int:
        return _general_zwritemask(*given((mask,), more), **kw)
    regs = ctx.raster
    regs.zwritemask = mask & _U32
    regs._snapshot = None


@gl_function()
def zclear(*ignored) -> None:
    """Set z to GD_ZMAX inside the raster rectangle, through zwritemask (zclear(3G)).

    zclear takes no argument, but the 1991 shadow article calls
    ``zclear(getgdesc(GD_ZMAX))`` (pre-ANSI C passed and ignored it), so one int is
    accepted and ignored: the value written is always GD_ZMAX.
    """
    ctx = current("zclear", ignored)
    if len(ignored) > 1:
        raise GLUsageError(f"{describe('zclear', ignored)}: zclear takes no arguments")
    for v in ignored:
        as_int("zclear", ignored, "the ignored argument", v)
    ctx.clear_planes(CLEAR_Z, z=ZMAX)


@gl_function()
def czclear(cval: int, zval: int) -> None:
    """Clear colour to ``cval`` (packed 0xAABBGGRR, or an index in cmode) and z to
    ``zval`` at once, through wmpack and zwritemask, in the raster rectangle
    (czclear(3G)).  ``zval`` must lie in GD_ZMIN..GD_ZMAX."""
    args = (cval, zval)
    ctx = current("czclear", args)
    c = _u32("czclear", args, "cval", cval)
    z = _in_range("czclear", args, "zval", zval, ZMIN, ZMAX, "getgdesc(GD_ZMIN..GD_ZMAX)")
    ctx.clear_planes(CLEAR_COLOUR | CLEAR_Z, colour=c, z=z)


def _depth_limits(ctx) -> tuple[int, int, str]:
    # lsetdepth(3G): with glcompat(GLC_ZRANGEMAP, 1) "the minimum is 0x0 and the
    # maximum is 0x7FFFFF", else the hardware range GD_ZMIN..GD_ZMAX.
    if ctx.compat.get(int(GL.GLC_ZRANGEMAP), 0):
        return 0, 0x7FFFFF, "glcompat(GLC_ZRANGEMAP, 1) range"
    return ZMIN, ZMAX, "getgdesc(GD_ZMIN..GD_ZMAX)"


def _general_lsetdepth(*args, **kwargs) -> None:
    if kwargs or session.recording is not None or len(args) != 2:
        return record_or_refuse(lsetdepth, args, kwargs)
    _lsetdepth(*args)


_ZRANGEMAP = int(GL.GLC_ZRANGEMAP)


@gl_function(binds=(2, 2, ("int", "int")))
def lsetdepth(near=_NO, far=_NO, /, *more, **kw) -> None:
    """lsetdepth(near, far): map the near and far clipping planes to these z values
    (lsetdepth(3G)).

    ``near > far`` is allowed (reversed depth, used with ZF_GREATER).  Under
    GLC_ZRANGEMAP 1 the range 0..0x7FFFFF is accepted and used as it is: those are
    valid hardware z values, so no remapping is needed for depth comparisons.
    """
    # Valid path (FAST_CALLS): two plain ints inside _depth_limits' range (without
    # GLC_ZRANGEMAP: GD_ZMIN..GD_ZMAX), stored as the general path stores them.
    ctx = session.imm
    if (ctx is None or kw or more or type(near) is not int or type(far) is not int
            or not (ZMIN <= near <= ZMAX and ZMIN <= far <= ZMAX)
            or ctx.compat.get(_ZRANGEMAP, 0)):
        return _general_lsetdepth(*given((near, far), more), **kw)
    ctx.depth_range = (near, far)


def _lsetdepth(near: int, far: int) -> None:
    args = (near, far)
    ctx = current("lsetdepth", args)
    lo, hi, why = _depth_limits(ctx)
    n = _in_range("lsetdepth", args, "near", near, lo, hi, why)
    f = _in_range("lsetdepth", args, "far", far, lo, hi, why)
    ctx.depth_range = (n, f)


@gl_function()
def setdepth(near: int, far: int) -> None:
    """Obsolete 16-bit form of :func:`lsetdepth` (Screencoord = short arguments).

    As in IGL the values are used unscaled: setdepth(n, f) is lsetdepth(n, f) with
    both limited to -0x8000..0x7FFF.
    """
    args = (near, far)
    ctx = current("setdepth", args)
    n = _in_range("setdepth", args, "near", near, -0x8000, _SHORT_MAX, "Screencoord")
    f = _in_range("setdepth", args, "far", far, -0x8000, _SHORT_MAX, "Screencoord")
    ctx.depth_range = (n, f)


# -- stencil ----------------------------------------------------------------------
def _general_stencil(*args, **kwargs) -> None:
    if kwargs or session.recording is not None or len(args) != 7:
        return record_or_refuse(stencil, args, kwargs)
    enable, ref, func, mask, fail, pass_, zpass = args
    ctx = current("stencil", args)
    on = as_int("stencil", args, "enable", enable) != 0
    if not on:
        ctx.raster.set(stencil=ctx.raster.stencil._replace(enable=False))
        return
    r = _u32("stencil", args, "ref", ref)
    fn = check_token("stencil", args, "func", func, _CMP, "SF_")
    m = _u32("stencil", args, "mask", mask)
    ops = [check_token("stencil", args, what, v, _STOPS, "ST_")
           for what, v in (("fail", fail), ("pass", pass_), ("zpass", zpass))]
    reg = StencilRegister(True, r, fn, m, ops[0], ops[1], ops[2])
    if _core.FAST_CALLS and all(type(a) in _INTS for a in args):
        # One register object per distinct valid argument tuple (the 1991 shadow faces
        # alternate between two), found again by stencil()'s valid path.
        memo = ctx.raster.stencil_memo
        if len(memo) >= 4096:
            memo.clear()
        memo[args] = _StencilEntry(reg)
    ctx.raster.set(stencil=reg)


class _StencilEntry:
    """stencil()'s memo entry for one valid argument tuple: its register, and the
    raster snapshot each snapshot becomes when only this register changes
    (``after[id(before)] = (before, after)``; ``before`` is kept so that its id
    cannot be reused; ``last``: the pair found last, tried first -- the 1991 shadow
    faces alternate between two argument tuples under one other state).  A snapshot
    is a function of the register values (RasterRegisters.snapshot), so the pair
    found once holds for good, and the next bgn* finds the snapshot made instead of
    building its 24-value key again."""

    __slots__ = ("reg", "after", "last")

    def __init__(self, reg: StencilRegister):
        self.reg = reg
        self.after: dict[int, tuple] = {}
        self.last: tuple = (None, None)


_INTS = (int, Token)  # plain ints and GL tokens (an int subclass)


@gl_function(binds=(7, 7, ("int",) * 7))
def stencil(enable=_NO, ref=_NO, func=_NO, mask=_NO, fail=_NO, pass_=_NO, zpass=_NO, /,
            *more, **kw) -> None:
    """stencil(enable, ref, func, mask, fail, pass_, zpass): set the stencil test and
    operations (stencil(3G)).

    ``fail`` applies when the stencil test fails, ``pass_`` when it passes and the z
    test fails, ``zpass`` when both pass -- and ``pass_`` also when z-buffering is
    off ("zpass ... is not significant when the z-buffer is not enabled").  With
    ``enable`` FALSE the other arguments are ignored (their previous values kept).
    Enabling without stencil planes (stensize 0) is stored but has no effect: the
    manual allows stencil only where planes exist, and the kernels skip the test.
    """
    ctx = session.imm
    if ctx is not None and not kw and not more:
        # The register of an argument tuple validated before (only enabling calls
        # whose arguments are all plain ints or GL tokens are remembered).  A float,
        # Fraction or numpy value equal to a remembered int would find it too, so the
        # sum must be a plain int: it is one only when every argument is an int (or a
        # bool or token, which the general path accepts alike); a float makes it a
        # float, numpy a numpy scalar, and a str, None or a missing argument (_NO)
        # raise TypeError.  One sum costs less than seven type checks.
        try:
            kind = type(enable + ref + func + mask + fail + pass_ + zpass)
        except TypeError:
            kind = None
        if kind is int:
            regs = ctx.raster
            entry = regs.stencil_memo.get((enable, ref, func, mask, fail, pass_, zpass))
            if entry is not None:
                before = regs._snapshot
                regs.stencil = entry.reg
                if before is None:
                    return  # (another register changed too: the next bgn* derives it)
                pair = entry.last
                if pair[0] is before:
                    regs._snapshot = pair[1]
                    return
                pair = entry.after.get(id(before))
                if pair is None or pair[0] is not before:
                    regs._snapshot = None
                    if len(entry.after) >= 64:
                        entry.after.clear()
                    pair = entry.after[id(before)] = (before, regs.snapshot())
                entry.last = pair
                regs._snapshot = pair[1]
                return
    _general_stencil(*given((enable, ref, func, mask, fail, pass_, zpass), more), **kw)


@gl_function()
def sclear(sval: int) -> None:
    """Set the stencil planes to ``sval`` in the raster rectangle, through swritemask
    (sclear(3G)); nothing happens without stencil planes."""
    ctx = current("sclear", (sval,))
    ctx.clear_planes(CLEAR_STENCIL, stencil=_u32("sclear", (sval,), "sval", sval))


@register_call("swritemask", wrap=True)
def swritemask(mask: int) -> None:
    """Which stencil bits may change; bits above the configured planes are ignored
    (swritemask(3G))."""
    ctx = current("swritemask", (mask,))
    ctx.raster.set(swritemask=_u32("swritemask", (mask,), "mask", mask))


# -- colour write masks, blending, alpha test, logic ops -----------------------------
def _need_rgb(ctx, name: str, args: tuple) -> None:
    if not ctx.config.rgb:
        raise GLUsageError(f"{describe(name, args)}: it is an error to call {name} while "
                           "the framebuffer is in colour map mode (wmpack(3G)); use "
                           "writemask()")


def _general_wmpack(*args, **kwargs) -> None:
    if kwargs or session.recording is not None or len(args) != 1:
        return record_or_refuse(wmpack, args, kwargs)
    ctx = current("wmpack", args)
    if not ctx.config.rgb:
        _need_rgb(ctx, "wmpack", args)
    regs = ctx.raster
    regs.wmpack = _u32("wmpack", args, "mask", args[0])
    regs._snapshot = None


@gl_function(binds=(1, 1, ("int",)))
def wmpack(mask=_NO, /, *more, **kw) -> None:
    """wmpack(mask): packed 0xAABBGGRR colour write mask (wmpack(3G)): ``wmpack(0xFF)``
    writes red only, ``wmpack(0)`` no colour at all."""
    ctx = session.imm
    if ctx is None or kw or more or type(mask) is not int or not ctx.config.rgb:
        return _general_wmpack(*given((mask,), more), **kw)
    regs = ctx.raster
    regs.wmpack = mask & _U32
    regs._snapshot = None


@gl_function()
def RGBwritemask(red: int, green: int, blue: int) -> None:
    """8-bit red, green and blue write masks; "the alpha mask component is set to
    enable writing to all alpha bitplanes" and "bits 8 through 15 of each component
    specification are ignored" (RGBwritemask(3G))."""
    args = (red, green, blue)
    ctx = current("RGBwritemask", args)
    _need_rgb(ctx, "RGBwritemask", args)
    r, g, b = (as_int("RGBwritemask", args, n, v) & 0xFF
               for n, v in zip(("red", "green", "blue"), args, strict=True))
    ctx.raster.set(wmpack=r | (g << 8) | (b << 16) | (0xFF << 24))


_POST_VGX_BF = range(9, 15)  # BF_CA .. BF_MAX (later IRIX gl.h, RealityEngine)


def _blend_factor(args: tuple, what: str, v, allowed: range) -> int:
    iv = as_int("blendfunction", args, what, v)
    if iv in _POST_VGX_BF:
        raise GLValueError(f"{describe('blendfunction', args)}: {what} {iv} (BF_CA..BF_MAX)"
                           " is a later, RealityEngine-era factor, not available on the VGX")
    if iv not in allowed:
        if what == "dfactr" and iv == int(GL.BF_MIN_SA_MDA):
            raise GLValueError(f"{describe('blendfunction', args)}: BF_MIN_SA_MDA is a "
                               "source factor only")
        raise GLValueError(f"{describe('blendfunction', args)}: {what} {iv} is not a valid "
                           "token (BF_*)")
    return iv


def _general_blendfunction(*args, **kwargs) -> None:
    if kwargs or session.recording is not None or len(args) != 2:
        return record_or_refuse(blendfunction, args, kwargs)
    sfactr, dfactr = args
    ctx = current("blendfunction", args)
    sf = _blend_factor(args, "sfactr", sfactr, range(0, 9))
    df = _blend_factor(args, "dfactr", dfactr, range(0, 8))
    if (sf, df) != (int(GL.BF_ONE), int(GL.BF_ZERO)):
        ctx.raster.set(blend=(sf, df), logicop=int(GL.LO_SRC))
    else:
        ctx.raster.set(blend=(sf, df))


@gl_function(binds=(2, 2, ("int", "int")))
def blendfunction(sfactr=_NO, dfactr=_NO, /, *more, **kw) -> None:
    """blendfunction(sfactr, dfactr): blend factors (blendfunction(3G)); (BF_ONE,
    BF_ZERO) is no blending.

    Values 2 and 3 are BF_DC/BF_MDC as a source factor and BF_SC/BF_MSC as a
    destination factor; BF_MIN_SA_MDA is a source factor only.  Blending and logic
    operations exclude each other: a blending function other than (BF_ONE, BF_ZERO)
    resets logicop to LO_SRC (IGL records the manual saying so).
    """
    ctx = session.imm
    # Valid path: two plain ints (or GL tokens) that are VGX factors; anything else
    # takes the general path, which raises naming the argument.
    if (ctx is not None and not kw and not more and type(sfactr) in _INTS
            and type(dfactr) in _INTS and sfactr in _SFACTORS and dfactr in _DFACTORS):
        regs = ctx.raster
        regs.blend = (int(sfactr), int(dfactr))
        if sfactr != _BF_ONE or dfactr != _BF_ZERO:
            regs.logicop = _LO_SRC
        regs._snapshot = None
        return
    _general_blendfunction(*given((sfactr, dfactr), more), **kw)


_SFACTORS = frozenset(range(0, 9))  # (BF_CA .. BF_MAX, 9..14, are not VGX factors)
_DFACTORS = frozenset(range(0, 8))  # (BF_MIN_SA_MDA, 8, is a source factor only)
_BF_ONE, _BF_ZERO, _LO_SRC = int(GL.BF_ONE), int(GL.BF_ZERO), int(GL.LO_SRC)


def _afunction(ref: int, func: int) -> None:
    args = (ref, func)
    ctx = current("afunction", args)
    r = _in_range("afunction", args, "ref", ref, 0, 255, "an 8-bit alpha")
    f = check_token("afunction", args, "func", func, _CMP, "AF_")
    ctx.raster.set(afunction=(r, f))


def _general_afunction(*args, **kwargs) -> None:
    if kwargs or session.recording is not None or len(args) != 2:
        return record_or_refuse(afunction, args, kwargs)
    _afunction(*args)


#: afunction's register value for each valid (ref, func), ``_AF_PAIRS[func][ref]``:
#: the valid path stores one of these instead of a new tuple (a constant table).
_AF_PAIRS = tuple(tuple((r, f) for r in range(256)) for f in _CMP)


@gl_function(binds=(2, 2, ("int", "int")))
def afunction(ref=_NO, func=_NO, /, *more, **kw) -> None:
    """afunction(ref, func): alpha test, a fragment is kept iff ``alpha FUNC ref``
    (afunction(3G)); ref is 0..255, func AF_NEVER..AF_ALWAYS (AF_ALWAYS, the
    default, disables the test)."""
    # Valid path (FAST_CALLS): two ints (or GL tokens) in range, stored as the
    # general path's set() stores them; anything else takes the general path.
    ctx = session.imm
    if (ctx is None or kw or more or (type(ref) is not int and type(ref) is not Token)
            or (type(func) is not int and type(func) is not Token)
            or not (0 <= ref <= 255 and 0 <= func <= 7)):
        return _general_afunction(*given((ref, func), more), **kw)
    regs = ctx.raster
    regs.afunction = _AF_PAIRS[func][ref]
    regs._snapshot = None


@gl_function()
def logicop(opcode: int) -> None:
    """Bitwise operation of source and destination words, LO_ZERO..LO_ONE
    (logicop(3G)); any op but LO_SRC resets blending to (BF_ONE, BF_ZERO)."""
    args = (opcode,)
    ctx = current("logicop", args)
    op = check_token("logicop", args, "opcode", opcode, range(16), "LO_")
    if op != int(GL.LO_SRC):
        ctx.raster.set(logicop=op, blend=(int(GL.BF_ONE), int(GL.BF_ZERO)))
    else:
        ctx.raster.set(logicop=op)


# -- faces and shading -----------------------------------------------------------------
@register_call("backface", boolean=True)
def backface(b: int) -> None:
    """Cull polygons whose window-space vertices run clockwise (backface(3G))."""
    ctx = current("backface", (b,))
    ctx.raster.set(backface=as_int("backface", (b,), "b", b) != 0)


@register_call("frontface", boolean=True)
def frontface(b: int) -> None:
    """Cull counter-clockwise (front-facing) polygons (frontface(3G))."""
    ctx = current("frontface", (b,))
    ctx.raster.set(frontface=as_int("frontface", (b,), "b", b) != 0)


@gl_function(record=False)
def getbackface() -> int:
    """1 if backface(TRUE) is in effect, else 0 (getbackface(3G))."""
    return int(bool(current("getbackface").raster.backface))


@register_call("shademodel", int(GL.FLAT), int(GL.GOURAUD))
def shademodel(mode: int) -> None:
    """FLAT (last vertex's colour) or GOURAUD, the default (shademodel(3G))."""
    args = (mode,)
    ctx = current("shademodel", args)
    m = as_int("shademodel", args, "mode", mode)
    if m not in (int(GL.FLAT), int(GL.GOURAUD)):
        raise GLValueError(f"{describe('shademodel', args)}: mode {m} is not a valid token "
                           "(FLAT or GOURAUD)")
    ctx.raster.set(shademodel=m)


@gl_function(record=False)
def getsm() -> int:
    """The shading model, FLAT or GOURAUD (getsm(3G))."""
    return int(current("getsm").raster.shademodel)


# -- lines and points ----------------------------------------------------------------------
@register_call("linewidth", 1, _SHORT_MAX)
def linewidth(n: int) -> None:
    """Line width in pixels, at least 1 (linewidth(3G))."""
    ctx = current("linewidth", (n,))
    ctx.raster.set(linewidth=_in_range("linewidth", (n,), "n", n, 1, _SHORT_MAX))


@gl_function()
def linewidthf(w: float) -> None:
    """Float line width; rounded to the nearest whole pixel (at least 1), since
    fractional widths only matter to smooth lines, which are not modelled."""
    ctx = current("linewidthf", (w,))
    v = as_float("linewidthf", (w,), "w", w)
    if not (math.isfinite(v) and v > 0):
        raise GLValueError(f"{describe('linewidthf', (w,))}: w must be a positive number")
    ctx.raster.set(linewidth=min(_SHORT_MAX, max(1, math.floor(v + 0.5))))


@gl_function(record=False)
def getlwidth() -> int:
    """The current line width (getlwidth(3G))."""
    return int(current("getlwidth").raster.linewidth)


@gl_function()
def deflinestyle(n: int, ls: int) -> None:
    """Define line style ``n`` as the 16-bit pattern ``ls``, bit 0 first
    (deflinestyle(3G)).  Index 0 is the reserved solid style.  Redefining the style
    in use changes the lines drawn from now on."""
    args = (n, ls)
    ctx = current("deflinestyle", args)
    idx = as_int("deflinestyle", args, "n", n)
    if idx == 0:
        raise GLValueError(f"{describe('deflinestyle', args)}: index 0 is reserved for the "
                           "solid line style")
    idx = _in_range("deflinestyle", args, "n", n, 1, _SHORT_MAX)
    pattern = _in_range("deflinestyle", args, "ls", ls, 0, 0xFFFF, "a 16-bit pattern")
    ctx.linestyles[idx] = pattern
    if ctx.linestyle_index == idx:
        ctx.raster.set(linestyle=pattern)


def _general_setlinestyle(*args, **kwargs) -> None:
    if kwargs or session.recording is not None or len(args) != 1:
        return record_or_refuse(setlinestyle, args, kwargs)
    _setlinestyle(*args)


@gl_function(binds=(1, 1, ("int",)))
def setlinestyle(n=_NO, /, *more, **kw) -> None:
    """setlinestyle(n): make line style ``n`` current (setlinestyle(3G)); it must
    have been defined."""
    # Valid path (FAST_CALLS): a plain int naming a defined style (no int outside
    # 0..0x7FFF is a key of Context.linestyles), stored as the general path does.
    ctx = session.imm
    if ctx is None or kw or more or type(n) is not int:
        return _general_setlinestyle(*given((n,), more), **kw)
    pattern = ctx.linestyles.get(n)
    if pattern is None:
        return _general_setlinestyle(n)  # raises: not defined
    ctx.linestyle_index = n
    regs = ctx.raster
    regs.linestyle = pattern
    regs._snapshot = None


def _setlinestyle(n: int) -> None:
    args = (n,)
    ctx = current("setlinestyle", args)
    idx = as_int("setlinestyle", args, "n", n)
    if idx not in ctx.linestyles:
        raise GLValueError(f"{describe('setlinestyle', args)}: line style {idx} is not "
                           "defined (deflinestyle first)")
    ctx.linestyle_index = idx
    ctx.raster.set(linestyle=ctx.linestyles[idx])


@gl_function(record=False)
def getlstyle() -> int:
    """The current line style index (getlstyle(3G))."""
    return int(current("getlstyle").linestyle_index)


@gl_function()
def lsrepeat(factor: int) -> None:
    """Repeat each line-style bit ``factor`` times, 1..255 (lsrepeat(3G); the upper
    limit of an 8-bit factor is assumed)."""
    ctx = current("lsrepeat", (factor,))
    ctx.raster.set(lsrepeat=_in_range("lsrepeat", (factor,), "factor", factor, 1, 255))


def _set_line_flag(name: str, b: int) -> None:
    """Set the window's line flag ``name`` (resetls, lsbackup) from a boolean argument;
    the flag is part of the draw state, so a new record is made per value."""
    args = (b,)
    ctx = current(name, args)
    setattr(ctx, name, bool(as_int(name, args, "b", b)))
    ctx.vertex_serial += 1


@gl_function()
def resetls(b: int) -> None:
    """resetls(FALSE): the line-style pattern continues from one line to the next
    instead of restarting at each bgnline, bgnclosedline and move (resetls(3G);
    TRUE, the default, restarts it).  The position is counted per pixel drawn
    (docs/numeric_model.md s. 5)."""
    _set_line_flag("resetls", b)


@gl_function(record=False)
def getresetls() -> int:
    """1 when the line style restarts at each line (resetls(TRUE)), else 0."""
    return int(current("getresetls").resetls)


@gl_function()
def lsbackup(b: int) -> None:
    """lsbackup(TRUE): the last two pixels of each line are drawn whatever the line
    style, so styled lines keep visible ends (lsbackup(3G): "it overrides the current
    linestyle to guarantee that the last two pixels in a line are colored"; FALSE, the
    default, applies the pattern to every pixel).  A line is one bgnline or
    bgnclosedline polyline, or one draw (docs/numeric_model.md s. 5)."""
    _set_line_flag("lsbackup", b)


@gl_function(record=False)
def getlsbackup() -> int:
    """1 while lsbackup(TRUE) is in effect, else 0 (getlsbackup(3G))."""
    return int(current("getlsbackup").lsbackup)


@gl_function(record=False)
def getlsrepeat() -> int:
    """The current line-style repeat factor (getlsrepeat(3G))."""
    return int(current("getlsrepeat").raster.lsrepeat)


def _smooth(name: str, mode, allowed, family: str, key: str) -> None:
    args = (mode,)
    ctx = current(name, args)
    ctx.smooth[key] = check_token(name, args, "mode", mode, allowed, family)


@gl_function()
def linesmooth(mode: int) -> None:
    """Antialiased lines, SML_OFF or SML_ON with SML_SMOOTHER/SML_END_CORRECT bits
    (linesmooth(3G)).  Accepted; smoothing is not modelled (lines stay aliased)."""
    _smooth("linesmooth", mode, range(8), "SML_", "line")


@gl_function()
def pntsmooth(mode: int) -> None:
    """Antialiased points, SMP_OFF/SMP_ON/SMP_SMOOTHER (pntsmooth(3G)).  Accepted;
    not modelled."""
    _smooth("pntsmooth", mode, range(4), "SMP_", "point")


@gl_function()
def polysmooth(mode: int) -> None:
    """Antialiased polygons, PYSM_OFF/PYSM_ON/PYSM_SHRINK (polysmooth(3G)).  Accepted;
    not modelled."""
    _smooth("polysmooth", mode, range(3), "PYSM_", "polygon")


@gl_function()
def pntsize(n: int) -> None:
    """Point size in pixels, at least 1 (pntsize(3G))."""
    ctx = current("pntsize", (n,))
    ctx.raster.set(pntsize=_in_range("pntsize", (n,), "n", n, 1, _SHORT_MAX))


@gl_function()
def pntsizef(n: float) -> None:
    """Float point size, rounded to the nearest whole pixel (at least 1)."""
    ctx = current("pntsizef", (n,))
    v = as_float("pntsizef", (n,), "n", n)
    if not (math.isfinite(v) and v > 0):
        raise GLValueError(f"{describe('pntsizef', (n,))}: n must be a positive number")
    ctx.raster.set(pntsize=min(_SHORT_MAX, max(1, math.floor(v + 0.5))))


@gl_function()
def polymode(mode: int) -> None:
    """PYM_FILL, PYM_POINT, PYM_LINE, PYM_HOLLOW or PYM_LINE_FAST (polymode(3G)).

    Stored for :func:`getpolymode`; only PYM_FILL is drawn -- polygons are filled
    in every mode (outline and point rendering of polygons is not implemented).
    """
    args = (mode,)
    ctx = current("polymode", args)
    ctx.polymode = check_token("polymode", args, "mode", mode, range(1, 6), "PYM_")


@gl_function(record=False)
def getpolymode() -> int:
    """The stored polymode (PYM_FILL by default)."""
    return int(current("getpolymode").polymode)


@gl_function()
def dither(mode: int) -> None:
    """DT_ON or DT_OFF (dither(3G)).  Accepted; with 8 bits per component the
    emulator never dithers (getgdesc(GD_DITHER) is 0)."""
    args = (mode,)
    ctx = current("dither", args)
    ctx.dither = check_token("dither", args, "mode", mode, (0, 1), "DT_")


_GLC_MODES = (0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 15)  # GLC_OLDPOLYGON .. GLC_COMPATRATE


@gl_function(record=False)
def glcompat(mode: int, value: int) -> None:
    """Set a compatibility mode (glcompat(3G)).

    GLC_ZRANGEMAP (0 or 1) changes the range :func:`lsetdepth` accepts; the other
    modes are stored only.
    """
    args = (mode, value)
    ctx = current("glcompat", args)
    m = check_token("glcompat", args, "mode", mode, _GLC_MODES, "GLC_")
    v = as_int("glcompat", args, "value", value)
    if m == int(GL.GLC_ZRANGEMAP) and v not in (0, 1):
        raise GLValueError(f"{describe('glcompat', args)}: GLC_ZRANGEMAP takes 0 or 1")
    ctx.compat[m] = v


# -- clear ---------------------------------------------------------------------------------
@gl_function()
def clear() -> None:
    """Fill the raster rectangle of the enabled draw buffers with the current colour
    (the packed RGBA, or the colour index in cmode) through the colour write mask;
    every test is ignored (clear(3G), docs/numeric_model.md section 8)."""
    ctx = current("clear")
    ctx.clear_planes(CLEAR_COLOUR, colour=packed_colour(ctx))
