"""At a flush: decode a window's command stream and draw what it holds.

The decode kernel (:func:`vgxsim.kernels.decode.decode_stream`) resolves every
vertex's colour, normal and lit flag in one pass and cuts the primitives; here the
primitives are grouped -- consecutive triangle primitives of one draw state become
one triangle list, assembled in one kernel pass
(:func:`vgxsim.kernels.decode.assemble_triangles`) -- and handed to the geometry
passes (:mod:`.draw`); the lit groups of the whole flush are lit together
(:func:`.draw.shade_groups`).  Clears are rows of the same table (CLEAR ops), done
in order between the primitives, so the clears of a frame cost no decode of their
own.
"""

from __future__ import annotations

import numpy as np

from vgxsim.geometry.pipeline import _plain_batch
from vgxsim.geometry.transform import apply
from vgxsim.kernels.decode import assemble_triangles, decode_stream
from vgxsim.kernels.front import fast_rows
from vgxsim.kernels.texture import decode_texcoords
from vgxsim.state.raster import needs_colour
from vgxsim.stream.opcodes import (
    CLEAR_KIND,
    CLOSEDLINE,
    DRAW_RESTART,
    DRAW_SEG,
    LINE,
    NAME_OF,
    P_CLEAR,
    P_KIND,
    P_LMCOLOR_SET,
    P_STATE,
    P_SWAP0,
    P_SWAP1,
    P_V0,
    P_V1,
    PMV,
    POINT,
    POLYGON,
    PRIM_COLUMNS,
    QSTRIP,
    TMESH,
)
from vgxsim.stream.recorder import Clear

from . import draw, flush_front
from .draw import commit_triangles, defer_triangles, draw_arrays

_TRIANGLES = np.zeros(16, bool)
_TRIANGLES[[POLYGON, TMESH, QSTRIP, PMV]] = True
_TRIANGLES.flags.writeable = False  # (a constant: which kinds are triangles)


def drain(ctx) -> None:
    """Decode and draw the window's stream up to its open primitive, if any."""
    s = ctx.stream
    nops = len(s)
    if nops == 0:
        return
    cut_ops, cut_fl = (s.open_ops, s.open_fl) if ctx.prim is not None else (nops, s.n_floats())
    if cut_ops <= 0:
        return
    ops, fl = s.arrays()
    pos, col, nrm, sent, prims, swaps = decode_stream(ops, cut_ops, fl, s.attrs)
    tc = decode_texcoords(ops, cut_ops, fl, s.tex_attrs) if s.has_texcoords else None
    s.keep_from(ops, fl, cut_ops, cut_fl)
    if cut_ops < nops:
        s.open_ops, s.open_fl = 0, 0
    records = ctx.states.records
    _draw_prims(ctx, records, pos, col, nrm, sent, prims, swaps, tc, s.clears)
    if ctx.prim is None:
        ctx.states.clear()
        s.clears = []
        s.attrs[9] = -1.0
        s.raster = None  # the next bgn* records its state again


def _lit(state, sent: np.ndarray) -> np.ndarray:
    """Which vertices are lit: with LMC_COLOR those whose normal was sent after the
    last colour; in every other lmcolor mode colour calls change the material (or are
    ignored, LMC_NULL), so every vertex is lit (lmcolor(3G))."""
    if state.lmcolor_mode != 0:
        return np.ones(sent.shape[0], dtype=bool)
    return sent


def _clear(ctx, c: Clear) -> None:
    """A CLEAR op: the triangles queued before it are drawn first."""
    commit_triangles(ctx)
    ctx.raw_batch.add_clear(c.planes, c.colour, c.z, c.stencil, c.state)


def _select_prims(ctx, records, pos, prims, swaps, clears) -> None:
    """Pick/select mode: hand each primitive to the hit test in clip space (its own
    state's transform, which holds the pick matrix), drawing nothing (pick(3G)); a
    clear recorded before the mode began is still done."""
    for r in prims[:, :PRIM_COLUMNS].tolist():
        kind, v0, v1 = r[P_KIND], r[P_V0], r[P_V1]
        if kind == CLEAR_KIND:
            _clear(ctx, clears[r[P_CLEAR]])
            continue
        if kind == DRAW_RESTART:
            # A move under resetls(TRUE) put the position at 0 while picking too
            # (nothing picked moves it on).
            ctx.linestyle_pos = 0
        if v1 == v0:
            continue
        # (draw(3G) segments are lines to the hit test)
        name = ("polygon" if kind in (POLYGON, PMV) else
                "line" if kind in (DRAW_SEG, DRAW_RESTART) else NAME_OF[kind])
        rec = records[r[P_STATE]]
        ctx.select_hook(name, apply(pos[v0:v1], rec.mvp), swaps[r[P_SWAP0]:r[P_SWAP1]].tolist(),
                        None, rec.user_planes)


