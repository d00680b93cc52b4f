"""IRIS GL ``<gl/gl.h>`` (and ``<gl/get.h>``) constants as named :class:`~vgxsim.tokens.Token`\\ s.

Usage mirrors the old Python ``GL`` module::

    from vgxsim.GL import *          # or: from vgxsim import GL
    stencil(TRUE, 0, SF_EQUAL, 0xFF, ST_KEEP, ST_KEEP, ST_KEEP)

Every constant is an ``int`` (a :class:`~vgxsim.tokens.Token`) whose ``repr`` is its
name; the five float literals of ``gl.h`` (``LMNULL``, ``N_FILL``, ``N_OUTLINE_POLY``,
``N_OUTLINE_PATCH``, ``N_ISOLINE_S``) are :class:`~vgxsim.tokens.FloatToken`\\ s.
Names that share a value (``BF_DC``/``BF_SC`` = 2, ``BF_MDC``/``BF_MSC`` = 3,
``FG_DEFINE``/``FG_VTX_EXP`` = 2, ``PUP_CURSOR``/``PUP_COLOR`` = 1, the ``N_P2D``/``N_ST``
pairs, ...) are separate tokens, each with its own name.

Sources (as collected in the project reference notes ``irisgl_reference.md`` and
``cpython_gl_module.md``):

* CPython ``Lib/plat-irix5/GL.py`` (python/cpython, commit 5c871ef), a one-to-one
  transcription of IRIX 5 ``<gl/gl.h>``: every name and value here comes from it,
  except the names listed in :data:`POST_IRIX5`.
* CPython ``Lib/plat-irix5/GET.py`` (same commit), the symbols of ``<gl/get.h>``:
  ``getbuffer()`` bits (``BCKBUFFER`` ...), ``getdisplaymode()`` answers (``DMRGB`` ...),
  monitor/video tokens and clipping-plane bits.
* A later IRIX ``<gl/gl.h>`` and IGL 0.4.2 ``include/igl.h`` (irixxxx/irix-igl; the
  reference notes found both agree with GL.py wherever they overlap) for the
  :data:`POST_IRIX5` names: ``BF_CA`` ... ``BF_MAX`` (9-14), ``GD_MULTISAMPLE`` ...
  ``GD_AFUNCTION_MODES`` (84-93), ``GC_*`` (``getgconfig``, 0-16) and ``TX_R``/``TX_Q``.
  The blend factors and gdesc inquiries are RealityEngine-era and not on the VGX;
  whether ``getgconfig`` existed in 1990 is unconfirmed.  The emulator may reject these
  names in strict VGX mode.

Values that deliberately differ from other emulators: Ygl's BF_*, GD_XPMAX and colour
indices, and Alice 4's drawmode / WINQUIT values, are *not* used (the notes show they are
non-SGI numbers).
"""

from vgxsim.tokens import FloatToken as _F
from vgxsim.tokens import Token as _T

# Booleans and stack depths
NULL = _T(0, "NULL")
FALSE = _T(0, "FALSE")
TRUE = _T(1, "TRUE")
ATTRIBSTACKDEPTH = _T(10, "ATTRIBSTACKDEPTH")
VPSTACKDEPTH = _T(8, "VPSTACKDEPTH")
MATRIXSTACKDEPTH = _T(32, "MATRIXSTACKDEPTH")
NAMESTACKDEPTH = _T(1025, "NAMESTACKDEPTH")

# Special pre-defined tags (objects)
STARTTAG = _T(-2, "STARTTAG")
ENDTAG = _T(-3, "ENDTAG")

# Colour-map names (colour map loaded by greset/makemap)
BLACK = _T(0, "BLACK")
RED = _T(1, "RED")
GREEN = _T(2, "GREEN")
YELLOW = _T(3, "YELLOW")
BLUE = _T(4, "BLUE")
MAGENTA = _T(5, "MAGENTA")
CYAN = _T(6, "CYAN")
WHITE = _T(7, "WHITE")

# Pop-up plane colours
PUP_CLEAR = _T(0, "PUP_CLEAR")
PUP_COLOR = _T(1, "PUP_COLOR")
PUP_BLACK = _T(2, "PUP_BLACK")
PUP_WHITE = _T(3, "PUP_WHITE")

# drawmode() / mswapbuffers()
NORMALDRAW = _T(0x010, "NORMALDRAW")
PUPDRAW = _T(0x020, "PUPDRAW")
OVERDRAW = _T(0x040, "OVERDRAW")
UNDERDRAW = _T(0x080, "UNDERDRAW")
CURSORDRAW = _T(0x100, "CURSORDRAW")
DUALDRAW = _T(0x200, "DUALDRAW")

# defpattern() sizes
PATTERN_16 = _T(16, "PATTERN_16")
PATTERN_32 = _T(32, "PATTERN_32")
PATTERN_64 = _T(64, "PATTERN_64")
PATTERN_16_SIZE = _T(16, "PATTERN_16_SIZE")
PATTERN_32_SIZE = _T(64, "PATTERN_32_SIZE")
PATTERN_64_SIZE = _T(256, "PATTERN_64_SIZE")

