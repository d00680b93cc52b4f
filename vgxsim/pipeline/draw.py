"""Drawing primitives from arrays: lighting, deferral, the geometry passes.

Triangles are deferred: consecutive triangle draws with the same draw state
(:class:`~.records.DrawState`, and the same lmcolor override) are transformed, lit,
clipped and set up in one vectorized call (Heidmann's DrawObjects: hundreds of
small polygons); the result is identical because every stage works per vertex or per
triangle with a row-independent rounding order.  Lines and points are drawn at once
(their line-style position carries to the next move/draw).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from vgxsim.geometry import assembly
from vgxsim.geometry.pipeline import Viewing, draw_points, draw_polyline, draw_triangles
from vgxsim.geometry.texgen import eye_texture_coords
from vgxsim.geometry.transform import apply
from vgxsim.lighting import shade, shade_object_runs
from vgxsim.state.raster import FLAT, needs_colour

from .depthcue import cue_vertices
from .fog import fog_vertices
from .records import DrawState, same_projection, same_state

#: Fast-path switch: one geometry pass for consecutive triangle primitives whose
#: records differ only in fragment state (stencil before every 1991 shadow face).
#: False: one pass per record (tests/stream/test_random_streams.py compares).
MERGE_FRAGMENT_STATES = True

#: Fast-path switch: at a flush, consecutive draw(3G) segments under one record
#: (DRAW_SEG and DRAW_RESTART rows, pipeline/decode.py) are drawn as one polyline of
#: disjoint segments, the pattern running on from each to the next and restarting
#: at 0 at each DRAW_RESTART.  False: one line per segment
#: (tests/gl/test_move_draw_stream.py compares).
MERGE_SEGMENTS = True

#: Fast-path switch: at a flush, the lit triangle groups under the same lights and
#: lighting model are lit in one pass (:func:`shade_groups`: the 1991 frame lights a
#: floor and a few small objects, each with its own material and matrix, per pass).
#: False: one lighting pass per group (tests/pipeline/test_batched_lighting.py).
BATCH_LIGHTING = True

#: Fast-path switch: at a flush, the triangle primitives whose records need only
#: transform, one-sided lighting, clipping, projection and set-up go through a
#: constant number of passes (vgxsim/pipeline/flush_front.py: one lighting and
#: transform pass over all their vertices, one clip and projection pass, one set-up
#: call per run of rows between clears) instead of group by group.  False: the
#: group-by-group path for every row (tests/pipeline/test_flush_front.py compares).
#: On by default: tests that count or spy on the group path's calls pin it off.
FLUSH_FRONT = True

#: Fast-path switch: a plain triangle draw of at least ``DIRECT_MIN_VERTICES``
#: vertices (no lighting, texture, texgen, depthcue, fog; not a concave polygon)
#: runs its geometry pass before draw_arrays returns, reading the caller's arrays in
#: place: (N, 3) or (N, 4) float64 coordinates, (N, 4) float64 colours.  Deferred,
#: the draw needs private copies (the caller may reuse its arrays before the flush):
#: for 200k 10-pixel triangles those copies and their first-touch page faults cost
#: about 100 ns a triangle (bench/small_stages.py: as_homogeneous, numpy.array).
#: The queued draws are committed first, so the order is kept; every geometry stage
#: works per vertex or per triangle, so committing apart changes no value.  False:
#: every draw is copied and deferred (tests/pipeline/test_direct_arrays.py compares).
DIRECT_ARRAYS = True
DIRECT_MIN_VERTICES = 3072  # below this the copies are cheap and merging draws pays

POLYGON, TMESH, QSTRIP, LINE, CLOSEDLINE, POINT = (
    "polygon", "tmesh", "qstrip", "line", "closedline", "point")


def override_of(state: DrawState, lmcolor_set: bool):
    """The lmcolor mode colours override the material with, or None (lmcolor(3G):
    colour commands change the bound material until the next lmbind/lmcolor)."""
    mode = state.lmcolor_mode
    return mode if (mode not in (0, 6) and lmcolor_set) else None


def shade_vertices(state: DrawState, lmcolor_set: bool, obj, normals, colours, lit,
                   back: bool = False) -> np.ndarray:
    """Per-vertex colour: lit vertices through the IRIS lighting equation.

    Parameters
    ----------
    state : DrawState
    lmcolor_set : bool
    obj : ndarray, shape (N, 4); normals : ndarray, shape (N, 3)
    colours : ndarray, shape (N, 4); lit : ndarray, shape (N,), bool
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
    ls = state.lighting
    if ls is None or not lit.any():
        return out
    eye = apply(obj[lit], ls.modelview)
    pos = eye[:, :3] / np.where(eye[:, 3:4] == 0, 1.0, eye[:, 3:4])
    nrm = apply(normals[lit], ls.normal_matrix)
    override = None
    mode = override_of(state, lmcolor_set)
    if mode is not None:
        override = (mode, np.asarray(colours, np.float64)[lit])
    facing = np.ones(pos.shape[0], bool) if back else None
    out[lit] = shade(pos, nrm, ls.material, list(ls.lights), ls.lmodel,
                     back_material=ls.back_material, facing=facing, color_override=override)
    return out


