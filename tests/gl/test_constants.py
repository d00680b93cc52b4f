"""Constant values of vgxsim.GL / vgxsim.DEVICE and the Token type.

The value tables below are copied by hand from the project reference notes
(irisgl_reference.md and cpython_gl_module.md, which cite CPython's
Lib/plat-irix5/GL.py and DEVICE.py, IGL's igl.h and a later IRIX gl.h), not generated
from the modules under test.
"""

import copy
import json
import pickle

import numpy as np
import pytest

from vgxsim import DEVICE, GL, tokens
from vgxsim.tokens import FloatToken, Token, define, family, lookup

# ---------------------------------------------------------------------------
# Value tables (hand-copied from the reference notes)
# ---------------------------------------------------------------------------

# irisgl_reference.md 1.1 (stencil)
STENCIL = {
    "SF_NEVER": 0, "SF_LESS": 1, "SF_EQUAL": 2, "SF_LEQUAL": 3,
    "SF_GREATER": 4, "SF_NOTEQUAL": 5, "SF_GEQUAL": 6, "SF_ALWAYS": 7,
    "ST_KEEP": 0, "ST_ZERO": 1, "ST_REPLACE": 2, "ST_INCR": 3, "ST_DECR": 4, "ST_INVERT": 5,
}

# 1.2 (z-buffer) and Appendix A (AF_* = ZF_* numbering)
DEPTH = {
    "ZF_NEVER": 0, "ZF_LESS": 1, "ZF_EQUAL": 2, "ZF_LEQUAL": 3,
    "ZF_GREATER": 4, "ZF_NOTEQUAL": 5, "ZF_GEQUAL": 6, "ZF_ALWAYS": 7,
    "AF_NEVER": 0, "AF_LESS": 1, "AF_EQUAL": 2, "AF_LEQUAL": 3,
    "AF_GREATER": 4, "AF_NOTEQUAL": 5, "AF_GEQUAL": 6, "AF_ALWAYS": 7,
    "ZSRC_DEPTH": 0, "ZSRC_COLOR": 1,
}

# 1.3 (blendfunction; 9-14 post-VGX) and the brief's logicop list
BLEND = {
    "BF_ZERO": 0, "BF_ONE": 1, "BF_DC": 2, "BF_SC": 2, "BF_MDC": 3, "BF_MSC": 3,
    "BF_SA": 4, "BF_MSA": 5, "BF_DA": 6, "BF_MDA": 7, "BF_MIN_SA_MDA": 8,
    "BF_CA": 9, "BF_MCA": 10, "BF_CC": 11, "BF_MCC": 12, "BF_MIN": 13, "BF_MAX": 14,
    "LO_ZERO": 0x0, "LO_AND": 0x1, "LO_ANDR": 0x2, "LO_SRC": 0x3,
    "LO_ANDI": 0x4, "LO_DST": 0x5, "LO_XOR": 0x6, "LO_OR": 0x7,
    "LO_NOR": 0x8, "LO_XNOR": 0x9, "LO_NDST": 0xA, "LO_ORR": 0xB,
    "LO_NSRC": 0xC, "LO_ORI": 0xD, "LO_NAND": 0xE, "LO_ONE": 0xF,
}