# readsource()
SRC_AUTO = _T(0, "SRC_AUTO")
SRC_FRONT = _T(1, "SRC_FRONT")
SRC_BACK = _T(2, "SRC_BACK")
SRC_ZBUFFER = _T(3, "SRC_ZBUFFER")
SRC_PUP = _T(4, "SRC_PUP")
SRC_OVER = _T(5, "SRC_OVER")
SRC_UNDER = _T(6, "SRC_UNDER")
SRC_FRAMEGRABBER = _T(7, "SRC_FRAMEGRABBER")

# blendfunction(): 2 and 3 mean DC/MDC as a source factor, SC/MSC as a destination factor
BF_ZERO = _T(0, "BF_ZERO")
BF_ONE = _T(1, "BF_ONE")
BF_DC = _T(2, "BF_DC")
BF_SC = _T(2, "BF_SC")
BF_MDC = _T(3, "BF_MDC")
BF_MSC = _T(3, "BF_MSC")
BF_SA = _T(4, "BF_SA")
BF_MSA = _T(5, "BF_MSA")
BF_DA = _T(6, "BF_DA")
BF_MDA = _T(7, "BF_MDA")
BF_MIN_SA_MDA = _T(8, "BF_MIN_SA_MDA")

# blendfunction(), later IRIX gl.h only (RealityEngine era; not on the VGX): see POST_IRIX5
BF_CA = _T(9, "BF_CA")
BF_MCA = _T(10, "BF_MCA")
BF_CC = _T(11, "BF_CC")
BF_MCC = _T(12, "BF_MCC")
BF_MIN = _T(13, "BF_MIN")
BF_MAX = _T(14, "BF_MAX")

# afunction()
AF_NEVER = _T(0, "AF_NEVER")
AF_LESS = _T(1, "AF_LESS")
AF_EQUAL = _T(2, "AF_EQUAL")
AF_LEQUAL = _T(3, "AF_LEQUAL")
AF_GREATER = _T(4, "AF_GREATER")
AF_NOTEQUAL = _T(5, "AF_NOTEQUAL")
AF_GEQUAL = _T(6, "AF_GEQUAL")
AF_ALWAYS = _T(7, "AF_ALWAYS")

# zfunction()
ZF_NEVER = _T(0, "ZF_NEVER")
ZF_LESS = _T(1, "ZF_LESS")
ZF_EQUAL = _T(2, "ZF_EQUAL")
ZF_LEQUAL = _T(3, "ZF_LEQUAL")
ZF_GREATER = _T(4, "ZF_GREATER")
ZF_NOTEQUAL = _T(5, "ZF_NOTEQUAL")
ZF_GEQUAL = _T(6, "ZF_GEQUAL")
ZF_ALWAYS = _T(7, "ZF_ALWAYS")

# zsource()
ZSRC_DEPTH = _T(0, "ZSRC_DEPTH")
ZSRC_COLOR = _T(1, "ZSRC_COLOR")

# pntsmooth()
SMP_OFF = _T(0x0, "SMP_OFF")
SMP_ON = _T(0x1, "SMP_ON")
SMP_SMOOTHER = _T(0x2, "SMP_SMOOTHER")

# linesmooth()
SML_OFF = _T(0x0, "SML_OFF")
SML_ON = _T(0x1, "SML_ON")
SML_SMOOTHER = _T(0x2, "SML_SMOOTHER")
SML_END_CORRECT = _T(0x4, "SML_END_CORRECT")

# polysmooth()
PYSM_OFF = _T(0, "PYSM_OFF")
PYSM_ON = _T(1, "PYSM_ON")
PYSM_SHRINK = _T(2, "PYSM_SHRINK")

# dither()
DT_OFF = _T(0, "DT_OFF")
DT_ON = _T(1, "DT_ON")

# setpup()
PUP_NONE = _T(0, "PUP_NONE")
PUP_GREY = _T(0x1, "PUP_GREY")
PUP_BOX = _T(0x2, "PUP_BOX")
PUP_CHECK = _T(0x4, "PUP_CHECK")

# glcompat()
GLC_OLDPOLYGON = _T(0, "GLC_OLDPOLYGON")
GLC_ZRANGEMAP = _T(1, "GLC_ZRANGEMAP")
GLC_MQUEUERATE = _T(2, "GLC_MQUEUERATE")
GLC_SOFTATTACH = _T(3, "GLC_SOFTATTACH")
GLC_MANAGEBG = _T(4, "GLC_MANAGEBG")
GLC_SLOWMAPCOLORS = _T(5, "GLC_SLOWMAPCOLORS")
GLC_INPUTCHANGEBUG = _T(6, "GLC_INPUTCHANGEBUG")
GLC_NOBORDERBUG = _T(7, "GLC_NOBORDERBUG")
GLC_SET_VSYNC = _T(8, "GLC_SET_VSYNC")
GLC_GET_VSYNC = _T(9, "GLC_GET_VSYNC")
GLC_VSYNC_SLEEP = _T(10, "GLC_VSYNC_SLEEP")
GLC_COMPATRATE = _T(15, "GLC_COMPATRATE")