def shade_groups(groups: list) -> list:
    """Vertex colours of several groups, lit together where they can be.

    Parameters
    ----------
    groups : list of LitGroup
        As :func:`shade_vertices` takes them.

    Returns
    -------
    list
        Per group, its (N, 4) float64 colours, or None for a group lit on its own
        (two-sided lighting, an lmcolor override, or no lit vertex).  Groups under
        the same lights and lighting model share one
        :func:`~vgxsim.lighting.shade_object_runs` pass, each with its own
        modelview and material: the equation is evaluated vertex by vertex, so the
        colours are those one pass per group gives.
    """
    out: list = [None] * len(groups)
    runs: dict[tuple, list[int]] = {}
    for i, grp in enumerate(groups):
        state = grp.state
        ls = state.lighting
        if ls is None or ls.lmodel.twoside or override_of(state, grp.lmcolor_set) is not None:
            continue
        if not grp.lit.any():
            continue
        runs.setdefault((id(ls.lmodel), tuple(id(e) for e in ls.lights)), []).append(i)
    for members in runs.values():
        if len(members) == 1:
            continue  # one group: shade_vertices does the same
        g = [groups[i] for i in members]
        ls = g[0].state.lighting
        counts = [m.obj.shape[0] for m in g]
        rgba = shade_object_runs(
            np.concatenate([m.obj for m in g]), np.concatenate([m.normals for m in g]),
            np.concatenate([m.colours for m in g]), np.concatenate([m.lit for m in g]),
            counts, [m.state.lighting.modelview for m in g],
            [m.state.lighting.normal_matrix for m in g],
            [m.state.lighting.material for m in g], list(ls.lights), ls.lmodel)
        at = 0
        for i, c in zip(members, counts, strict=True):
            out[i] = rgba[at:at + c]
            at += c
    return out


def vertex_colour_stage(state: DrawState, obj, rgba):
    """Vertex colours after lighting: depth cueing replaces them (depthcue(3G)), then
    fog blends them (fogvertex(3G)).  ``rgba`` is returned as is when neither is on."""
    if state.depthcue is not None:
        rgba = cue_vertices(state.depthcue, obj, rgba, state.mvp, state.depth)
    if state.fog is not None:
        rgba = fog_vertices(state.fog, obj, rgba)
    return rgba


class PendingPart(NamedTuple):
    """One queued triangle draw of :class:`PendingTriangles`.

    ``obj`` (N, 4) float64 object coordinates; ``rgba`` (N, 4) float64 vertex colours
    already lit, or None; ``tris`` (T, 3) and ``prov`` (T,) int64 vertex indices into
    the pending pass (already offset); ``rasters`` None (the pending state's raster)
    or (list of RasterState, (T,) int64 index per triangle); ``texcoords`` (N, 2)
    float64 or None.
    """

    obj: np.ndarray
    rgba: np.ndarray | None
    tris: np.ndarray
    prov: np.ndarray
    rasters: tuple | None
    texcoords: np.ndarray | None


class LitGroup(NamedTuple):
    """A group handed to :func:`shade_groups`: its draw state, lmcolor_set flag,
    (N, 4) object coordinates, (N, 3) normals, (N, 4) colours and (N,) lit flags."""

    state: DrawState
    lmcolor_set: bool
    obj: np.ndarray
    normals: np.ndarray
    colours: np.ndarray
    lit: np.ndarray


