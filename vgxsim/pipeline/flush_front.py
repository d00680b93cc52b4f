"""The flush-time front end in a constant number of passes (``draw.FLUSH_FRONT``).

The group-by-group path (:func:`vgxsim.pipeline.decode._draw_groups`) walks the
decoded primitives group by group: per group it lights (or collects the group for
:func:`.draw.shade_groups`), defers, and per run of groups that project alike runs
the geometry passes.  The 1991 frame has about fifteen groups and five geometry
passes per flush, each a few hundred triangles, so the front end's time is the
Python around the kernels, not the kernels.

Here, for the rows whose records need nothing but transform, one-sided lighting,
clipping, projection and set-up (:func:`_plain_record`), a flush is:

1. one pass over the window's records (:class:`Tables`) and three small kernels
   over the rows (kernels/front.py ``fast_rows``, ``flush_rows``,
   ``flush_segments``) in place of per-group Python;
2. one :func:`~vgxsim.kernels.decode.assemble_triangles` over all the rows;
3. one :func:`~vgxsim.kernels.front.light_transform_rows` pass: every vertex lit in
   its record's lighting and taken to clip space by its record's transform, into
   one array each (no per-group arrays, no concatenation);
4. when the records share one projection (viewport, depth range, subpixel mode,
   user clip planes), one clip and one projection pass for all triangles; else one
   geometry pass per segment (:func:`_draw_segments`);
5. one set-up call per *segment*: consecutive rows between clears whose records
   share projection and shading model.  Records with and without colour share a
   segment (the fragment stage reads colour planes only where
   :func:`~vgxsim.state.raster.needs_colour`): the 1991 frame's flush is three
   set-up calls and three clears.

Every value is computed vertex by vertex or triangle by triangle in the arithmetic
of the group-by-group passes, so the planes are the same
(tests/pipeline/test_flush_front.py).  Rows that need more (concave polygons,
lines and points, textures and texgen, depth cueing, fog, two-sided lighting, an
lmcolor override, the numpy lighting form) go through the group-by-group path in
order, between the runs of rows this module draws.
"""

from __future__ import annotations

import numpy as np

from vgxsim.geometry.pipeline import Viewing, _guard, draw_triangles
from vgxsim.kernels.clip import clip_triangles, project_snap
from vgxsim.kernels.decode import assemble_triangles
from vgxsim.kernels.front import flush_rows, flush_segments, light_transform_rows
from vgxsim.kernels.lighting import LIGHT_COLUMNS, LMODEL_COLUMNS
from vgxsim.lighting import equation
from vgxsim.state.raster import FLAT, needs_colour
from vgxsim.stream.opcodes import (
    CLEAR_KIND,
    P_CLEAR,
    P_KIND,
    P_STATE,
)


def _plain_record(state) -> bool:
    """Whether a record's triangles need only transform, lighting (one-sided, the
    kernel form), clipping, projection and set-up."""
    ls = state.lighting
    return (not state.concave and state.texgen_eye is None and state.depthcue is None
            and state.fog is None and state.raster.texture == 0
            and (ls is None or (not ls.lmodel.twoside and equation.JIT_LIGHTING)))


def _overridden(state) -> bool:
    """Whether lmcolor colours override the material when set (draw.override_of)."""
    return state.lmcolor_mode not in (0, 6)


