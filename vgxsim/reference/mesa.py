"""Mesa's OpenGL (llvmpipe through OSMesa) as an independent peer of vgxsim.

The peer renders the *same* command lists as the naive reference
(``vgxsim.reference.naive``): triangles given in IRIS GL window coordinates with a
:class:`~vgxsim.state.raster.RasterState` each, and clears.  It is used by the
conformance tests (buffer-by-buffer comparison) and by the benchmarks (speed ratios
against Mesa on the same scene and thread count).

Conventions (see docs/numeric_model.md and DESIGN.md section 4)
------------------------------------------------------------------
* IRIS integer window coordinates are pixel *centres*; GL pixel centres lie at
  half-integers.  IRIS ``x`` maps to GL ``x + 0.5`` (same for ``y``); both have the
  origin at the lower-left pixel.  The modelview is the identity and the
  projection an ortho that maps vertex (x, y) to GL window (x, y) unchanged; it
  equals ``glOrtho(0, W, 0, H, 0, -1)`` with ``glViewport(0, 0, W, H)`` but spans a
  larger viewport (see the guard band below).  Vertex ``z`` is GL window depth.
* Before the offset, vertex x and y are snapped exactly as the numeric model's
  section 2 does (``subpixel(FALSE)``: nearest pixel centre, ties upward;
  ``subpixel(TRUE)``: nearest 1/256), so Mesa sees the same fixed-point vertices
  (llvmpipe also keeps 8 subpixel bits).
* IRIS z in ``[-0x800000, 0x7FFFFF]`` maps linearly to GL depth
  ``(zw + 0x800000) / 0xFFFFFF`` in ``[0, 1]`` (``glDepthRange(0, 1)``), which
  preserves order; the 24-bit depth buffer then holds ``zw + 0x800000`` up to float
  rounding in Mesa's depth interpolation.  ``GL_DEPTH_CLAMP`` is enabled so that no
  geometry is clipped by the near/far planes.
* IRIS ``stencil(enable, ref, func, mask, fail, pass, zpass)`` becomes
  ``glStencilFunc(func, ref & 0xFF, mask)`` and ``glStencilOp(fail, pass, zpass)``
  when the z-buffer is on.  With the z-buffer off IRIS applies ``pass`` to a
  fragment that passes the stencil test (stencil(3G): ``zpass`` "is not significant
  when the z-buffer is not enabled") while GL applies its zpass op, so the peer passes
  ``pass`` as GL's zpass op in that case.

Differences that cannot be removed
----------------------------------
* Tie rule: GL does not fix one.  llvmpipe's rule (Mesa 22.3, half-pixel centres,
  lower-left origin) turned out to be the numeric model's: left edges and
  horizontal bottom edges own the pixel centres on them.  Randomised comparisons
  (both subpixel modes, vertices far outside the window) found no coverage
  difference, but only because the peer uses a guard band (below): when GL's
  clipper cuts a triangle, the new vertices are off the original edges and tie
  pixels move.  Tests that must not depend on this should keep edges off pixel
  centres.
* Guard band: the GL viewport is a power-of-two square (8192 by default, at most
  GL_MAX_VIEWPORT_DIMS) centred on the window, with the matching ortho projection,
  so triangles reaching ``guard`` pixels beyond the window are not clipped and
  window coordinates pass through float32 unchanged.
* Depth: llvmpipe interpolates z in float32, so on a sloped triangle the stored
  depth may differ from ours by a few tens of units of 2**-24 (seen up to about
  30); constant-z triangles and clears are exact.  Compare with a tolerance, or
  compare the depth-test outcome rather than the stored value.
* Per-bit write masks: ``glColorMask`` is per component and ``glDepthMask`` all or
  nothing, so a ``wmpack`` byte counts as enabled when it is nonzero and
  ``zwritemask`` as enabled when its low 24 bits are nonzero.  Partial masks are
  not reproduced (:func:`mesa_caveats` lists them).  The stencil write mask is
  per bit in GL too and is exact.
* Rounding: Gouraud colours and blending use llvmpipe's own rounding, which may
  differ from ours by one unit (Gouraud: about 1 pixel in 30 000 in a randomised
  check); the alpha test compares llvmpipe's float alpha with ``aref / 255``.
* Logic ops: ``GL_CLEAR + op`` (the LO_* and GL logic-op tables are in the same
  order).  Note that this order is the X11 one, in which the result for source
  bit ``s`` and destination bit ``d`` is bit ``3 - (2*s + d)`` of ``op``.
* Draw buffers: OSMesa has one colour buffer.  It stands for whichever of
  front/back is enabled; with neither enabled colour writes are off.

Threads
-------
llvmpipe reads ``LP_NUM_THREADS`` once, when the first OSMesa context of the
process creates its screen; later changes have no effect.  Call :func:`set_threads`
(or export ``LP_NUM_THREADS``) before creating the first :class:`MesaPeer`.
``LP_NUM_THREADS=0`` rasterizes in the calling thread.
"""

