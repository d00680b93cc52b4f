"""IRIS GL texture calls: texdef2d, tevdef, texbind, tevbind, texgen.

Texture mapping is on while a non-zero texture and a non-zero environment are bound
(texbind(3G), tevbind(3G)); the binding becomes one id in the raster registers
(``RasterState.texture``), so textured and untextured drawing are different state
records and untextured drawing is untouched.  What is modelled, and how texels are
addressed and filtered, is docs/numeric_model.md section 14:

* texdef2d: 1..4 components, TX_MINFILTER TX_POINT, TX_BILINEAR or a MIPMAP filter
  (TX_MIPMAP_POINT, _LINEAR, _BILINEAR, _TRILINEAR, TX_MIPMAP; the pyramid is built
  here by a box filter), TX_MAGFILTER TX_POINT or TX_BILINEAR, TX_WRAP / TX_WRAP_S /
  TX_WRAP_T TX_REPEAT or TX_CLAMP.  TX_TILE, TX_BORDER and TX_SELECT are refused with
  a GLValueError (not modelled);
* tevdef: TV_MODULATE (the default), TV_DECAL, TV_BLEND with TV_COLOR;
* texgen: TX_S / TX_T with TG_LINEAR (an object-space plane), TG_CONTOUR (an
  eye-space plane: transformed by the inverse of the modelview in effect at the
  call, as OpenGL's GL_EYE_LINEAR, its translation [MSDN "Translating texgen"]),
  TG_SPHEREMAP (the reflection-vector sphere map, GL_SPHERE_MAP), TG_ON, TG_OFF.

The image: a numpy array of shape (height, width, nc) with components 0..255 in
the order I / I A / R G B / R G B A, row 0 the bottom row (the Python form of this
emulator; the C call takes packed longs), or a flat sequence of 32-bit words in the
C layout (rows padded to whole words; a word holds its bytes most significant
first, components in memory order I / A I / B G R / A B G R, as texdef2d(3G) packs
them on the big-endian IRIS).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from vgxsim import GL
from vgxsim.state import codes as C
from vgxsim.state.textures import (
    GEN_CONTOUR,
    GEN_LINEAR,
    GEN_SPHEREMAP,
    TexEnv,
    TexGen,
    Texture,
    binding_id,
    mipmap_pyramid,
)

from ._core import (
    GLTypeError,
    GLValueError,
    as_float,
    as_int,
    current,
    describe,
    gl_function,
    window_of,
)

__all__ = ["texdef2d", "tevdef", "texbind", "tevbind", "texgen"]

_FILTERS = {int(GL.TX_POINT): C.TEXF_POINT, int(GL.TX_BILINEAR): C.TEXF_BILINEAR}
# TX_MIPMAP, "the machine's mipmap filter": TX_MIPMAP_BILINEAR, the best of the VGX's
# texture modes (point, bilinear, MIPmap point, linear and bilinear: [pstech] s. 4,
# shared/reference/irisgl_reference.md) (*choice*).
_MIPMAPS = {int(GL.TX_MIPMAP): C.TEXF_MIPMAP_BILINEAR,
            int(GL.TX_MIPMAP_POINT): C.TEXF_MIPMAP_POINT,
            int(GL.TX_MIPMAP_LINEAR): C.TEXF_MIPMAP_LINEAR,
            int(GL.TX_MIPMAP_BILINEAR): C.TEXF_MIPMAP_BILINEAR,
            int(GL.TX_MIPMAP_TRILINEAR): C.TEXF_MIPMAP_TRILINEAR}
_WRAPS = {int(GL.TX_REPEAT): C.TEXW_REPEAT, int(GL.TX_CLAMP): C.TEXW_CLAMP}
_ENVS = {int(GL.TV_MODULATE): C.TEV_MODULATE, int(GL.TV_DECAL): C.TEV_DECAL,
         int(GL.TV_BLEND): C.TEV_BLEND}


class TextureUnit:
    """A window's texture definitions, bindings and texgen state."""

    def __init__(self):
        self.textures: dict[int, Texture] = {}
        self.envs: dict[int, TexEnv] = {}
        self.bound_texture = 0
        self.bound_env = 0
        # Per coordinate (TX_S, TX_T): the defined (GEN_* mode, plane) and whether on.
        self.planes: list = [None, None]
        self.gen_on = [False, False]


