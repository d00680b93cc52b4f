"""One window's OpenGL surface: an OSMesa context drawing into a framebuffer object.

The context and the translation of a :class:`~vgxsim.state.raster.RasterState` into
GL state (pixel centres, the stencil() ``pass`` rule with the z-buffer off, 24-bit
signed z, blend factors, logic ops, culling) are those of the Mesa peer
(:class:`vgxsim.reference.mesa.MesaPeer`, whose docstring gives the mapping and
its reasons).  What a backend needs beyond the peer is here:

* Front and back colour buffers: OSMesa has one, so the surface draws into a
  framebuffer object with two RGBA8 colour textures and a DEPTH24_STENCIL8
  texture.  frontbuffer(TRUE) and backbuffer(TRUE) together select both
  attachments with ``glDrawBuffers``; fixed-function colour goes to every draw
  buffer, and each blends with its own destination, as IRIS does.
* The planes are the numpy arrays of :class:`~vgxsim.state.planes.Framebuffer`:
  uploaded with ``glTexSubImage2D`` (no fragment operations touch them) and read
  back with ``glReadPixels``; depth and stencil travel packed as
  ``GL_UNSIGNED_INT_24_8``, so both round-trip bit-exactly.
"""

from __future__ import annotations

import atexit
import ctypes
import os
import weakref

import numpy as np

from vgxsim import threads
from vgxsim.reference import mesa
from vgxsim.state.planes import ZMIN, Framebuffer
from vgxsim.state.raster import RasterState

_live: weakref.WeakSet = weakref.WeakSet()


@atexit.register
def _close_all() -> None:
    """Destroy the contexts before the interpreter tears PyOpenGL down (a context
    destroyed from __del__ at shutdown makes PyOpenGL print its handler table)."""
    for surface in list(_live):
        surface.close()


#: Fast-path switch: upload only the planes that differ from what GL holds (False:
#: upload every plane before every batch).
UPLOAD_CHANGED_ONLY = True


def _same(plane, known) -> bool:
    return plane is not None and known is not None and np.array_equal(plane, known)


def available() -> bool:
    """Whether PyOpenGL and libOSMesa can be used in this process."""
    return mesa.mesa_available()


def _raw():
    """PyOpenGL's unwrapped image calls (its wrappers know no GL_UNSIGNED_INT_24_8;
    these take a pointer, so every plane moves without conversion)."""
    from OpenGL.raw.GL.VERSION.GL_1_0 import glReadPixels, glTexImage2D
    from OpenGL.raw.GL.VERSION.GL_1_1 import glTexSubImage2D

    return glTexImage2D, glTexSubImage2D, glReadPixels


def _raw_arrays():
    """PyOpenGL's unwrapped vertex-array pointer calls (vertex, colour, texture
    coordinate)."""
    from OpenGL.raw.GL.VERSION.GL_1_1 import glColorPointer, glTexCoordPointer, glVertexPointer

    return glVertexPointer, glColorPointer, glTexCoordPointer


def _ptr(a: np.ndarray):
    return a.ctypes.data_as(ctypes.c_void_p)


def _pick_threads() -> None:
    """llvmpipe reads LP_NUM_THREADS once, at its first context: unless the user set
    it, take vgxsim's render thread count (vgxsim.threads)."""
    if "LP_NUM_THREADS" not in os.environ and not mesa._context_created:
        mesa.set_threads(threads.get_threads())


