"""Texture state of the Mesa peer (vgxsim.reference.mesa): a RasterState's texture
binding (vgxsim.state.textures) as OpenGL 1.x texture state.

* The texture: ``glTexImage2D`` with the binding's texels, row 0 first (GL's row 0
  is t = 0, as texdef2d's); internal format GL_LUMINANCE, GL_LUMINANCE_ALPHA, GL_RGB
  or GL_RGBA for 1..4 components.
* Filters TX_POINT / TX_BILINEAR -> GL_NEAREST / GL_LINEAR, the MIPMAP ones ->
  GL_NEAREST_MIPMAP_NEAREST, NEAREST_MIPMAP_LINEAR, LINEAR_MIPMAP_NEAREST,
  LINEAR_MIPMAP_LINEAR (MSDN "Translating texdef"), with vgxsim's pyramid uploaded
  level by level (GL_TEXTURE_MAX_LEVEL the last); wraps TX_REPEAT /
  TX_CLAMP -> GL_REPEAT / GL_CLAMP_TO_EDGE (docs/numeric_model.md s. 14: the edge
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
        # The pyramid as vgxsim built it, level by level, so that a comparison sees
        # the level choice and the filters, not two box filters.
        for k, level in enumerate(tex.levels, start=1):
            lv = np.ascontiguousarray(level[..., comps], np.uint8)
            GL.glTexImage2D(GL.GL_TEXTURE_2D, k, internal, lv.shape[1], lv.shape[0], 0, fmt,
                            GL.GL_UNSIGNED_BYTE, lv)
        GL.glTexParameteri(GL.GL_TEXTURE_2D, GL.GL_TEXTURE_MAX_LEVEL, len(tex.levels))
    GL.glBindTexture(GL.GL_TEXTURE_2D, name)
    filt = {C.TEXF_POINT: GL.GL_NEAREST, C.TEXF_BILINEAR: GL.GL_LINEAR,
            C.TEXF_MIPMAP_POINT: GL.GL_NEAREST_MIPMAP_NEAREST,
            C.TEXF_MIPMAP_LINEAR: GL.GL_NEAREST_MIPMAP_LINEAR,
            C.TEXF_MIPMAP_BILINEAR: GL.GL_LINEAR_MIPMAP_NEAREST,
            C.TEXF_MIPMAP_TRILINEAR: GL.GL_LINEAR_MIPMAP_LINEAR}
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


def texgen_feedback(peer, modes, planes, texgen_modelview, modelview, obj, normals):
    """Mesa's generated texture coordinates of vertices (feedback mode, drawn as
    points so that GL neither clips nor reorders them).

    Parameters
    ----------
    peer : vgxsim.reference.mesa.MesaPeer
    modes : pair of {'linear', 'contour', 'spheremap'}
        For s and t: GL_OBJECT_LINEAR, GL_EYE_LINEAR, GL_SPHERE_MAP.
    planes : pair of 4-tuples or None
        The planes, given to GL while ``texgen_modelview`` is the modelview (GL
        transforms an eye plane by its inverse then, as texgen(3G) TG_CONTOUR).
    texgen_modelview, modelview : ndarray, shape (4, 4), float64
        IRIS row-vector matrices (the same 16 numbers as GL's column-major ones).
    obj : ndarray, shape (N, 3), float64
        Object-space vertices.
    normals : ndarray, shape (N, 3), float64

    Returns
    -------
    ndarray, shape (N, 2), float64
        (s, t) per vertex, in the order given.
    """
    import ctypes

    from OpenGL.raw.GL.VERSION import GL_1_0 as raw  # PyOpenGL's wrapper breaks here

    from .mesa import _import_gl

    GL, _ = _import_gl()
    peer._make_current()
    name = GL.glGenTextures(1)
    GL.glBindTexture(GL.GL_TEXTURE_2D, name)
    GL.glTexImage2D(GL.GL_TEXTURE_2D, 0, GL.GL_RGBA, 1, 1, 0, GL.GL_RGBA,
                    GL.GL_UNSIGNED_BYTE, np.zeros(4, np.uint8))
    GL.glEnable(GL.GL_TEXTURE_2D)  # Mesa generates coordinates only when texturing
    GL.glMatrixMode(GL.GL_PROJECTION)
    GL.glPushMatrix()
    GL.glLoadIdentity()
    GL.glScaled(1e-4, 1e-4, 1e-4)  # every vertex inside the clip volume
    GL.glMatrixMode(GL.GL_MODELVIEW)
    GL.glPushMatrix()
    GL.glLoadMatrixd(np.asarray(texgen_modelview, np.float64).reshape(-1))
    gl_mode = {"linear": GL.GL_OBJECT_LINEAR, "contour": GL.GL_EYE_LINEAR,
               "spheremap": GL.GL_SPHERE_MAP}
    for coord, enable, mode, plane in zip((GL.GL_S, GL.GL_T),
                                          (GL.GL_TEXTURE_GEN_S, GL.GL_TEXTURE_GEN_T),
                                          modes, planes, strict=True):
        GL.glTexGeni(coord, GL.GL_TEXTURE_GEN_MODE, gl_mode[mode])
        if mode != "spheremap":
            which = GL.GL_OBJECT_PLANE if mode == "linear" else GL.GL_EYE_PLANE
            GL.glTexGendv(coord, which, np.asarray(plane, np.float64))
        GL.glEnable(enable)
    GL.glLoadMatrixd(np.asarray(modelview, np.float64).reshape(-1))
    buf = (ctypes.c_float * 256)()
    raw.glFeedbackBuffer(256, GL.GL_4D_COLOR_TEXTURE, buf)
    raw.glRenderMode(GL.GL_FEEDBACK)
    GL.glDisable(GL.GL_SCISSOR_TEST)
    GL.glBegin(GL.GL_POINTS)
    for v, n in zip(np.asarray(obj, np.float64), np.asarray(normals, np.float64), strict=True):
        GL.glNormal3d(*n)
        GL.glVertex3d(*v)
    GL.glEnd()
    count = raw.glRenderMode(GL.GL_RENDER)
    for enable in (GL.GL_TEXTURE_GEN_S, GL.GL_TEXTURE_GEN_T):
        GL.glDisable(enable)
    GL.glDisable(GL.GL_TEXTURE_2D)
    GL.glDeleteTextures([name])
    GL.glPopMatrix()
    GL.glMatrixMode(GL.GL_PROJECTION)
    GL.glPopMatrix()
    GL.glMatrixMode(GL.GL_MODELVIEW)
    GL.glEnable(GL.GL_SCISSOR_TEST)
    peer._state = None  # texture state changed under the peer
    n = len(obj)
    if count != 13 * n:  # per point: the token, x y z w, r g b a, s t r q
        raise RuntimeError(f"feedback returned {count} values for {n} points")
    per = np.array(buf[:count], np.float64).reshape(n, 13)
    return per[:, 9:11] / per[:, 12:13]