class Tables:
    """Per record of a flush's table, in one pass over them: whether its rows take
    the flush pass (``code``), what :func:`light_transform_rows` reads (kernel
    argument order), its segment class, projection and raster numbers; the
    lighting rows come from the window's :class:`RowMemo` ``memo``.

    Attributes
    ----------
    code : ndarray, shape (R,), int64
        1 plain (:func:`_plain_record`), 2 plain but overridden by a set lmcolor
        colour, 0 neither (kernels/front.py fast_rows).
    klass, proj, rast, colour : ndarray, shape (R,), int64
        Segment class (projection and shading model), projection, raster number
        (records may share a raster; ``rasters[n]`` is raster ``n``), and 1 when
        the record writes or tests colour (needs_colour).
    """

    def __init__(self, records, memo: RowMemo | None = None):
        if memo is None:
            memo = RowMemo()  # (a caller without a window's memo: rows made afresh)
        modes, mvps, mvs, nms, mats, lms, spans = [], [], [], [], [], [], []
        code, klass, proj, wants, rast = [], [], [], [], []
        tables: list[np.ndarray] = []
        light_rows: dict[tuple, tuple[int, int]] = {}
        classes: dict[tuple, int] = {}
        projections: dict[tuple, int] = {}
        rast_ids: dict[int, int] = {}
        self.rasters: list = []
        top = 0
        for st in records:
            rs = st.raster
            n = rast_ids.setdefault(id(rs), len(rast_ids))
            if n == len(self.rasters):
                self.rasters.append(rs)
            rast.append(n)
            mvps.append(st.mvp)
            colour = needs_colour(rs)
            wants.append(colour)
            ls = st.lighting
            plain = _plain_record(st)
            code.append((1 + _overridden(st)) if plain else 0)
            if plain:
                # user_planes by identity: the common NO_PLANES is one object, and
                # two equal arrays in different objects only cost a segment break.
                pkey = (st.viewport, st.depth, rs.subpixel, id(st.user_planes))
                p = projections.setdefault(pkey, len(projections))
                # Records with and without colour share a segment: set-up then
                # computes colour planes that the fragment stage of the latter
                # never reads (no colour write, no alpha test: needs_colour), and
                # one call is saved.
                k = classes.setdefault((p, rs.shademodel), len(classes))
            else:
                p = k = -1
            proj.append(p)
            klass.append(k)
            if not plain or ls is None or not colour:  # keeps its colour (light_mode 0)
                modes.append(0)
                mvs.append(_EYE4)
                nms.append(_EYE3)
                mats.append(_NO_MATERIAL)
                lms.append(_NO_LMODEL)
                spans.append((0, 0))
                continue
            modes.append(2 if st.lmcolor_mode != 0 else 1)
            mvs.append(ls.modelview)
            nms.append(ls.normal_matrix)
            mats.append(memo.material_row(ls.material))
            lms.append(memo.lmodel_row(ls.lmodel))
            lkey = tuple(map(id, ls.lights))
            span = light_rows.get(lkey)
            if span is None:
                table = memo.light_table(ls.lights)
                span = light_rows[lkey] = (top, top + table.shape[0])
                tables.append(table)
                top += table.shape[0]
            spans.append(span)
        self.code = np.array(code, np.int64)
        self.klass = np.array(klass, np.int64)
        self.proj = np.array(proj, np.int64)
        self.rast = np.array(rast, np.int64)
        self.colour = np.array(wants, np.int64)
        self.mvp = np.array(mvps, np.float64).reshape(-1, 4, 4)
        self.light_mode = np.array(modes, np.int64)
        self.modelview = np.array(mvs, np.float64).reshape(-1, 4, 4)
        self.normal_matrix = np.array(nms, np.float64).reshape(-1, 3, 3)
        mat = np.array(mats, np.float64).reshape(-1, 14)
        # Contiguous copies of the columns (a few numbers per record), not views: a
        # column view is C-contiguous for one record and not for more (numpy's flags),
        # and Numba compiles light_transform_rows once per layout, so a program's
        # second flush with more records than its first would compile it again
        # (3 s of a cold `vgxsim shadows`, docs/cold_start.md).
        col = np.ascontiguousarray
        self.terms = [col(mat[:, k:k + 3]) for k in (0, 3, 6, 9)]
        self.shininess = col(mat[:, 12])
        self.alpha = col(mat[:, 13])
        sp = np.array(spans, np.int64).reshape(-1, 2)
        self.light_lo = col(sp[:, 0])
        self.light_hi = col(sp[:, 1])
        self.lmodel = np.array(lms, np.float64).reshape(-1, LMODEL_COLUMNS)
        self.lights = np.concatenate(tables) if tables else np.zeros((0, LIGHT_COLUMNS))