# 1.4 (getgdesc table, the >= 84 row, and its answers)
GDESC = {
    "GD_XPMAX": 0, "GD_YPMAX": 1, "GD_XMMAX": 2, "GD_YMMAX": 3, "GD_ZMIN": 4, "GD_ZMAX": 5,
    "GD_BITS_NORM_SNG_RED": 6, "GD_BITS_NORM_SNG_GREEN": 7, "GD_BITS_NORM_SNG_BLUE": 8,
    "GD_BITS_NORM_DBL_RED": 9, "GD_BITS_NORM_DBL_GREEN": 10, "GD_BITS_NORM_DBL_BLUE": 11,
    "GD_BITS_NORM_SNG_CMODE": 12, "GD_BITS_NORM_DBL_CMODE": 13,
    "GD_BITS_NORM_SNG_MMAP": 14, "GD_BITS_NORM_DBL_MMAP": 15,
    "GD_BITS_NORM_ZBUFFER": 16, "GD_BITS_OVER_SNG_CMODE": 17,
    "GD_BITS_UNDR_SNG_CMODE": 18, "GD_BITS_PUP_SNG_CMODE": 19,
    "GD_BITS_NORM_SNG_ALPHA": 21, "GD_BITS_NORM_DBL_ALPHA": 22, "GD_BITS_CURSOR": 23,
    "GD_OVERUNDER_SHARED": 24, "GD_BLEND": 25, "GD_CIFRACT": 26,
    "GD_CROSSHAIR_CINDEX": 27, "GD_DITHER": 28, "GD_LINESMOOTH_CMODE": 30,
    "GD_LINESMOOTH_RGB": 31, "GD_LOGICOP": 33, "GD_NSCRNS": 35, "GD_NURBS_ORDER": 36,
    "GD_NBLINKS": 37, "GD_NVERTEX_POLY": 39, "GD_PATSIZE_64": 40,
    "GD_PNTSMOOTH_CMODE": 41, "GD_PNTSMOOTH_RGB": 42, "GD_PUP_TO_OVERUNDER": 43,
    "GD_READSOURCE": 44, "GD_READSOURCE_ZBUFFER": 48, "GD_STEREO": 50,
    "GD_SUBPIXEL_LINE": 51, "GD_SUBPIXEL_PNT": 52, "GD_SUBPIXEL_POLY": 53,
    "GD_TRIMCURVE_ORDER": 54, "GD_WSYS": 55, "GD_ZDRAW_GEOM": 57, "GD_ZDRAW_PIXELS": 58,
    "GD_SCRNTYPE": 61, "GD_TEXTPORT": 62, "GD_NMMAPS": 63, "GD_FRAMEGRABBER": 64,
    "GD_TIMERHZ": 66, "GD_DBBOX": 67, "GD_AFUNCTION": 68, "GD_ALPHA_OVERUNDER": 69,
    "GD_BITS_ACBUF": 70, "GD_BITS_ACBUF_HW": 71, "GD_BITS_STENCIL": 72,
    "GD_CLIPPLANES": 73, "GD_FOGVERTEX": 74, "GD_LIGHTING_TWOSIDE": 76,
    "GD_POLYMODE": 77, "GD_POLYSMOOTH": 78, "GD_SCRBOX": 79, "GD_TEXTURE": 80,
    "GD_FOGPIXEL": 81, "GD_TEXTURE_PERSP": 82, "GD_MUXPIPES": 83,
    "GD_MULTISAMPLE": 84, "GD_TEXTURE_3D": 85, "GD_TEXTURE_LUT": 86,
    "GD_TEXTURE_SHARP": 87, "GD_TEXTURE_DETAIL": 88, "GD_STEREO_IN_WINDOW": 89,
    "GD_BLENDCOLOR": 90, "GD_LIGHTING_SPOTLIGHT": 91, "GD_LIGHTING_ATT2": 92,
    "GD_AFUNCTION_MODES": 93,
    "GD_NOLIMIT": -2, "GD_WSYS_NONE": 0, "GD_WSYS_4S": 1,
    "GD_SCRNTYPE_WM": 0, "GD_SCRNTYPE_NOWM": 1,
}

# 1.4 (getgconfig, the values the notes spell out)
GCONFIG = {
    "GC_BITS_CMODE": 0, "GC_BITS_RED": 1, "GC_BITS_GREEN": 2, "GC_BITS_BLUE": 3,
    "GC_BITS_ALPHA": 4, "GC_BITS_ZBUFFER": 5, "GC_ZMIN": 6, "GC_ZMAX": 7,
    "GC_BITS_STENCIL": 8, "GC_BITS_ACBUF": 9, "GC_MS_SAMPLES": 10, "GC_DOUBLE": 16,
}

# 1.5 (accumulation buffer)
ACBUF = {
    "AC_CLEAR": 0, "AC_ACCUMULATE": 1, "AC_CLEAR_ACCUMULATE": 2,
    "AC_RETURN": 3, "AC_MULT": 4, "AC_ADD": 5,
}