class Surface(mesa.MesaPeer):
    """The GL side of one framebuffer.

    Parameters
    ----------
    framebuffer : Framebuffer
        The planes this surface uploads from and reads back into; its config
        decides which planes exist (a missing z or stencil plane turns the GL test
        off, as the software batch does).
    """

    #: Texels as 32-bit floats: llvmpipe then filters and applies the texture
    #: environment in float32, not in its 8-bit fixed point (docs/opengl_backend.md,
    #: D6: within one level of the model, where 8-bit texels give two).
    float_texels = True

    def __init__(self, framebuffer: Framebuffer):
        if not available():
            from vgxsim.backends import BackendError

            raise BackendError("the opengl backend needs PyOpenGL and libOSMesa "
                               "(pip install 'vgxsim[opengl]'; apt install libosmesa6)")
        _pick_threads()
        cfg = framebuffer.config
        super().__init__(cfg.width, cfg.height, stencil_bits=8, depth_bits=24, guard=1 << 16)
        self.fb = framebuffer
        self._make_fbo()
        if framebuffer.z is None:
            self.depth_bits = 0
        if framebuffer.stencil is None:
            self.stencil_bits = 0
        self._buffers = None
        self._known: list = [None, None, None, None]  # front, back, z, stencil in GL
        _live.add(self)

    def _make_fbo(self) -> None:
        GL, _ = mesa._import_gl()
        tex_image, _sub, _read = _raw()
        w, h = self.width, self.height
        tex = GL.glGenTextures(3)
        self._tex = [int(t) for t in tex]
        for t, (internal, fmt, typ) in zip(self._tex, (
                (GL.GL_RGBA8, GL.GL_RGBA, GL.GL_UNSIGNED_BYTE),
                (GL.GL_RGBA8, GL.GL_RGBA, GL.GL_UNSIGNED_BYTE),
                (GL.GL_DEPTH24_STENCIL8, GL.GL_DEPTH_STENCIL, GL.GL_UNSIGNED_INT_24_8)),
                strict=True):
            GL.glBindTexture(GL.GL_TEXTURE_2D, t)
            GL.glTexParameteri(GL.GL_TEXTURE_2D, GL.GL_TEXTURE_MIN_FILTER, GL.GL_NEAREST)
            GL.glTexParameteri(GL.GL_TEXTURE_2D, GL.GL_TEXTURE_MAG_FILTER, GL.GL_NEAREST)
            tex_image(GL.GL_TEXTURE_2D, 0, internal, w, h, 0, fmt, typ, None)
        GL.glBindTexture(GL.GL_TEXTURE_2D, 0)
        self._fbo = int(GL.glGenFramebuffers(1))
        GL.glBindFramebuffer(GL.GL_FRAMEBUFFER, self._fbo)
        GL.glFramebufferTexture2D(GL.GL_FRAMEBUFFER, GL.GL_COLOR_ATTACHMENT0,
                                  GL.GL_TEXTURE_2D, self._tex[0], 0)
        GL.glFramebufferTexture2D(GL.GL_FRAMEBUFFER, GL.GL_COLOR_ATTACHMENT1,
                                  GL.GL_TEXTURE_2D, self._tex[1], 0)
        GL.glFramebufferTexture2D(GL.GL_FRAMEBUFFER, GL.GL_DEPTH_STENCIL_ATTACHMENT,
                                  GL.GL_TEXTURE_2D, self._tex[2], 0)
        status = GL.glCheckFramebufferStatus(GL.GL_FRAMEBUFFER)
        if status != GL.GL_FRAMEBUFFER_COMPLETE:
            raise RuntimeError(f"OpenGL framebuffer object incomplete (status 0x{status:X})")
        GL.glPointSize(1.0)
        GL.glDisable(GL.GL_POINT_SMOOTH)

    def begin(self) -> None:
        """Make the context current and upload the planes the CPU changed since
        the last readback (before drawing a batch).

        ``_known`` holds what each GL attachment is known to contain: the arrays
        read back last, or uploaded.  A plane equal to it is not uploaded again;
        after swapbuffers (front and back exchanged) the two colour textures
        exchange their attachments instead of being uploaded.
        """
        GL, _ = mesa._import_gl()
        self._make_current()
        GL.glBindFramebuffer(GL.GL_FRAMEBUFFER, self._fbo)
        self._state = None
        self._buffers = None
        GL.glDisable(GL.GL_TEXTURE_2D)  # until a textured state enables it (apply)
        _tex, sub_image, _read = _raw()
        fb = self.fb
        w, h = self.width, self.height
        known = self._known
        if (fb.back is not None and known[0] is not None and known[1] is not None
                and not _same(fb.front, known[0]) and _same(fb.front, known[1])
                and _same(fb.back, known[0])):
            self._tex[0], self._tex[1] = self._tex[1], self._tex[0]
            known[0], known[1] = known[1], known[0]
            for i in (0, 1):
                GL.glFramebufferTexture2D(GL.GL_FRAMEBUFFER, GL.GL_COLOR_ATTACHMENT0 + i,
                                          GL.GL_TEXTURE_2D, self._tex[i], 0)
        colours = (fb.front,) if fb.back is None else (fb.front, fb.back)
        for i, plane in enumerate(colours):
            if UPLOAD_CHANGED_ONLY and _same(plane, known[i]):
                continue
            data = np.ascontiguousarray(plane).copy()
            GL.glBindTexture(GL.GL_TEXTURE_2D, self._tex[i])
            sub_image(GL.GL_TEXTURE_2D, 0, 0, 0, w, h, GL.GL_RGBA, GL.GL_UNSIGNED_BYTE,
                      _ptr(data))
            known[i] = data
        if fb.z is not None or fb.stencil is not None:
            if not (UPLOAD_CHANGED_ONLY and _same(fb.z, known[2])
                    and _same(fb.stencil, known[3])):
                GL.glBindTexture(GL.GL_TEXTURE_2D, self._tex[2])
                packed = self._packed_depth_stencil()
                sub_image(GL.GL_TEXTURE_2D, 0, 0, 0, w, h, GL.GL_DEPTH_STENCIL,
                          GL.GL_UNSIGNED_INT_24_8, _ptr(packed))
                known[2] = None if fb.z is None else fb.z.copy()
                known[3] = None if fb.stencil is None else fb.stencil.copy()
        GL.glBindTexture(GL.GL_TEXTURE_2D, 0)

    def _packed_depth_stencil(self) -> np.ndarray:
        fb = self.fb
        packed = np.zeros((self.height, self.width), np.uint32)
        if fb.z is not None:
            packed |= (fb.z.astype(np.int64) - ZMIN).astype(np.uint32) << np.uint32(8)
        if fb.stencil is not None:
            packed |= fb.stencil
        return packed

    def end(self, front: bool, back: bool, depth_stencil: bool) -> None:
        """Read the planes a batch drew into back into the numpy arrays."""
        GL, _ = mesa._import_gl()
        _tex, _sub, read = _raw()
        fb = self.fb
        w, h = self.width, self.height
        targets = []
        if front:
            targets.append((0, fb.front))
        if back and fb.back is not None:
            targets.append((1, fb.back))
        for i, plane in targets:
            GL.glReadBuffer(GL.GL_COLOR_ATTACHMENT0 + i)
            out = np.empty((h, w), np.uint32)
            read(0, 0, w, h, GL.GL_RGBA, GL.GL_UNSIGNED_BYTE, _ptr(out))
            plane[...] = out
            self._known[i] = out
        if depth_stencil and (fb.z is not None or fb.stencil is not None):
            raw = np.empty((h, w), np.uint32)
            read(0, 0, w, h, GL.GL_DEPTH_STENCIL, GL.GL_UNSIGNED_INT_24_8, _ptr(raw))
            if fb.z is not None:
                z = ((raw >> np.uint32(8)).astype(np.int32) + np.int32(ZMIN))
                fb.z[...] = z
                self._known[2] = z
            if fb.stencil is not None:
                # Fewer than 8 stencil planes (stensize): only those bits exist.
                st = (raw & np.uint32((1 << fb.config.stencil) - 1)).astype(np.uint8)
                fb.stencil[...] = st
                self._known[3] = st

    def apply(self, state: RasterState) -> None:
        """GL state for ``state``: the peer's mapping plus the draw buffers."""
        if state is self._state:
            return
        self._apply_state(state)
        front = bool(state.draw_front)
        back = bool(state.draw_back)
        if self.fb.back is None:  # single-buffered: one colour buffer takes both
            front, back = front or back, False
        buffers = (front, back)
        if buffers != self._buffers:
            GL, _ = mesa._import_gl()
            att = [a for a, on in zip((GL.GL_COLOR_ATTACHMENT0, GL.GL_COLOR_ATTACHMENT1),
                                      buffers, strict=True) if on]
            GL.glDrawBuffers(len(att) or 1, np.array(att or [GL.GL_NONE], np.uint32))
            self._buffers = buffers

    def draw(self, mode: int, pos: np.ndarray, col: np.ndarray | None,
             tex: np.ndarray | None = None) -> None:
        """Draw vertex arrays (client memory) with the current state.

        Parameters
        ----------
        mode : GL primitive (GL_TRIANGLES or GL_POINTS)
        pos : ndarray, shape (N, 3), float32
            GL window x, y and depth.
        col : ndarray, shape (N, 4), float32, or shape (N,), uint32 packed RGBA, or None
        tex : ndarray, shape (N, 4), float32, optional
            Texture coordinates (s/w, t/w, 0, 1/w) of textured triangles.
        """
        GL, _ = mesa._import_gl()
        vertex_ptr, colour_ptr, coord_ptr = _raw_arrays()
        # The raw calls take pointers: PyOpenGL's wrappers would also store a reference
        # to every array in the context's data (a third of an OpenGL frame in
        # profiles); the arrays are alive until glDrawArrays returns, which is all
        # client arrays need.
        pos = np.ascontiguousarray(pos, np.float32)
        GL.glEnableClientState(GL.GL_VERTEX_ARRAY)
        vertex_ptr(3, GL.GL_FLOAT, 0, _ptr(pos))
        if col is not None:
            GL.glEnableClientState(GL.GL_COLOR_ARRAY)
            col = np.ascontiguousarray(col)
            if col.dtype == np.uint32:
                colour_ptr(4, GL.GL_UNSIGNED_BYTE, 0, _ptr(col))
            else:
                col = col.astype(np.float32, copy=False)
                colour_ptr(4, GL.GL_FLOAT, 0, _ptr(col))
        else:
            GL.glColor4f(0.0, 0.0, 0.0, 0.0)
        if tex is not None:
            tex = np.ascontiguousarray(tex, np.float32)
            GL.glEnableClientState(GL.GL_TEXTURE_COORD_ARRAY)
            coord_ptr(4, GL.GL_FLOAT, 0, _ptr(tex))
        GL.glDrawArrays(mode, 0, pos.shape[0])
        GL.glDisableClientState(GL.GL_VERTEX_ARRAY)
        GL.glDisableClientState(GL.GL_COLOR_ARRAY)
        GL.glDisableClientState(GL.GL_TEXTURE_COORD_ARRAY)

    def close(self) -> None:
        """Free the framebuffer object and destroy the context.

        Freeing the framebuffer object needs this context current; the context
        that was current before is made current again afterwards, because close
        also runs from ``__del__``, whenever the garbage collector chooses, which
        may be between another surface's ``begin`` and its draws (that surface's
        next GL call would then find no context).
        """
        before = mesa._last_peer
        if self._ctx is not None and getattr(self, "_fbo", 0):
            try:
                GL, _ = mesa._import_gl()
                self._make_current()
                GL.glDeleteFramebuffers(1, [self._fbo])
                GL.glDeleteTextures(self._tex)
            except Exception:
                pass
            self._fbo = 0
        super().close()
        if before is not None and before is not self and before._ctx is not None:
            before._make_current()
