"""Texture state of the Mesa peer (vgxsim.reference.mesa): a RasterState's texture
binding (vgxsim.state.textures) as OpenGL 1.x texture state.

* The texture: ``glTexImage2D`` with the binding's texels, row 0 first (GL's row 0
  is t = 0, as texdef2d's); internal format GL_LUMINANCE, GL_LUMINANCE_ALPHA, GL_RGB
  or GL_RGBA for 1..4 components.
* Filters TX_POINT / TX_BILINEAR -> GL_NEAREST / GL_LINEAR; wraps TX_REPEAT /
  TX_CLAMP -> GL_REPEAT / GL_CLAMP_TO_EDGE (docs/numeric_model.md s. 13: the edge
  texel, no border).
* Environments TV_MODULATE / TV_DECAL / TV_BLEND -> GL_MODULATE / GL_DECAL /
  GL_BLEND with GL_TEXTURE_ENV_COLOR.  GL leaves DECAL undefined for luminance
  textures: compare DECAL on 3- and 4-component textures only.
* Coordinates: the peer sends a vertex's (s/w, t/w, 1/w) as ``glTexCoord4d(s/w, t/w,
  0, 1/w)``: GL interpolates (s, t, q) and divides by q per fragment, which is the
  model's perspective-correct division.
"""

from __future__ import annotations

import numpy as np

from vgxsim.state import codes as C
from vgxsim.state.textures import binding

#: Float internal formats (ARB_texture_float) of GL_LUMINANCE .. GL_RGBA.
_FLOAT_FORMATS = {0x1909: 0x8818, 0x190A: 0x8819, 0x1907: 0x8815, 0x1908: 0x8814}


def apply_texture(GL, state, cache: dict, float_texels: bool = False) -> None:
    """Make the GL texture state that of ``state.texture`` (0: texturing off).

    ``float_texels``: store the texels as 32-bit floats (exactly k / 255), so that
    llvmpipe filters and applies the environment in float32 instead of its 8-bit
    fixed point (the OpenGL backend's choice, docs/opengl_backend.md); the peer
    keeps GL's 8-bit formats, as an OpenGL program would use them."""
    if state.texture == 0:
        GL.glDisable(GL.GL_TEXTURE_2D)
        return
    b = binding(state.texture)
    tex = b.texture
    name = cache.get(id(tex))
    if name is None:
        name = int(GL.glGenTextures(1))
        cache[id(tex)] = name
        GL.glBindTexture(GL.GL_TEXTURE_2D, name)
        fmt = {1: GL.GL_LUMINANCE, 2: GL.GL_LUMINANCE_ALPHA, 3: GL.GL_RGB,
               4: GL.GL_RGBA}[tex.nc]
        comps = {1: [0], 2: [0, 3], 3: [0, 1, 2], 4: [0, 1, 2, 3]}[tex.nc]
        data = np.ascontiguousarray(tex.texels[..., comps], np.uint8)
        h, w = data.shape[:2]
        internal = _FLOAT_FORMATS[int(fmt)] if float_texels else fmt
        GL.glTexImage2D(GL.GL_TEXTURE_2D, 0, internal, w, h, 0, fmt, GL.GL_UNSIGNED_BYTE, data)
    GL.glBindTexture(GL.GL_TEXTURE_2D, name)
    filt = {C.TEXF_POINT: GL.GL_NEAREST, C.TEXF_BILINEAR: GL.GL_LINEAR}
    wrap = {C.TEXW_REPEAT: GL.GL_REPEAT, C.TEXW_CLAMP: GL.GL_CLAMP_TO_EDGE}
    GL.glTexParameteri(GL.GL_TEXTURE_2D, GL.GL_TEXTURE_MIN_FILTER, filt[tex.minfilter])
    GL.glTexParameteri(GL.GL_TEXTURE_2D, GL.GL_TEXTURE_MAG_FILTER, filt[tex.magfilter])
    GL.glTexParameteri(GL.GL_TEXTURE_2D, GL.GL_TEXTURE_WRAP_S, wrap[tex.wrap_s])
    GL.glTexParameteri(GL.GL_TEXTURE_2D, GL.GL_TEXTURE_WRAP_T, wrap[tex.wrap_t])
    env = {C.TEV_MODULATE: GL.GL_MODULATE, C.TEV_DECAL: GL.GL_DECAL,
           C.TEV_BLEND: GL.GL_BLEND}[b.env.mode]
    GL.glTexEnvi(GL.GL_TEXTURE_ENV, GL.GL_TEXTURE_ENV_MODE, env)
    GL.glTexEnvfv(GL.GL_TEXTURE_ENV, GL.GL_TEXTURE_ENV_COLOR,
                  np.asarray(b.env.colour, np.float32))
    GL.glEnable(GL.GL_TEXTURE_2D)
