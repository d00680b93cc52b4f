"""The OpenGL backend's batch: the software batch's interface, drawn by OpenGL.

The pipeline hands a batch what it has already decided: triangles after transform,
lighting, clipping and subpixel(3G) snapping (fixed-point window coordinates, the
IRIS lighting equation's colours), lines and points already rasterized into
fragments by the IRIS line and point rules, text and pixel writes as fragments, and
clears of the raster rectangle.  This class keeps them in drawing order and, at a
flush, draws them with OpenGL: triangles as ``GL_TRIANGLES`` (GL interpolates colour
linearly in window space under the identity ortho, which is IRIS's screen-linear
Gouraud rule, shademodel(3G)), fragments as one-pixel ``GL_POINTS`` on their pixel
centres, clears as ``glClear`` inside the scissor box.  The fragment stage -- z,
stencil, alpha test, blending, logic ops, write masks -- is OpenGL's.
"""

from __future__ import annotations

import numpy as np

from vgxsim.backends.opengl.surface import Surface
from vgxsim.batch import CLEAR_COLOUR, CLEAR_STENCIL, CLEAR_Z, MAX_PRIMITIVES, CommandBatch
from vgxsim.kernels.clip import ONE
from vgxsim.state.planes import ZMAX, ZMIN
from vgxsim.state.raster import FLAT, RasterState

Z_SPAN = float(ZMAX - ZMIN)
_TRIANGLES, _POINTS, _CLEAR = range(3)


def gl_window_xy(fixed: np.ndarray) -> np.ndarray:
    """GL window coordinate of a fixed-point IRIS one: IRIS integers are pixel
    centres, GL's lie at half-integers (float32 holds every 1/256 step exactly
    below 2**15 pixels)."""
    return fixed / ONE + 0.5


def gl_depth(zw: np.ndarray) -> np.ndarray:
    """GL depth in [0, 1] of IRIS window z in [-0x800000, 0x7FFFFF] (order kept)."""
    return (np.asarray(zw, np.float64) - ZMIN) / Z_SPAN


class OpenGLBatch(CommandBatch):
    """A :class:`~vgxsim.batch.CommandBatch` whose flush draws with OpenGL.

    Parameters
    ----------
    framebuffer : vgxsim.state.planes.Framebuffer
        The planes: uploaded to GL before a flush draws and read back after it.
    """

    def __init__(self, framebuffer):
        super().__init__(framebuffer)
        self.surface: Surface | None = None

    def _allocate(self) -> None:
        """No kernel arrays: the queue is a list of draw calls."""

    def _reset(self) -> None:
        self._ops: list[tuple] = []
        self.nprims = 0
        self.ntris = 0
        self.nfrags = 0
        self.nruns = 0
        self.nclears = 0

    def _queue(self, op: tuple, count: int) -> None:
        self._ops.append(op)
        self.nprims += count
        if self.nprims >= MAX_PRIMITIVES:
            self.flush()

    def add_triangles(self, xf, yf, zw, col, tris, src, flat_col, rs: RasterState) -> int:
        """Queue triangles in fixed-point window coordinates (parameters as
        :meth:`CommandBatch.add_triangles`); culling is GL's (counter-clockwise in
        window coordinates is front-facing, backface(3G)).

        Returns
        -------
        int
            Number of triangles queued.
        """
        tris = np.asarray(tris, np.int64).reshape(-1, 3)
        nt = tris.shape[0]
        if nt == 0:
            return 0
        flat = rs.shademodel == FLAT or col is None
        corners = tris.reshape(-1)
        pos = np.empty((3 * nt, 3), np.float32)
        pos[:, 0] = gl_window_xy(np.asarray(xf)[corners])
        pos[:, 1] = gl_window_xy(np.asarray(yf)[corners])
        pos[:, 2] = gl_depth(np.asarray(zw)[corners])
        colours = None
        if flat and flat_col is not None:
            per_tri = np.asarray(flat_col, np.float64)[np.asarray(src, np.int64)]
            colours = np.repeat(per_tri, 3, axis=0).astype(np.float32)
        elif col is not None:
            colours = np.asarray(col, np.float32)[corners]
        self.ntris += nt
        self._queue((_TRIANGLES, rs, pos, colours), nt)
        return nt

    def add_fragments(self, xy, z, rgba, rs: RasterState) -> None:
        """Queue fragments (a point, a line, text or pixels) as one-pixel GL points.

        Parameters
        ----------
        xy : ndarray, shape (F, 2), int64
        z : ndarray, shape (F,), int64
        rgba : ndarray, shape (F,), int64 packed 0xAABBGGRR
        """
        n = xy.shape[0]
        if n == 0:
            return
        xy = np.asarray(xy)
        pos = np.empty((n, 3), np.float32)
        pos[:, 0] = xy[:, 0] + 0.5
        pos[:, 1] = xy[:, 1] + 0.5
        pos[:, 2] = gl_depth(z)
        colours = (np.asarray(rgba, np.int64) & 0xFFFFFFFF).astype(np.uint32)
        self.nfrags += n
        self.nruns += 1
        self._queue((_POINTS, rs, pos, colours), 1)

    def add_clear(self, planes: int, colour: int, z: int, stencil: int, rs: RasterState) -> None:
        """Queue a clear of the raster rectangle of ``rs`` through its write masks."""
        if self.fb.z is None:
            planes &= ~CLEAR_Z
        if self.fb.stencil is None:
            planes &= ~CLEAR_STENCIL
        if planes == 0:
            return
        names = {name for bit, name in ((CLEAR_COLOUR, "color"), (CLEAR_Z, "z"),
                                        (CLEAR_STENCIL, "stencil")) if planes & bit}
        values = {"color": int(colour) & 0xFFFFFFFF, "z": int(z), "stencil": int(stencil)}
        self.nclears += 1
        self._queue((_CLEAR, rs, names, values), 1)

    def flush(self) -> None:
        """Draw everything queued with OpenGL, in order, and read the planes back."""
        if not self._ops:
            return
        if self.surface is None:
            self.surface = Surface(self.fb)
        gl = self.surface
        from vgxsim.reference.mesa import _import_gl

        GL, _ = _import_gl()
        gl.begin()
        front = back = False
        for op in self._ops:
            kind, rs = op[0], op[1]
            gl.apply(rs)
            front = front or bool(rs.draw_front) or self.fb.back is None
            back = back or bool(rs.draw_back)
            if kind == _CLEAR:
                gl._clear(op[2], op[3], rs)
            else:
                gl.draw(GL.GL_TRIANGLES if kind == _TRIANGLES else GL.GL_POINTS, op[2], op[3])
        gl.end(front, back, True)
        self.flushes += 1
        self._reset()

    def close(self) -> None:
        """Destroy the GL surface (a later flush makes a new one)."""
        if self.surface is not None:
            self.surface.close()
            self.surface = None


__all__ = ["OpenGLBatch", "gl_depth", "gl_window_xy"]