# 1.6 (lighting)
LIGHTING = {
    "DEFMATERIAL": 0, "DEFLIGHT": 100, "DEFLMODEL": 200,
    "EMISSION": 1, "AMBIENT": 2, "DIFFUSE": 3, "SPECULAR": 4, "SHININESS": 5,
    "COLORINDEXES": 6, "ALPHA": 7,
    "LCOLOR": 101, "POSITION": 102, "SPOTDIRECTION": 103, "SPOTLIGHT": 104,
    "LOCALVIEWER": 201, "ATTENUATION": 202, "ATTENUATION2": 203, "TWOSIDE": 204,
    "MATERIAL": 1000, "BACKMATERIAL": 1001,
    "LIGHT0": 1100, "LIGHT1": 1101, "LIGHT2": 1102, "LIGHT3": 1103,
    "LIGHT4": 1104, "LIGHT5": 1105, "LIGHT6": 1106, "LIGHT7": 1107,
    "LMODEL": 1200,
    "LMC_COLOR": 0, "LMC_EMISSION": 1, "LMC_AMBIENT": 2, "LMC_DIFFUSE": 3,
    "LMC_SPECULAR": 4, "LMC_AD": 5, "LMC_NULL": 6,
    "MAXLIGHTS": 8, "MAXRESTRICTIONS": 4,
}

# 1.7 - 1.9 (matrices, stacks, primitives, shading, polygon mode)
GEOMETRY = {
    "MSINGLE": 0, "MPROJECTION": 1, "MVIEWING": 2, "MTEXTURE": 3,
    "MATRIXSTACKDEPTH": 32, "ATTRIBSTACKDEPTH": 10, "VPSTACKDEPTH": 8,
    "NAMESTACKDEPTH": 1025,
    "NAUTO": 0, "NNORMALIZE": 1,
    "FLAT": 0, "GOURAUD": 1,
    "PYM_FILL": 1, "PYM_POINT": 2, "PYM_LINE": 3, "PYM_HOLLOW": 4, "PYM_LINE_FAST": 5,
    "TRUE": 1, "FALSE": 0,
}

# 1.10 (textures)
TEXTURE = {
    "TX_MINFILTER": 0x100, "TX_MAGFILTER": 0x200, "TX_WRAP": 0x300, "TX_WRAP_S": 0x310,
    "TX_WRAP_T": 0x320, "TX_TILE": 0x400, "TX_BORDER": 0x500, "TX_NULL": 0,
    "TX_POINT": 0x110, "TX_BILINEAR": 0x220, "TX_MIPMAP": 0x120,
    "TX_MIPMAP_POINT": 0x121, "TX_MIPMAP_LINEAR": 0x122, "TX_MIPMAP_BILINEAR": 0x123,
    "TX_MIPMAP_TRILINEAR": 0x124,
    "TX_REPEAT": 0x301, "TX_CLAMP": 0x302, "TX_SELECT": 0x303, "TX_TEXTURE_0": 0,
    "TV_MODULATE": 0x101, "TV_BLEND": 0x102, "TV_DECAL": 0x103, "TV_COLOR": 0x200,
    "TV_NULL": 0, "TV_ENV0": 0,
    "TX_S": 0, "TX_T": 1, "TX_R": 2, "TX_Q": 3,
    "TG_OFF": 0, "TG_ON": 1, "TG_CONTOUR": 2, "TG_LINEAR": 3, "TG_SPHEREMAP": 4,
    "TG_REFRACTMAP": 5,
}