class PendingTriangles:
    """Triangle draws queued for one combined geometry pass (``parts``: a list of
    :class:`PendingPart`)."""

    __slots__ = ("state", "parts", "n")

    def __init__(self, state: DrawState):
        self.state = state
        self.parts: list = []
        self.n = 0


def _lit_colours(state: DrawState, lmcolor_set: bool, obj, cols, normals, lit, tris, prov):
    """Vertex colours of one part through the lighting equation, with two-sided
    lighting's duplicated vertices: (obj, rgba, tris, prov)."""
    if cols is None or normals is None or state.lighting is None:
        if cols is not None:
            cols = vertex_colour_stage(state, obj, cols)
        return obj, cols, tris, prov
    rgba = shade_vertices(state, lmcolor_set, obj, normals, cols, lit)
    if state.lighting.lmodel.twoside:
        # Two-sided lighting: back-facing triangles take colours lit from the back
        # (flipped normal, BACKMATERIAL); vertices are duplicated so a vertex shared
        # by a front and a back face gets both.
        back_rgba = shade_vertices(state, lmcolor_set, obj, normals, cols, lit, back=True)
        backs = _back_facing(apply(obj, state.mvp), tris)
        n = obj.shape[0]
        obj = np.concatenate([obj, obj])
        rgba = np.concatenate([rgba, back_rgba])
        tris = np.where(backs[:, None], tris + n, tris)
        prov = np.where(backs, prov + n, prov)
    return obj, vertex_colour_stage(state, obj, rgba), tris, prov


def defer_triangles(ctx, state: DrawState, lmcolor_set: bool, obj, cols, normals, lit,
                    tris, prov, tri_states=None, lit_rgba=None, texcoords=None,
                    eye_normals=None) -> None:
    """Light one primitive's (or one group's) vertices and queue its triangles on
    ``ctx`` for a geometry pass shared with the queued ones that project alike.

    ``tri_states`` (list of DrawState, per-triangle index) gives triangles of several
    records that :func:`~.records.same_geometry` joins; ``state`` is one of them.
    Lighting is per vertex, so lighting each part on its own gives the colours
    lighting them together would.  ``lit_rgba``: the colours already lit
    (:func:`shade_groups`).  ``texcoords`` (N, 2): t2* per vertex, or None.
    ``eye_normals`` (N, 3): the vertex normals TG_SPHEREMAP reads when lighting does
    not hand them over (default ``normals``, else the current normal).
    """
    n_in = obj.shape[0]
    if state.texgen_eye is not None:  # TG_CONTOUR / TG_SPHEREMAP: in this modelview
        from vgxsim.state.textures import binding

        nrm = eye_normals if eye_normals is not None else normals
        if nrm is None:
            nrm = np.broadcast_to(np.asarray(ctx.normal, np.float64), (n_in, 3))
        texcoords = eye_texture_coords(binding(state.raster.texture).texgen, obj,
                                       *state.texgen_eye, nrm, texcoords)
    if lit_rgba is not None:
        rgba = vertex_colour_stage(state, obj, lit_rgba)  # two-sided is never batched
    else:
        obj, rgba, tris, prov = _lit_colours(state, lmcolor_set, obj, cols, normals, lit,
                                             tris, prov)
    if texcoords is not None and obj.shape[0] != n_in:  # two-sided: vertices doubled
        texcoords = np.concatenate([texcoords, texcoords])
    pend = ctx.pending_triangles
    if pend is not None and not (same_state(pend.state, state) or (
            MERGE_FRAGMENT_STATES and same_projection(pend.state, state))):
        commit_triangles(ctx)
        pend = None
    if pend is None:
        pend = ctx.pending_triangles = PendingTriangles(state)
    rasters = None
    if tri_states is not None:
        recs, per_tri = tri_states
        rasters = ([r.raster for r in recs], per_tri)
    elif state.raster is not pend.state.raster:
        rasters = ([state.raster], np.zeros(tris.shape[0], np.int64))
    base = pend.n
    pend.parts.append(PendingPart(obj, rgba, tris + base, prov + base, rasters, texcoords))
    pend.n = base + obj.shape[0]


