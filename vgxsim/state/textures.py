"""Texture state as data: defined textures, environments, texgen, and bindings.

texdef2d(3G) defines a texture, tevdef(3G) an environment, texgen(3G) how s and t
come from the vertex; texture mapping is on while a non-zero texture *and* a non-zero
environment are bound (texbind(3G), tevbind(3G)).  What a draw needs of all this is
one immutable :class:`Binding`, interned here under a small integer id that the
RasterState carries (``RasterState.texture``; 0: off), so that texture state splits
state records like any other register and a batch packs only the bindings it uses
into arrays for the kernels (:func:`pack_bindings`).

The texture contract (texel centres, perspective-correct coordinates, filters,
wraps, environments) is docs/numeric_model.md section 14.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from . import codes as C


@dataclass(frozen=True, eq=False)
class Texture:
    """One texdef2d definition.

    Attributes
    ----------
    texels : ndarray, shape (H, W, 4), uint8
        RGBA per texel, row 0 the bottom row (t near 0), as texdef2d's image is
        stored; a 1- or 2-component (intensity, intensity-alpha) image is expanded
        to I, I, I, 255 or I, I, I, A, a 3-component one gets alpha 255.
    nc : int
        Components as defined (1..4): the environments treat them differently.
    minfilter, magfilter : int
        TEXF_* (vgxsim.state.codes).
    wrap_s, wrap_t : int
        TEXW_*.
    levels : tuple of ndarray, shape (H_k, W_k, 4), uint8
        Mipmap levels 1, 2, .. down to 1 x 1 (:func:`mipmap_pyramid`); empty unless
        the minification filter is a MIPMAP one.
    """

    texels: np.ndarray
    nc: int
    minfilter: int = C.TEXF_POINT
    magfilter: int = C.TEXF_POINT
    wrap_s: int = C.TEXW_REPEAT
    wrap_t: int = C.TEXW_REPEAT
    levels: tuple = ()


def mipmap_pyramid(texels: np.ndarray) -> tuple:
    """Mipmap levels 1.. of a (H, W, 4) uint8 image, by a 2 x 2 box filter (texdef(3G)).

    Level k + 1 is ``max(W_k // 2, 1)`` x ``max(H_k // 2, 1)``; its texel (i, j) is the
    mean of level k's texels (2i, 2j), (2i + 1, 2j), (2i, 2j + 1), (2i + 1, 2j + 1),
    an index past the last column or row taken as the last (a level one texel wide
    or high averages each texel with itself; an odd size drops its last column or
    row), rounded half up: ``(a + b + c + d + 2) // 4`` per component.

    Returns
    -------
    tuple of ndarray, shape (H_k, W_k, 4), uint8
        Levels 1, 2, .. ending with 1 x 1; empty for a 1 x 1 image.
    """
    out = []
    cur = np.asarray(texels, np.int64)
    while cur.shape[0] > 1 or cur.shape[1] > 1:
        h, w = cur.shape[:2]
        nh, nw = max(h // 2, 1), max(w // 2, 1)
        i0 = np.minimum(2 * np.arange(nw), w - 1)
        i1 = np.minimum(2 * np.arange(nw) + 1, w - 1)
        j0 = np.minimum(2 * np.arange(nh), h - 1)
        j1 = np.minimum(2 * np.arange(nh) + 1, h - 1)
        total = (cur[j0][:, i0] + cur[j0][:, i1]) + (cur[j1][:, i0] + cur[j1][:, i1])
        cur = (total + 2) // 4
        out.append(cur.astype(np.uint8))
    return tuple(out)


@dataclass(frozen=True)
class TexEnv:
    """One tevdef definition: the environment (TEV_*) and TV_COLOR's constant colour
    (0..1 floats, used by TV_BLEND)."""

    mode: int = C.TEV_MODULATE
    colour: tuple = (0.0, 0.0, 0.0, 0.0)


# texgen(3G) modes of one coordinate, as TexGen stores them.
GEN_LINEAR, GEN_CONTOUR, GEN_SPHEREMAP = "linear", "contour", "spheremap"


@dataclass(frozen=True)
class TexGen:
    """Texture-coordinate generation for s and t (texgen(3G)).

    Per coordinate a mode (None: generation off, the coordinate comes from t2*) and
    a plane (a, b, c, d):

    * ``GEN_LINEAR`` (TG_LINEAR): an object-space plane, ``s = plane . (x, y, z, w)``;
    * ``GEN_CONTOUR`` (TG_CONTOUR, OpenGL's GL_EYE_LINEAR): an eye-space plane, already
      transformed by the inverse of the modelview in effect when texgen was called,
      dotted with the eye-space vertex;
    * ``GEN_SPHEREMAP`` (TG_SPHEREMAP, GL_SPHERE_MAP): no plane; the coordinate comes
      from the eye-space reflection vector (docs/numeric_model.md s. 14).
    """

    s_plane: tuple | None = None
    t_plane: tuple | None = None
    s_mode: str | None = None
    t_mode: str | None = None

    def __post_init__(self):
        # A plane given without a mode is TG_LINEAR (the form TexGen(plane, plane)).
        for k in ("s", "t"):
            if getattr(self, f"{k}_mode") is None and getattr(self, f"{k}_plane") is not None:
                object.__setattr__(self, f"{k}_mode", GEN_LINEAR)

    def modes(self) -> tuple:
        """(s mode, t mode), each a GEN_* or None."""
        return self.s_mode, self.t_mode

    def planes(self) -> tuple:
        """(s plane, t plane), each a 4-tuple or None."""
        return self.s_plane, self.t_plane

    @property
    def eye_space(self) -> bool:
        """Whether a coordinate is generated in eye space (TG_CONTOUR, TG_SPHEREMAP):
        the draw needs the modelview and, for the sphere map, the normals."""
        return any(m in (GEN_CONTOUR, GEN_SPHEREMAP) for m in self.modes())


@dataclass(frozen=True, eq=False)
class Binding:
    """What a draw with texturing on needs: texture, environment, texgen."""

    texture: Texture
    env: TexEnv
    texgen: TexGen


_BINDINGS: list[Binding | None] = [None]  # id 0: texturing off
_IDS: dict[tuple, int] = {}


def binding_id(texture: Texture, env: TexEnv, texgen: TexGen) -> int:
    """The id of a binding (the same objects give the same id)."""
    key = (id(texture), env, texgen)
    got = _IDS.get(key)
    if got is not None and _BINDINGS[got].texture is texture:
        return got
    _BINDINGS.append(Binding(texture, env, texgen))
    _IDS[key] = len(_BINDINGS) - 1
    return _IDS[key]


def binding(ident: int) -> Binding:
    """The binding of a non-zero id."""
    b = _BINDINGS[ident]
    if b is None:
        raise KeyError(ident)
    return b


def pack_rgba(texels: np.ndarray) -> np.ndarray:
    """(H, W, 4) uint8 -> (H * W,) uint32 packed 0xAABBGGRR (cpack order)."""
    t = texels.astype(np.uint32)
    return (t[..., 0] | (t[..., 1] << 8) | (t[..., 2] << 16) | (t[..., 3] << 24)).reshape(-1)


def pack_bindings(ids: list[int]):
    """The kernels' texture table for the bindings ``ids`` (in that order).

    Returns
    -------
    info : ndarray, shape (K, X_SIZE), int64
        One row per binding (X_* columns of vgxsim.state.codes).
    env_colour : ndarray, shape (K, 4), float64
        TV_COLOR of each binding's environment, 0..255.
    texels : ndarray, shape (sum of H * W,), uint32
        Every texture's texels, packed, row after row from the bottom, each
        texture's mipmap levels after its level 0.
    """
    info = np.zeros((max(len(ids), 1), C.X_SIZE), np.int64)
    env = np.zeros((max(len(ids), 1), 4), np.float64)
    chunks = []
    offset = 0
    for k, ident in enumerate(ids):
        b = binding(ident)
        tex = b.texture
        h, w = tex.texels.shape[:2]
        info[k] = (offset, w, h, tex.nc, tex.minfilter, tex.magfilter, tex.wrap_s,
                   tex.wrap_t, b.env.mode, 1 + len(tex.levels))
        env[k] = [float(c) * 255.0 for c in b.env.colour]
        for level in (tex.texels, *tex.levels):  # level k at offset + sizes of 0..k-1
            chunks.append(pack_rgba(level))
            offset += level.shape[0] * level.shape[1]
    texels = np.concatenate(chunks) if chunks else np.zeros(1, np.uint32)
    return info, env, np.ascontiguousarray(texels)


__all__ = ["Texture", "TexEnv", "TexGen", "GEN_LINEAR", "GEN_CONTOUR", "GEN_SPHEREMAP",
           "Binding", "binding_id", "binding", "mipmap_pyramid", "pack_bindings",
           "pack_rgba"]