# curstype()
C16X1 = _T(0, "C16X1")
C16X2 = _T(1, "C16X2")
C32X1 = _T(2, "C32X1")
C32X2 = _T(3, "C32X2")
CCROSS = _T(4, "CCROSS")

# shademodel()
FLAT = _T(0, "FLAT")
GOURAUD = _T(1, "GOURAUD")

# logicop()
LO_ZERO = _T(0x0, "LO_ZERO")
LO_AND = _T(0x1, "LO_AND")
LO_ANDR = _T(0x2, "LO_ANDR")
LO_SRC = _T(0x3, "LO_SRC")
LO_ANDI = _T(0x4, "LO_ANDI")
LO_DST = _T(0x5, "LO_DST")
LO_XOR = _T(0x6, "LO_XOR")
LO_OR = _T(0x7, "LO_OR")
LO_NOR = _T(0x8, "LO_NOR")
LO_XNOR = _T(0x9, "LO_XNOR")
LO_NDST = _T(0xA, "LO_NDST")
LO_ORR = _T(0xB, "LO_ORR")
LO_NSRC = _T(0xC, "LO_NSRC")
LO_ORI = _T(0xD, "LO_ORI")
LO_NAND = _T(0xE, "LO_NAND")
LO_ONE = _T(0xF, "LO_ONE")

# getwscrn() / scrnselect()
INFOCUSSCRN = _T(-2, "INFOCUSSCRN")

# stencil(): operations (fail, pass, zpass)
ST_KEEP = _T(0, "ST_KEEP")
ST_ZERO = _T(1, "ST_ZERO")
ST_REPLACE = _T(2, "ST_REPLACE")
ST_INCR = _T(3, "ST_INCR")
ST_DECR = _T(4, "ST_DECR")
ST_INVERT = _T(5, "ST_INVERT")

# stencil(): comparison functions
SF_NEVER = _T(0, "SF_NEVER")
SF_LESS = _T(1, "SF_LESS")
SF_EQUAL = _T(2, "SF_EQUAL")
SF_LEQUAL = _T(3, "SF_LEQUAL")
SF_GREATER = _T(4, "SF_GREATER")
SF_NOTEQUAL = _T(5, "SF_NOTEQUAL")
SF_GEQUAL = _T(6, "SF_GEQUAL")
SF_ALWAYS = _T(7, "SF_ALWAYS")

# scrsubdivide()
SS_OFF = _T(0, "SS_OFF")
SS_DEPTH = _T(1, "SS_DEPTH")

# polymode()
PYM_FILL = _T(1, "PYM_FILL")
PYM_POINT = _T(2, "PYM_POINT")
PYM_LINE = _T(3, "PYM_LINE")
PYM_HOLLOW = _T(4, "PYM_HOLLOW")
PYM_LINE_FAST = _T(5, "PYM_LINE_FAST")

# fogvertex()
FG_OFF = _T(0, "FG_OFF")
FG_ON = _T(1, "FG_ON")
FG_DEFINE = _T(2, "FG_DEFINE")
FG_VTX_EXP = _T(2, "FG_VTX_EXP")
FG_VTX_LIN = _T(3, "FG_VTX_LIN")
FG_PIX_EXP = _T(4, "FG_PIX_EXP")
FG_PIX_LIN = _T(5, "FG_PIX_LIN")
FG_VTX_EXP2 = _T(6, "FG_VTX_EXP2")
FG_PIX_EXP2 = _T(7, "FG_PIX_EXP2")

# pixmode()
PM_SHIFT = _T(0, "PM_SHIFT")
PM_EXPAND = _T(1, "PM_EXPAND")
PM_C0 = _T(2, "PM_C0")
PM_C1 = _T(3, "PM_C1")
PM_ADD24 = _T(4, "PM_ADD24")
PM_SIZE = _T(5, "PM_SIZE")
PM_OFFSET = _T(6, "PM_OFFSET")
PM_STRIDE = _T(7, "PM_STRIDE")
PM_TTOB = _T(8, "PM_TTOB")
PM_RTOL = _T(9, "PM_RTOL")
PM_ZDATA = _T(10, "PM_ZDATA")
PM_WARP = _T(11, "PM_WARP")
PM_RDX = _T(12, "PM_RDX")
PM_RDY = _T(13, "PM_RDY")
PM_CDX = _T(14, "PM_CDX")
PM_CDY = _T(15, "PM_CDY")
PM_XSTART = _T(16, "PM_XSTART")
PM_YSTART = _T(17, "PM_YSTART")
PM_VO1 = _T(1000, "PM_VO1")

# nmode()
NAUTO = _T(0, "NAUTO")
NNORMALIZE = _T(1, "NNORMALIZE")