def _triangle_states(pend: PendingTriangles):
    """(list of RasterState, per-triangle index) of the queued parts, or None when
    they all draw with the pending state's raster.  The list keeps one entry per
    primitive (entries may repeat), so a capture of the batch's input
    (vgxsim.reference.recorder) still sees one record per primitive."""
    if all(p.rasters is None for p in pend.parts):
        return None
    states = [pend.state.raster]
    per = []
    for p in pend.parts:
        if p.rasters is None:
            per.append(np.zeros(p.tris.shape[0], np.int64))
            continue
        rl, idx = p.rasters
        per.append(idx + len(states))
        states.extend(rl)
    return states, np.concatenate(per)


def commit_triangles(ctx) -> None:
    """Run the geometry pass of the queued triangles into the batch."""
    pend, ctx.pending_triangles = ctx.pending_triangles, None
    if pend is None:
        return
    state = pend.state
    rs = state.raster
    parts = pend.parts
    tri_states = _triangle_states(pend)

    def joined(field):
        # One part (a mesh drawn in one call) needs no concatenation copy.
        if len(parts) == 1:
            return getattr(parts[0], field)
        return np.concatenate([getattr(p, field) for p in parts])

    obj = joined("obj")
    rgba = joined("rgba") if parts[0].rgba is not None else None
    tris = joined("tris")
    prov = joined("prov")
    flat = None if (rgba is None or rs.shademodel != FLAT) else rgba[prov]
    texcoords = None
    if any(p.texcoords is not None for p in parts):  # t2* per vertex (0, 0 where not sent)
        texcoords = np.concatenate([p.texcoords if p.texcoords is not None
                                    else np.zeros((p.obj.shape[0], 2)) for p in parts])
    draw_triangles(ctx.raw_batch, rs, Viewing(state.mvp, state.viewport, state.depth,
                                               state.user_planes), obj,
                   rgba, tris, flat, tri_states=tri_states, texcoords=texcoords)


def as_homogeneous(obj) -> np.ndarray:
    """(N, 2 | 3 | 4) object coordinates as a private (N, 4) float64 array."""
    obj = np.asarray(obj, dtype=np.float64)
    if obj.shape[1] == 3:
        return np.concatenate([obj, np.ones((obj.shape[0], 1))], axis=1)
    if obj.shape[1] == 2:
        return np.concatenate([obj, np.zeros((obj.shape[0], 1)),
                               np.ones((obj.shape[0], 1))], axis=1)
    return obj.copy()  # drawing is deferred: keep the caller free to reuse its array