# 1.11 and Appendix A (readsource, glcompat, smoothing, fog, clip planes, pixmode, ...)
MISC = {
    "SRC_AUTO": 0, "SRC_FRONT": 1, "SRC_BACK": 2, "SRC_ZBUFFER": 3, "SRC_PUP": 4,
    "SRC_OVER": 5, "SRC_UNDER": 6, "SRC_FRAMEGRABBER": 7,
    "GLC_OLDPOLYGON": 0, "GLC_ZRANGEMAP": 1, "GLC_MQUEUERATE": 2, "GLC_SOFTATTACH": 3,
    "GLC_MANAGEBG": 4, "GLC_SLOWMAPCOLORS": 5, "GLC_INPUTCHANGEBUG": 6,
    "GLC_NOBORDERBUG": 7, "GLC_SET_VSYNC": 8, "GLC_GET_VSYNC": 9, "GLC_VSYNC_SLEEP": 10,
    "GLC_COMPATRATE": 15,
    "SMP_OFF": 0, "SMP_ON": 1, "SMP_SMOOTHER": 2,
    "SML_OFF": 0, "SML_ON": 1, "SML_SMOOTHER": 2, "SML_END_CORRECT": 4,
    "PYSM_OFF": 0, "PYSM_ON": 1, "PYSM_SHRINK": 2,
    "DT_OFF": 0, "DT_ON": 1,
    "FG_OFF": 0, "FG_ON": 1, "FG_DEFINE": 2, "FG_VTX_EXP": 2, "FG_VTX_LIN": 3,
    "FG_PIX_EXP": 4, "FG_PIX_LIN": 5, "FG_VTX_EXP2": 6, "FG_PIX_EXP2": 7,
    "CP_OFF": 0, "CP_ON": 1, "CP_DEFINE": 2,
    "PM_SHIFT": 0, "PM_EXPAND": 1, "PM_C0": 2, "PM_C1": 3, "PM_ADD24": 4, "PM_SIZE": 5,
    "PM_OFFSET": 6, "PM_STRIDE": 7, "PM_TTOB": 8, "PM_RTOL": 9, "PM_ZDATA": 10,
    "PM_WARP": 11, "PM_YSTART": 17,
    "NORMALDRAW": 0x010, "PUPDRAW": 0x020, "OVERDRAW": 0x040, "UNDERDRAW": 0x080,
    "CURSORDRAW": 0x100,
    "BLACK": 0, "RED": 1, "GREEN": 2, "YELLOW": 3, "BLUE": 4, "MAGENTA": 5, "CYAN": 6,
    "WHITE": 7,
    "PUP_CLEAR": 0, "PUP_COLOR": 1, "PUP_BLACK": 2, "PUP_WHITE": 3,
    "XMAXSCREEN": 1279, "YMAXSCREEN": 1023,
    "DMRGB": 0,
}

GL_TABLES = {
    "stencil": STENCIL, "depth": DEPTH, "blend": BLEND, "gdesc": GDESC,
    "gconfig": GCONFIG, "acbuf": ACBUF, "lighting": LIGHTING, "geometry": GEOMETRY,
    "texture": TEXTURE, "misc": MISC,
}
GL_VALUES = [(n, v) for table in GL_TABLES.values() for n, v in table.items()]

# Device numbers named in the notes (irisgl_reference.md 1.11; cpython_gl_module.md)
DEVICES = {
    "LEFTMOUSE": 103, "MIDDLEMOUSE": 102, "RIGHTMOUSE": 101, "MENUBUTTON": 101,
    "MOUSEX": 266, "MOUSEY": 267, "DIAL0": 257, "KEYBD": 513, "TIMER0": 515,
    "REDRAW": 528, "INPUTCHANGE": 534, "WINFREEZE": 539, "WINTHAW": 540,
    "WINQUIT": 542, "DEPTHCHANGE": 543, "WINSHUT": 546,
    "ESCKEY": 7, "AKEY": 11, "SPACEKEY": 83, "DOWNARROWKEY": 74, "UPARROWKEY": 81,
}


# ---------------------------------------------------------------------------
# Values
# ---------------------------------------------------------------------------


@pytest.mark.parametrize(("name", "value"), GL_VALUES, ids=[n for n, _ in GL_VALUES])
def test_gl_value(name, value):
    tok = getattr(GL, name)
    assert isinstance(tok, Token)
    assert tok == value
    assert int(tok) == value
    assert repr(tok) == name
    assert tok.name == name
    assert name in GL.__all__


def test_lmnull_is_a_float_zero():
    assert isinstance(GL.LMNULL, FloatToken)
    assert isinstance(GL.LMNULL, float)
    assert GL.LMNULL == 0.0 == 0
    assert repr(GL.LMNULL) == "LMNULL"
    for name, value in [("N_FILL", 1.0), ("N_OUTLINE_POLY", 2.0),
                        ("N_OUTLINE_PATCH", 5.0), ("N_ISOLINE_S", 12.0)]:
        tok = getattr(GL, name)
        assert isinstance(tok, FloatToken) and tok == value and repr(tok) == name