# acbuf()
AC_CLEAR = _T(0, "AC_CLEAR")
AC_ACCUMULATE = _T(1, "AC_ACCUMULATE")
AC_CLEAR_ACCUMULATE = _T(2, "AC_CLEAR_ACCUMULATE")
AC_RETURN = _T(3, "AC_RETURN")
AC_MULT = _T(4, "AC_MULT")
AC_ADD = _T(5, "AC_ADD")

# clipplane()
CP_OFF = _T(0, "CP_OFF")
CP_ON = _T(1, "CP_ON")
CP_DEFINE = _T(2, "CP_DEFINE")

# sbox / spaceball
SB_RESET = _T(0, "SB_RESET")
SB_TRACK = _T(1, "SB_TRACK")
SB_HOLD = _T(2, "SB_HOLD")

# readdisplay() hints
RD_FREEZE = _T(0x00000001, "RD_FREEZE")
RD_ALPHAONE = _T(0x00000002, "RD_ALPHAONE")
RD_IGNORE_UNDERLAY = _T(0x00000004, "RD_IGNORE_UNDERLAY")
RD_IGNORE_OVERLAY = _T(0x00000008, "RD_IGNORE_OVERLAY")
RD_IGNORE_PUP = _T(0x00000010, "RD_IGNORE_PUP")
RD_OFFSCREEN = _T(0x00000020, "RD_OFFSCREEN")

# getgdesc() inquiries
GD_XPMAX = _T(0, "GD_XPMAX")
GD_YPMAX = _T(1, "GD_YPMAX")
GD_XMMAX = _T(2, "GD_XMMAX")
GD_YMMAX = _T(3, "GD_YMMAX")
GD_ZMIN = _T(4, "GD_ZMIN")
GD_ZMAX = _T(5, "GD_ZMAX")
GD_BITS_NORM_SNG_RED = _T(6, "GD_BITS_NORM_SNG_RED")
GD_BITS_NORM_SNG_GREEN = _T(7, "GD_BITS_NORM_SNG_GREEN")
GD_BITS_NORM_SNG_BLUE = _T(8, "GD_BITS_NORM_SNG_BLUE")
GD_BITS_NORM_DBL_RED = _T(9, "GD_BITS_NORM_DBL_RED")
GD_BITS_NORM_DBL_GREEN = _T(10, "GD_BITS_NORM_DBL_GREEN")
GD_BITS_NORM_DBL_BLUE = _T(11, "GD_BITS_NORM_DBL_BLUE")
GD_BITS_NORM_SNG_CMODE = _T(12, "GD_BITS_NORM_SNG_CMODE")
GD_BITS_NORM_DBL_CMODE = _T(13, "GD_BITS_NORM_DBL_CMODE")
GD_BITS_NORM_SNG_MMAP = _T(14, "GD_BITS_NORM_SNG_MMAP")
GD_BITS_NORM_DBL_MMAP = _T(15, "GD_BITS_NORM_DBL_MMAP")
GD_BITS_NORM_ZBUFFER = _T(16, "GD_BITS_NORM_ZBUFFER")
GD_BITS_OVER_SNG_CMODE = _T(17, "GD_BITS_OVER_SNG_CMODE")
GD_BITS_UNDR_SNG_CMODE = _T(18, "GD_BITS_UNDR_SNG_CMODE")
GD_BITS_PUP_SNG_CMODE = _T(19, "GD_BITS_PUP_SNG_CMODE")
GD_BITS_NORM_SNG_ALPHA = _T(21, "GD_BITS_NORM_SNG_ALPHA")
GD_BITS_NORM_DBL_ALPHA = _T(22, "GD_BITS_NORM_DBL_ALPHA")
GD_BITS_CURSOR = _T(23, "GD_BITS_CURSOR")
GD_OVERUNDER_SHARED = _T(24, "GD_OVERUNDER_SHARED")
GD_BLEND = _T(25, "GD_BLEND")
GD_CIFRACT = _T(26, "GD_CIFRACT")
GD_CROSSHAIR_CINDEX = _T(27, "GD_CROSSHAIR_CINDEX")
GD_DITHER = _T(28, "GD_DITHER")
GD_LINESMOOTH_CMODE = _T(30, "GD_LINESMOOTH_CMODE")
GD_LINESMOOTH_RGB = _T(31, "GD_LINESMOOTH_RGB")
GD_LOGICOP = _T(33, "GD_LOGICOP")
GD_NSCRNS = _T(35, "GD_NSCRNS")
GD_NURBS_ORDER = _T(36, "GD_NURBS_ORDER")
GD_NBLINKS = _T(37, "GD_NBLINKS")
GD_NVERTEX_POLY = _T(39, "GD_NVERTEX_POLY")
GD_PATSIZE_64 = _T(40, "GD_PATSIZE_64")
GD_PNTSMOOTH_CMODE = _T(41, "GD_PNTSMOOTH_CMODE")
GD_PNTSMOOTH_RGB = _T(42, "GD_PNTSMOOTH_RGB")
GD_PUP_TO_OVERUNDER = _T(43, "GD_PUP_TO_OVERUNDER")
GD_READSOURCE = _T(44, "GD_READSOURCE")
GD_READSOURCE_ZBUFFER = _T(48, "GD_READSOURCE_ZBUFFER")
GD_STEREO = _T(50, "GD_STEREO")
GD_SUBPIXEL_LINE = _T(51, "GD_SUBPIXEL_LINE")
GD_SUBPIXEL_PNT = _T(52, "GD_SUBPIXEL_PNT")
GD_SUBPIXEL_POLY = _T(53, "GD_SUBPIXEL_POLY")
GD_TRIMCURVE_ORDER = _T(54, "GD_TRIMCURVE_ORDER")
GD_WSYS = _T(55, "GD_WSYS")
GD_ZDRAW_GEOM = _T(57, "GD_ZDRAW_GEOM")
GD_ZDRAW_PIXELS = _T(58, "GD_ZDRAW_PIXELS")
GD_SCRNTYPE = _T(61, "GD_SCRNTYPE")
GD_TEXTPORT = _T(62, "GD_TEXTPORT")
GD_NMMAPS = _T(63, "GD_NMMAPS")
GD_FRAMEGRABBER = _T(64, "GD_FRAMEGRABBER")
GD_TIMERHZ = _T(66, "GD_TIMERHZ")
GD_DBBOX = _T(67, "GD_DBBOX")
GD_AFUNCTION = _T(68, "GD_AFUNCTION")
GD_ALPHA_OVERUNDER = _T(69, "GD_ALPHA_OVERUNDER")
GD_BITS_ACBUF = _T(70, "GD_BITS_ACBUF")
GD_BITS_ACBUF_HW = _T(71, "GD_BITS_ACBUF_HW")
GD_BITS_STENCIL = _T(72, "GD_BITS_STENCIL")
GD_CLIPPLANES = _T(73, "GD_CLIPPLANES")
GD_FOGVERTEX = _T(74, "GD_FOGVERTEX")
GD_LIGHTING_TWOSIDE = _T(76, "GD_LIGHTING_TWOSIDE")
GD_POLYMODE = _T(77, "GD_POLYMODE")
GD_POLYSMOOTH = _T(78, "GD_POLYSMOOTH")
GD_SCRBOX = _T(79, "GD_SCRBOX")
GD_TEXTURE = _T(80, "GD_TEXTURE")
GD_FOGPIXEL = _T(81, "GD_FOGPIXEL")
GD_TEXTURE_PERSP = _T(82, "GD_TEXTURE_PERSP")
GD_MUXPIPES = _T(83, "GD_MUXPIPES")