from __future__ import annotations

import ctypes
import math
import os
from collections.abc import Iterable, Sequence
from typing import Any

import numpy as np

from vgxsim.state.raster import (
    BF_MIN_SA_MDA,
    CULL_BACK,
    CULL_FRONT,
    CULL_NONE,
    FLAT,
    LO_SRC,
    RasterState,
)

__all__ = [
    "MesaArrays",
    "MesaPeer",
    "iris_z_to_gl",
    "gl_depth_to_iris",
    "mesa_available",
    "mesa_caveats",
    "mesa_renderer_string",
    "mesa_version_string",
    "set_threads",
]

Z_MIN = -0x800000
Z_MAX = 0x7FFFFF
Z_SPAN = 0xFFFFFF
SUBPIXEL_ONE = 256

_available: bool | None = None
_context_created = False  # set once any OSMesa context exists in this process
_GL: Any = None  # OpenGL.GL, imported lazily
_last_peer: Any = None  # the MesaPeer whose context was made current last
_OSMESA: Any = None  # OpenGL.osmesa, imported lazily


# ---------------------------------------------------------------------------
# Import and process-level setup


def _import_gl() -> tuple[Any, Any]:
    """Import PyOpenGL on the OSMesa platform (once) and return ``(GL, osmesa)``."""
    global _GL, _OSMESA
    if _GL is None:
        import sys

        # PyOpenGL picks its platform when OpenGL.platform is first imported.
        if "OpenGL.platform" not in sys.modules:
            os.environ["PYOPENGL_PLATFORM"] = "osmesa"
        from OpenGL import platform

        if not hasattr(platform.PLATFORM, "OSMesa"):
            raise ImportError(
                "PyOpenGL chose another platform before PYOPENGL_PLATFORM=osmesa was "
                "set; the OSMesa peer cannot be used in this process"
            )
        from OpenGL import GL, osmesa

        _GL, _OSMESA = GL, osmesa
    return _GL, _OSMESA


def mesa_available() -> bool:
    """Tell whether PyOpenGL and Mesa's OSMesa library can be used.

    Sets ``PYOPENGL_PLATFORM=osmesa`` before importing OpenGL.  No context is
    created, so :func:`set_threads` still works afterwards.

    Returns
    -------
    bool
        True when OSMesa contexts can be created; False (never an exception) when
        PyOpenGL or libOSMesa is missing, or PyOpenGL was already imported on
        another platform.
    """
    global _available
    if _available is None:
        try:
            _import_gl()
            from OpenGL import platform

            lib = platform.PLATFORM.OSMesa  # the loaded libOSMesa (ctypes CDLL)
            for symbol in ("OSMesaCreateContextExt", "OSMesaMakeCurrent", "glReadPixels"):
                getattr(lib, symbol)  # AttributeError when the symbol is missing
            _available = True
        except Exception:  # ImportError, missing library, null function, ...
            _available = False
    return _available


def set_threads(n: int) -> None:
    """Set llvmpipe's rasterizer thread count (``LP_NUM_THREADS``).

    llvmpipe reads the variable once, when the first OSMesa context of the process
    is created, so this must be called before any :class:`MesaPeer` exists (or the
    variable exported before Python starts).  ``n = 0`` rasterizes in the calling
    thread.

    Parameters
    ----------
    n : int
        Number of rasterizer threads, ``>= 0``.

    Raises
    ------
    ValueError
        If ``n`` is negative.
    RuntimeError
        If a context was already created with a different setting: the new value
        would be silently ignored.
    """
    if n < 0:
        raise ValueError(f"thread count must be >= 0, got {n}")
    value = str(int(n))
    if _context_created:
        if os.environ.get("LP_NUM_THREADS") == value:
            return
        raise RuntimeError(
            "LP_NUM_THREADS must be set before the first OSMesa context is created; "
            f"it is {os.environ.get('LP_NUM_THREADS')!r} for this process"
        )
    os.environ["LP_NUM_THREADS"] = value