@pytest.mark.parametrize(("name", "value"), sorted(DEVICES.items()))
def test_device_value(name, value):
    tok = getattr(DEVICE, name)
    assert isinstance(tok, Token)
    assert tok == value
    assert repr(tok) == name
    assert DEVICE.by_name(name) == value
    assert name in DEVICE.__all__


def test_menubutton_is_rightmouse():
    assert DEVICE.MENUBUTTON == DEVICE.RIGHTMOUSE == 101
    assert repr(DEVICE.MENUBUTTON) == "MENUBUTTON"
    assert repr(DEVICE.RIGHTMOUSE) == "RIGHTMOUSE"


def test_keyboard_positions():
    # BUTn = n + BUTOFFSET; keys are SGI keyboard positions, not ASCII.
    assert DEVICE.BUTOFFSET == 1
    assert DEVICE.BUT0 == 1 and DEVICE.BUT82 == 83 == DEVICE.MAXKBDBUT
    assert DEVICE.BUT6 == DEVICE.ESCKEY
    assert DEVICE.BUT10 == DEVICE.AKEY
    assert DEVICE.BUT82 == DEVICE.SPACEKEY
    assert DEVICE.RETKEY == 51
    assert DEVICE.BUT102 == DEVICE.LEFTMOUSE
    letters = [getattr(DEVICE, f"{c}KEY") for c in "ABCDEFGHIJKLMNOPQRSTUVWXYZ"]
    digits = [getattr(DEVICE, f"{w}KEY") for w in
              ("ZERO", "ONE", "TWO", "THREE", "FOUR", "FIVE", "SIX", "SEVEN", "EIGHT", "NINE")]
    keys = letters + digits
    assert len(set(keys)) == 36
    assert all(1 <= k <= 83 for k in keys)
    assert [int(getattr(DEVICE, f"F{i}KEY")) for i in range(1, 13)] == list(range(146, 158))
    assert [int(getattr(DEVICE, f"TIMER{i}")) for i in range(4)] == [515, 516, 517, 518]
    assert [int(getattr(DEVICE, f"DIAL{i}")) for i in range(9)] == list(range(257, 266))


def test_shared_values_keep_their_own_names():
    assert GL.BF_DC == 2 and GL.BF_SC == 2
    assert GL.BF_DC == GL.BF_SC
    assert hash(GL.BF_DC) == hash(GL.BF_SC) == hash(2)
    assert GL.BF_DC is not GL.BF_SC
    assert repr(GL.BF_DC) == "BF_DC" and repr(GL.BF_SC) == "BF_SC"
    assert repr(GL.BF_MDC) == "BF_MDC" and repr(GL.BF_MSC) == "BF_MSC"
    assert GL.BF_MDC == GL.BF_MSC == 3
    assert repr(GL.FG_DEFINE) == "FG_DEFINE" and repr(GL.FG_VTX_EXP) == "FG_VTX_EXP"
    assert repr(GL.PUP_CURSOR) == "PUP_CURSOR" and GL.PUP_CURSOR == GL.PUP_COLOR


def test_post_irix5_names():
    assert GL.POST_IRIX5 <= set(GL.__all__)
    for name in ("BF_CA", "BF_MAX", "GD_MULTISAMPLE", "GD_AFUNCTION_MODES", "GC_DOUBLE",
                 "TX_R", "TX_Q"):
        assert name in GL.POST_IRIX5
    for name in ("BF_MIN_SA_MDA", "GD_MUXPIPES", "GD_BITS_STENCIL", "SF_EQUAL"):
        assert name not in GL.POST_IRIX5


# ---------------------------------------------------------------------------
# Module structure
# ---------------------------------------------------------------------------


@pytest.mark.parametrize("module", [GL, DEVICE], ids=["GL", "DEVICE"])
def test_every_constant_is_a_named_token(module):
    assert len(module.__all__) == len(set(module.__all__))
    for name in module.__all__:
        tok = getattr(module, name)
        assert tokens.is_token(tok), name
        assert repr(tok) == name
        assert tok.name == name