_EYE4 = np.eye(4)
_EYE3 = np.eye(3)
_EYE4.flags.writeable = False  # (constants: the kernels read them, nothing writes)
_EYE3.flags.writeable = False
_NO_MATERIAL = (0.0,) * 14
_NO_LMODEL = (0.0,) * LMODEL_COLUMNS
class RowMemo:
    """A window's kernel rows of lighting definitions, kept across flushes
    (``Context.row_memo``): a frame binds the same materials, lighting models and
    lights again, and their rows are made once.  Each entry keeps the definition
    objects its key names by id, so no id is reused while the entry lives;
    definitions are replaced, never mutated.

    Attributes
    ----------
    lmodels : dict
        id(LightModel) -> (LightModel, row).
    lights : dict
        value key -> (Light objects, table) (:meth:`light_table`).
    materials : dict
        id(Material) -> (Material, row).
    """

    __slots__ = ("lmodels", "lights", "materials")

    #: Entries each dict holds before it is emptied (memory stays bounded).
    LIMIT = 256

    def __init__(self):
        self.lmodels: dict[int, tuple] = {}
        self.lights: dict[tuple, tuple] = {}
        self.materials: dict[int, tuple] = {}

    def light_table(self, lights: tuple) -> np.ndarray:
        """The kernel's light rows of bound lights (equation._light_table), once per
        value: a frame lmbinds its lights again (new eye-space arrays of the same
        values), so the key is each Light definition's identity with the bytes of
        its eye-space position and spot direction."""
        key = tuple((id(light), None if p is None else np.asarray(p, np.float64).tobytes(),
                     None if d is None else np.asarray(d, np.float64).tobytes())
                    for light, p, d in lights)
        memo = self.lights
        hit = memo.get(key)
        if hit is None or any(a is not b for a, (b, _p, _d) in zip(hit[0], lights,
                                                                   strict=True)):
            if len(memo) > self.LIMIT:
                memo.clear()
            hit = memo[key] = (tuple(e[0] for e in lights), equation._light_table(lights))
        return hit[1]

    def material_row(self, m) -> tuple:
        """A material's kernel terms (emission, ambient, diffuse, specular,
        shininess, alpha: 14 floats), once per material object."""
        memo = self.materials
        hit = memo.get(id(m))
        if hit is None or hit[0] is not m:
            if len(memo) > self.LIMIT:
                memo.clear()
            hit = memo[id(m)] = (m, (*m.emission, *m.ambient, *m.diffuse, *m.specular,
                                     m.shininess, m.alpha))
        return hit[1]

    def lmodel_row(self, lmodel) -> np.ndarray:
        """The kernel's light-model row, once per lighting model object."""
        memo = self.lmodels
        hit = memo.get(id(lmodel))
        if hit is None or hit[0] is not lmodel:
            if len(memo) > self.LIMIT:
                memo.clear()
            hit = memo[id(lmodel)] = (lmodel, equation._lmodel_row(lmodel))
        return hit[1]


def draw_rows(ctx, records, tab: Tables, pos, col, nrm, sent, rows: np.ndarray, swaps,
              clears, clear_fn) -> None:
    """Draw primitive rows that kernels/front.py ``fast_rows`` accepts, in order.

    Parameters
    ----------
    tab : Tables
        Of ``records``.
    rows : ndarray, shape (P, PRIM_COLUMNS), int64
        Decoded primitive rows (clears and triangle primitives).
    pos, col, nrm, sent, swaps
        The decoded vertices and swaptmesh positions (decode_stream).
    clears : list
        The stream's clear arguments (CLEAR rows index it).
    clear_fn : callable
        ``clear_fn(ctx, clears[i])`` does a clear (vgxsim.pipeline.decode._clear).
    """
    rows, tri_rows, rec_of, row_v0, row_v1, vlo, vhi, nproj = flush_rows(rows, tab.proj)
    if tri_rows.shape[0] == 0:
        for r in rows.tolist():
            clear_fn(ctx, clears[r[P_CLEAR]])
        return
    nv = vhi - vlo
    clip_v = np.empty((nv, 4))
    rgba = np.empty((nv, 4))
    light_transform_rows(pos[vlo:vhi], col[vlo:vhi], nrm[vlo:vhi], sent[vlo:vhi], row_v0,
                         row_v1, rec_of, tab.mvp, tab.light_mode, tab.modelview,
                         tab.normal_matrix, *tab.terms, tab.shininess, tab.alpha, tab.light_lo,
                         tab.light_hi, tab.lights, tab.lmodel, equation._MIN_SHININESS, clip_v,
                         rgba)
    tris, prov, tri_row = assemble_triangles(tri_rows, 0, swaps)
    distinct = tab.rasters
    if nproj != 1:
        _draw_segments(ctx, records, rows, rows[:, P_KIND] == CLEAR_KIND, clears, clear_fn,
                       tab.klass, tab.colour, rec_of, tris, prov, tri_row, tab.rast,
                       distinct, row_v0, row_v1, clip_v, rgba)
        return
    # One projection for every triangle row: one clip and one projection pass for
    # them all, then one set-up call per segment.
    st = records[int(rec_of[0])]
    l, r, b, t = st.viewport
    gx, gy = _guard(st.viewport)
    out_v, out_attr, out_tris, out_src = clip_triangles(clip_v, rgba, tris, gx, gy,
                                                        st.user_planes)
    xf, yf, zw = project_snap(out_v, l, r, b, t, float(st.depth[0]), float(st.depth[1]),
                              st.raster.subpixel)
    segs, out_rast, present, local = flush_segments(rows, rec_of, tab.klass, tab.rast,
                                                    tab.colour, tri_row, out_src)
    flat = None
    batch = ctx.raw_batch
    for q, (h, clear, ta, tb, mixed, wants) in enumerate(segs.tolist()):
        if clear:
            clear_fn(ctx, clears[int(rows[h, P_CLEAR])])
            continue
        if tb == ta:
            continue
        rs = records[int(rows[h, P_STATE])].raster
        colour = out_attr if wants else None
        seg_flat = None
        if colour is not None and rs.shademodel == FLAT:
            if flat is None:
                flat = rgba[prov]  # per input triangle: its provoking vertex's colour
            seg_flat = flat
        if mixed:
            states = [distinct[i] for i in np.flatnonzero(present[q]).tolist()]
            batch.add_triangles_states(xf, yf, zw, colour, out_tris[ta:tb], out_src[ta:tb],
                                       seg_flat, states, local[ta:tb])
        else:
            batch.add_triangles(xf, yf, zw, colour, out_tris[ta:tb], out_src[ta:tb],
                                seg_flat, distinct[int(out_rast[ta])])