def _gl_string(name: str) -> str:
    GL, _ = _import_gl()
    temp = _last_peer is None or _last_peer._ctx is None
    peer = MesaPeer(1, 1) if temp else _last_peer
    try:
        peer._make_current()
        raw = GL.glGetString(getattr(GL, name))
    finally:
        if temp:
            peer.close()
    return raw.decode() if isinstance(raw, bytes) else str(raw)


def mesa_renderer_string() -> str:
    """Return ``GL_RENDERER``, e.g. ``"llvmpipe (LLVM 15.0.6, 256 bits)"``.

    Creates a 1x1 context if none exists yet, which fixes the thread count (see
    :func:`set_threads`).

    Returns
    -------
    str
        The renderer string.
    """
    return _gl_string("GL_RENDERER")


def mesa_version_string() -> str:
    """Return ``GL_VERSION``, e.g. ``"4.5 (Compatibility Profile) Mesa 22.3.6"``.

    Returns
    -------
    str
        The version string (it names the Mesa release).
    """
    return _gl_string("GL_VERSION")


# ---------------------------------------------------------------------------
# Coordinate and state translation


def iris_z_to_gl(zw: float | np.ndarray) -> float | np.ndarray:
    """Map IRIS window z (24-bit signed units) to GL window depth in ``[0, 1]``.

    Parameters
    ----------
    zw : float or ndarray
        IRIS z in ``[-0x800000, 0x7FFFFF]``.

    Returns
    -------
    float or ndarray
        ``(zw + 0x800000) / 0xFFFFFF``.
    """
    return (zw - Z_MIN) / Z_SPAN


def gl_depth_to_iris(d: float | np.ndarray) -> int | np.ndarray:
    """Map GL window depth in ``[0, 1]`` back to IRIS z (rounded to an integer).

    Parameters
    ----------
    d : float or ndarray
        GL depth.

    Returns
    -------
    int or ndarray
        ``round(d * 0xFFFFFF) - 0x800000`` (int32 for arrays).
    """
    if np.ndim(d) == 0:
        return int(math.floor(float(d) * Z_SPAN + 0.5)) + Z_MIN
    return (np.floor(np.asarray(d, np.float64) * Z_SPAN + 0.5) + Z_MIN).astype(np.int32)


def _snap(v: float, subpixel: bool) -> float:
    """Snap one window coordinate as numeric_model.md section 2 does."""
    if subpixel:
        return math.floor(v * SUBPIXEL_ONE + 0.5) / SUBPIXEL_ONE
    return float(math.floor(v + 0.5))


def _snap_array(v: np.ndarray, subpixel: bool) -> np.ndarray:
    if subpixel:
        return np.floor(v * SUBPIXEL_ONE + 0.5) / SUBPIXEL_ONE
    return np.floor(v + 0.5)


def mesa_caveats(state: RasterState) -> list[str]:
    """List what of ``state`` the peer cannot reproduce exactly in OpenGL.

    Parameters
    ----------
    state : RasterState
        The state to check.

    Returns
    -------
    list of str
        One line per inexact feature (empty when GL expresses the state exactly,
        up to rounding and tie-rule differences, which apply always).
    """
    out = []
    for i, name in enumerate("rgba"):
        byte = (state.wmpack >> (8 * i)) & 0xFF
        if byte not in (0, 0xFF):
            out.append(f"wmpack {name} byte 0x{byte:02X} is partial; GL writes all or nothing")
    zwm = state.zwritemask & 0xFFFFFF
    if zwm not in (0, 0xFFFFFF):
        out.append(f"zwritemask 0x{zwm:06X} is partial; glDepthMask is all or nothing")
    if state.draw_front and state.draw_back:
        out.append("front and back both drawn; OSMesa has one colour buffer")
    if state.blend_df == BF_MIN_SA_MDA:
        out.append("BF_MIN_SA_MDA is a source-only factor")
    return out


def _cmp(GL: Any, code: int) -> int:
    if not 0 <= code <= 7:
        raise ValueError(f"comparison code must be 0..7, got {code}")
    return GL.GL_NEVER + code  # GL_NEVER..GL_ALWAYS are in the same order as SF_/ZF_/AF_


def _stencil_op(GL: Any, op: int) -> int:
    table = (GL.GL_KEEP, GL.GL_ZERO, GL.GL_REPLACE, GL.GL_INCR, GL.GL_DECR, GL.GL_INVERT)
    if not 0 <= op < len(table):
        raise ValueError(f"stencil op must be 0..5, got {op}")
    return table[op]


