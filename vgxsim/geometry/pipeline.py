"""Geometry stage: object -> clip -> window -> fixed point, then into the batch.

Pure functions over numpy arrays; the only state they see is what the caller passes
(the composite matrix, viewport, depth range and the raster snapshot).  Colour is
carried only when the raster state writes colour ("model only what a scene needs").
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from vgxsim.geometry.transform import apply
from vgxsim.kernels.clip import NO_PLANES, clip_segments, clip_triangles, outcodes, project_snap
from vgxsim.kernels.lines import count_line_fragments, line_fragments, line_steps, point_fragments
from vgxsim.state.raster import FLAT, RasterState

from .texgen import per_w, texture_coords

#: Fast-path switch: transform, clip, project, snap and set-up of triangles fused per
#: chunk and run on the worker threads (CommandBatch.add_object_triangles,
#: kernels/front.py).  False: the stage-by-stage passes below, which give the same
#: planes (tests/pipeline/test_fused_front.py compares).  On by default since its
#: vertex pass runs as one scalar loop (no per-stage arrays): 200k 10-pixel
#: triangles cost 763 ns each with it, 906 without (1 thread, CPU time, alternating
#: rounds, bench/small_stages.py --ab vgxsim.geometry.pipeline.FUSED_FRONT), and it
#: lets CommandBatch.band_setup write set-up records in band order; bench/report.py
#: times both.  Its kernels compile in the cold-start helper process
#: (vgxsim/coldstart.py draws through draw_arrays), beside the band kernel.
FUSED_FRONT = True

GUARD_PIXELS = 16384.0  # guard band half-width beyond the viewport centre, pixels


class Viewing(NamedTuple):
    """What maps object coordinates to the window.

    Attributes
    ----------
    mvp : ndarray, shape (4, 4), float64
        Object -> clip matrix (row vectors).
    viewport : tuple of 4 int
        Inclusive (l, r, b, t).
    depth : tuple of 2 float
        lsetdepth (near, far).
    user_planes : ndarray, shape (K, 4), float64
        The user clip planes on (clipplane(3G)), in clip space: a clip-space point
        ``p`` (row) is kept where ``user_planes @ p >= 0`` for every row.
    """

    mvp: np.ndarray
    viewport: tuple
    depth: tuple
    user_planes: np.ndarray = NO_PLANES


def _guard(viewport) -> tuple[float, float]:
    l, r, b, t = viewport
    hx = max((r - l + 1) / 2.0, 0.5)
    hy = max((t - b + 1) / 2.0, 0.5)
    return max(1.0, GUARD_PIXELS / hx), max(1.0, GUARD_PIXELS / hy)


def _project(clip_v, view: Viewing, subpixel: bool):
    l, r, b, t = view.viewport
    return project_snap(clip_v, l, r, b, t, float(view.depth[0]), float(view.depth[1]),
                        subpixel)


HUGE = 1e300  # clip coordinates beyond this are rescaled before clipping


def _tame(clip_v: np.ndarray) -> np.ndarray:
    """Rescale vertices whose homogeneous coordinates are near float overflow.

    (x, y, z, w) and (x, y, z, w) / m (m > 0) are the same point, so dividing the
    rare vertex with a component beyond 1e300 by its largest magnitude keeps the
    plane distances of the clipper (``gx * w - x``) finite.
    """
    if clip_v.shape[0] == 0 or np.abs(clip_v).max() <= HUGE:
        return clip_v  # the usual case: one reduction, no copy
    big = np.abs(clip_v).max(axis=1)
    rows = np.isfinite(big) & (big > HUGE)
    if rows.any():
        clip_v = clip_v.copy()
        clip_v[rows] /= big[rows, None]
    return clip_v


def to_clip(obj: np.ndarray, mvp: np.ndarray) -> np.ndarray:
    """Object (N, 3 or 4) -> clip (N, 4) float64, as row vectors ``p @ mvp``."""
    obj = np.asarray(obj, dtype=np.float64)
    if obj.shape[1] == 3:
        obj = np.concatenate([obj, np.ones((obj.shape[0], 1))], axis=1)
    return _tame(apply(obj, mvp))  # row-independent rounding (transform.apply)


def draw_triangles(batch, rs: RasterState, view: Viewing, obj, rgba, tris, flat_rgba=None,
                   clip_coords=None, tri_states=None, texcoords=None) -> int:
    """Transform, clip, project, snap and queue triangles.

    Parameters
    ----------
    batch : vgxsim.batch.CommandBatch
    rs : RasterState
    view : Viewing
    obj : ndarray, shape (N, 3) or (N, 4), float64
        Object-space vertices (ignored when ``clip_coords`` is given).
    rgba : ndarray, shape (N, 4), float64 or None
        Vertex colours in [0, 1]; None when colour is not written.
    tris : ndarray, shape (T, 3), int64
    flat_rgba : ndarray, shape (T, 4), float64, optional
        Per-triangle colour for flat shading (the last vertex's).
    clip_coords : ndarray, shape (N, 4), optional
        Already transformed vertices.
    tri_states : (list of RasterState, ndarray shape (T,) int64), optional
        Triangles of several raster states that differ only in what the fragment
        stage reads (``rs`` is the first): each triangle's index into the list.
    texcoords : ndarray, shape (N, 2), float64, optional
        Per-vertex (s, t) for coordinates texgen does not generate (default 0).

    Returns
    -------
    int
        Triangles queued.
    """
    tris = np.ascontiguousarray(tris, dtype=np.int64).reshape(-1, 3)
    if tris.shape[0] == 0:
        return 0
    want = rgba is not None
    textured = want and rs.texture != 0
    # The fused pass carries colour only: textured triangles take the passes below.
    if FUSED_FRONT and clip_coords is None and not textured and _plain_batch(batch):
        return _draw_fused(batch, rs, view, obj, rgba, tris, flat_rgba, tri_states)
    clip_v = _tame(clip_coords) if clip_coords is not None else to_clip(obj, view.mvp)
    attr = np.ascontiguousarray(rgba, dtype=np.float64) if want else np.zeros((clip_v.shape[0], 0))
    if textured:  # s, t ride through the clipper as two more attributes
        attr = np.ascontiguousarray(np.concatenate([attr, texture_coords(rs, obj, texcoords)],
                                                   axis=1))
    gx, gy = _guard(view.viewport)
    out_v, out_attr, out_tris, out_src = clip_triangles(
        np.ascontiguousarray(clip_v), attr, tris, gx, gy, view.user_planes)
    xf, yf, zw = _project(out_v, view, rs.subpixel)
    tex = None
    if textured:
        tex = per_w(out_attr[:, 4:6], out_v[:, 3])
        out_attr = np.ascontiguousarray(out_attr[:, :4])
    flat = None
    if want and (rs.shademodel == FLAT):
        flat = (np.ascontiguousarray(flat_rgba, dtype=np.float64) if flat_rgba is not None
                else attr[tris[:, 2]])
    if tri_states is not None:
        states, per_tri = tri_states
        return batch.add_triangles_states(xf, yf, zw, out_attr if want else None, out_tris,
                                          out_src, flat, states,
                                          np.ascontiguousarray(per_tri[out_src]), tex=tex)
    if tex is not None:
        return batch.add_triangles(xf, yf, zw, out_attr if want else None, out_tris, out_src,
                                   flat, rs, tex=tex)
    return batch.add_triangles(xf, yf, zw, out_attr if want else None, out_tris, out_src,
                               flat, rs)


def _plain_batch(batch) -> bool:
    """Whether ``batch`` takes triangles only through its own methods: a capture of
    the batch's input (vgxsim.reference.recorder) wraps add_triangles, which the
    fused pass would go around."""
    from vgxsim import batch as batch_mod

    return getattr(type(batch), "add_triangles", None) is batch_mod._ADD_TRIANGLES


def _draw_fused(batch, rs: RasterState, view: Viewing, obj, rgba, tris, flat_rgba,
                tri_states) -> int:
    """:func:`draw_triangles` through the fused front end (``FUSED_FRONT``)."""
    obj = np.ascontiguousarray(obj, dtype=np.float64)  # (N, 3) or (N, 4): front_vertices
    attr = np.ascontiguousarray(rgba, dtype=np.float64) if rgba is not None else None
    flat = None
    if attr is not None and rs.shademodel == FLAT:
        flat = (np.ascontiguousarray(flat_rgba, dtype=np.float64) if flat_rgba is not None
                else attr[tris[:, 2]])
    mvp = np.ascontiguousarray(view.mvp, dtype=np.float64)
    if tri_states is not None:
        states, per_tri = tri_states
        return batch.add_object_triangles(obj, mvp, view.viewport, view.depth,
                                          _guard(view.viewport), view.user_planes, attr,
                                          tris, flat, states,
                                          np.ascontiguousarray(per_tri, dtype=np.int64))
    return batch.add_object_triangles(obj, mvp, view.viewport, view.depth,
                                      _guard(view.viewport), view.user_planes, attr, tris,
                                      flat, [rs])


def draw_lines(batch, rs: RasterState, view: Viewing, obj, rgba, segs, pattern_start,
               closed: bool | None = None) -> int:
    """Transform, clip, rasterize and queue line segments as fragments.

    Parameters
    ----------
    obj : ndarray, shape (N, 3) or (N, 4)
    rgba : ndarray, shape (N, 4) or None
    segs : ndarray, shape (S, 2), int64
        Vertex indices; with flat shading each segment takes its second vertex's colour.
    pattern_start : ndarray, shape (S,), int64
        Line-style position at each segment's first vertex.
    closed : bool, optional
        Defaults to the IRIS rule: closed without subpixel, half-open with it.

    Returns
    -------
    int
        Fragments queued.
    """
    seg = _clipped_segments(rs, view, obj, rgba, segs)
    if seg is None:
        return 0
    starts = np.asarray(pattern_start, np.int64)[seg[-1]]
    return _queue_segments(batch, rs, seg, starts, closed)


def draw_polyline(batch, rs: RasterState, view: Viewing, obj, rgba, segs,
                  pattern_offset: int = 0, backup: bool = False, restarts=None) -> int:
    """:func:`draw_lines` for the segments of one polyline, in order, with the
    line-style position counted per pixel drawn (deflinestyle(3G)).

    The first segment starts at ``pattern_offset``; each following one starts where
    the previous one's last pixel is, counted with the rasterizer's own step count on
    the snapped (and clipped) endpoints (docs/numeric_model.md s. 5).  With
    ``backup`` (lsbackup(3G)) the polyline's last two pixels are drawn whatever the
    pattern says.  ``restarts`` (S,) bool, one per segment of ``segs`` (draw(3G)
    segments): the pattern is at 0 where one is set -- after it
    the count runs on as before -- whether or not that segment survives the clip (a
    move under resetls(TRUE) put the position there; ``restarts[0]`` is taken to be
    the caller's, in ``pattern_offset``).

    Returns
    -------
    int
        Line-style position after the last segment (where the next draw continues).
    """
    offset = int(pattern_offset)
    later = None  # per input segment: a restart after the first one
    if restarts is not None:
        later = np.asarray(restarts, bool).copy()
        later[0] = False  # (the first segment's restart is the caller's offset)
        if not later.any():
            later = None
    seg = _clipped_segments(rs, view, obj, rgba, segs)
    if seg is None:
        return offset if later is None else 0
    steps = line_steps(seg[0], seg[1])
    starts = np.cumsum(steps) - steps  # steps before each surviving segment
    trailing = False
    if later is None:
        starts += offset
    else:
        # Each run of segments from one restart to the next counts from 0 (the first
        # run from the offset), each segment starting where the surviving one before
        # it in its run ended: what drawing the runs one after the other gives.
        run = np.cumsum(later)  # per input segment: its run (0 before any restart)
        runs = run[seg[-1]]  # the run of each surviving segment (non-decreasing)
        head = np.ones(runs.shape[0], bool)
        head[1:] = runs[1:] != runs[:-1]
        starts -= starts[head][np.cumsum(head) - 1]  # from its run's first survivor
        starts += np.where(runs == 0, offset, 0)
        trailing = run[-1] > runs[-1]  # a restart after the last segment drawn
    end = int(starts[-1] + steps[-1])
    always = NO_BACKUP
    if backup:
        # The last pixel drawn sits at position end with closed lines (the end
        # vertex is drawn) and end - 1 with half-open ones.
        always = end - (1 if not rs.subpixel else 2)
    _queue_segments(batch, rs, seg, starts, None, always)
    return 0 if trailing else end


def _clipped_segments(rs: RasterState, view: Viewing, obj, rgba, segs):
    """Clip and snap segments: (seg_xf, seg_yf, seg_z, seg_c, src) or None when
    nothing is left; ``src`` is the input segment of each (in input order)."""
    clip_v = to_clip(obj, view.mvp)
    segs = np.ascontiguousarray(segs, dtype=np.int64).reshape(-1, 2)
    n = clip_v.shape[0]
    attr = (np.ascontiguousarray(rgba, dtype=np.float64) * 255.0 if rgba is not None
            else np.zeros((n, 4)))
    if rs.shademodel == FLAT:
        attr = attr.copy()
        flat = attr[segs[:, 1]]
    gx, gy = _guard(view.viewport)
    cv, ca, src, _t0 = clip_segments(np.ascontiguousarray(clip_v), attr, segs, gx, gy,
                                     view.user_planes)
    if cv.shape[0] == 0:
        return None
    xf, yf, zw = _project(np.ascontiguousarray(cv.reshape(-1, 4)), view, rs.subpixel)
    seg_c = np.ascontiguousarray(ca)
    if rs.shademodel == FLAT:
        seg_c = np.repeat(flat[src][:, None, :], 2, axis=1)
    return (np.ascontiguousarray(xf.reshape(-1, 2)), np.ascontiguousarray(yf.reshape(-1, 2)),
            np.ascontiguousarray(zw.reshape(-1, 2)), seg_c, src)


#: A line-style position no line reaches: every pixel follows the pattern.
NO_BACKUP = 1 << 62


def _queue_segments(batch, rs: RasterState, seg, starts, closed,
                    always_from: int = NO_BACKUP) -> int:
    seg_xf, seg_yf, seg_z, seg_c, _src = seg
    closed = (not rs.subpixel) if closed is None else closed
    total = count_line_fragments(seg_xf, seg_yf, closed, rs.linewidth)
    out_xy = np.empty((total, 2), np.int64)
    out_z = np.empty(total, np.int64)
    out_c = np.empty(total, np.int64)
    nf = line_fragments(seg_xf, seg_yf, seg_z, seg_c, np.ascontiguousarray(starts, np.int64),
                        closed, rs.linewidth, rs.linestyle, max(1, rs.lsrepeat),
                        always_from, out_xy, out_z, out_c, 0)
    batch.add_fragments(out_xy[:nf], out_z[:nf], out_c[:nf], rs)
    return nf


def draw_points(batch, rs: RasterState, view: Viewing, obj, rgba) -> int:
    """Transform, cull outside the view volume, and queue points as fragments."""
    clip_v = np.ascontiguousarray(to_clip(obj, view.mvp))
    gx, gy = _guard(view.viewport)
    keep = outcodes(clip_v, gx, gy, view.user_planes) == 0
    if not keep.any():
        return 0
    clip_v = np.ascontiguousarray(clip_v[keep])
    c = (np.asarray(rgba, np.float64)[keep] * 255.0 if rgba is not None
         else np.zeros((clip_v.shape[0], 4)))
    xf, yf, zw = _project(clip_v, view, rs.subpixel)
    size = max(1, rs.pntsize)
    total = clip_v.shape[0] * size * size
    out_xy = np.empty((total, 2), np.int64)
    out_z = np.empty(total, np.int64)
    out_c = np.empty(total, np.int64)
    nf = point_fragments(xf, yf, zw, np.ascontiguousarray(c), size, out_xy, out_z, out_c, 0)
    batch.add_fragments(out_xy[:nf], out_z[:nf], out_c[:nf], rs)
    return nf