# getgdesc() inquiries, later IRIX gl.h only (not in IRIX 5 GL.py): see POST_IRIX5
GD_MULTISAMPLE = _T(84, "GD_MULTISAMPLE")
GD_TEXTURE_3D = _T(85, "GD_TEXTURE_3D")
GD_TEXTURE_LUT = _T(86, "GD_TEXTURE_LUT")
GD_TEXTURE_SHARP = _T(87, "GD_TEXTURE_SHARP")
GD_TEXTURE_DETAIL = _T(88, "GD_TEXTURE_DETAIL")
GD_STEREO_IN_WINDOW = _T(89, "GD_STEREO_IN_WINDOW")
GD_BLENDCOLOR = _T(90, "GD_BLENDCOLOR")
GD_LIGHTING_SPOTLIGHT = _T(91, "GD_LIGHTING_SPOTLIGHT")
GD_LIGHTING_ATT2 = _T(92, "GD_LIGHTING_ATT2")
GD_AFUNCTION_MODES = _T(93, "GD_AFUNCTION_MODES")

# getgdesc() answers
GD_NOLIMIT = _T(-2, "GD_NOLIMIT")
GD_WSYS_NONE = _T(0, "GD_WSYS_NONE")
GD_WSYS_4S = _T(1, "GD_WSYS_4S")
GD_SCRNTYPE_WM = _T(0, "GD_SCRNTYPE_WM")
GD_SCRNTYPE_NOWM = _T(1, "GD_SCRNTYPE_NOWM")

# getgconfig() inquiries, later IRIX gl.h only (not in IRIX 5 GL.py): see POST_IRIX5
GC_BITS_CMODE = _T(0, "GC_BITS_CMODE")
GC_BITS_RED = _T(1, "GC_BITS_RED")
GC_BITS_GREEN = _T(2, "GC_BITS_GREEN")
GC_BITS_BLUE = _T(3, "GC_BITS_BLUE")
GC_BITS_ALPHA = _T(4, "GC_BITS_ALPHA")
GC_BITS_ZBUFFER = _T(5, "GC_BITS_ZBUFFER")
GC_ZMIN = _T(6, "GC_ZMIN")
GC_ZMAX = _T(7, "GC_ZMAX")
GC_BITS_STENCIL = _T(8, "GC_BITS_STENCIL")
GC_BITS_ACBUF = _T(9, "GC_BITS_ACBUF")
GC_MS_SAMPLES = _T(10, "GC_MS_SAMPLES")
GC_BITS_MS_ZBUFFER = _T(11, "GC_BITS_MS_ZBUFFER")
GC_MS_ZMIN = _T(12, "GC_MS_ZMIN")
GC_MS_ZMAX = _T(13, "GC_MS_ZMAX")
GC_BITS_MS_STENCIL = _T(14, "GC_BITS_MS_STENCIL")
GC_STEREO = _T(15, "GC_STEREO")
GC_DOUBLE = _T(16, "GC_DOUBLE")