def _draw_prims(ctx, records, pos, col, nrm, sent, prims, swaps, tc=None, clears=()) -> None:
    npr = prims.shape[0]
    if npr == 0:
        return
    if ctx.select_hook is not None:
        _select_prims(ctx, records, pos, prims, swaps, clears)
        return
    if draw.FLUSH_FRONT and tc is None and _plain_batch(ctx.raw_batch):
        tab = flush_front.Tables(records, ctx.row_memo)
        fast, nfast = fast_rows(prims, tab.code)
        if nfast == npr:
            commit_triangles(ctx)  # queued before this flush's rows
            flush_front.draw_rows(ctx, records, tab, pos, col, nrm, sent, prims, swaps,
                                  clears, _clear)
            return
        if nfast:
            # Runs of rows the flush pass takes, between runs of rows that need the
            # group-by-group path, in order.
            cuts = (np.flatnonzero(fast[1:] != fast[:-1]) + 1).tolist()
            for a, b in zip([0, *cuts], [*cuts, npr], strict=True):
                if fast[a]:
                    commit_triangles(ctx)
                    flush_front.draw_rows(ctx, records, tab, pos, col, nrm, sent, prims[a:b],
                                          swaps, clears, _clear)
                else:
                    _draw_groups(ctx, records, pos, col, nrm, sent, prims[a:b], swaps, tc,
                                 clears)
            return
    _draw_groups(ctx, records, pos, col, nrm, sent, prims, swaps, tc, clears)


def _draw_groups(ctx, records, pos, col, nrm, sent, prims, swaps, tc, clears) -> None:
    """Draw primitive rows group by group (the path without ``draw.FLUSH_FRONT``)."""
    npr = prims.shape[0]
    kinds = prims[:, P_KIND]
    tri = _TRIANGLES[kinds]
    if draw.MERGE_FRAGMENT_STATES:
        # (-1 for a CLEAR before any state record: the appended entry.)
        geometry = np.asarray(ctx.states.geometry + [-1], np.int64)[prims[:, P_STATE]]
    else:
        geometry = prims[:, P_STATE]
    key = geometry * 2 + prims[:, P_LMCOLOR_SET]
    # A group: consecutive triangle primitives of one geometry class (records that
    # differ at most in fragment state) and one lmcolor_set.
    brk = np.ones(npr, bool)
    brk[1:] = ~(tri[1:] & tri[:-1] & (key[1:] == key[:-1]))
    # ... or: draw(3G) segments after one under the same record (one polyline of
    # disjoint segments: the pattern runs on from each to the next, or restarts).
    if draw.MERGE_SEGMENTS:
        seg = (kinds == DRAW_SEG) | (kinds == DRAW_RESTART)
        brk[1:] &= ~(seg[1:] & seg[:-1] & (prims[1:, P_STATE] == prims[:-1, P_STATE])
                     & (prims[1:, P_LMCOLOR_SET] == prims[:-1, P_LMCOLOR_SET]))
    first = np.flatnonzero(brk)
    starts = first.tolist()
    ends = starts[1:] + [npr]
    # Per group, as lists (one conversion, not one numpy call per group): its first
    # row, the end of its last primitive's vertices, whether it is triangles and
    # whether all its primitives share the first one's record.
    stops = np.append(first[1:], npr)
    heads = prims[first, :PRIM_COLUMNS].tolist()
    last_v1 = prims[stops - 1, P_V1].tolist()
    tri_l = tri[first].tolist()
    head_state = np.repeat(prims[first, P_STATE], stops - first)
    one_record = np.logical_and.reduceat(prims[:, P_STATE] == head_state, first).tolist()
    # Drawn in order below; collected first so that lighting runs once over the lit
    # groups that share lights (draw.shade_groups).
    jobs: list = []
    lit_groups: list = []
    for g, (a, b) in enumerate(zip(starts, ends, strict=True)):
        head = heads[g]
        kind, v0, v1 = head[P_KIND], head[P_V0], last_v1[g]
        si, lms = head[P_STATE], head[P_LMCOLOR_SET]
        if kind == CLEAR_KIND:
            jobs.append((_clear, (ctx, clears[head[P_CLEAR]]), {}))
            continue
        if v1 == v0:
            continue  # bgn*/end* without vertices draws nothing
        state = records[si]
        sl = slice(v0, v1)
        lit = _lit(state, sent[sl])
        if kind == DRAW_SEG or kind == DRAW_RESTART:
            restarts = prims[a:b, P_KIND] == DRAW_RESTART
            if state.lsbackup and b - a > 1:
                # lsbackup(3G) draws the last two pixels of each line: one job a
                # segment (each its own polyline), as drawn at the call.
                for r in range(a, b):
                    ps = slice(v0 + 2 * (r - a), v0 + 2 * (r - a) + 2)
                    jobs.append((_draw_segments, (ctx, restarts[r - a:r - a + 1], state,
                                                  bool(lms), pos[ps], col[ps], nrm[ps],
                                                  lit[2 * (r - a):2 * (r - a) + 2]), {}))
                continue
            jobs.append((_draw_segments, (ctx, restarts, state, bool(lms), pos[sl], col[sl],
                                          nrm[sl], lit), {}))
            continue
        if not tri_l[g]:
            # Lines and points: one primitive per group (the line-style pattern
            # restarts at every bgnline).
            jobs.append((draw_arrays, (ctx, state, bool(lms), NAME_OF[kind], pos[sl], col[sl],
                                       nrm[sl], lit), {"private": True}))
            continue
        if state.concave or b - a == 1:
            for r in prims[a:b, :PRIM_COLUMNS].tolist():
                if r[P_V1] == r[P_V0]:
                    continue
                ps = slice(r[P_V0], r[P_V1])
                st = records[r[P_STATE]]
                name = "polygon" if r[P_KIND] in (POLYGON, PMV) else NAME_OF[r[P_KIND]]
                jobs.append((draw_arrays, (ctx, st, bool(lms), name, pos[ps], col[ps], nrm[ps],
                                           _lit(st, sent[ps])),
                             {"swaps": swaps[r[P_SWAP0]:r[P_SWAP1]].tolist(), "private": True,
                              "texcoords": None if tc is None else tc[ps]}))
            continue
        tris, prov, tri_prim = _group_triangles(prims[a:b], v0, swaps)
        tri_states = None
        if not one_record[g]:  # one record: one raster (most groups)
            recs = [records[r] for r in prims[a:b, P_STATE].tolist()]
            if any(r.raster is not state.raster for r in recs):
                tri_states = (recs, tri_prim)  # one entry per primitive of the group
        normals = nrm[sl] if state.lighting is not None else None
        cols = col[sl] if _wants_colour(state) else None
        lit = lit if normals is not None else None
        kw = {"texcoords": None if tc is None else tc[sl]}
        if state.texgen_eye is not None:  # TG_SPHEREMAP reads normals, lit or not
            kw["eye_normals"] = nrm[sl]
        if draw.BATCH_LIGHTING and cols is not None and normals is not None:
            kw["lit_rgba"] = len(lit_groups)  # filled in once all groups are known
            lit_groups.append(draw.LitGroup(state, bool(lms), pos[sl], normals, cols, lit))
        jobs.append((defer_triangles, (ctx, state, bool(lms), pos[sl], cols, normals, lit,
                                       tris, prov, tri_states), kw))
    shaded = draw.shade_groups(lit_groups) if len(lit_groups) > 1 else [None] * len(lit_groups)
    for fn, args, kw in jobs:
        if "lit_rgba" in kw:
            kw = {**kw, "lit_rgba": shaded[kw["lit_rgba"]]}
        fn(*args, **kw)