def _unit(ctx) -> TextureUnit:
    rec = window_of(ctx)
    if rec.texture is None:  # (made on first use: most windows never texture)
        rec.texture = TextureUnit()
    return rec.texture


def _rebind(ctx) -> None:
    """Put the current binding's id into the raster registers (0: off)."""
    u = _unit(ctx)
    tex = u.textures.get(u.bound_texture)
    env = u.envs.get(u.bound_env)
    ident = 0
    if tex is not None and env is not None:
        (ms, ps), (mt, pt) = ((u.planes[k] if u.gen_on[k] else None) or (None, None)
                              for k in (0, 1))
        gen = TexGen(ps, pt, ms, mt)
        ident = binding_id(tex, env, gen)
    ctx.raster.set(texture=ident)


def _props(name: str, args: tuple, props) -> list[float]:
    if props is None:
        return []
    if isinstance(props, (str, bytes)) or not isinstance(props, (Sequence, np.ndarray)):
        raise GLTypeError(f"{describe(name, args)}: props must be a flat sequence of "
                          f"numbers, not {type(props).__name__}")
    return [as_float(name, args, "props", v) for v in np.asarray(props).reshape(-1).tolist()]


def _index(name: str, args: tuple, v) -> int:
    idx = as_int(name, args, "index", v)
    if not 0 <= idx <= 0x7FFF:
        raise GLValueError(f"{describe(name, args)}: index {idx} is outside 0..32767")
    return idx


def _image(name: str, args: tuple, nc: int, w: int, h: int, image) -> np.ndarray:
    """The image as (h, w, nc) uint8, row 0 the bottom row."""
    if isinstance(image, np.ndarray) and image.ndim == 3:
        if image.shape != (h, w, nc):
            raise GLValueError(f"{describe(name, args)}: image has shape {image.shape}, "
                               f"expected (height, width, nc) = ({h}, {w}, {nc})")
        arr = np.asarray(image)
        if arr.dtype.kind not in "ui" or arr.min() < 0 or arr.max() > 255:
            raise GLValueError(f"{describe(name, args)}: image components must be "
                               f"integers 0..255")
        return arr.astype(np.uint8)
    if isinstance(image, (str, bytes)) or not isinstance(image, (Sequence, np.ndarray)):
        raise GLTypeError(f"{describe(name, args)}: image must be an (height, width, nc) "
                          f"array or a sequence of packed 32-bit words")
    words = np.asarray(image).reshape(-1)
    per_row = (w * nc + 3) // 4
    if words.shape[0] != per_row * h:
        raise GLValueError(f"{describe(name, args)}: image has {words.shape[0]} words, "
                           f"expected {per_row * h} ({h} rows of {per_row})")
    if words.dtype.kind not in "ui":
        raise GLTypeError(f"{describe(name, args)}: image words must be integers")
    raw = (words.astype(np.int64) & 0xFFFFFFFF).astype(">u4").view(np.uint8)
    raw = raw.reshape(h, per_row * 4)[:, :w * nc].reshape(h, w, nc)
    return np.ascontiguousarray(raw[:, :, ::-1])  # memory order A B G R -> R G B A


def _expand(img: np.ndarray) -> np.ndarray:
    """(h, w, nc) -> (h, w, 4) RGBA (see vgxsim.state.textures.Texture)."""
    h, w, nc = img.shape
    out = np.full((h, w, 4), 255, np.uint8)
    if nc <= 2:
        out[..., :3] = img[..., :1]
        if nc == 2:
            out[..., 3] = img[..., 1]
    else:
        out[..., :nc] = img
    return out