# setnurbsproperty() / getnurbsproperty() properties
N_PIXEL_TOLERANCE = _T(1, "N_PIXEL_TOLERANCE")
N_CULLING = _T(2, "N_CULLING")
N_DISPLAY = _T(3, "N_DISPLAY")
N_ERRORCHECKING = _T(4, "N_ERRORCHECKING")
N_SUBDIVISIONS = _T(5, "N_SUBDIVISIONS")
N_S_STEPS = _T(6, "N_S_STEPS")
N_T_STEPS = _T(7, "N_T_STEPS")
N_TILES = _T(8, "N_TILES")
N_TMP1 = _T(9, "N_TMP1")
N_TMP2 = _T(10, "N_TMP2")
N_TMP3 = _T(11, "N_TMP3")
N_TMP4 = _T(12, "N_TMP4")
N_TMP5 = _T(13, "N_TMP5")
N_TMP6 = _T(14, "N_TMP6")

# N_DISPLAY values (floats in gl.h)
N_FILL = _F(1.0, "N_FILL")
N_OUTLINE_POLY = _F(2.0, "N_OUTLINE_POLY")
N_OUTLINE_PATCH = _F(5.0, "N_OUTLINE_PATCH")
N_ISOLINE_S = _F(12.0, "N_ISOLINE_S")

# nurbscurve() / pwlcurve() / nurbssurface() control-point types
N_ST = _T(0x8, "N_ST")
N_STW = _T(0xD, "N_STW")
N_XYZ = _T(0x4C, "N_XYZ")
N_XYZW = _T(0x51, "N_XYZW")
N_TEX = _T(0x88, "N_TEX")
N_TEXW = _T(0x8D, "N_TEXW")
N_RGBA = _T(0xD0, "N_RGBA")
N_RGBAW = _T(0xD5, "N_RGBAW")
N_P2D = _T(0x8, "N_P2D")
N_P2DR = _T(0xD, "N_P2DR")
N_V3D = _T(0x4C, "N_V3D")
N_V3DR = _T(0x51, "N_V3DR")
N_T2D = _T(0x88, "N_T2D")
N_T2DR = _T(0x8D, "N_T2DR")
N_C4D = _T(0xD0, "N_C4D")
N_C4DR = _T(0xD5, "N_C4DR")

# lmdef() property-list terminator (a float in gl.h)
LMNULL = _F(0.0, "LMNULL")

# mmode()
MSINGLE = _T(0, "MSINGLE")
MPROJECTION = _T(1, "MPROJECTION")
MVIEWING = _T(2, "MVIEWING")
MTEXTURE = _T(3, "MTEXTURE")

# lighting limits
MAXLIGHTS = _T(8, "MAXLIGHTS")
MAXRESTRICTIONS = _T(4, "MAXRESTRICTIONS")

# lmdef(DEFMATERIAL, ...) properties
DEFMATERIAL = _T(0, "DEFMATERIAL")
EMISSION = _T(1, "EMISSION")
AMBIENT = _T(2, "AMBIENT")
DIFFUSE = _T(3, "DIFFUSE")
SPECULAR = _T(4, "SPECULAR")
SHININESS = _T(5, "SHININESS")
COLORINDEXES = _T(6, "COLORINDEXES")
ALPHA = _T(7, "ALPHA")

# lmdef(DEFLIGHT, ...) properties (AMBIENT is shared with materials)
DEFLIGHT = _T(100, "DEFLIGHT")
LCOLOR = _T(101, "LCOLOR")
POSITION = _T(102, "POSITION")
SPOTDIRECTION = _T(103, "SPOTDIRECTION")
SPOTLIGHT = _T(104, "SPOTLIGHT")

# lmdef(DEFLMODEL, ...) properties (AMBIENT is shared with materials)
DEFLMODEL = _T(200, "DEFLMODEL")
LOCALVIEWER = _T(201, "LOCALVIEWER")
ATTENUATION = _T(202, "ATTENUATION")
ATTENUATION2 = _T(203, "ATTENUATION2")
TWOSIDE = _T(204, "TWOSIDE")