def _draw_segments(ctx, restarts: np.ndarray, state, lms: bool, pos, col, nrm, lit) -> None:
    """draw(3G) segments recorded in a row under one record (DRAW_SEG and
    DRAW_RESTART rows, two vertices each; ``restarts`` says which are the latter):
    one polyline whose pattern starts where the last line drawn before it left
    Context.linestyle_pos -- read here, when the jobs run in drawing order, not when
    the rows were collected -- runs on from segment to segment and is at 0 at each
    restart, a move under resetls(TRUE) before it (docs/numeric_model.md s. 5), as
    when each draw was drawn at its call."""
    if restarts[0]:
        ctx.linestyle_pos = 0
    n = pos.shape[0] // 2
    segs = np.arange(2 * n, dtype=np.int64).reshape(n, 2)
    draw_arrays(ctx, state, lms, "line", pos, col, nrm, lit, pattern_offset=ctx.linestyle_pos,
                private=True, segments=segs, restarts=restarts if n > 1 else None)


def _wants_colour(state) -> bool:
    return needs_colour(state.raster)


def _group_triangles(block: np.ndarray, base: int, swaps: np.ndarray):
    """Triangles (indices from ``base``), flat-shading vertices and primitive (its row
    in ``block``) of consecutive triangle primitives, in one kernel pass
    (:func:`vgxsim.kernels.decode.assemble_triangles`, which assembles each kind as
    :mod:`vgxsim.geometry.assembly` does)."""
    return assemble_triangles(np.ascontiguousarray(block), base, swaps)


__all__ = ["drain", "LINE", "CLOSEDLINE", "POINT"]