def _blend_factors(GL: Any, sf: int, df: int) -> tuple[int, int]:
    common = {
        0: GL.GL_ZERO,
        1: GL.GL_ONE,
        4: GL.GL_SRC_ALPHA,
        5: GL.GL_ONE_MINUS_SRC_ALPHA,
        6: GL.GL_DST_ALPHA,
        7: GL.GL_ONE_MINUS_DST_ALPHA,
    }
    src = dict(common)
    src.update({2: GL.GL_DST_COLOR, 3: GL.GL_ONE_MINUS_DST_COLOR,
                BF_MIN_SA_MDA: GL.GL_SRC_ALPHA_SATURATE})
    dst = dict(common)
    dst.update({2: GL.GL_SRC_COLOR, 3: GL.GL_ONE_MINUS_SRC_COLOR})
    if sf not in src:
        raise ValueError(f"invalid source blend factor {sf}")
    if df not in dst:
        raise ValueError(f"invalid destination blend factor {df}")
    return src[sf], dst[df]


def _color_mask(state: RasterState) -> tuple[bool, bool, bool, bool]:
    if not (state.draw_front or state.draw_back):
        return (False, False, False, False)
    m = state.wmpack
    return tuple(bool((m >> (8 * i)) & 0xFF) for i in range(4))  # type: ignore[return-value]


# ---------------------------------------------------------------------------
# Vertex arrays


class MesaArrays:
    """Triangle vertex data uploaded to GL buffer objects of one :class:`MesaPeer`.

    Made by :meth:`MesaPeer.upload_arrays`; drawn by :meth:`MesaPeer.draw_arrays`.

    Attributes
    ----------
    count : int
        Number of vertices (three per triangle).
    """

    def __init__(self, peer: MesaPeer, vbo_pos: int, vbo_col: int, count: int):
        self._peer = peer
        self._vbo_pos = vbo_pos
        self._vbo_col = vbo_col
        self.count = count

    def delete(self) -> None:
        """Free the GL buffers (the owning peer's context must still exist)."""
        if self._vbo_pos and self._peer._ctx is not None:
            GL, _ = _import_gl()
            self._peer._make_current()
            GL.glDeleteBuffers(2, np.array([self._vbo_pos, self._vbo_col], np.uint32))
        self._vbo_pos = self._vbo_col = 0


# ---------------------------------------------------------------------------
# The peer


