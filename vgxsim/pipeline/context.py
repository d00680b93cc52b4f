"""The emulated VGX: one window's state data, command stream and batch.

The state itself is data in :mod:`vgxsim.state` (registers, planes, colour map,
matrices); this pipeline-layer object holds one window's worth of it together with
what drives drawing: the command stream the gl calls append to
(:mod:`vgxsim.stream`), its decoding at a flush (:mod:`.decode`), the deferred
geometry passes (:mod:`.draw`) and the batch the kernels render.  The IRIS GL layer
(:mod:`vgxsim.gl`) validates arguments and then stores here; library users may also
drive a :class:`Context` directly (``draw_arrays``, ``read_rgba``).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from vgxsim.backends import make_batch
from vgxsim.batch import CLEAR_COLOUR, CLEAR_STENCIL, CLEAR_Z, CommandBatch
from vgxsim.geometry.pipeline import Viewing
from vgxsim.kernels.accum import accumulate
from vgxsim.kernels.clip import NO_PLANES
from vgxsim.lighting import LightingError, LightingTables, light_to_eye
from vgxsim.pipeline import layers
from vgxsim.pipeline.decode import drain
from vgxsim.pipeline.draw import commit_triangles
from vgxsim.pipeline.draw import draw_arrays as pipeline_draw_arrays
from vgxsim.pipeline.flush_front import RowMemo
from vgxsim.pipeline.records import DrawState, StateTable
from vgxsim.state import colormap
from vgxsim.state.colormap import default_colormap
from vgxsim.state.matrices import MatrixState
from vgxsim.state.planes import ZMAX, ZMIN, Framebuffer, PlaneConfig, unpack_rgba
from vgxsim.state.registers import RasterRegisters
from vgxsim.stream.opcodes import CLEAR as CLEAR_OP
from vgxsim.stream.recorder import MAX_STREAM_OPS, Clear, CommandStream

POLYGON, TMESH, QSTRIP, LINE, CLOSEDLINE, POINT = (
    "polygon", "tmesh", "qstrip", "line", "closedline", "point")


class Context:
    """One IRIS GL window and its graphics state.

    Parameters
    ----------
    width, height : int
        Window size in pixels.
    rgb, double : bool
        RGBmode/cmode and doublebuffer/singlebuffer, as if configured by gconfig().
    stencil, zbits, acbits : int
        stensize, zbsize and acsize.
    """

    def __init__(self, width: int = 640, height: int = 512, *, rgb: bool = True,
                 double: bool = False, stencil: int = 0, zbits: int = 24, acbits: int = 0):
        self.pending = PlaneConfig(width, height, double=double, zbits=zbits,
                                   stencil=stencil, acbits=acbits, rgb=rgb)
        self.matrices = MatrixState()
        self.colour = (1.0, 1.0, 1.0, 1.0)  # current RGBA (floats 0..1)
        self.colour_index = 0
        self.normal = (0.0, 0.0, 1.0)
        self.texcoord = (0.0, 0.0)
        self.last_sent = "colour"  # lmcolor(3G): colour or normal sent last decides
        self.lighting = LightingTables()
        self.bound = {"material": 0, "backmaterial": 0, "lmodel": 0, "lights": {}}
        self.lmcolor_mode = 0
        # lmcolor(3G): colour commands change the bound material "in the hardware";
        # the change is lost when a material is bound.  True once a colour command
        # has reached the material since the last lmbind(MATERIAL)/lmcolor.
        self.lmcolor_set = True
        # Colour map (cmode): mapcolor(3G) entries, multimap(3G)/setmap(3G).
        self.colormap = default_colormap()
        self.multimap = False
        self.curmap = 0
        # Attributes that only queries read (gl/_raster.py): deflinestyle(3G) table
        # and current index, polymode, smoothing, dither and glcompat(3G) modes.
        self.linestyles: dict[int, int] = {0: 0xFFFF}
        self.linestyle_index = 0
        self.polymode = 1  # PYM_FILL
        self.smooth = {"point": 0, "line": 0, "polygon": 0}
        self.dither = 1  # DT_ON
        self.compat: dict[int, int] = {}
        self.depth_range = (ZMIN, ZMAX)
        self.sink = None
        self.frames = 0
        self.readsource = 0  # SRC_AUTO
        # The command stream (vgxsim/stream): what the gl calls recorded and no flush
        # has drawn yet; the open bgn* primitive; interned draw states; triangles
        # queued for one geometry pass (vgxsim/pipeline/draw.py).
        self.stream = CommandStream()
        self.states = StateTable()
        self.pending_triangles = None
        self.lighting_serial = 0  # bumped by every lighting call (lmdef, lmbind, lmcolor)
        self.prim: str | None = None
        self.concave = False
        self.linestyle_pos = 0  # line-style position after the last line drawn
        # A move(3G) under resetls(TRUE) since the last line recorded: the next line
        # starts the pattern at 0.  The move sets it (no drain); a draw records it in
        # its segment (DRAW_RESTART), any other line applies it at its start
        # (restart_pattern), both in drawing order (gl/_oldstyle.py).
        self.ls_restart = False
        self.resetls = True  # resetls(3G): the pattern restarts at each line
        self.lsbackup = False  # lsbackup(3G): the last two pixels drawn whatever the style
        # clipplane(3G) (gl/_clip.py): the six planes' eye-space equations (None:
        # never defined), which are on, and the (K, 4) array of those on (replaced,
        # never mutated).  fogvertex(3G) (gl/_fog.py): the fog definition (a
        # FogState without its modelview, or None) and whether fog is on.  Every
        # clipplane and fogvertex call bumps ``vertex_serial`` (draw-state interning).
        self.clip_plane_defs: list = [None] * 6
        self.clip_planes_on: set[int] = set()
        self.user_planes = NO_PLANES
        self.fog_def = None
        self.fog_on = False
        self.depthcue = None  # depthcue(3G) (gl/_depthcue.py): the RGB DepthCue ramp
        self.shaderange = None  # lshaderange(3G): the colour-index ramp
        self.depthcue_on = False
        self.vertex_serial = 0
        # Old-style drawing (gl/_oldstyle.py): the current graphics position (object
        # coordinates, move(3G)/draw(3G)); text (gl/_text.py): the current character
        # position in window pixels (cmov(3G)), its z, whether it is defined (cmov:
        # "undefined if the transformed point is outside the viewport"), the font.
        self.gpos = (0.0, 0.0, 0.0, 1.0)
        self.cpos = (0, 0)
        self.cpos_z = 0
        self.cpos_valid = True
        # cmov's window mapping (gl/_text.py _window_map): the mvp, viewport and depth
        # range it was made for, then their floats; None until the first cmov.
        self.cpos_map: tuple | None = None
        self.font = 0
        # pick(3G)/gselect(3G) mode (gl/_pick.py): a callable that hit-tests each
        # primitive in clip space instead of drawing it; None when drawing.
        self.select_hook = None
        # The flush pass's lighting rows (vgxsim.pipeline.flush_front.RowMemo).
        self.row_memo = RowMemo()
        # What configure() replaces: none before the first one.  The framebuffers
        # (vgxsim.pipeline.layers: the normal planes and overlay, underlay, pop-up and
        # cursor planes) and the one selected; zdraw(3G)'s batch, when on.
        self.plane_sets: dict = {}
        self.planes_selected = layers.NORMAL
        self.zdraw_batch = None
        self._batch: CommandBatch | None = None
        self.raster: RasterRegisters | None = None
        self.configure(self.pending)

    # -- configuration ----------------------------------------------------------------
    def configure(self, config: PlaneConfig) -> None:
        """gconfig(): allocate the planes the pending modes ask for.

        Queued drawing is flushed to the old planes first; the new planes start
        cleared (colour 0, z = GD_ZMAX, stencil 0) and registers that gconfig resets
        (swritemask, the draw buffers) are reset.  The overlay and underlay planes are
        (re)allocated too (vgxsim.pipeline.layers); the draw mode is kept.
        """
        selected = self.planes_selected
        if selected != layers.NORMAL:
            layers.select(self, layers.NORMAL)
        if self.zdraw_batch is not None:
            # zdraw(3G): "By default, and after each call to gconfig, zdraw is FALSE."
            layers.set_zdraw(self, False)
        self.zdraw_batch = None
        if self._batch is not None:
            self.batch.flush()
        self.config = config
        self.fb = Framebuffer(config)
        self._batch = make_batch(self.fb)  # the backend switch (vgxsim/backends)
        self.stream.forget()
        old = self.raster
        self.raster = RasterRegisters(config.width, config.height, config.double)
        if old is not None:
            keep = {k: getattr(old, k) for k in (
                "zbuffer", "zfunc", "zwritemask", "stencil", "blend", "logicop", "wmpack",
                "afunction", "shademodel", "subpixel", "backface", "frontface", "linewidth",
                "linestyle", "lsrepeat", "pntsize")}
            self.raster.set(**keep)
        self.raster.set(swritemask=(1 << config.stencil) - 1 if config.stencil else 0)
        layers.configure(self)
        if selected != layers.NORMAL:
            layers.select(self, selected)

    @property
    def width(self) -> int:
        return self.config.width

    @property
    def height(self) -> int:
        return self.config.height

    def viewing(self) -> Viewing:
        return Viewing(self.matrices.mvp(), self.raster.viewport, self.depth_range)

    # -- lighting -------------------------------------------------------------------
    def lighting_active(self) -> bool:
        """Lighting is on iff a material and a lighting model are bound (lmbind(3G))."""
        return self.bound["material"] != 0 and self.bound["lmodel"] != 0

    def bind_light(self, slot: int, index: int) -> None:
        """lmbind(LIGHTn, index): position transformed by the current modelview."""
        self.lighting_serial += 1
        if index == 0:
            self.bound["lights"].pop(slot, None)
            return
        light = self.lighting.light(index)
        if light is None:
            raise LightingError(f"lmbind: light {index} is not defined (lmdef(DEFLIGHT, ...))")
        self.bound["lights"][slot] = (index, light_to_eye(light, self.matrices.modelview_matrix()))

    # -- drawing ---------------------------------------------------------------------
    @property
    def batch(self) -> CommandBatch:
        """The command batch, after decoding the command stream and queuing any
        deferred triangle draws (so every user of the batch sees primitives in
        drawing order)."""
        if len(self.stream):
            drain(self)
        if self.pending_triangles is not None:
            commit_triangles(self)
        return self._batch

    @property
    def raw_batch(self) -> CommandBatch:
        """The batch as it is (for the pipeline, which keeps the order itself)."""
        return self._batch

    def draw_state(self) -> DrawState:
        """The current draw state as an interned record."""
        return self.states.records[self.states.intern(self)]

    def draw_arrays(self, kind: str, obj, colours=None, normals=None, lit=None,
                    swaps=(), indices=None, provoking=None, pattern_offset: int = 0,
                    texcoords=None) -> None:
        """Draw one primitive (or a mesh, with ``indices``) from arrays.

        Parameters
        ----------
        kind : {'polygon', 'tmesh', 'qstrip', 'line', 'closedline', 'point', 'triangles'}
        obj : ndarray, shape (N, 3) or (N, 4)
            Object-space vertices.
        colours : ndarray, shape (N, 4), optional
            Vertex colours (default: the current colour).
        normals : ndarray, shape (N, 3), optional
        lit : ndarray, shape (N,), bool, optional
            Which vertices are lit (default: all when lighting is active and normals
            were given).
        swaps : sequence of int
            tmesh only: vertex counts at which swaptmesh() was called.
        indices : ndarray, shape (T, 3), optional
            'triangles' only: a triangle list.
        provoking : ndarray, shape (T,), optional
            'triangles' only: the vertex whose colour each triangle takes under
            shademodel(FLAT) (default: its third vertex).
        pattern_offset : int
            Lines only: line-style position at the first vertex (move/draw continue
            the pattern, docs/numeric_model.md s. 5).  ``self.linestyle_pos`` is left
            at the position after the last segment.
        texcoords : ndarray, shape (N, 2), optional
            Triangles only: per-vertex (s, t), as t2* gives them (docs/numeric_model.md
            s. 13; texgen replaces the coordinates it generates).
        """
        if len(self.stream):
            drain(self)  # what the stream holds was drawn first
        if self.ls_restart and kind in ("line", "closedline"):
            self.restart_pattern()
        pipeline_draw_arrays(self, self.draw_state(), self.lmcolor_set, kind, obj, colours,
                             normals, lit, swaps, indices, provoking, pattern_offset,
                             texcoords=texcoords)

    def restart_pattern(self) -> None:
        """Apply a pending move's pattern restart (:attr:`ls_restart`) before a line
        that is not a draw segment: the stream's lines before it are drawn first (they
        move :attr:`linestyle_pos`), then the position is 0, as the move left it."""
        drain(self)
        self.linestyle_pos = 0
        self.ls_restart = False

    # -- clears, readback, frames ------------------------------------------------------
    def clear_planes(self, planes: int, colour: int = 0, z: int = ZMAX, stencil: int = 0) -> None:
        """Queue a clear of the raster rectangle (CLEAR_* plane bits); none in pick or
        select mode, which draws nothing (pick(3G))."""
        if self.select_hook is not None:
            return
        # Recorded in the stream (a CLEAR op), so the clears between the 1991 frame's
        # passes (sclear before each light's shadow faces) cost no flush of their own.
        st = self.stream
        if len(st) > MAX_STREAM_OPS:
            drain(self)
        st.ops.append(CLEAR_OP)
        st.ops.append(len(st.clears))
        st.clears.append(Clear(planes, colour, z, stencil, self.raster.clear_state()))

    def flush(self) -> None:
        """Render everything queued."""
        self.batch.flush()

    def colour_buffer(self, which: str = "auto") -> np.ndarray:
        """The packed (H, W) uint32 buffer readsource selects, after a flush."""
        self.flush()
        if which == "auto":
            which = "back" if self.fb.back is not None else "front"
        if which == "back" and self.fb.back is not None:
            return self.fb.back
        return self.fb.front

    def layer_buffer(self, name: str) -> np.ndarray:
        """The (H, W) uint32 index words of the 'overlay', 'underlay' or 'popup'
        planes, after a flush (zeros where the window has none)."""
        self.flush()
        ps = self.plane_sets[name]
        if ps.fb is None or ps.bits == 0:
            return np.zeros((self.height, self.width), np.uint32)
        return ps.fb.front

    def read_rgba(self, which: str = "front") -> np.ndarray:
        """(H, W, 4) uint8 RGBA copy of a colour buffer, row 0 = bottom."""
        return unpack_rgba(self.colour_buffer(which))

    def swap(self) -> None:
        """swapbuffers(): flush, exchange the normal framebuffer's buffers (whichever
        draw mode is in effect) and hand the new front to the sink."""
        self.flush()
        layers.normal_modes(self)["fb"].swap()
        self.emit_frame()

    def emit_frame(self) -> None:
        if self.sink is not None:
            self.sink.write(self.display_rgba())
        self.frames += 1

    def display_rgba(self, ignore=frozenset()) -> np.ndarray:
        """What the monitor shows: the front buffer as RGBA (colour-mapped in cmode),
        under the pop-up and overlay planes and over the underlay planes where they
        have been configured (vgxsim.pipeline.layers.display); ``ignore`` names
        framebuffers ('popup', 'overlay', 'underlay') to leave out."""
        self.flush()
        return layers.display(self, ignore)

    def colormap_lookup(self, packed: np.ndarray) -> np.ndarray:
        """(H, W, 4) uint8 RGBA of index words through the current colour map."""
        return colormap.lookup(self.colormap, packed, self.multimap, self.curmap)

    # -- accumulation ----------------------------------------------------------------
    def acbuf(self, op: int, value: float) -> None:
        """acbuf(op, value) over the raster rectangle (docs/numeric_model.md s. 9)."""
        if self.fb.accum is None:
            return
        self.flush()
        x0, x1, y0, y1 = self.raster.raster_rect()
        if x0 > x1 or y0 > y1:
            return
        rs = self.raster.snapshot()
        if op == 3:  # AC_RETURN writes the draw buffer(s)
            targets = []
            if self.fb.back is not None and rs.draw_back:
                targets.append(self.fb.back)
            if rs.draw_front or self.fb.back is None:
                targets.append(self.fb.front)
            for buf in targets:
                accumulate(self.fb.accum, buf, op, float(value), x0, x1, y0, y1,
                           rs.wmpack & 0xFFFFFFFF)
        else:
            src = self.colour_buffer(self._readsource_name())
            accumulate(self.fb.accum, src, op, float(value), x0, x1, y0, y1, 0xFFFFFFFF)

    def _readsource_name(self) -> str:
        return {1: "front", 2: "back"}.get(self.readsource, "auto")


def replace_config(ctx: Context, **changes) -> PlaneConfig:
    """The pending configuration with some fields changed (for the gl layer)."""
    ctx.pending = replace(ctx.pending, **changes)
    return ctx.pending


__all__ = ["Context", "CLEAR_COLOUR", "CLEAR_Z", "CLEAR_STENCIL", "replace_config"]