# lmbind() targets
MATERIAL = _T(1000, "MATERIAL")
BACKMATERIAL = _T(1001, "BACKMATERIAL")
LIGHT0 = _T(1100, "LIGHT0")
LIGHT1 = _T(1101, "LIGHT1")
LIGHT2 = _T(1102, "LIGHT2")
LIGHT3 = _T(1103, "LIGHT3")
LIGHT4 = _T(1104, "LIGHT4")
LIGHT5 = _T(1105, "LIGHT5")
LIGHT6 = _T(1106, "LIGHT6")
LIGHT7 = _T(1107, "LIGHT7")
LMODEL = _T(1200, "LMODEL")

# lmcolor()
LMC_COLOR = _T(0, "LMC_COLOR")
LMC_EMISSION = _T(1, "LMC_EMISSION")
LMC_AMBIENT = _T(2, "LMC_AMBIENT")
LMC_DIFFUSE = _T(3, "LMC_DIFFUSE")
LMC_SPECULAR = _T(4, "LMC_SPECULAR")
LMC_AD = _T(5, "LMC_AD")
LMC_NULL = _T(6, "LMC_NULL")

# texdef2d() properties
TX_MINFILTER = _T(0x100, "TX_MINFILTER")
TX_MAGFILTER = _T(0x200, "TX_MAGFILTER")
TX_WRAP = _T(0x300, "TX_WRAP")
TX_WRAP_S = _T(0x310, "TX_WRAP_S")
TX_WRAP_T = _T(0x320, "TX_WRAP_T")
TX_TILE = _T(0x400, "TX_TILE")
TX_BORDER = _T(0x500, "TX_BORDER")
TX_NULL = _T(0x000, "TX_NULL")

# texdef2d() filters
TX_POINT = _T(0x110, "TX_POINT")
TX_BILINEAR = _T(0x220, "TX_BILINEAR")
TX_MIPMAP = _T(0x120, "TX_MIPMAP")
TX_MIPMAP_POINT = _T(0x121, "TX_MIPMAP_POINT")
TX_MIPMAP_LINEAR = _T(0x122, "TX_MIPMAP_LINEAR")
TX_MIPMAP_BILINEAR = _T(0x123, "TX_MIPMAP_BILINEAR")
TX_MIPMAP_TRILINEAR = _T(0x124, "TX_MIPMAP_TRILINEAR")

# texdef2d() wrap modes
TX_REPEAT = _T(0x301, "TX_REPEAT")
TX_CLAMP = _T(0x302, "TX_CLAMP")
TX_SELECT = _T(0x303, "TX_SELECT")

# texbind() target
TX_TEXTURE_0 = _T(0, "TX_TEXTURE_0")

# tevdef() properties / tevbind() target
TV_MODULATE = _T(0x101, "TV_MODULATE")
TV_BLEND = _T(0x102, "TV_BLEND")
TV_DECAL = _T(0x103, "TV_DECAL")
TV_COLOR = _T(0x200, "TV_COLOR")
TV_NULL = _T(0x000, "TV_NULL")
TV_ENV0 = _T(0, "TV_ENV0")

# texgen() coordinates and modes
TX_S = _T(0, "TX_S")
TX_T = _T(1, "TX_T")
TG_OFF = _T(0, "TG_OFF")
TG_ON = _T(1, "TG_ON")
TG_CONTOUR = _T(2, "TG_CONTOUR")
TG_LINEAR = _T(3, "TG_LINEAR")
TG_SPHEREMAP = _T(4, "TG_SPHEREMAP")
TG_REFRACTMAP = _T(5, "TG_REFRACTMAP")

# texgen() coordinates, later IRIX gl.h only (not in IRIX 5 GL.py): see POST_IRIX5
TX_R = _T(2, "TX_R")
TX_Q = _T(3, "TX_Q")

# dglopen() connection types
DGLSINK = _T(0, "DGLSINK")
DGLLOCAL = _T(1, "DGLLOCAL")
DGLTSOCKET = _T(2, "DGLTSOCKET")
DGL4DDN = _T(3, "DGL4DDN")

# pop-up cursor colour (same index as PUP_COLOR)
PUP_CURSOR = _T(1, "PUP_CURSOR")

# gl error severities
FATAL = _T(1, "FATAL")
WARNING = _T(2, "WARNING")
ASK_CONT = _T(3, "ASK_CONT")
ASK_RESTART = _T(4, "ASK_RESTART")

# obsolete screen sizes (maximum coordinates)
XMAXSCREEN = _T(1279, "XMAXSCREEN")
YMAXSCREEN = _T(1023, "YMAXSCREEN")
XMAXMEDIUM = _T(1023, "XMAXMEDIUM")
YMAXMEDIUM = _T(767, "YMAXMEDIUM")
XMAX170 = _T(645, "XMAX170")
YMAX170 = _T(484, "YMAX170")
XMAXPAL = _T(779, "XMAXPAL")
YMAXPAL = _T(574, "YMAXPAL")

# <gl/get.h>: getbuffer() bits
NOBUFFER = _T(0x0, "NOBUFFER")
BCKBUFFER = _T(0x1, "BCKBUFFER")
FRNTBUFFER = _T(0x2, "FRNTBUFFER")
BOTHBUFFERS = _T(0x3, "BOTHBUFFERS")
DRAWZBUFFER = _T(0x4, "DRAWZBUFFER")