@pytest.mark.parametrize("module", [GL, DEVICE], ids=["GL", "DEVICE"])
def test_star_import(module):
    ns: dict = {}
    exec(f"from {module.__name__} import *", ns)
    names = {n for n in ns if n != "__builtins__"}
    assert names == set(module.__all__)


def test_sizes():
    assert len(GL.__all__) >= 449  # every IRIX 5 GL.py + GET.py name, plus POST_IRIX5
    assert len(DEVICE.__all__) >= 400


def test_gl_and_device_names_do_not_conflict():
    # C programs include gl.h and device.h together; a star import of both must agree.
    for name in set(GL.__all__) & set(DEVICE.__all__):
        assert getattr(GL, name) == getattr(DEVICE, name), name


# ---------------------------------------------------------------------------
# Token behaves like an int
# ---------------------------------------------------------------------------


def test_token_arithmetic_gives_plain_ints():
    t = GL.SF_EQUAL
    assert t + 1 == 3 and type(t + 1) is int
    assert 1 + t == 3 and type(1 + t) is int
    assert t * 2 == 4 and t - 2 == 0 and -t == -2 and t // 2 == 1 and t % 2 == 0
    assert GL.NORMALDRAW | GL.PUPDRAW == 0x30
    assert GL.RD_FREEZE | GL.RD_ALPHAONE == 3
    assert 0xFF & GL.LO_ONE == 0xF
    assert t << 1 == 4
    assert [10, 20, 30][GL.SF_EQUAL] == 30  # __index__
    assert isinstance(t, int)


def test_token_comparison_and_hash():
    t = GL.SF_EQUAL
    assert t == 2 and 2 == t and t != 3
    assert GL.SF_LESS < t < GL.SF_LEQUAL
    assert t >= 2 and t <= 2
    assert hash(t) == hash(2)
    d = {2: "two"}
    assert d[t] == "two"
    d2 = {t: "tok"}
    assert d2[2] == "tok"
    assert t in {2, 3}
    assert bool(GL.FALSE) is False and bool(GL.TRUE) is True
    assert sorted([GL.SF_ALWAYS, GL.SF_NEVER, GL.SF_EQUAL]) == [0, 2, 7]


def test_token_str_format_and_serialisation():
    t = GL.SF_EQUAL
    assert repr(t) == "SF_EQUAL"
    assert f"{t!r}" == "SF_EQUAL"
    assert repr([GL.BF_SA, GL.BF_MSA]) == "[BF_SA, BF_MSA]"
    # str/format stay numeric (IntEnum convention; Numba emits globals via str()).
    assert str(t) == "2"
    assert f"{t}" == "2" and f"{t:d}" == "2" and f"{GL.LO_ONE:#x}" == "0xf"
    assert "%d" % t == "2"  # noqa: UP031 (percent formatting is what is tested)
    assert json.dumps([t, GL.LMNULL]) == "[2, 0.0]"
    assert int(str(GL.GD_NOLIMIT)) == -2


@pytest.mark.parametrize("protocol", range(pickle.HIGHEST_PROTOCOL + 1))
def test_token_pickles(protocol):
    for tok in (GL.SF_EQUAL, GL.BF_SC, GL.GD_NOLIMIT, GL.LMNULL, DEVICE.ESCKEY):
        back = pickle.loads(pickle.dumps(tok, protocol))
        assert back == tok
        assert type(back) is type(tok)
        assert repr(back) == repr(tok)
    back = pickle.loads(pickle.dumps({GL.BF_DC: [GL.BF_SC]}, protocol))
    ((k, v),) = back.items()
    assert repr(k) == "BF_DC" and repr(v[0]) == "BF_SC"


def test_token_copy():
    assert copy.copy(GL.SF_EQUAL) is GL.SF_EQUAL
    assert copy.deepcopy([GL.SF_EQUAL])[0] is GL.SF_EQUAL


def test_token_is_read_only():
    with pytest.raises(AttributeError):
        GL.SF_EQUAL.foo = 1  # type: ignore[attr-defined]
    with pytest.raises(AttributeError):
        GL.SF_EQUAL._name = "X"  # type: ignore[misc]
    with pytest.raises(AttributeError):
        GL.LMNULL._name = "X"  # type: ignore[misc]