def draw_arrays(ctx, state: DrawState, lmcolor_set: bool, kind: str, obj, colours=None,
                normals=None, lit=None, swaps=(), indices=None, provoking=None,
                pattern_offset: int = 0, private: bool = False, texcoords=None,
                segments=None, restarts=None) -> None:
    """Draw one primitive (or a mesh, with ``indices``) with ``state``.

    See :meth:`vgxsim.pipeline.context.Context.draw_arrays` for the parameters;
    ``private`` says the arrays are already private float64 (N, 4) copies;
    ``texcoords`` (N, 2) are per-vertex t2* coordinates (triangles only);
    ``segments`` (S, 2) int64, lines only: the vertex pairs to draw, in order, as one
    polyline's segments (the pattern continues from each to the next), in place of
    the line's own (draw(3G) segments recorded in a row, pipeline/decode.py), and
    ``restarts`` (S,) bool with them: the segments at which the pattern restarts at 0
    (a move under resetls(TRUE) came before; the first one's restart is the caller's).
    """
    direct = False
    if not private:
        obj = np.asarray(obj, dtype=np.float64)
        if obj.ndim != 2 or obj.shape[0] == 0:
            return
        direct = ctx.select_hook is None and _direct(state, kind, obj, normals, texcoords)
        obj = np.ascontiguousarray(obj) if direct else as_homogeneous(obj)
    n = obj.shape[0]
    if n == 0:
        return
    if ctx.select_hook is not None:  # pick/select mode: hit-test, draw nothing
        ctx.select_hook(kind, apply(obj, state.mvp), swaps, indices, state.user_planes)
        return
    rs = state.raster
    cols = None
    lighting = normals is not None and state.lighting is not None
    if needs_colour(rs):
        if colours is None:
            cols = np.broadcast_to(np.asarray(ctx.colour, np.float64), (n, 4))
        else:
            cols = np.asarray(colours, np.float64)
    litm = None
    if lighting:
        litm = np.ones(n, bool) if lit is None else np.asarray(lit, bool)
    view = Viewing(state.mvp, state.viewport, state.depth, state.user_planes)
    if kind not in (LINE, CLOSEDLINE, POINT):
        tris, prov = triangles_of(state, kind, n, obj, view, swaps, indices, provoking)
        if direct:
            if cols is not None:
                cols = np.ascontiguousarray(cols)
            # Drawn now, after the draws queued before it: nothing keeps the caller's
            # arrays after this call (see DIRECT_ARRAYS); commit_triangles' pass for
            # one part of one state, without the queue's offset copies of tris.
            commit_triangles(ctx)
            flat = None if (cols is None or rs.shademodel != FLAT) else cols[prov]
            draw_triangles(ctx.raw_batch, rs, view, obj, cols, tris, flat)
            return
        if cols is not None and not private:
            cols = np.array(cols, dtype=np.float64)
        nrm = None
        if lighting:
            nrm = normals if private else np.array(normals, np.float64)
        if texcoords is not None:
            texcoords = np.array(texcoords, np.float64).reshape(n, 2)
        eye_nrm = None
        if state.texgen_eye is not None and normals is not None:
            eye_nrm = np.asarray(normals, np.float64)
        defer_triangles(ctx, state, lmcolor_set, obj, cols, nrm, litm, tris, prov,
                        texcoords=texcoords, eye_normals=eye_nrm)
        return
    commit_triangles(ctx)
    rgba = None
    if cols is not None:
        if lighting:
            rgba = shade_vertices(state, lmcolor_set, obj, np.asarray(normals, np.float64),
                                  cols, litm)
        else:
            rgba = np.array(cols, dtype=np.float64)
        rgba = vertex_colour_stage(state, obj, rgba)
    if kind in (LINE, CLOSEDLINE):
        segs = (assembly.line_segments(n, kind == CLOSEDLINE) if segments is None
                else segments)
        # resetls(FALSE): the pattern continues from the last line drawn.
        start = int(pattern_offset) if state.resetls else ctx.linestyle_pos
        ctx.linestyle_pos = draw_polyline(ctx.raw_batch, rs, view, obj, rgba, segs, start,
                                          state.lsbackup, restarts)
        return
    draw_points(ctx.raw_batch, rs, view, obj, rgba)


def _direct(state: DrawState, kind: str, obj: np.ndarray, normals, texcoords) -> bool:
    """Whether a draw takes the DIRECT_ARRAYS path: a large plain triangle draw whose
    stages read (N, 3) coordinates as well as (N, 4) ones (the fused front end and
    vgxsim.geometry.pipeline.to_clip do; lighting, texgen, depthcue, fog and the
    concave tessellator read (N, 4))."""
    return (DIRECT_ARRAYS and obj.shape[0] >= DIRECT_MIN_VERTICES
            and obj.shape[1] in (3, 4) and kind not in (LINE, CLOSEDLINE, POINT)
            and not (kind == POLYGON and state.concave)
            and (normals is None or state.lighting is None) and texcoords is None
            and state.texgen_eye is None and state.raster.texture == 0
            and state.depthcue is None and state.fog is None)


def triangles_of(state: DrawState, kind, n, obj, view, swaps, indices, provoking):
    """Triangles of a primitive and, per triangle, the vertex whose colour it
    takes under shademodel(FLAT) (the last vertex, shademodel(3G))."""
    if kind == POLYGON:
        tris = (_concave_triangles(obj, view) if state.concave
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


def _concave_triangles(obj, view) -> np.ndarray:
    clip = apply(obj, view.mvp)
    w = np.where(np.abs(clip[:, 3]) < 1e-300, 1e-300, clip[:, 3])
    xy = np.stack([clip[:, 0] / w, clip[:, 1] / w], axis=1)
    return assembly.triangulate_concave(xy)


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