@gl_function()
def texdef2d(index: int, nc: int, width: int, height: int, image, np_: int,
             props) -> None:
    """Define texture ``index`` (texdef2d(3G)): ``nc`` components (1..4), a
    ``width`` x ``height`` image and a property list ending in TX_NULL."""
    args = (index, nc, width, height, image, np_, props)
    name = "texdef2d"
    idx = _index(name, args, index)
    if idx == 0:
        raise GLValueError(f"{describe(name, args)}: index 0 is reserved (texbind(.., 0) "
                           f"turns texturing off)")
    ncv = as_int(name, args, "nc", nc)
    if not 1 <= ncv <= 4:
        raise GLValueError(f"{describe(name, args)}: nc {ncv} is outside 1..4")
    w = as_int(name, args, "width", width)
    h = as_int(name, args, "height", height)
    if w < 1 or h < 1:
        raise GLValueError(f"{describe(name, args)}: width and height must be >= 1")
    img = _image(name, args, ncv, w, h, image)
    p = _props(name, args, props)
    fil = {C.X_MINFILTER: C.TEXF_POINT, C.X_MAGFILTER: C.TEXF_POINT}
    wrap = [C.TEXW_REPEAT, C.TEXW_REPEAT]
    i = 0
    while i < len(p) and int(p[i]) != int(GL.TX_NULL):
        tok = int(p[i])
        if i + 1 >= len(p):
            raise GLValueError(f"{describe(name, args)}: property {tok:#x} has no value")
        val = int(p[i + 1])
        if tok in (int(GL.TX_MINFILTER), int(GL.TX_MAGFILTER)):
            if val in _MIPMAPS and tok == int(GL.TX_MAGFILTER):
                raise GLValueError(f"{describe(name, args)}: MIPMAP filter {val:#x} is a "
                                   f"minification filter (TX_MAGFILTER takes TX_POINT or "
                                   f"TX_BILINEAR)")
            if val not in _FILTERS and val not in _MIPMAPS:
                raise GLValueError(f"{describe(name, args)}: filter {val:#x} is not a "
                                   f"valid TX_* filter")
            fil[C.X_MINFILTER if tok == int(GL.TX_MINFILTER) else C.X_MAGFILTER] = \
                _FILTERS.get(val, _MIPMAPS.get(val))
        elif tok in (int(GL.TX_WRAP), int(GL.TX_WRAP_S), int(GL.TX_WRAP_T)):
            if val not in _WRAPS:
                raise GLValueError(f"{describe(name, args)}: wrap {val:#x} is not modelled "
                                   f"(TX_REPEAT, TX_CLAMP are)")
            if tok != int(GL.TX_WRAP_T):
                wrap[0] = _WRAPS[val]
            if tok != int(GL.TX_WRAP_S):
                wrap[1] = _WRAPS[val]
        else:
            raise GLValueError(f"{describe(name, args)}: property {tok:#x} is not modelled "
                               f"(TX_MINFILTER, TX_MAGFILTER, TX_WRAP[_S|_T] are)")
        i += 2
    ctx = current(name, args)
    u = _unit(ctx)
    texels = _expand(img)
    # The pyramid is built once, here, and only for a MIPMAP minification filter.
    levels = mipmap_pyramid(texels) if fil[C.X_MINFILTER] >= C.TEXF_MIPMAP_POINT else ()
    u.textures[idx] = Texture(texels, ncv, fil[C.X_MINFILTER], fil[C.X_MAGFILTER],
                              wrap[0], wrap[1], levels)
    _rebind(ctx)


@gl_function()
def tevdef(index: int, np_: int, props) -> None:
    """Define texture environment ``index`` (tevdef(3G)): TV_MODULATE (default),
    TV_DECAL or TV_BLEND, and TV_COLOR r g b a (the TV_BLEND colour)."""
    args = (index, np_, props)
    name = "tevdef"
    idx = _index(name, args, index)
    if idx == 0:
        raise GLValueError(f"{describe(name, args)}: index 0 is reserved")
    p = _props(name, args, props)
    mode = C.TEV_MODULATE
    colour = (0.0, 0.0, 0.0, 0.0)
    i = 0
    while i < len(p) and int(p[i]) != int(GL.TV_NULL):
        tok = int(p[i])
        if tok in _ENVS:
            mode = _ENVS[tok]
            i += 1
        elif tok == int(GL.TV_COLOR):
            if i + 4 >= len(p):
                raise GLValueError(f"{describe(name, args)}: TV_COLOR needs 4 values")
            colour = tuple(min(max(v, 0.0), 1.0) for v in p[i + 1:i + 5])
            i += 5
        else:
            raise GLValueError(f"{describe(name, args)}: property {tok:#x} is not modelled "
                               f"(TV_MODULATE, TV_DECAL, TV_BLEND, TV_COLOR are)")
    ctx = current(name, args)
    _unit(ctx).envs[idx] = TexEnv(mode, colour)
    _rebind(ctx)