def _draw_segments(ctx, records, rows, is_clear, clears, clear_fn, rec_klass, rec_colour,
                   rec_of, tris, prov, tri_row, rast_of_rec, distinct, row_v0, row_v1, clip_v,
                   rgba) -> None:
    """:func:`draw_rows`' segments through one geometry pass each (records of
    several viewports, depth ranges, snapping modes or user clip planes)."""
    klass = np.full(rows.shape[0], -1, np.int64)
    klass[~is_clear] = rec_klass[rec_of]
    brk = np.ones(rows.shape[0], bool)
    brk[1:] = (klass[1:] != klass[:-1]) | is_clear[1:] | is_clear[:-1]
    seg_of_row = np.cumsum(brk) - 1
    nseg = int(seg_of_row[-1]) + 1
    row_seg = seg_of_row[~is_clear]  # per triangle row, nondecreasing
    tri_seg = row_seg[tri_row]  # per triangle, nondecreasing
    tri_rast = rast_of_rec[rec_of[tri_row]]
    tri_colour = rec_colour[rec_of[tri_row]]
    heads = np.flatnonzero(brk).tolist()
    segs = np.arange(nseg + 1)
    t_cut = np.searchsorted(tri_seg, segs).tolist()
    r_cut = np.searchsorted(row_seg, segs)
    v_first = row_v0[np.minimum(r_cut[:-1], row_v0.shape[0] - 1)].tolist()
    v_last = row_v1[np.maximum(r_cut[1:] - 1, 0)].tolist()
    batch = ctx.raw_batch
    for s, h in enumerate(heads):
        if is_clear[h]:
            clear_fn(ctx, clears[int(rows[h, P_CLEAR])])
            continue
        ta, tb = t_cut[s], t_cut[s + 1]
        if tb == ta:
            continue
        v0, v1 = v_first[s], v_last[s]
        st = records[int(rows[h, P_STATE])]
        rs = st.raster
        colour = rgba[v0:v1] if tri_colour[ta:tb].any() else None
        flat = rgba[prov[ta:tb]] if (colour is not None and rs.shademodel == FLAT) else None
        ids = tri_rast[ta:tb]
        tri_states = None
        if (ids != ids[0]).any():
            present = np.unique(ids)
            seg_rasters = [distinct[i] for i in present.tolist()]
            tri_states = (seg_rasters, np.searchsorted(present, ids))
            rs = seg_rasters[0]
        else:
            rs = distinct[int(ids[0])]
        draw_triangles(batch, rs, Viewing(st.mvp, st.viewport, st.depth, st.user_planes),
                       None, colour, tris[ta:tb] - v0, flat, clip_coords=clip_v[v0:v1],
                       tri_states=tri_states)