def test_token_with_numpy():
    a = np.array([GL.SF_EQUAL, GL.LO_XOR, GL.LIGHT7])
    assert a.dtype.kind == "i"
    assert a.tolist() == [2, 6, 1107]
    assert np.int32(GL.SF_EQUAL) == 2
    assert np.asarray([GL.DIFFUSE, 0.8, 0.8, 0.8, GL.LMNULL], dtype=np.float32)[-1] == 0.0


def test_token_constructor_checks():
    t = Token(5, "FIVE")
    assert t == 5 and repr(t) == "FIVE" and t.value == 5
    assert Token(2.0, "TWO") == 2
    with pytest.raises(ValueError):
        Token(2.5, "BAD")
    with pytest.raises(TypeError):
        Token(1, "not a name")
    with pytest.raises(TypeError):
        Token(1, None)  # type: ignore[arg-type]
    f = FloatToken(0.5, "HALF")
    assert f == 0.5 and repr(f) == "HALF" and str(f) == "0.5"


def test_token_in_numba_kernel():
    numba = pytest.importorskip("numba")

    @numba.njit(cache=False)
    def passes(func, ref, val):
        # Tokens used both as a global constant and as an argument.
        if func == GL.SF_EQUAL:
            return ref == val
        if func == GL.SF_ALWAYS:
            return True
        return False

    assert passes(GL.SF_EQUAL, 3, 3)
    assert not passes(GL.SF_EQUAL, 3, 4)
    assert passes(GL.SF_ALWAYS, 0, 1)
    assert not passes(GL.SF_NEVER, 0, 0)


# ---------------------------------------------------------------------------
# define / lookup / family
# ---------------------------------------------------------------------------


def test_lookup():
    assert lookup(GL, "SF_", 2) == "SF_EQUAL"
    assert lookup(GL, "ST_", 3) == "ST_INCR"
    assert lookup(GL, "ZF_", GL.ZF_LEQUAL) == "ZF_LEQUAL"
    assert lookup(GL, "BF_", 2) == "BF_DC"  # first of the names sharing 2
    assert lookup(GL, "GD_", 72) == "GD_BITS_STENCIL"
    assert lookup(GL, "LO_", 0x3) == "LO_SRC"
    assert lookup(GL, "SF_", np.int64(7)) == "SF_ALWAYS"
    assert lookup(GL, "SF_", 99) is None
    assert lookup(GL, "SF_", 99, "99") == "99"
    assert lookup(GL, "SF_", "x") is None
    assert lookup(DEVICE, "", 542) == "WINQUIT"
    assert lookup(vars(GL), "AC_", 3) == "AC_RETURN"


def test_family():
    sf = family(GL, "SF_")
    assert list(sf) == ["SF_NEVER", "SF_LESS", "SF_EQUAL", "SF_LEQUAL",
                        "SF_GREATER", "SF_NOTEQUAL", "SF_GEQUAL", "SF_ALWAYS"]
    assert [int(v) for v in sf.values()] == list(range(8))
    assert len(family(GL, "LIGHT")) == 8
    assert len(family(GL, "ST_")) == 6


def test_define():
    ns: dict = {}
    t = define(ns, "FOO", 3)
    assert ns["FOO"] is t and isinstance(t, Token) and repr(t) == "FOO" and t == 3
    assert define(ns, "FOO", 3) is t  # same value: fine
    with pytest.raises(ValueError):
        define(ns, "FOO", 4)
    f = define(ns, "BAR", 0.0)
    assert isinstance(f, FloatToken) and repr(f) == "BAR"
    a = define(ns, "ALIAS", 3)
    assert a == t and repr(a) == "ALIAS"
    assert lookup(ns, "F", 3) == "FOO"


# ---------------------------------------------------------------------------
# DEVICE.by_name / name_of
# ---------------------------------------------------------------------------