# <gl/get.h>: getdisplaymode() answers
DMRGB = _T(0, "DMRGB")
DMSINGLE = _T(1, "DMSINGLE")
DMDOUBLE = _T(2, "DMDOUBLE")
DMINTENSITYSINGLE = _T(3, "DMINTENSITYSINGLE")
DMINTENSITYDOUBLE = _T(4, "DMINTENSITYDOUBLE")
DMRGBDOUBLE = _T(5, "DMRGBDOUBLE")

# <gl/get.h>: setmonitor() / getmonitor() video formats
HZ30 = _T(0, "HZ30")
HZ60 = _T(1, "HZ60")
NTSC = _T(2, "NTSC")
HDTV = _T(3, "HDTV")
HZ50 = _T(3, "HZ50")
VGA = _T(4, "VGA")
IRIS3K = _T(5, "IRIS3K")
PR60 = _T(6, "PR60")
PAL = _T(9, "PAL")
HZ30_SG = _T(11, "HZ30_SG")
A343 = _T(14, "A343")
STR_RECT = _T(15, "STR_RECT")
VOF0 = _T(16, "VOF0")
VOF1 = _T(17, "VOF1")
VOF2 = _T(18, "VOF2")
VOF3 = _T(19, "VOF3")
SGI0 = _T(20, "SGI0")
SGI1 = _T(21, "SGI1")
SGI2 = _T(22, "SGI2")
HZ72 = _T(23, "HZ72")
MONSPECIAL = _T(0x20, "MONSPECIAL")
MONA = _T(5, "MONA")
MONB = _T(6, "MONB")
MONC = _T(7, "MONC")
MOND = _T(8, "MOND")
MON_ALL = _T(12, "MON_ALL")
MON_GEN_ALL = _T(13, "MON_GEN_ALL")

# <gl/get.h>: setvideo() / getvideo()
GL_VIDEO_REG = _T(0x00800000, "GL_VIDEO_REG")
GLV_GENLOCK = _T(0x00000001, "GLV_GENLOCK")
GLV_UNBLANK = _T(0x00000002, "GLV_UNBLANK")
GLV_SRED = _T(0x00000004, "GLV_SRED")
GLV_SGREEN = _T(0x00000008, "GLV_SGREEN")
GLV_SBLUE = _T(0x00000010, "GLV_SBLUE")
GLV_SALPHA = _T(0x00000020, "GLV_SALPHA")
GLV_TTLGENLOCK = _T(0x00000080, "GLV_TTLGENLOCK")
GLV_TTLSYNC = _T(0x00000080, "GLV_TTLSYNC")
GLV_GREENGENLOCK = _T(0x00000100, "GLV_GREENGENLOCK")

# <gl/get.h>: clipping-plane bits
LEFTPLANE = _T(0x0001, "LEFTPLANE")
RIGHTPLANE = _T(0x0002, "RIGHTPLANE")
BOTTOMPLANE = _T(0x0004, "BOTTOMPLANE")
TOPPLANE = _T(0x0008, "TOPPLANE")
NEARPLANE = _T(0x0010, "NEARPLANE")
FARPLANE = _T(0x0020, "FARPLANE")

# <gl/get.h>: getcmmode() answers
CMAPMULTI = _T(0, "CMAPMULTI")
CMAPONE = _T(1, "CMAPONE")


#: Names defined here that are not in IRIX 5 ``GL.py`` (taken from a later IRIX gl.h /
#: IGL): RealityEngine-era blend factors and gdesc inquiries, getgconfig() inquiries,
#: and the r/q texgen coordinates (none of them documented for the VGX).
POST_IRIX5 = frozenset(
    """
    BF_CA BF_MCA BF_CC BF_MCC BF_MIN BF_MAX
    GD_MULTISAMPLE GD_TEXTURE_3D GD_TEXTURE_LUT GD_TEXTURE_SHARP GD_TEXTURE_DETAIL
    GD_STEREO_IN_WINDOW GD_BLENDCOLOR GD_LIGHTING_SPOTLIGHT GD_LIGHTING_ATT2
    GD_AFUNCTION_MODES
    GC_BITS_CMODE GC_BITS_RED GC_BITS_GREEN GC_BITS_BLUE GC_BITS_ALPHA GC_BITS_ZBUFFER
    GC_ZMIN GC_ZMAX GC_BITS_STENCIL GC_BITS_ACBUF GC_MS_SAMPLES GC_BITS_MS_ZBUFFER
    GC_MS_ZMIN GC_MS_ZMAX GC_BITS_MS_STENCIL GC_STEREO GC_DOUBLE
    TX_R TX_Q
    """.split()
)

#: Every constant name, in definition order (``from vgxsim.GL import *`` exports these).
__all__ = [_n for _n, _v in globals().items() if isinstance(_v, (_T, _F))]
