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
stencil, alpha test, blending, logic ops, write masks -- is OpenGL's, and so is
point and bilinear texturing (:func:`texture_inexpressible`).  What OpenGL 1.x cannot
draw as the numeric model does (:func:`inexpressible`) is drawn by the software
batch on the same planes, in order (docs/opengl_backend.md).
"""

from __future__ import annotations

from dataclasses import fields, replace

import numpy as np

from vgxsim.backends.opengl.surface import Surface, available
from vgxsim.batch import CLEAR_COLOUR, CLEAR_STENCIL, CLEAR_Z, MAX_PRIMITIVES, CommandBatch
from vgxsim.kernels.clip import ONE
from vgxsim.state.planes import ZMAX, ZMIN
from vgxsim.state.raster import BF_MIN_SA_MDA, FLAT, LO_SRC, OP_INCR, RasterState

Z_SPAN = float(ZMAX - ZMIN)
_TRIANGLES, _POINTS, _CLEAR, _CPU = range(4)

#: Test switch: with False, states OpenGL cannot express are drawn by OpenGL anyway
#: (approximately) instead of by the software batch.
EMULATE_INEXPRESSIBLE = True

#: Bilinear texturing drawn by GL (True; within allowed difference D6) or by the
#: software batch, exactly (False).  Point-sampled textures are always GL's.
NATIVE_BILINEAR = True

#: Fast-path switch: consecutive draws of one raster state and one vertex layout go
#: to GL as one glDrawArrays (GL draws an array's primitives in order, so the planes
#: are those of the separate draws); False: one GL draw per queued call.
MERGE_DRAWS = True


def _partial(value: int, width: int) -> bool:
    return value not in (0, (1 << width) - 1)


def inexpressible(rs: RasterState, stencil_planes: int, clear: bool = False) -> list[str]:
    """What of ``rs`` OpenGL 1.x cannot draw exactly (empty: OpenGL draws it).

    Parameters
    ----------
    rs : RasterState
    stencil_planes : int
        stensize of the window.
    clear : bool
        For a clear (masks matter whatever the z-buffer and stencil modes are).

    Returns
    -------
    list of str
        Reasons; a primitive with any is drawn by the software batch instead.
    """
    out = []
    colour = bool(rs.draw_front or rs.draw_back)
    if colour and any(_partial((rs.wmpack >> (8 * i)) & 0xFF, 8) for i in range(4)):
        # glColorMask is per component (wmpack(3G), writemask(3G) are per bit).
        out.append("partial colour write mask")
    if (clear or rs.zbuffer) and _partial(rs.zwritemask & 0xFFFFFF, 24):
        out.append("partial zwritemask")  # glDepthMask is all or nothing
    if not clear and rs.blend_df == BF_MIN_SA_MDA and rs.logicop == LO_SRC:
        out.append("BF_MIN_SA_MDA destination factor")  # GL has it as a source factor only
    if (not clear and rs.stencil and 0 < stencil_planes < 8
            and OP_INCR in (rs.sfail, rs.spass, rs.szpass)):
        # IRIS clamps ST_INCR at 2**stensize - 1; GL's 8-bit buffer at 255.
        out.append("ST_INCR with fewer than 8 stencil planes")
    if not clear and rs.texture:
        out.extend(texture_inexpressible(rs.texture))
    # Overlay, underlay and pop-up planes (drawmode(3G) other than NORMALDRAW) never
    # reach this batch: vgxsim/pipeline/layers.py gives them a software batch of their own.
    return out


def texture_inexpressible(ident: int) -> list[str]:
    """What of texture binding ``ident`` GL 1.x texturing cannot draw as the
    numeric model (docs/numeric_model.md section 14) does (empty: drawn by GL).

    GL_NEAREST/GL_LINEAR and GL_REPEAT/GL_CLAMP_TO_EDGE are the model's point and
    bilinear filters (texel centres at half-integers in both) and its wraps;
    GL_MODULATE/GL_DECAL/GL_BLEND its environments (DECAL on 3 and 4
    components: GL leaves it undefined below).  Texture coordinates arrive as the
    pipeline computed them (texgen, t2*, clipping), as (s/w, t/w, 0, 1/w), and GL's
    per-fragment division by q is the model's perspective correction.  Texels are
    stored as floats (:attr:`Surface.float_texels`), so filtering and environment
    run in float32 against the model's float64.  Not exact -- allowed difference D6:
    the environment takes GL's interpolated colour unrounded where the model rounds
    it to 0..255 first, and float32 bilinear sums round differently now and then;
    :data:`NATIVE_BILINEAR` off leaves bilinear textures to the software batch.
    GL chooses between minifying and magnifying from differences over a 2 x 2 pixel
    quad, not from the exact derivatives of u and v, so unequal TX_MINFILTER and
    TX_MAGFILTER stay on the software batch; so do filters, wraps, environments and
    texgen modes beyond these (mipmaps, TG_SPHEREMAP, ...).
    """
    from vgxsim.state import codes as C
    from vgxsim.state.textures import binding

    b = binding(ident)
    tex = b.texture
    out = []
    if tex.minfilter not in (C.TEXF_POINT, C.TEXF_BILINEAR) or tex.magfilter not in (
            C.TEXF_POINT, C.TEXF_BILINEAR):
        out.append("texture filter not point or bilinear")
    elif tex.minfilter != tex.magfilter:
        out.append("unequal minify and magnify texture filters")
    elif tex.minfilter == C.TEXF_BILINEAR and not NATIVE_BILINEAR:
        out.append("bilinear texture filter (NATIVE_BILINEAR off)")
    if tex.wrap_s not in (C.TEXW_REPEAT, C.TEXW_CLAMP) or tex.wrap_t not in (
            C.TEXW_REPEAT, C.TEXW_CLAMP):
        out.append("texture wrap not repeat or clamp")
    if b.env.mode not in (C.TEV_MODULATE, C.TEV_DECAL, C.TEV_BLEND):
        out.append("texture environment not modulate, decal or blend")
    elif b.env.mode == C.TEV_DECAL and tex.nc < 3:
        out.append("TV_DECAL on a 1- or 2-component texture")
    if any(getattr(b.texgen, f.name) != f.default for f in fields(b.texgen)
           if f.name not in ("s_plane", "t_plane")):
        out.append("texgen mode beyond TG_LINEAR")  # coordinates from a later model
    return out


def gl_window_xy(fixed: np.ndarray) -> np.ndarray:
    """GL window coordinate of a fixed-point IRIS one: IRIS integers are pixel
    centres, GL's lie at half-integers (float32 holds every 1/256 step exactly
    below 2**15 pixels)."""
    return fixed / ONE + 0.5


def gl_depth(zw: np.ndarray) -> np.ndarray:
    """GL depth in [0, 1] of IRIS window z in [-0x800000, 0x7FFFFF] (order kept)."""
    return (np.asarray(zw, np.float64) - ZMIN) / Z_SPAN


def unorm8(rgba: np.ndarray) -> np.ndarray:
    """Vertex colours as packed 0xAABBGGRR words, each component ``floor(c * 255 +
    0.5)`` as the software batch rounds (docs/numeric_model.md): a constant colour
    is then exact, where llvmpipe's own float-to-byte conversion rounds some
    halves down (0.3 gives 76, not 77)."""
    q = np.clip(np.floor(np.asarray(rgba, np.float64) * 255.0 + 0.5), 0, 255).astype(np.uint32)
    return q[..., 0] | (q[..., 1] << 8) | (q[..., 2] << 16) | (q[..., 3] << 24)


def gouraud_colours(corner_rgba: np.ndarray) -> np.ndarray:
    """Float vertex colours, three per triangle, for GL's linear interpolation.

    Unquantized colours follow the software batch's plane equations (it
    interpolates ``c * 255`` and rounds per pixel); a triangle whose three corners
    share one colour gets that colour as an exact ``k / 255``, which llvmpipe then
    writes as ``k`` (its own rounding of 0.3 gives 76, not ``floor(76.5 + 0.5)``).

    Parameters
    ----------
    corner_rgba : ndarray, shape (3 * T, 4), float64

    Returns
    -------
    ndarray, shape (3 * T, 4), float32
    """
    tri = corner_rgba.reshape(-1, 3, 4)
    constant = (tri == tri[:, :1]).all(axis=(1, 2))
    q = np.clip(np.floor(tri * 255.0 + 0.5), 0, 255) / 255.0
    out = np.where(constant[:, None, None], q, tri)
    return out.reshape(-1, 4).astype(np.float32)


def _layout(op: tuple) -> tuple:
    col, coords = op[3], op[4]
    return (op[0], None if col is None else col.dtype, coords is None)


def merged_draws(ops: list[tuple]) -> list[tuple]:
    """``ops`` with each run of consecutive triangle (or point) draws that share a
    raster state and a vertex layout joined into one draw, order kept.

    Parameters
    ----------
    ops : list of tuple
        The batch's queue: ``(kind, state, ...)``; draws are ``(kind, state, pos,
        colours, coords)`` with ``pos`` (N, 3) float32, ``colours`` (N,) uint32 or
        (N, 4) float32 or None, ``coords`` (N, 4) float32 or None.

    Returns
    -------
    list of tuple
    """
    runs: list[list[tuple]] = []
    for op in ops:
        last = runs[-1][-1] if runs else None
        if (last is not None and op[0] in (_TRIANGLES, _POINTS) and last[0] == op[0]
                and (op[1] is last[1] or op[1] == last[1]) and _layout(op) == _layout(last)):
            runs[-1].append(op)
        else:
            runs.append([op])
    out = []
    for run in runs:
        if len(run) == 1:
            out.append(run[0])
            continue
        kind, rs = run[0][0], run[0][1]
        joined = [None if run[0][k] is None else np.concatenate([op[k] for op in run])
                  for k in (2, 3, 4)]
        out.append((kind, rs, *joined))
    return out


def _copies(*arrays):
    return tuple(None if a is None else np.array(a) for a in arrays)


class OpenGLBatch(CommandBatch):
    """A :class:`~vgxsim.batch.CommandBatch` whose flush draws with OpenGL.

    Parameters
    ----------
    framebuffer : vgxsim.state.planes.Framebuffer
        The planes: uploaded to GL before a flush draws and read back after it.
    """

    def __init__(self, framebuffer):
        if not available():
            from vgxsim.backends import BackendError

            raise BackendError("the opengl backend needs PyOpenGL and libOSMesa "
                               "(pip install 'vgxsim[opengl]'; apt install libosmesa6)")
        super().__init__(framebuffer)
        self.surface: Surface | None = None
        # The software batch on the same planes draws what OpenGL cannot express.
        self.software = CommandBatch(framebuffer)
        self._routes: dict = {}
        self._untextured: dict = {}

    def _allocate(self) -> None:
        """No kernel arrays: the queue is a list of draw calls."""

    def _reset(self) -> None:
        self._ops: list[tuple] = []
        self.nprims = 0
        self.ntris = 0
        self.nfrags = 0
        self.nruns = 0
        self.nclears = 0

    def _cpu_route(self, rs: RasterState, clear: bool = False) -> bool:
        if not EMULATE_INEXPRESSIBLE:
            return False
        hit = self._routes.get((rs, clear))
        if hit is None:
            hit = self._routes[(rs, clear)] = bool(
                inexpressible(rs, self.fb.config.stencil, clear))
        return hit

    def _queue(self, op: tuple, count: int) -> None:
        self._ops.append(op)
        self.nprims += count
        if self.nprims >= MAX_PRIMITIVES:
            self.flush()

    def add_triangles(self, xf, yf, zw, col, tris, src, flat_col, rs: RasterState,
                      tex=None) -> int:
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
        textured = bool(rs.texture) and tex is not None
        if self._cpu_route(rs) or (bool(rs.texture) != textured):
            self.ntris += nt
            # Copies: the software batch sets up at the flush, and the caller may
            # reuse its arrays once this call returns.  ``tex``: (Nv, 3) s/w, t/w, 1/w
            # of textured triangles whose texture state GL cannot express.
            self._queue((_CPU, rs, "add_triangles", (*_copies(xf, yf, zw, col, tris, src,
                                                              flat_col), rs,
                                                     *_copies(tex))), nt)
            return nt
        flat = rs.shademodel == FLAT or col is None
        corners = tris.reshape(-1)
        pos = np.empty((3 * nt, 3), np.float32)
        pos[:, 0] = gl_window_xy(np.asarray(xf)[corners])
        pos[:, 1] = gl_window_xy(np.asarray(yf)[corners])
        pos[:, 2] = gl_depth(np.asarray(zw)[corners])
        colours = None
        if flat and flat_col is not None:
            per_tri = np.asarray(flat_col, np.float64)[np.asarray(src, np.int64)]
            colours = np.repeat(unorm8(per_tri), 3, axis=0)
        elif col is not None:
            colours = gouraud_colours(np.asarray(col, np.float64)[corners])
        coords = None
        if textured:
            # (s/w, t/w, 0, 1/w): GL interpolates them linearly in window space and
            # divides by q per fragment, the model's perspective correction.
            t = np.asarray(tex, np.float64)[corners]
            coords = np.zeros((3 * nt, 4), np.float32)
            coords[:, 0], coords[:, 1], coords[:, 3] = t[:, 0], t[:, 1], t[:, 2]
        self.ntris += nt
        self._queue((_TRIANGLES, rs, pos, colours, coords), nt)
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
        if rs.texture:  # only triangles are textured (docs/numeric_model.md section 14)
            rs = self._untextured.get(rs) or self._untextured.setdefault(
                rs, replace(rs, texture=0))
        if self._cpu_route(rs):
            self._queue((_CPU, rs, "add_fragments", (*_copies(xy, z, rgba), rs)), 1)
            return
        xy = np.asarray(xy)
        pos = np.empty((n, 3), np.float32)
        pos[:, 0] = xy[:, 0] + 0.5
        pos[:, 1] = xy[:, 1] + 0.5
        pos[:, 2] = gl_depth(z)
        colours = (np.asarray(rgba, np.int64) & 0xFFFFFFFF).astype(np.uint32)
        self.nfrags += n
        self.nruns += 1
        self._queue((_POINTS, rs, pos, colours, None), 1)

    def add_clear(self, planes: int, colour: int, z: int, stencil: int, rs: RasterState) -> None:
        """Queue a clear of the raster rectangle of ``rs`` through its write masks."""
        if self.fb.z is None:
            planes &= ~CLEAR_Z
        if self.fb.stencil is None:
            planes &= ~CLEAR_STENCIL
        if planes == 0:
            return
        if self._cpu_route(rs, clear=True):
            self._queue((_CPU, rs, "add_clear", (planes, colour, z, stencil, rs)), 1)
            return
        names = {name for bit, name in ((CLEAR_COLOUR, "color"), (CLEAR_Z, "z"),
                                        (CLEAR_STENCIL, "stencil")) if planes & bit}
        values = {"color": int(colour) & 0xFFFFFFFF, "z": int(z), "stencil": int(stencil)}
        self.nclears += 1
        self._queue((_CLEAR, rs, names, values), 1)

    def flush(self) -> None:
        """Draw everything queued, in order, and read the planes back: runs of
        OpenGL draws between an upload and a readback, and the primitives OpenGL
        cannot express drawn by the software batch on the planes in between."""
        if not self._ops:
            return
        from vgxsim.reference.mesa import _import_gl

        GL, _ = _import_gl()
        gl = None
        front = back = False
        single = self.fb.back is None
        for op in merged_draws(self._ops) if MERGE_DRAWS else self._ops:
            kind, rs = op[0], op[1]
            if kind == _CPU:
                if gl is not None:
                    gl.end(front, back, True)
                    gl = None
                getattr(CommandBatch, op[2])(self.software, *op[3])
                continue
            if gl is None:
                self.software.flush()
                if self.surface is None:
                    self.surface = Surface(self.fb)
                gl = self.surface
                gl.begin()
                front = back = False
            gl.apply(rs)
            front = front or bool(rs.draw_front) or single
            back = back or bool(rs.draw_back)
            if kind == _CLEAR:
                gl._clear(op[2], op[3], rs)
            else:
                gl.draw(GL.GL_TRIANGLES if kind == _TRIANGLES else GL.GL_POINTS, op[2], op[3],
                        op[4])
        if gl is not None:
            gl.end(front, back, True)
        self.software.flush()
        self.flushes += 1
        self._reset()

    def close(self) -> None:
        """Destroy the GL surface (a later flush makes a new one)."""
        if self.surface is not None:
            self.surface.close()
            self.surface = None


__all__ = ["OpenGLBatch", "gl_depth", "gl_window_xy"]