def _bind(name: str, args: tuple, target, index, token, table: str, what: str,
          definer: str) -> None:
    """texbind/tevbind: check the target, bind definition ``index`` of ``table`` (0
    turns texturing off) and re-derive the raster's texture state."""
    if as_int(name, args, "target", target) != int(token):
        raise GLValueError(f"{describe(name, args)}: target must be {token!r}")
    idx = _index(name, args, index)
    ctx = current(name, args)
    u = _unit(ctx)
    if idx and idx not in getattr(u, table):
        raise GLValueError(f"{describe(name, args)}: {what} {idx} is not defined "
                           f"(define it with {definer})")
    setattr(u, "bound_texture" if table == "textures" else "bound_env", idx)
    _rebind(ctx)


@gl_function()
def texbind(target: int, index: int) -> None:
    """Bind texture ``index`` to TX_TEXTURE_0 (texbind(3G)); 0 turns texturing off."""
    _bind("texbind", (target, index), target, index, GL.TX_TEXTURE_0, "textures", "texture",
          "texdef2d")


@gl_function()
def tevbind(target: int, index: int) -> None:
    """Bind environment ``index`` to TV_ENV0 (tevbind(3G)); 0 turns texturing off."""
    _bind("tevbind", (target, index), target, index, GL.TV_ENV0, "envs", "environment",
          "tevdef")


def _eye_plane(ctx, plane: tuple) -> tuple:
    """TG_CONTOUR: the plane in eye coordinates, ``M^-1 p`` for the modelview M in
    effect now (row vectors: an eye point ``e = o M`` is on it where ``e . M^-1 p =
    o . p``), so that the plane stays fixed in eye space however the modelview
    changes later (texgen(3G); OpenGL's GL_EYE_PLANE transforms the same way)."""
    m = ctx.matrices.modelview_matrix()
    try:
        inv = np.linalg.inv(m)
    except np.linalg.LinAlgError:
        inv = np.linalg.pinv(m)
    return tuple(float(v) for v in inv @ np.asarray(plane, np.float64))


@gl_function()
def texgen(coord: int, mode: int, params) -> None:
    """Texture-coordinate generation (texgen(3G)) for TX_S or TX_T: TG_LINEAR defines
    an object-space plane (a, b, c, d: s = a x + b y + c z + d w), TG_CONTOUR a plane
    in eye coordinates (taken through the current modelview), TG_SPHEREMAP the sphere
    map (no parameters); TG_ON turns the defined generation on, TG_OFF off (the
    coordinate comes from t2* again)."""
    args = (coord, mode, params)
    c = as_int("texgen", args, "coord", coord)
    if c not in (int(GL.TX_S), int(GL.TX_T)):
        raise GLValueError(f"{describe('texgen', args)}: coord must be TX_S or TX_T")
    m = as_int("texgen", args, "mode", mode)
    ctx = current("texgen", args)
    u = _unit(ctx)
    if m in (int(GL.TG_LINEAR), int(GL.TG_CONTOUR)):
        p = _props("texgen", args, params)
        if len(p) < 4:
            which = "TG_LINEAR" if m == int(GL.TG_LINEAR) else "TG_CONTOUR"
            raise GLValueError(f"{describe('texgen', args)}: {which} needs a plane of "
                               f"4 values")
        if m == int(GL.TG_LINEAR):
            u.planes[c] = (GEN_LINEAR, tuple(p[:4]))
        else:
            u.planes[c] = (GEN_CONTOUR, _eye_plane(ctx, tuple(p[:4])))
    elif m == int(GL.TG_SPHEREMAP):
        u.planes[c] = (GEN_SPHEREMAP, None)
    elif m == int(GL.TG_ON):
        if u.planes[c] is None:
            raise GLValueError(f"{describe('texgen', args)}: TG_ON before a TG_LINEAR, "
                               f"TG_CONTOUR or TG_SPHEREMAP definition for this coordinate")
        u.gen_on[c] = True
    elif m == int(GL.TG_OFF):
        u.gen_on[c] = False
    else:
        if m == int(GL.TG_REFRACTMAP):
            raise GLValueError(f"{describe('texgen', args)}: TG_REFRACTMAP is not modelled "
                               f"(TG_LINEAR, TG_CONTOUR, TG_SPHEREMAP are)")
        raise GLValueError(f"{describe('texgen', args)}: mode {m} is not a valid TG_* "
                           f"token")
    _rebind(ctx)