def test_by_name():
    assert DEVICE.by_name("ESCKEY") == 7
    assert repr(DEVICE.by_name("ESCKEY")) == "ESCKEY"
    assert DEVICE.by_name(" esckey\n") == 7
    assert DEVICE.by_name("MENUBUTTON") == 101
    assert DEVICE.by_name("TIMER0") == 515
    for bad in ("NOSUCHKEY", "", "by_name", "__all__"):
        with pytest.raises(KeyError):
            DEVICE.by_name(bad)
    with pytest.raises(TypeError):
        DEVICE.by_name(7)  # type: ignore[arg-type]


def test_name_of():
    assert DEVICE.name_of(7) == "ESCKEY"
    assert DEVICE.name_of(101) == "RIGHTMOUSE"  # not MENUBUTTON / MOUSE1 / BUT100
    assert DEVICE.name_of(103) == "LEFTMOUSE"
    assert DEVICE.name_of(3) == "CTRLKEY"  # not LEFTCTRLKEY / BUT2
    assert DEVICE.name_of(4) == "CAPSLOCKKEY"  # not TIMCOUNT
    assert DEVICE.name_of(83) == "SPACEKEY"  # not MAXKBDBUT
    assert DEVICE.name_of(143) == "LEFTALTKEY"  # not XKBDOFFSET
    assert DEVICE.name_of(515) == "TIMER0"  # not TIMOFFSET
    assert DEVICE.name_of(111) == "SW0"  # not SWBASE
    assert DEVICE.name_of(182) == "SBPICK"  # not SBBASE
    assert DEVICE.name_of(256) == "SGIRESERVED"  # not VALOFFSET
    assert DEVICE.name_of(0) == "NULLDEV"
    assert DEVICE.name_of(110) == "BUT109"  # only known by number
    assert DEVICE.name_of(DEVICE.WINQUIT) == "WINQUIT"
    assert DEVICE.name_of(np.int16(528)) == "REDRAW"
    with pytest.raises(KeyError):
        DEVICE.name_of(9999)
    assert DEVICE.name_of(9999, None) is None
    assert DEVICE.name_of(9999, "?") == "?"
    assert repr(DEVICE.device(266)) == "MOUSEX"


def test_by_name_name_of_round_trip():
    for name in DEVICE.__all__:
        number = DEVICE.by_name(name)
        assert number == getattr(DEVICE, name)
        canonical = DEVICE.name_of(number)
        assert DEVICE.by_name(canonical) == number
    # every device the notes name is its own canonical name, except the alias
    for name, number in DEVICES.items():
        expected = "RIGHTMOUSE" if name == "MENUBUTTON" else name
        assert DEVICE.name_of(number) == expected
        assert DEVICE.name_of(DEVICE.by_name(name)) == expected
    # and each canonical number maps back to the name (no two primary names collide)
    for name in DEVICE.__all__:
        if name.startswith("BUT") and name[3:].isdigit():
            continue
        if name in ("MENUBUTTON", "LEFTCTRLKEY", "MOUSE1", "MOUSE2", "MOUSE3",
                    "SWBASE", "SBBASE") or "OFFSET" in name or "COUNT" in name:
            continue
        if name in ("MAXKBDBUT", "MAXSGIDEVICE"):
            continue
        assert DEVICE.name_of(DEVICE.by_name(name)) == name


def test_device_classes():
    assert DEVICE.is_button(DEVICE.LEFTMOUSE) and DEVICE.is_button(DEVICE.ESCKEY)
    assert not DEVICE.is_button(DEVICE.MOUSEX)
    assert DEVICE.is_valuator(DEVICE.MOUSEX) and DEVICE.is_valuator(DEVICE.DIAL0)
    assert not DEVICE.is_valuator(DEVICE.REDRAW)
    assert DEVICE.is_timer(DEVICE.TIMER0) and DEVICE.is_timer(DEVICE.TIMER3)
    assert not DEVICE.is_timer(DEVICE.KEYBD)
    assert DEVICE.is_keyboard(DEVICE.AKEY) and DEVICE.is_keyboard(DEVICE.F12KEY)
    assert DEVICE.is_keyboard(DEVICE.PADPLUSKEY)
    assert not DEVICE.is_keyboard(DEVICE.LEFTMOUSE)
    assert not DEVICE.is_keyboard(DEVICE.REDRAW)