class MesaPeer:
    """An OSMesa RGBA context that renders vgxsim command lists with OpenGL.

    Every method makes this peer's context current first, so several peers may be
    used in one process in any order.

    Parameters
    ----------
    width, height : int
        Window size in pixels.
    stencil_bits : int, optional
        Stencil planes (default 8).
    depth_bits : int, optional
        Depth bits (default 24; the IRIS z mapping assumes 24).
    guard : int, optional
        Pixels beyond each window edge inside the GL viewport (default 2048), so
        that GL does not clip (and move the tie pixels of) triangles reaching that
        far.  The viewport is the smallest power-of-two square holding the window
        plus the guard on each side, capped at ``GL_MAX_VIEWPORT_DIMS``.

    Examples
    --------
    >>> peer = MesaPeer(8, 8)                                    # doctest: +SKIP
    >>> st = RasterState(scissor=(0, 7, 0, 7))                   # doctest: +SKIP
    >>> peer.render([("clear", {"color"}, {"color": 0xFF0000FF}, st)])  # doctest: +SKIP
    >>> hex(peer.color()[0, 0])                                  # doctest: +SKIP
    '0xff0000ff'
    """

    #: Texels as 32-bit floats (vgxsim.reference.mesa_texture.apply_texture); the
    #: peer keeps GL's 8-bit formats.
    float_texels = False

    def __init__(self, width: int, height: int, stencil_bits: int = 8, depth_bits: int = 24,
                 guard: int = 2048):
        global _context_created, _last_peer
        if width <= 0 or height <= 0:
            raise ValueError(f"window size must be positive, got {width}x{height}")
        GL, osmesa = _import_gl()
        self.width = int(width)
        self.height = int(height)
        self.stencil_bits = int(stencil_bits)
        self.depth_bits = int(depth_bits)
        self._guard = max(int(guard), 0)
        self._ctx = None
        ctx = None
        try:
            attribs = [
                osmesa.OSMESA_FORMAT, osmesa.OSMESA_RGBA,
                osmesa.OSMESA_DEPTH_BITS, self.depth_bits,
                osmesa.OSMESA_STENCIL_BITS, self.stencil_bits,
                osmesa.OSMESA_ACCUM_BITS, 0,
                osmesa.OSMESA_PROFILE, osmesa.OSMESA_COMPAT_PROFILE,
                0,
            ]
            ctx = osmesa.OSMesaCreateContextAttribs(attribs, None)
        except Exception:
            ctx = None
        if not ctx:
            ctx = osmesa.OSMesaCreateContextExt(
                osmesa.OSMESA_RGBA, self.depth_bits, self.stencil_bits, 0, None
            )
        if not ctx:
            raise RuntimeError("OSMesa context creation failed")
        _context_created = True
        self._ctx = ctx
        self._buf = (ctypes.c_ubyte * (self.width * self.height * 4))()
        self._state: RasterState | None = None
        _last_peer = self
        self._make_current()
        self._init_gl()

    # -- context handling -------------------------------------------------

    def _make_current(self) -> None:
        global _last_peer
        if self._ctx is None:
            raise RuntimeError("MesaPeer is closed")
        GL, osmesa = _import_gl()
        if not osmesa.OSMesaMakeCurrent(
            self._ctx, self._buf, GL.GL_UNSIGNED_BYTE, self.width, self.height
        ):
            raise RuntimeError("OSMesaMakeCurrent failed")
        _last_peer = self

    def _init_gl(self) -> None:
        GL, _ = _import_gl()
        # Guard band: GL clips primitives to the viewport, and the vertices the
        # clipper makes are no longer exactly on the original edges, which moves
        # tie pixels.  So the viewport is a power-of-two square, larger than the
        # window, with the window inside it; the ortho projection over it maps GL
        # window x to itself (an exact float32 computation), and pixels outside
        # the buffer are discarded by Mesa.
        max_dims = GL.glGetIntegerv(GL.GL_MAX_VIEWPORT_DIMS)
        limit = int(min(max_dims[0], max_dims[1]))
        size = 1
        while size < max(self.width, self.height) + 2 * self._guard and size * 2 <= limit:
            size *= 2
        size = max(size, self.width, self.height)
        mx, my = (size - self.width) // 2, (size - self.height) // 2
        self._viewport = (-mx, -my, size)
        GL.glViewport(-mx, -my, size, size)
        GL.glDepthRange(0.0, 1.0)
        GL.glMatrixMode(GL.GL_PROJECTION)
        GL.glLoadIdentity()
        # z_ndc = 2 z - 1 for vertex z, so window depth == vertex z.
        GL.glOrtho(-mx, size - mx, -my, size - my, 0.0, -1.0)
        GL.glMatrixMode(GL.GL_MODELVIEW)
        GL.glLoadIdentity()
        GL.glDisable(GL.GL_DITHER)
        GL.glDisable(GL.GL_LIGHTING)
        GL.glEnable(GL.GL_DEPTH_CLAMP)
        GL.glEnable(GL.GL_SCISSOR_TEST)
        GL.glFrontFace(GL.GL_CCW)
        GL.glPixelStorei(GL.GL_PACK_ALIGNMENT, 1)
        GL.glPixelStorei(GL.GL_UNPACK_ALIGNMENT, 1)
        self.depth_bits = int(GL.glGetIntegerv(GL.GL_DEPTH_BITS))
        self.stencil_bits = int(GL.glGetIntegerv(GL.GL_STENCIL_BITS))

    def close(self) -> None:
        """Destroy the OSMesa context (safe to call twice)."""
        global _last_peer
        if self._ctx is not None:
            _, osmesa = _import_gl()
            osmesa.OSMesaDestroyContext(self._ctx)
            self._ctx = None
        if _last_peer is self:
            _last_peer = None

    def __enter__(self) -> MesaPeer:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def __del__(self) -> None:
        try:
            self.close()
        except Exception:
            pass

    # -- state -----------------------------------------------------------

    def _apply_state(self, state: RasterState) -> None:
        """Translate ``state`` into GL state (skipped when unchanged)."""
        if state == self._state:
            return
        GL, _ = _import_gl()
        # Raster rectangle (inclusive bounds) -> scissor box, clipped to the window.
        x0, x1, y0, y1 = (int(v) for v in state.scissor)
        x0, y0 = max(x0, 0), max(y0, 0)
        x1, y1 = min(x1, self.width - 1), min(y1, self.height - 1)
        GL.glScissor(x0, y0, max(x1 - x0 + 1, 0), max(y1 - y0 + 1, 0))

        # Alpha test.
        if state.afunc == 7:
            GL.glDisable(GL.GL_ALPHA_TEST)
        else:
            GL.glEnable(GL.GL_ALPHA_TEST)
            GL.glAlphaFunc(_cmp(GL, state.afunc), state.aref / 255.0)

        # Stencil: IRIS (fail, pass, zpass) -> GL (sfail, dpfail, dppass).
        if state.stencil and self.stencil_bits > 0:
            GL.glEnable(GL.GL_STENCIL_TEST)
            GL.glStencilFunc(_cmp(GL, state.sfunc), state.sref & 0xFF, state.smask & 0xFF)
            zpass = state.szpass if state.zbuffer else state.spass  # IRIS `pass` rule
            GL.glStencilOp(
                _stencil_op(GL, state.sfail),
                _stencil_op(GL, state.spass),
                _stencil_op(GL, zpass),
            )
        else:
            GL.glDisable(GL.GL_STENCIL_TEST)
        GL.glStencilMask(state.swritemask & 0xFF)

        # Depth.
        if state.zbuffer and self.depth_bits > 0:
            GL.glEnable(GL.GL_DEPTH_TEST)
            GL.glDepthFunc(_cmp(GL, state.zfunc))
        else:
            GL.glDisable(GL.GL_DEPTH_TEST)  # also disables depth writes, as in IRIS
        GL.glDepthMask(bool(state.zwritemask & 0xFFFFFF))

        # Colour: logic op replaces blending.
        if state.logicop != LO_SRC:
            if not 0 <= state.logicop <= 15:
                raise ValueError(f"logic op must be 0..15, got {state.logicop}")
            GL.glDisable(GL.GL_BLEND)
            GL.glEnable(GL.GL_COLOR_LOGIC_OP)
            GL.glLogicOp(GL.GL_CLEAR + state.logicop)  # LO_* and GL_CLEAR.. share order
        else:
            GL.glDisable(GL.GL_COLOR_LOGIC_OP)
            if (state.blend_sf, state.blend_df) == (1, 0):
                GL.glDisable(GL.GL_BLEND)
            else:
                GL.glEnable(GL.GL_BLEND)
                GL.glBlendEquation(GL.GL_FUNC_ADD)
                GL.glBlendFunc(*_blend_factors(GL, state.blend_sf, state.blend_df))
        GL.glColorMask(*_color_mask(state))

        # Culling: CCW in window coordinates is front-facing (backface(3G)).
        if state.cull == CULL_NONE:
            GL.glDisable(GL.GL_CULL_FACE)
        else:
            GL.glEnable(GL.GL_CULL_FACE)
            face = {CULL_BACK: GL.GL_BACK, CULL_FRONT: GL.GL_FRONT}.get(
                state.cull, GL.GL_FRONT_AND_BACK
            )
            GL.glCullFace(face)

        GL.glShadeModel(GL.GL_FLAT if state.shademodel == FLAT else GL.GL_SMOOTH)
        if state.texture or (self._state is not None and self._state.texture):
            from .mesa_texture import apply_texture

            apply_texture(GL, state, self.__dict__.setdefault("_textures", {}),
                          float_texels=self.float_texels)
        self._state = state

    # -- rendering -------------------------------------------------------

    def render(self, commands: Iterable[tuple]) -> None:
        """Render a command list with immediate-mode OpenGL.

        Parameters
        ----------
        commands : iterable of tuple
            ``("triangle", verts, state)`` with ``verts`` three tuples
            ``(xw, yw, zw, (r, g, b, a))`` in IRIS window coordinates (integer =
            pixel centre, lower-left origin, ``zw`` in 24-bit signed units, colour
            components floats in [0, 1]) and ``state`` a RasterState; or
            ``("clear", planes, values, state)`` with ``planes`` a subset of
            ``{"color", "z", "stencil"}`` and ``values`` a dict
            ``{"color": 0xAABBGGRR, "z": int, "stencil": int}``.  A clear writes the
            raster rectangle (``state.scissor``) through the state's write masks.

        Raises
        ------
        ValueError
            On an unknown command or an inexpressible state value.
        """
        GL, _ = _import_gl()
        self._make_current()
        in_begin = False
        try:
            for cmd in commands:
                kind = cmd[0]
                if kind == "triangle":
                    _, verts, state = cmd
                    if state is not self._state and state != self._state:
                        if in_begin:
                            GL.glEnd()
                            in_begin = False
                        self._apply_state(state)
                    if not in_begin:
                        GL.glBegin(GL.GL_TRIANGLES)
                        in_begin = True
                    sub = bool(state.subpixel)
                    for xw, yw, zw, rgba, *tex in verts:
                        if tex:  # (s/w, t/w, 1/w): see mesa_texture
                            GL.glTexCoord4d(tex[0][0], tex[0][1], 0.0, tex[0][2])
                        GL.glColor4d(*rgba)
                        GL.glVertex3d(
                            _snap(xw, sub) + 0.5, _snap(yw, sub) + 0.5, iris_z_to_gl(zw)
                        )
                elif kind == "clear":
                    if in_begin:
                        GL.glEnd()
                        in_begin = False
                    _, planes, values, state = cmd
                    self._clear(planes, values, state)
                else:
                    raise ValueError(f"unknown command {kind!r}")
        finally:
            if in_begin:
                GL.glEnd()

    def _clear(self, planes: Iterable[str], values: dict, state: RasterState) -> None:
        GL, _ = _import_gl()
        planes = set(planes)
        unknown = planes - {"color", "z", "stencil"}
        if unknown:
            raise ValueError(f"unknown planes {sorted(unknown)}")
        self._apply_state(state)
        bits = 0
        if "color" in planes:
            c = int(values["color"]) & 0xFFFFFFFF
            GL.glClearColor(*(((c >> (8 * i)) & 0xFF) / 255.0 for i in range(4)))
            bits |= GL.GL_COLOR_BUFFER_BIT
        if "z" in planes and self.depth_bits > 0:
            GL.glClearDepth(iris_z_to_gl(int(values["z"])))
            bits |= GL.GL_DEPTH_BUFFER_BIT
        if "stencil" in planes and self.stencil_bits > 0:
            GL.glClearStencil(int(values["stencil"]) & 0xFF)
            bits |= GL.GL_STENCIL_BUFFER_BIT
        if bits:
            GL.glClear(bits)

    def upload_arrays(self, positions: np.ndarray, colors: Sequence[float] | np.ndarray,
                      subpixel: bool = False) -> MesaArrays:
        """Convert and upload triangle vertices to GL buffer objects.

        Parameters
        ----------
        positions : ndarray, shape (3*n, 3) or (n, 3, 3)
            IRIS window coordinates ``(xw, yw, zw)`` of each triangle's vertices.
        colors : ndarray, shape (3*n, 4) or (n, 3, 4), or a sequence of 4 floats
            RGBA in [0, 1] per vertex, or one colour for all.
        subpixel : bool, optional
            Snap x and y as ``subpixel(TRUE)`` (to 1/256) instead of to pixel centres.

        Returns
        -------
        MesaArrays
            Handle for :meth:`draw_arrays`.
        """
        GL, _ = _import_gl()
        self._make_current()
        pos = np.asarray(positions, np.float64).reshape(-1, 3)
        if pos.shape[0] % 3:
            raise ValueError("positions must hold three vertices per triangle")
        n = pos.shape[0]
        out = np.empty((n, 3), np.float32)
        out[:, 0] = _snap_array(pos[:, 0], subpixel) + 0.5
        out[:, 1] = _snap_array(pos[:, 1], subpixel) + 0.5
        out[:, 2] = iris_z_to_gl(pos[:, 2])
        col = np.asarray(colors, np.float32)
        if col.ndim == 1:
            col = np.broadcast_to(col, (n, 4))
        col = np.ascontiguousarray(col.reshape(n, 4), np.float32)
        vbos = np.zeros(2, np.uint32)
        GL.glGenBuffers(2, vbos)
        GL.glBindBuffer(GL.GL_ARRAY_BUFFER, int(vbos[0]))
        GL.glBufferData(GL.GL_ARRAY_BUFFER, out.nbytes, out, GL.GL_STATIC_DRAW)
        GL.glBindBuffer(GL.GL_ARRAY_BUFFER, int(vbos[1]))
        GL.glBufferData(GL.GL_ARRAY_BUFFER, col.nbytes, col, GL.GL_STATIC_DRAW)
        GL.glBindBuffer(GL.GL_ARRAY_BUFFER, 0)
        return MesaArrays(self, int(vbos[0]), int(vbos[1]), n)

    def draw_arrays(self, arrays: MesaArrays, state: RasterState,
                    first: int = 0, count: int | None = None) -> None:
        """Draw uploaded triangles with one ``glDrawArrays(GL_TRIANGLES)`` call.

        Does not wait for completion; call :meth:`finish` before stopping a timer.

        Parameters
        ----------
        arrays : MesaArrays
            Vertices from :meth:`upload_arrays` of this peer.
        state : RasterState
            State for all the triangles (its ``subpixel`` flag is ignored here:
            snapping happened at upload).
        first, count : int, optional
            Vertex range to draw (default: all).
        """
        if arrays._peer is not self:
            raise ValueError("arrays belong to another MesaPeer")
        GL, _ = _import_gl()
        self._make_current()
        self._apply_state(state)
        if count is None:
            count = arrays.count - first
        GL.glEnableClientState(GL.GL_VERTEX_ARRAY)
        GL.glEnableClientState(GL.GL_COLOR_ARRAY)
        GL.glBindBuffer(GL.GL_ARRAY_BUFFER, arrays._vbo_pos)
        GL.glVertexPointer(3, GL.GL_FLOAT, 0, None)
        GL.glBindBuffer(GL.GL_ARRAY_BUFFER, arrays._vbo_col)
        GL.glColorPointer(4, GL.GL_FLOAT, 0, None)
        GL.glBindBuffer(GL.GL_ARRAY_BUFFER, 0)
        GL.glDrawArrays(GL.GL_TRIANGLES, int(first), int(count))
        GL.glDisableClientState(GL.GL_VERTEX_ARRAY)
        GL.glDisableClientState(GL.GL_COLOR_ARRAY)

    def render_arrays(self, positions: np.ndarray, colors: Sequence[float] | np.ndarray,
                      state: RasterState) -> None:
        """Upload and draw many triangles at once (vertex-array path).

        Parameters
        ----------
        positions : ndarray, shape (3*n, 3) or (n, 3, 3)
            IRIS window coordinates ``(xw, yw, zw)``.
        colors : ndarray or sequence of 4 floats
            Per-vertex RGBA in [0, 1] or one colour.
        state : RasterState
            State for all the triangles.

        See Also
        --------
        upload_arrays, draw_arrays : separate the upload from the timed draw.
        """
        arrays = self.upload_arrays(positions, colors, subpixel=bool(state.subpixel))
        try:
            self.draw_arrays(arrays, state)
        finally:
            arrays.delete()

    def finish(self) -> None:
        """Wait until Mesa has finished all rendering (``glFinish``)."""
        GL, _ = _import_gl()
        self._make_current()
        GL.glFinish()

    # -- readback --------------------------------------------------------

    def _read(self, fmt: int, typ: int, dtype: Any, comps: int = 1) -> np.ndarray:
        GL, _ = _import_gl()
        self._make_current()
        GL.glFinish()
        out = np.empty((self.height, self.width, comps), dtype)
        GL.glReadPixels(0, 0, self.width, self.height, fmt, typ, out)
        return out if comps > 1 else out[:, :, 0]

    def color(self) -> np.ndarray:
        """Read the colour buffer.

        Returns
        -------
        ndarray of uint32, shape (H, W)
            Packed ``0xAABBGGRR``; row 0 is the bottom row.
        """
        GL, _ = _import_gl()
        rgba = self._read(GL.GL_RGBA, GL.GL_UNSIGNED_BYTE, np.uint8, 4)
        return np.ascontiguousarray(rgba).view("<u4")[:, :, 0].astype(np.uint32)

    def depth(self) -> np.ndarray:
        """Read the depth buffer as GL depth.

        Returns
        -------
        ndarray of float64, shape (H, W)
            Depth in [0, 1]; row 0 is the bottom row.  See :meth:`depth_iris`.
        """
        GL, _ = _import_gl()
        return self._read(GL.GL_DEPTH_COMPONENT, GL.GL_FLOAT, np.float32).astype(np.float64)

    def depth_iris(self) -> np.ndarray:
        """Read the depth buffer in IRIS z units (exact 24-bit values).

        Returns
        -------
        ndarray of int32, shape (H, W)
            ``D - 0x800000`` where ``D`` is the stored 24-bit depth, so a clear to
            IRIS ``z`` reads back as ``z``.
        """
        GL, _ = _import_gl()
        raw = self._read(GL.GL_DEPTH_COMPONENT, GL.GL_UNSIGNED_INT, np.uint32)
        shift = 32 - self.depth_bits
        return ((raw >> np.uint32(shift)).astype(np.int64) + Z_MIN).astype(np.int32)

    def stencil(self) -> np.ndarray:
        """Read the stencil buffer.

        Returns
        -------
        ndarray of uint8, shape (H, W)
            Row 0 is the bottom row.
        """
        GL, _ = _import_gl()
        return self._read(GL.GL_STENCIL_INDEX, GL.GL_UNSIGNED_BYTE, np.uint8)
