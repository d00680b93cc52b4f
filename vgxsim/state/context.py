"""The emulated VGX: one window's configuration, registers, matrices and batch.

The IRIS GL layer (:mod:`vgxsim.gl`) validates arguments and then stores into the
registers held here; drawing goes geometry -> batch -> kernels -> planes.  Library
users may also drive a :class:`Context` directly (``draw_arrays``, ``read_rgba``).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from vgxsim.batch import CLEAR_COLOUR, CLEAR_STENCIL, CLEAR_Z, CommandBatch
from vgxsim.geometry import assembly
from vgxsim.geometry.pipeline import Viewing, draw_lines, draw_points, draw_triangles
from vgxsim.geometry.transform import apply
from vgxsim.kernels.accum import accumulate
from vgxsim.lighting import LightingError, LightingTables, light_to_eye, shade
from vgxsim.state import colormap
from vgxsim.state.colormap import default_colormap
from vgxsim.state.matrices import MatrixState
from vgxsim.state.planes import ZMAX, ZMIN, Framebuffer, PlaneConfig, unpack_rgba
from vgxsim.state.raster import FLAT, needs_colour
from vgxsim.state.registers import RasterRegisters

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
        # Vertex assembly (gl/_draw.py): the open bgn* primitive, its vertices as
        # ((x, y, z, w), colour, normal, normal_sent_last) and swaptmesh() positions.
        self.prim: str | None = None
        self.prim_verts: list = []
        self.prim_swaps: list[int] = []
        self.concave = False
        self.linestyle_pos = 0  # line-style position after the last line drawn
        # Old-style drawing (gl/_oldstyle.py): the current graphics position (object
        # coordinates, move(3G)/draw(3G)); text (gl/_text.py): the current character
        # position in window pixels (cmov(3G)), its z, whether it is defined (cmov:
        # "undefined if the transformed point is outside the viewport"), the font.
        self.gpos = (0.0, 0.0, 0.0, 1.0)
        self.cpos = (0, 0)
        self.cpos_z = 0
        self.cpos_valid = True
        self.font = 0
        # pick(3G)/gselect(3G) mode (gl/_pick.py): a callable that hit-tests each
        # primitive in clip space instead of drawing it; None when drawing.
        self.select_hook = None
        self.configure(self.pending)

    # -- configuration ----------------------------------------------------------------
    def configure(self, config: PlaneConfig) -> None:
        """gconfig(): allocate the planes the pending modes ask for.

        Queued drawing is flushed to the old planes first; the new planes start
        cleared (colour 0, z = GD_ZMAX, stencil 0) and registers that gconfig resets
        (swritemask, the draw buffers) are reset.
        """
        if getattr(self, "_batch", None) is not None:
            self.batch.flush()
        self.config = config
        self.fb = Framebuffer(config)
        self._batch = CommandBatch(self.fb)
        self._pending = None  # deferred triangle draws (see _defer_triangles)
        old = getattr(self, "raster", None)
        self.raster = RasterRegisters(config.width, config.height, config.double)
        if old is not None:
            keep = {k: getattr(old, k) for k in (
                "zbuffer", "zfunc", "zwritemask", "stencil", "blend", "logicop", "wmpack",
                "afunction", "shademodel", "subpixel", "backface", "frontface", "linewidth",
                "linestyle", "lsrepeat", "pntsize")}
            self.raster.set(**keep)
        self.raster.set(swritemask=(1 << config.stencil) - 1 if config.stencil else 0)

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
        if index == 0:
            self.bound["lights"].pop(slot, None)
            return
        light = self.lighting.light(index)
        if light is None:
            raise LightingError(f"lmbind: light {index} is not defined (lmdef(DEFLIGHT, ...))")
        self.bound["lights"][slot] = (index, light_to_eye(light, self.matrices.modelview_matrix()))

    def lighting_snapshot(self):
        """Everything per-vertex lighting reads, as immutable objects, or None when
        lighting is off (matrices and definitions are replaced, never mutated)."""
        if not self.lighting_active() or not self.config.rgb:
            return None
        lights = tuple(entry for _slot, (_i, entry) in sorted(self.bound["lights"].items()))
        override = self.lmcolor_mode if (self.lmcolor_mode not in (0, 6)
                                         and self.lmcolor_set) else None
        back = self.bound.get("backmaterial", 0)
        return (self.matrices.modelview_matrix(), self.matrices.normal_matrix(),
                self.lighting.material(self.bound["material"]),
                self.lighting.lmodel(self.bound["lmodel"]), lights, override,
                self.lighting.material(back) if back else None)

    def shade_vertices(self, obj, normals, colours, lit, snapshot=None,
                       back: bool = False) -> np.ndarray:
        """Per-vertex colour: lit vertices through the IRIS lighting equation.

        Parameters
        ----------
        obj : ndarray, shape (N, 4); normals : ndarray, shape (N, 3)
        colours : ndarray, shape (N, 4); lit : ndarray, shape (N,), bool
        snapshot : tuple, optional
            A :meth:`lighting_snapshot` (default: the current lighting state).
        back : bool
            Light the back side (two-sided lighting: flipped normals and the
            BACKMATERIAL if one is bound, lmdef(3G) TWOSIDE).

        Returns
        -------
        ndarray, shape (N, 4), float64
        """
        out = np.array(colours, dtype=np.float64)
        # cmode lighting (COLORINDEXES) is not modelled: lit vertices keep the
        # current colour index rather than getting RGB written into index planes.
        snap = self.lighting_snapshot() if snapshot is None else snapshot
        if snap is None or not lit.any():
            return out
        mv, nmat, mat, lm, lights, override_mode, back_mat = snap
        eye = apply(obj[lit], mv)
        pos = eye[:, :3] / np.where(eye[:, 3:4] == 0, 1.0, eye[:, 3:4])
        nrm = apply(normals[lit], nmat)
        override = None
        if override_mode is not None:
            override = (override_mode, np.asarray(colours, np.float64)[lit])
        facing = np.ones(pos.shape[0], bool) if back else None
        out[lit] = shade(pos, nrm, mat, list(lights), lm, back_material=back_mat,
                         facing=facing, color_override=override)
        return out

    @property
    def batch(self) -> CommandBatch:
        """The command batch, after queuing any deferred triangle draws (so every
        user of the batch sees primitives in drawing order)."""
        if self._pending is not None:
            self._commit_triangles()
        return self._batch

    def _defer_triangles(self, obj, cols, normals, lit, tris, prov) -> None:
        """Queue one primitive's triangles for a combined geometry pass.

        Consecutive primitives drawn with the same raster snapshot, transform and
        lighting (Heidmann's DrawObjects: hundreds of small polygons) are
        transformed, lit, clipped and set up in one vectorized call instead of one
        each; the result is identical because every stage works per vertex or per
        triangle with a row-independent rounding order.
        """
        rs = self.raster.snapshot()
        key = (rs, self.matrices.mvp(), self.raster.viewport, self.depth_range,
               self.lighting_snapshot() if normals is not None else None)
        pend = self._pending
        if pend is not None and not _same_key(pend["key"], key):
            self._commit_triangles()
            pend = None
        if pend is None:
            pend = self._pending = {"key": key, "parts": [], "n": 0}
        base = pend["n"]
        pend["parts"].append((obj, cols, normals, lit, tris + base, prov + base))
        pend["n"] = base + obj.shape[0]

    def _commit_triangles(self) -> None:
        pend, self._pending = self._pending, None
        rs, mvp, viewport, depth, snap = pend["key"]
        parts = pend["parts"]

        def joined(i):
            # One part (a mesh drawn in one call) needs no concatenation copy.
            return parts[0][i] if len(parts) == 1 else np.concatenate([p[i] for p in parts])

        obj = joined(0)
        tris = joined(4)
        prov = joined(5)
        rgba = None
        if parts[0][1] is not None:
            cols = joined(1)
            if snap is not None:
                normals = np.concatenate([p[2] if p[2] is not None
                                          else np.zeros((p[0].shape[0], 3)) for p in parts])
                lit = np.concatenate([p[3] for p in parts])
                rgba = self.shade_vertices(obj, normals, cols, lit, snapshot=snap)
                if snap[3].twoside:
                    # Two-sided lighting: back-facing triangles take colours lit from
                    # the back (flipped normal, BACKMATERIAL); vertices are duplicated
                    # so a vertex shared by a front and a back face gets both.
                    back_rgba = self.shade_vertices(obj, normals, cols, lit, snapshot=snap,
                                                    back=True)
                    backs = _back_facing(apply(obj, mvp), tris)
                    n = obj.shape[0]
                    obj = np.concatenate([obj, obj])
                    rgba = np.concatenate([rgba, back_rgba])
                    tris = np.where(backs[:, None], tris + n, tris)
                    prov = np.where(backs, prov + n, prov)
            else:
                rgba = cols  # already a private float64 copy (draw_arrays)
        flat = None if (rgba is None or rs.shademodel != FLAT) else rgba[prov]
        draw_triangles(self._batch, rs, Viewing(mvp, viewport, depth), obj, rgba, tris, flat)

    # -- drawing ---------------------------------------------------------------------
    def draw_arrays(self, kind: str, obj, colours=None, normals=None, lit=None,
                    swaps=(), indices=None, provoking=None, pattern_offset: int = 0) -> None:
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
            shademodel(FLAT) (default: its third vertex).  Display objects use it to
            keep each polygon's last-vertex colour when many polygons become one draw.
        pattern_offset : int
            Lines only: line-style position at the first vertex (move/draw continue
            the pattern, docs/numeric_model.md s. 5).  ``self.linestyle_pos`` is left
            at the position after the last segment.
        """
        obj = np.asarray(obj, dtype=np.float64)
        if obj.ndim != 2 or obj.shape[0] == 0:
            return
        if obj.shape[1] == 3:
            obj = np.concatenate([obj, np.ones((obj.shape[0], 1))], axis=1)
        elif obj.shape[1] == 2:
            obj = np.concatenate([obj, np.zeros((obj.shape[0], 1)),
                                  np.ones((obj.shape[0], 1))], axis=1)
        else:
            obj = obj.copy()  # drawing is deferred: keep the caller free to reuse its array
        if self.select_hook is not None:  # pick/select mode: hit-test, draw nothing
            self.select_hook(kind, apply(obj, self.matrices.mvp()), swaps, indices)
            return
        n = obj.shape[0]
        rs = self.raster.snapshot()
        cols = None
        lighting = normals is not None and self.lighting_active()
        if needs_colour(rs):
            cols = (np.broadcast_to(np.asarray(self.colour, np.float64), (n, 4))
                    if colours is None else np.asarray(colours, np.float64))
        litm = None
        if lighting:
            litm = np.ones(n, bool) if lit is None else np.asarray(lit, bool)
        view = self.viewing()
        if kind not in (LINE, CLOSEDLINE, POINT):
            tris, prov = self._triangles_of(kind, n, obj, view, swaps, indices, provoking)
            self._defer_triangles(
                obj, None if cols is None else np.array(cols, dtype=np.float64),
                np.array(normals, np.float64) if lighting else None, litm, tris, prov)
            return
        rgba = None
        if cols is not None:
            if lighting:
                rgba = self.shade_vertices(obj, np.asarray(normals, np.float64), cols, litm)
            else:
                rgba = np.array(cols, dtype=np.float64)
        if kind in (LINE, CLOSEDLINE):
            segs = assembly.line_segments(n, kind == CLOSEDLINE)
            starts, end = self._pattern_starts(obj, segs, view)
            draw_lines(self.batch, rs, view, obj, rgba, segs, starts + int(pattern_offset))
            self.linestyle_pos = int(pattern_offset) + end
            return
        if kind == POINT:
            draw_points(self.batch, rs, view, obj, rgba)
            return

    def _triangles_of(self, kind, n, obj, view, swaps, indices, provoking):
        """Triangles of a primitive and, per triangle, the vertex whose colour it
        takes under shademodel(FLAT) (the last vertex, shademodel(3G))."""
        if kind == POLYGON:
            tris = (self._concave_triangles(obj, view) if self.concave
                    else assembly.polygon_fan(n))
            prov = np.full(len(tris), n - 1, np.int64)
        elif kind == TMESH:
            tris = assembly.tmesh_triangles(n, list(swaps))
            prov = tris[:, 2].copy()
        elif kind == QSTRIP:
            tris = assembly.qstrip_triangles(n)
            # Both triangles of a quad take its last vertex (q + 3), the largest index.
            prov = tris.max(axis=1)
        elif kind == "triangles":
            tris = np.asarray(indices, np.int64).reshape(-1, 3)
            prov = tris[:, 2].copy() if provoking is None else np.asarray(provoking, np.int64)
        else:
            raise ValueError(f"unknown primitive kind {kind!r}")
        return np.asarray(tris, np.int64).reshape(-1, 3), prov

    def _pattern_starts(self, obj, segs, view) -> tuple[np.ndarray, int]:
        """Line-style position of each segment (it continues along a polyline), and
        the position after the last segment."""
        if segs.shape[0] == 0:
            return np.zeros(0, np.int64), 0
        clip = apply(obj, view.mvp)
        w = np.where(clip[:, 3] == 0, 1e-30, clip[:, 3])
        l, r, b, t = view.viewport
        x = (clip[:, 0] / w + 1) * (r - l + 1) / 2
        y = (clip[:, 1] / w + 1) * (t - b + 1) / 2
        steps = np.maximum(np.abs(np.round(x[segs[:, 1]]) - np.round(x[segs[:, 0]])),
                           np.abs(np.round(y[segs[:, 1]]) - np.round(y[segs[:, 0]])))
        steps = np.nan_to_num(steps, nan=0.0, posinf=0.0, neginf=0.0).astype(np.int64)
        total = np.cumsum(steps)
        return np.concatenate([[0], total[:-1]]).astype(np.int64), int(total[-1])

    def _concave_triangles(self, obj, view) -> np.ndarray:
        clip = apply(obj, view.mvp)
        w = np.where(np.abs(clip[:, 3]) < 1e-300, 1e-300, clip[:, 3])
        xy = np.stack([clip[:, 0] / w, clip[:, 1] / w], axis=1)
        return assembly.triangulate_concave(xy)

    # -- clears, readback, frames ------------------------------------------------------
    def clear_planes(self, planes: int, colour: int = 0, z: int = ZMAX, stencil: int = 0) -> None:
        """Queue a clear of the raster rectangle (CLEAR_* plane bits); none in pick or
        select mode, which draws nothing (pick(3G))."""
        if self.select_hook is not None:
            return
        self.batch.add_clear(planes, colour, z, stencil, self.raster.clear_state())

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

    def read_rgba(self, which: str = "front") -> np.ndarray:
        """(H, W, 4) uint8 RGBA copy of a colour buffer, row 0 = bottom."""
        return unpack_rgba(self.colour_buffer(which))

    def swap(self) -> None:
        """swapbuffers(): flush, exchange buffers and hand the new front to the sink."""
        self.flush()
        self.fb.swap()
        self.emit_frame()

    def emit_frame(self) -> None:
        if self.sink is not None:
            self.sink.write(self.display_rgba())
        self.frames += 1

    def display_rgba(self) -> np.ndarray:
        """What the monitor shows: the front buffer as RGBA (colour-mapped in cmode)."""
        self.flush()
        if self.config.rgb:
            return unpack_rgba(self.fb.front)
        return self.colormap_lookup(self.fb.front)

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


def _back_facing(clip: np.ndarray, tris: np.ndarray) -> np.ndarray:
    """Per triangle, whether it is clockwise in window coordinates (back-facing).

    The sign of det[x y w] of the clip-space vertices times the sign of w0*w1*w2 is
    the sign of the window-space area (the viewport scales x and y positively).
    """
    a, b, c = clip[tris[:, 0]], clip[tris[:, 1]], clip[tris[:, 2]]
    det = (a[:, 0] * (b[:, 1] * c[:, 3] - b[:, 3] * c[:, 1])
           - a[:, 1] * (b[:, 0] * c[:, 3] - b[:, 3] * c[:, 0])
           + a[:, 3] * (b[:, 0] * c[:, 1] - b[:, 1] * c[:, 0]))
    return det * np.sign(a[:, 3] * b[:, 3] * c[:, 3]) < 0


def _same_key(a: tuple, b: tuple) -> bool:
    """Deferral keys match: same objects (matrices and snapshots are immutable)."""
    rs_a, mvp_a, vp_a, depth_a, snap_a = a
    rs_b, mvp_b, vp_b, depth_b, snap_b = b
    if rs_a is not rs_b or mvp_a is not mvp_b or vp_a != vp_b or depth_a != depth_b:
        return False
    if snap_a is None or snap_b is None:
        return snap_a is snap_b
    if len(snap_a[4]) != len(snap_b[4]) or snap_a[5] != snap_b[5] or snap_a[6] is not snap_b[6]:
        return False
    return all(x is y for x, y in zip(snap_a[:4], snap_b[:4], strict=True)) and all(
        x is y for x, y in zip(snap_a[4], snap_b[4], strict=True))


def replace_config(ctx: Context, **changes) -> PlaneConfig:
    """The pending configuration with some fields changed (for the gl layer)."""
    ctx.pending = replace(ctx.pending, **changes)
    return ctx.pending


__all__ = ["Context", "CLEAR_COLOUR", "CLEAR_Z", "CLEAR_STENCIL", "replace_config"]
