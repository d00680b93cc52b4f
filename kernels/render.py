"""The band driver: a whole command batch renders in one pass over row bands.

The window is cut into bands of rows.  Each worker thread owns every ``nthreads``-th band
and walks the batch's primitives in their original order, so the per-pixel order
of stencil and blend operations (part of the semantics) is kept while threads never
touch the same pixel.  A band of a full frame stays in cache while clears, the
scene pass, the shadow-volume faces and the lit pass run over it.

Primitive kinds: triangles (set up by :mod:`.setup`), fragment runs (points and
lines expanded by :mod:`.lines`) and clears.
"""

from __future__ import annotations

import types as _types

import numpy as np

from vgxsim.state.codes import (
    CBLEND_ADD,
    CBLEND_GENERAL,
    CBLEND_REPLACE,
    CBLEND_SA_MSA,
    CLEAR_COLOUR,
    CLEAR_STENCIL,
    CLEAR_Z,
    D_CBLEND,
    D_DZFAIL,
    D_DZPASS,
    D_MODE,
    D_RGBA,
    D_SMAX,
    D_STENCIL,
    D_SWM,
    D_ZFAIL_NOOP,
    D_ZMASK,
    D_ZTEST,
    D_ZWRITE,
    KIND_FRAGMENTS,
    KIND_TRIANGLE,
    LO_SRC,
    MODE_COLOUR,
    MODE_GENERAL,
    MODE_ZONLY,
    MODE_ZSTENCIL,
    MODE_ZSTENCIL_ADD,
    S_BLEND_DF,
    S_BLEND_SF,
    S_DRAW_BACK,
    S_DRAW_FRONT,
    S_SFUNC,
    S_SMASK,
    S_SREF,
    S_SX0,
    S_SX1,
    S_SY0,
    S_SY1,
    S_TEXTURE,
    S_WMPACK,
    S_ZFUNC,
    WORK_FRAGMENTS,
    WORK_STENCIL_WRITES,
)

from .blocks import z_passed_row
from .borrow import borrow, keep_alive
from .fill import FILL_MIN_SPAN, zonly_span, zstencil_span
from .fragment import (
    add_sat,
    blend_sa_msa,
    cmp_bits,
    cmp_select,
    colour_row,
    combine,
    fragment,
    pack_rgba,
    pack_rgba_i32,
    round_c,
    round_z,
    round_z_i32,
    wrap_z24,
    write_z,
)
from .lit import LIT_MIN_SPAN, alpha_span_lanes, lanes_ok, lit_span, lit_span_lanes
from .options import callee, inline_ir, jit
from .prefetch import PREFETCH_DISTANCE, prefetch_box
from .raster import covers, row_span
from .small import NARROW as SMALL_NARROW
from .small import small_mode, small_triangle
from .spans import edge_next, edge_start_at, span_from
from .texture import texture_fragment
from .tiles import (
    RUN_SFREE,
    RUN_SIZE,
    TB_SIZE,
    TB_SVALID,
    TB_UNKNOWN,
    TB_VALID,
    TILE_FULL,
    TILE_H,
    TILE_H_SHIFT,
    TILE_MIN_PIXELS,
    TILE_PARTIAL,
    TILE_ROW_MIN_PIXELS,
    TILE_SHIFT,
    TILE_W,
    TILE_ZPASS,
    TILE_ZPASS_SPAN,
    classify_tiles,
    note_stencil_written,
    note_z_cleared,
    note_z_written,
)

NARROW = 8  # triangles at most this many pixels wide find their spans by scanning

#: Whether the band kernel compiles its rare paths in: the general per-fragment rows
#: (:func:`_general_row`, with the texture stage), :func:`_colour_span_slow`, the
#: SA+MSA blend spans (:func:`_alpha_span`, :func:`.lit.alpha_span_lanes`) and the
#: fragment runs of points and lines.  True in :func:`render_bands`; False in
#: :data:`render_bands_lean`, the same code compiled without them for batches that
#: never take them (:func:`lean_fits`): a cold start compiles only what the first
#: image needs (issue 7 item 4; the pruned calls are removed before typing).
_FULL = True


@jit
def bin_primitives(py0, py1, nprims, band_shift, nbands):
    """Bucket primitives into bands of ``2**band_shift`` rows, keeping their order.

    Returns
    -------
    starts : ndarray, shape (nbands + 1,), int64
    items : ndarray, int64
        ``items[starts[b]:starts[b+1]]`` are the primitives touching band b, in order.
    """
    counts = np.zeros(nbands + 1, dtype=np.int64)
    for p in range(nprims):
        b0 = max(py0[p], 0) >> band_shift
        b1 = min(py1[p] >> band_shift, nbands - 1)
        for b in range(b0, b1 + 1):
            counts[b + 1] += 1
    for b in range(nbands):
        counts[b + 1] += counts[b]
    items = np.empty(counts[nbands], dtype=np.int64)
    fill = counts[:nbands].copy()
    for p in range(nprims):
        b0 = max(py0[p], 0) >> band_shift
        b1 = min(py1[p] >> band_shift, nbands - 1)
        for b in range(b0, b1 + 1):
            items[fill[b]] = p
            fill[b] += 1
    return counts, items


@jit
def gather_band_records(items, lo, hi, p_kind, p_ref, t_edge, t_box, t_z, t_zlim, t_col,
                        t_state, g_kind, g_ref, g_edge, g_box, g_z, g_zlim, g_col, g_state):
    """Copy the set-up records of ``items[lo:hi]`` into slots ``lo .. hi - 1``.

    After binning, a band's primitives are a sparse, scattered subset of the batch;
    copied into band order, each band reads its records front to back (a frame of
    small triangles is otherwise bound by the latency of those scattered reads).
    The band kernel then runs on ``g_*`` with items ``0, 1, 2, ...``: each entry's
    kind in ``g_kind``, a triangle's record at its own slot (``g_ref[i] = i``), the
    other kinds' references unchanged.  Disjoint ``[lo, hi)`` ranges may be filled
    by different threads.
    """
    for i in range(lo, hi):
        p = items[i]
        k = p_kind[p]
        g_kind[i] = k
        if k != KIND_TRIANGLE:
            g_ref[i] = p_ref[p]
            continue
        t = p_ref[p]
        g_ref[i] = i
        for e in range(3):
            for c in range(3):
                g_edge[i, e, c] = t_edge[t, e, c]
        for c in range(4):
            g_box[i, c] = t_box[t, c]
        for c in range(5):
            g_z[i, c] = t_z[t, c]
        g_zlim[i, 0] = t_zlim[t, 0]
        g_zlim[i, 1] = t_zlim[t, 1]
        for ch in range(4):
            for c in range(3):
                g_col[i, ch, c] = t_col[t, ch, c]
        g_state[i] = t_state[t]


@inline_ir
def _triangle_rows(
    t, y_lo, y_hi, t_edge, t_box, t_z, t_zlim, t_col, st, dv, tab,
    front, back, zbuf, sten, edge_mode, general_only, skip_tiles, cover_blocks,
    tight_tiles, step_spans, vector_pack, small_path, block_update, lit, tb, runs, spans,
    work, tex,
):
    # lit = (lit_spans, lit_lanes, fill_spans, zpass_spans, span_zwrite,
    # stencil_bounds, sided_bounds): one argument, as an inlined call of more than 30
    # arguments compiles to CALL_FUNCTION_EX, which Numba cannot inline.
    (lit_spans, lit_lanes, fill_spans, zpass_spans, span_zwrite, stencil_bounds,
     sided_bounds) = lit
    ylo = max(y_lo, max(t_box[t, 2], st[S_SY0]))
    yhi = min(y_hi, min(t_box[t, 3], st[S_SY1]))
    xlo = max(t_box[t, 0], st[S_SX0])
    xhi = min(t_box[t, 1], st[S_SX1])
    if xlo > xhi or ylo > yhi:
        return
    skip = skip_tiles and dv[D_ZTEST] != 0 and dv[D_ZFAIL_NOOP] != 0
    # The block update (kernels/blocks.py): the passes with a z-passed row loop.  Only
    # where z failure is a no-op: those passes read tile bounds anyway (skip_tiles), so
    # the switch changes no bound, hence no skipped tile nor any other work counter.
    zpass = (block_update and cover_blocks and dv[D_ZTEST] != 0 and dv[D_ZFAIL_NOOP] != 0
             and not edge_mode and not general_only
             and (dv[D_MODE] == MODE_ZSTENCIL_ADD or dv[D_MODE] == MODE_ZSTENCIL
                  or dv[D_MODE] == MODE_ZONLY
                  or (dv[D_MODE] == MODE_COLOUR and (dv[D_CBLEND] == CBLEND_REPLACE
                                                     or dv[D_CBLEND] == CBLEND_ADD))))
    if span_zwrite and dv[D_MODE] == MODE_COLOUR and dv[D_ZWRITE] != 0:
        # A depth-writing colour pass (Heidmann's ambient pass over a cleared z
        # buffer): its z compare is one select of the vectorized lit span loop, so the
        # block update saves little, while z-passed tiles cut each row into runs of
        # their own (each with the colour and lanes set-up of a span); classified
        # without it, full and partial tiles merge into one span per row.  (Not
        # tied to lit_spans or vector_pack: those switches then change no counter.)
        zpass = False
    step = step_spans and not edge_mode
    # Stencil bounds (kernels/tiles.py): a colour pass's stencil test only masks, so
    # a tile whose stored values all fail it is skipped and one whose values all pass
    # it runs without it (Heidmann's lit pass after the shadow faces: stencil EQUAL
    # to the "zero" 128 over the unshadowed tiles, not EQUAL over the shadowed ones).
    sbounds = stencil_bounds and dv[D_MODE] == MODE_COLOUR and dv[D_STENCIL] != 0
    stencil_writes = dv[D_STENCIL] != 0 and dv[D_MODE] != MODE_COLOUR
    classify = (skip or cover_blocks or sbounds) and (
        (xhi - xlo + 1) * (yhi - ylo + 1) >= TILE_MIN_PIXELS)
    if (small_path and not classify and xhi - xlo < SMALL_NARROW and not general_only
            and not edge_mode and small_mode(dv)):
        # A small triangle: one pass over its box, no span set-up (kernels/small.py).
        tested = small_triangle(t, xlo, xhi, ylo, yhi, t_edge, t_z, t_zlim, t_col, st, dv,
                                tab, front, back, zbuf, sten)
        work[WORK_FRAGMENTS] += tested
        if stencil_writes:
            work[WORK_STENCIL_WRITES] += tested
            if tested > 0:
                note_stencil_written(tb, xlo, xhi, ylo, yhi, y_lo,
                                     (front.shape[1] + TILE_W - 1) >> TILE_SHIFT)
        if dv[D_ZWRITE] != 0 and tested > 0:
            note_z_written(tb, xlo, xhi, ylo, yhi, y_lo, (front.shape[1] + TILE_W - 1)
                           >> TILE_SHIFT, t_zlim[t, 0], t_zlim[t, 1], dv[D_ZMASK],
                           st[S_ZFUNC], sided_bounds)
        return
    # Edge quotients carried row to row (kernels/spans.py); dummies when not stepping.
    s0, q0, r0, d0, bq0, br0 = edge_start_at(t_edge, t, 0, ylo)
    s1, q1, r1, d1, bq1, br1 = edge_start_at(t_edge, t, 1, ylo)
    s2, q2, r2, d2, bq2, br2 = edge_start_at(t_edge, t, 2, ylo)
    stored = classify and step and tight_tiles
    ys = ylo  # row of spans[0]
    if stored:
        # Solve the band's row spans first: the triangle's own pixels in each tile
        # row bound the tiles to classify (a thin shadow face's bounding box holds
        # many tiles it never touches) and its corners' depth range (tighter bounds
        # skip more); the rows below read the stored spans instead of stepping.
        ry0 = yhi + 1
        ry1 = ylo - 1
        for y in range(ylo, yhi + 1):
            sl, sr = span_from(s0, q0, s1, q1, s2, q2, xlo, xhi)
            q0, r0 = edge_next(q0, r0, d0, bq0, br0)
            q1, r1 = edge_next(q1, r1, d1, bq1, br1)
            q2, r2 = edge_next(q2, r2, d2, bq2, br2)
            spans[y - ys, 0] = sl
            spans[y - ys, 1] = sr
            if sl <= sr:
                ry0 = min(ry0, y)
                ry1 = y
        if ry0 > ry1:
            return  # no pixel centre of this band is inside
        ylo, yhi = ry0, ry1
    ntx = (front.shape[1] + TILE_W - 1) >> TILE_SHIFT
    runs[0, 0] = xlo
    runs[0, 1] = xhi
    runs[0, 2] = TILE_PARTIAL
    runs[0, RUN_SFREE] = 0
    nruns = 1
    next_chunk = ylo  # with classify: the first row of the next tile row
    z0 = t_z[t, 0]
    x0 = t_z[t, 1]
    y0 = t_z[t, 2]
    dzdx = t_z[t, 3]
    dzdy = t_z[t, 4]
    zmin = t_zlim[t, 0]
    zmax = t_zlim[t, 1]
    mode = dv[D_MODE]
    if general_only or edge_mode:
        mode = MODE_GENERAL
    colour = dv[D_RGBA] != 0
    lt, eq, gt = cmp_bits(st[S_ZFUNC])
    dpass = dv[D_DZPASS]
    dfail = dv[D_DZFAIL]
    smax = dv[D_SMAX]
    narrow = xhi - xlo < NARROW
    cbuf = back if st[S_DRAW_BACK] else front  # MODE_COLOUR draws one buffer
    tested = 0
    for y in range(ylo, yhi + 1):
        sl = 0
        sr = -1
        solved = False
        if stored:
            sl = spans[y - ys, 0]
            sr = spans[y - ys, 1]
            solved = True
        elif step:
            sl, sr = span_from(s0, q0, s1, q1, s2, q2, xlo, xhi)
            solved = True
            q0, r0 = edge_next(q0, r0, d0, bq0, br0)
            q1, r1 = edge_next(q1, r1, d1, bq1, br1)
            q2, r2 = edge_next(q2, r2, d2, bq2, br2)
        if classify and y == next_chunk:
            # A new tile row (TILE_H rows of the band): classify its tiles over the
            # triangle's rectangle in it (its own pixels when the spans are stored).
            ty = (y - y_lo) >> TILE_H_SHIFT
            c_lo = y_lo + (ty << TILE_H_SHIFT)
            c_hi = min(y_hi, c_lo + TILE_H - 1)
            cy1 = min(yhi, c_hi)
            next_chunk = cy1 + 1
            cxl = xlo
            cxr = xhi
            cy0 = y
            if stored:
                cxl = xhi + 1
                cxr = xlo - 1
                cy0 = cy1 + 1
                for yy in range(y, cy1 + 1):
                    if spans[yy - ys, 0] <= spans[yy - ys, 1]:
                        cxl = min(cxl, spans[yy - ys, 0])
                        cxr = max(cxr, spans[yy - ys, 1])
                        cy0 = min(cy0, yy)
                        cy1 = yy
            if cxl > cxr:
                nruns = 0
            elif (cxr - cxl + 1) * (cy1 - cy0 + 1) >= (TILE_ROW_MIN_PIXELS if stored
                                                         else TILE_MIN_PIXELS):
                nruns = classify_tiles(t, cxl, cxr, cy0, cy1, c_lo, c_hi, ty * ntx, t_edge,
                                       t_z, t_zlim, st, zbuf, tb, runs, skip, cover_blocks,
                                       not edge_mode, zpass, zpass and zpass_spans, work,
                                       sbounds, tab, sten)
            else:
                runs[0, 0] = cxl
                runs[0, 1] = cxr
                runs[0, 2] = TILE_PARTIAL
                runs[0, RUN_SFREE] = 0
                nruns = 1
        if nruns == 0 or (stored and sl > sr):
            continue  # every tile of this tile row skipped, or an empty row
        for r in range(nruns):
            full = runs[r, 2] == TILE_FULL or runs[r, 2] == TILE_ZPASS
            if full or edge_mode:
                xl = runs[r, 0]
                xr = runs[r, 1]
            else:
                if not solved:
                    solved = True
                    edge = t_edge[t]  # (step_spans off: the hot path takes no view)
                    if narrow:
                        # Small triangles: scan the few pixel centres of the row with
                        # the edge functions (multiply-adds) instead of solving for the
                        # span (divisions).
                        sl = xhi + 1
                        for x in range(xlo, xhi + 1):
                            if covers(edge, x, y):
                                if x < sl:
                                    sl = x
                                sr = x
                    else:
                        sl, sr = row_span(edge, y, xlo, xhi)
                xl = max(sl, runs[r, 0])
                xr = min(sr, runs[r, 1])
                if xl > xr:
                    continue
            tested += xr - xl + 1
            za = z0 + dzdy * (y - y0)
            # Planes are indexed [row, column] rather than through row views: a view
            # costs two (atomic, out-of-line) reference-count updates, several per
            # row of a small triangle, and the threads share the counts' cache line.
            uy = np.uintp(y)
            if runs[r, 2] == TILE_ZPASS or runs[r, 2] == TILE_ZPASS_SPAN:
                z_passed_row(t, uy, xl, xr, za, dzdx, x0, y0, zmin, zmax, t_col, st, dv, tab,
                             cbuf, zbuf, sten, vector_pack, lit_lanes, runs[r, RUN_SFREE] != 0)
            elif (mode == MODE_ZSTENCIL_ADD and fill_spans and vector_pack
                  and xr - xl >= FILL_MIN_SPAN - 1 and zmin >= -2147483648
                  and zmax <= 2147483647):
                # The same loop compiled on its own, on int32 lanes (kernels/fill.py:
                # in this kernel its invariants are spilled and reloaded per vector).
                zstencil_span(uy, xl, xr, za, dzdx, x0, zmin, zmax, lt, eq, gt, dpass, dfail,
                              smax, zbuf, sten)
            elif mode == MODE_ZSTENCIL_ADD and vector_pack and zmin >= -2147483648 \
                    and zmax <= 2147483647:
                # The shadow-volume pass with z rounded through int32 (vectorizes;
                # the same values as round_z, kernels/fragment.py round_z_i32).
                for x in range(xl, xr + 1):
                    ux = np.uintp(x)
                    zi = round_z_i32(za + dzdx * (x - x0), zmin, zmax)
                    passed = cmp_select(lt, eq, gt, zi, np.int64(zbuf[uy, ux]))
                    sv = np.int64(sten[uy, ux]) + (dpass if passed else dfail)
                    sten[uy, ux] = min(max(sv, 0), smax)
            elif mode == MODE_ZSTENCIL_ADD:
                for x in range(xl, xr + 1):
                    ux = np.uintp(x)  # unsigned: no negative-index wraparound: vectorizes
                    zi = round_z(za + dzdx * (x - x0), zmin, zmax)
                    passed = cmp_select(lt, eq, gt, zi, np.int64(zbuf[uy, ux]))
                    sv = np.int64(sten[uy, ux]) + (dpass if passed else dfail)
                    sten[uy, ux] = min(max(sv, 0), smax)
            elif mode == MODE_COLOUR:
                _colour_span(t, uy, xl, xr, za, dzdx, x0, y0, zmin, zmax, t_col, st, dv,
                             cbuf, zbuf, sten, front, back, tab, vector_pack, lit_spans,
                             lit_lanes, runs[r, RUN_SFREE] != 0)
            elif mode == MODE_ZSTENCIL:
                for x in range(xl, xr + 1):
                    ux = np.uintp(x)
                    zi = round_z(za + dzdx * (x - x0), zmin, zmax)
                    sv = sten[uy, ux]
                    if cmp_select(lt, eq, gt, zi, np.int64(zbuf[uy, ux])):
                        sten[uy, ux] = tab[0, sv]
                    else:
                        sten[uy, ux] = tab[1, sv]
            elif (mode == MODE_ZONLY and fill_spans and vector_pack
                  and xr - xl >= FILL_MIN_SPAN - 1 and zmin >= -2147483648
                  and zmax <= 2147483647):
                zonly_span(uy, xl, xr, za, dzdx, x0, zmin, zmax, lt, eq, gt, dv[D_ZMASK], zbuf)
            elif mode == MODE_ZONLY:
                for x in range(xl, xr + 1):
                    ux = np.uintp(x)
                    zi = round_z(za + dzdx * (x - x0), zmin, zmax)
                    if cmp_select(lt, eq, gt, zi, np.int64(zbuf[uy, ux])):
                        zbuf[uy, ux] = wrap_z24(zi)
            elif _FULL:  # (lean_fits: no state of a lean batch gets here)
                _general_row(t, y, xl, xr, za, dzdx, x0, y0, zmin, zmax, t_col, t_edge, colour,
                             edge_mode and not full, st, dv, tab, front, back, zbuf, sten, tex)
    work[WORK_FRAGMENTS] += tested
    if stencil_writes:
        work[WORK_STENCIL_WRITES] += tested
        if tested > 0:  # (every tile skipped: nothing written)
            note_stencil_written(tb, xlo, xhi, ylo, yhi, y_lo, ntx)
    if dv[D_ZWRITE] != 0 and tested > 0:  # every tile skipped: nothing written
        note_z_written(tb, xlo, xhi, ylo, yhi, y_lo, ntx, zmin, zmax, dv[D_ZMASK], st[S_ZFUNC],
                       sided_bounds)


@callee
def _general_row(t, y, xl, xr, za, dzdx, x0, y0, zmin, zmax, t_col, t_edge, colour,
                 edge_mode, st, dv, tab, front, back, zbuf, sten, tex):
    """The general per-fragment path for one row (any state; the edge-function
    rasterizer when ``edge_mode``).  Compiled out of line: it is the rare path, and
    keeping it out of the band kernel shortens that kernel's cold compile.
    ``tex`` = (t_tex, info, env_colour, texels): the texture stage's planes and
    table, read when the state's S_TEXTURE slot is non-zero."""
    ra, ga, ba, aa, rdx, gdx, bdx, adx = colour_row(t_col, t, y - y0)
    edge = t_edge[t]
    slot = st[S_TEXTURE] - 1
    for x in range(xl, xr + 1):
        if edge_mode and not covers(edge, x, y):
            continue
        zi = round_z(za + dzdx * (x - x0), zmin, zmax)
        rgba = 0
        if colour:
            dx = x - x0
            if slot >= 0:
                r, g, b, a = texture_fragment(
                    tex[0], t, x, y, x0, y0, tex[1], tex[2], tex[3], slot,
                    round_c(ra + rdx * dx), round_c(ga + gdx * dx), round_c(ba + bdx * dx),
                    round_c(aa + adx * dx))
                rgba = pack_rgba(r, g, b, a)
            else:
                rgba = pack_rgba(ra + rdx * dx, ga + gdx * dx, ba + bdx * dx, aa + adx * dx)
        fragment(x, y, zi, rgba, st, dv, tab, front, back, zbuf, sten)


@inline_ir
def _colour_span(t, uy, xl, xr, za, dzdx, x0, y0, zmin, zmax, t_col, st, dv, cbuf, zbuf,
                 sten, front, back, tab, vector_pack, lit_spans, lit_lanes, sfree):
    """MODE_COLOUR: shaded span of row ``uy`` with read-only stencil, optional z,
    simple blend, into ``cbuf`` (the one colour buffer the state draws).
    ``vector_pack``: the stencil-tested loop packs colour through
    :func:`pack_rgba_i32` (same words, a conversion AVX2 vectorizes);
    ``lit_spans`` (with ``vector_pack``): spans of at least ``LIT_MIN_SPAN`` pixels
    of the replace and ONE+ONE passes run :func:`.lit.lit_span`, or with
    ``lit_lanes``, where :func:`.lit.lanes_ok` allows, :func:`.lit.lit_span_lanes`;
    ``sfree``: the stencil test is known to pass on the whole span (the tiles'
    stencil bounds, kernels/tiles.py), so the fast loops leave it out."""
    ztest = dv[D_ZTEST] != 0
    stest = dv[D_STENCIL] != 0 and not sfree
    zwrite = dv[D_ZWRITE] != 0
    lt, eq, gt = cmp_bits(st[S_ZFUNC])
    blend = dv[D_CBLEND]
    wm = st[S_WMPACK] & 0xFFFFFFFF
    keep = ~wm & 0xFFFFFFFF
    y = np.int64(uy)
    ra, ga, ba, aa, rdx, gdx, bdx, adx = colour_row(t_col, t, y - y0)
    if ztest and blend != CBLEND_GENERAL:
        # Branch-free form for the common passes (z test on; replace, add or SA+MSA
        # blend; Heidmann's ambient and lit passes): every pixel computes everything
        # and the writes select old or new values, so LLVM can vectorize the loop.
        sfunc = st[S_SFUNC]
        smask = st[S_SMASK]
        sref = st[S_SREF] & smask
        slt, seq, sgt = cmp_bits(sfunc)
        add = blend == CBLEND_ADD
        # (lean_fits: a lean batch has no SA+MSA blend.  Each branch tests _FULL
        # first: Numba prunes a branch whose condition is a False global before
        # typing, and only then -- a `not _FULL` branch of its own left the two
        # SA+MSA branches below it reachable, so the lean kernel compiled them.)
        if not _FULL and blend == CBLEND_SA_MSA:
            pass
        elif (_FULL and blend == CBLEND_SA_MSA and lit_lanes and vector_pack
                and lanes_ok(xl, xr, x0, za, dzdx, zmin, zmax, ra, ga, ba, aa, rdx, gdx, bdx,
                             adx)):
            alpha_span_lanes(uy, xl, xr, za, dzdx, x0, zmin, zmax, ra, ga, ba, aa, rdx, gdx,
                             bdx, adx, lt, eq, gt, zwrite, stest, slt, seq, sgt,
                             smask, sref, wm, dv[D_ZMASK], cbuf, zbuf, sten)
        elif _FULL and blend == CBLEND_SA_MSA:
            _alpha_span(uy, xl, xr, za, dzdx, x0, zmin, zmax, ra, ga, ba, aa, rdx, gdx, bdx,
                        adx, lt, eq, gt, zwrite, stest, slt, seq, sgt, smask, sref,
                        wm, keep, cbuf, zbuf, sten)
        elif (lit_spans and vector_pack and xr - xl + 1 >= LIT_MIN_SPAN
              and zmin >= -2147483648 and zmax <= 2147483647):
            # The same loop compiled on its own (kernels/lit.py: inside this kernel
            # its invariants are spilled and reloaded on every pixel), on 32-bit lanes
            # where the planes' values are bounded (lit_lanes).
            if lit_lanes and lanes_ok(xl, xr, x0, za, dzdx, zmin, zmax, ra, ga, ba, aa, rdx,
                                      gdx, bdx, adx):
                lit_span_lanes(uy, xl, xr, za, dzdx, x0, zmin, zmax, ra, ga, ba, aa, rdx, gdx,
                               bdx, adx, lt, eq, gt, zwrite, stest, slt, seq, sgt,
                               smask, sref, add, wm, dv[D_ZMASK], cbuf, zbuf, sten)
            else:
                lit_span(uy, xl, xr, za, dzdx, x0, zmin, zmax, ra, ga, ba, aa, rdx, gdx, bdx,
                         adx, lt, eq, gt, zwrite, stest, slt, seq, sgt, smask,
                         sref, add, wm, keep, cbuf, zbuf, sten)
        elif (stest and vector_pack and zmin >= -2147483648
              and zmax <= 2147483647):
            # Heidmann's lit pass (stencil test, ONE+ONE): the switch is tested once
            # per span, so the loop itself carries no branch on it.
            for x in range(xl, xr + 1):
                ux = np.uintp(x)
                sv = np.int64(sten[uy, ux]) & smask
                sok = cmp_select(slt, seq, sgt, sref, sv)
                zi = round_z_i32(za + dzdx * (x - x0), zmin, zmax)
                zb = np.int64(zbuf[uy, ux])
                ok = sok & cmp_select(lt, eq, gt, zi, zb)
                zbuf[uy, ux] = wrap_z24(zi) if (ok & zwrite) else zb
                dx = x - x0
                src = pack_rgba_i32(ra + rdx * dx, ga + gdx * dx, ba + bdx * dx,
                                    aa + adx * dx)
                dst = np.int64(cbuf[uy, ux])
                out = add_sat(src, dst) if add else src
                cbuf[uy, ux] = ((dst & keep) | (out & wm)) if ok else dst
        elif stest:
            for x in range(xl, xr + 1):
                ux = np.uintp(x)
                sv = np.int64(sten[uy, ux]) & smask
                sok = cmp_select(slt, seq, sgt, sref, sv)
                zi = round_z(za + dzdx * (x - x0), zmin, zmax)
                zb = np.int64(zbuf[uy, ux])
                ok = sok & cmp_select(lt, eq, gt, zi, zb)
                zbuf[uy, ux] = wrap_z24(zi) if (ok & zwrite) else zb
                dx = x - x0
                src = pack_rgba(ra + rdx * dx, ga + gdx * dx, ba + bdx * dx, aa + adx * dx)
                dst = np.int64(cbuf[uy, ux])
                out = add_sat(src, dst) if add else src
                cbuf[uy, ux] = ((dst & keep) | (out & wm)) if ok else dst
        else:
            for x in range(xl, xr + 1):
                ux = np.uintp(x)
                zi = round_z(za + dzdx * (x - x0), zmin, zmax)
                zb = np.int64(zbuf[uy, ux])
                ok = cmp_select(lt, eq, gt, zi, zb)
                zbuf[uy, ux] = wrap_z24(zi) if (ok & zwrite) else zb
                dx = x - x0
                src = pack_rgba(ra + rdx * dx, ga + gdx * dx, ba + bdx * dx, aa + adx * dx)
                dst = np.int64(cbuf[uy, ux])
                out = add_sat(src, dst) if add else src
                cbuf[uy, ux] = ((dst & keep) | (out & wm)) if ok else dst
        return
    if _FULL:  # (lean_fits: no state of a lean batch gets here)
        _colour_span_slow(t, y, xl, xr, za, dzdx, x0, y0, zmin, zmax, t_col, st, dv, tab,
                          front, back, zbuf, sten)


@callee
def _alpha_span(uy, xl, xr, za, dzdx, x0, zmin, zmax, ra, ga, ba, aa, rdx, gdx, bdx, adx,
                lt, eq, gt, zwrite, stest, slt, seq, sgt, smask, sref, wm, keep, cbuf, zbuf,
                sten):
    """MODE_COLOUR with blendfunction(BF_SA, BF_MSA) and the z test on: the
    branch-free span loop of :func:`_colour_span` with the alpha blend computed
    component by component (compiled out of line: keeps the band kernel's compile
    short; one call per row span)."""
    if stest:
        for x in range(xl, xr + 1):
            ux = np.uintp(x)
            sok = cmp_select(slt, seq, sgt, sref, np.int64(sten[uy, ux]) & smask)
            zi = round_z(za + dzdx * (x - x0), zmin, zmax)
            zb = np.int64(zbuf[uy, ux])
            ok = sok & cmp_select(lt, eq, gt, zi, zb)
            zbuf[uy, ux] = wrap_z24(zi) if (ok & zwrite) else zb
            dst = np.int64(cbuf[uy, ux])
            out = blend_sa_msa(x - x0, ra, ga, ba, aa, rdx, gdx, bdx, adx, dst)
            cbuf[uy, ux] = ((dst & keep) | (out & wm)) if ok else dst
    else:
        for x in range(xl, xr + 1):
            ux = np.uintp(x)
            zi = round_z(za + dzdx * (x - x0), zmin, zmax)
            zb = np.int64(zbuf[uy, ux])
            ok = cmp_select(lt, eq, gt, zi, zb)
            zbuf[uy, ux] = wrap_z24(zi) if (ok & zwrite) else zb
            dst = np.int64(cbuf[uy, ux])
            out = blend_sa_msa(x - x0, ra, ga, ba, aa, rdx, gdx, bdx, adx, dst)
            cbuf[uy, ux] = ((dst & keep) | (out & wm)) if ok else dst


@callee
def _colour_span_slow(t, y, xl, xr, za, dzdx, x0, y0, zmin, zmax, t_col, st, dv, tab,
                      front, back, zbuf, sten):
    """MODE_COLOUR without a z test or with a general blend: per-pixel branches,
    compiled out of line (the rarer case; keeps the band kernel's compile short)."""
    buf = back[y] if st[S_DRAW_BACK] else front[y]
    ztest = dv[D_ZTEST] != 0
    zwrite = dv[D_ZWRITE] != 0
    stest = dv[D_STENCIL] != 0
    lt, eq, gt = cmp_bits(st[S_ZFUNC])
    blend = dv[D_CBLEND]
    sf = st[S_BLEND_SF]
    df = st[S_BLEND_DF]
    wm = st[S_WMPACK] & 0xFFFFFFFF
    keep = ~wm & 0xFFFFFFFF
    zrow = zbuf[y]
    srow = sten[y]
    spass = tab[2]
    ra, ga, ba, aa, rdx, gdx, bdx, adx = colour_row(t_col, t, y - y0)
    for x in range(xl, xr + 1):
        ux = np.uintp(x)
        if stest and spass[srow[ux]] == 0:
            continue
        if ztest:
            zi = round_z(za + dzdx * (x - x0), zmin, zmax)
            zb = np.int64(zrow[ux])
            if not cmp_select(lt, eq, gt, zi, zb):
                continue
            if zwrite:
                zrow[ux] = wrap_z24(zi)
        dx = x - x0
        src = pack_rgba(ra + rdx * dx, ga + gdx * dx, ba + bdx * dx, aa + adx * dx)
        dst = np.int64(buf[ux])
        if blend == CBLEND_REPLACE:
            out = src
        elif blend == CBLEND_ADD:
            out = add_sat(src, dst)
        else:
            out = combine(src, dst, sf, df, LO_SRC, 0xFFFFFFFF)
        buf[ux] = (dst & keep) | (out & wm)


@callee
def _clear_rows(c, y_lo, y_hi, c_vals, st, dv, front, back, zbuf, sten, tb):
    ylo = max(y_lo, st[S_SY0])
    yhi = min(y_hi, st[S_SY1])
    xlo = st[S_SX0]
    xhi = st[S_SX1]
    if ylo > yhi or xlo > xhi:
        return
    planes = c_vals[c, 0]
    if planes & CLEAR_COLOUR:
        wm = st[S_WMPACK] & 0xFFFFFFFF
        val = c_vals[c, 1] & wm
        keep = ~wm & 0xFFFFFFFF
        for y in range(ylo, yhi + 1):
            if st[S_DRAW_BACK]:
                row = back[y]
                for x in range(xlo, xhi + 1):
                    ux = np.uintp(x)
                    row[ux] = (np.int64(row[ux]) & keep) | val
            if st[S_DRAW_FRONT]:
                row = front[y]
                for x in range(xlo, xhi + 1):
                    ux = np.uintp(x)
                    row[ux] = (np.int64(row[ux]) & keep) | val
    if planes & CLEAR_Z:
        zmask = dv[D_ZMASK]
        zval = c_vals[c, 2]
        for y in range(ylo, yhi + 1):
            row = zbuf[y]
            for x in range(xlo, xhi + 1):
                ux = np.uintp(x)
                row[ux] = write_z(np.int64(row[ux]), zval, zmask)
        note_z_cleared(tb, xlo, xhi, ylo, yhi, y_lo, y_hi, front.shape[1], zval, zmask)
    if planes & CLEAR_STENCIL:
        tb[:, TB_SVALID] = TB_UNKNOWN  # found again by the next pass that asks
        wm = dv[D_SWM]
        sval = c_vals[c, 3] & wm
        for y in range(ylo, yhi + 1):
            row = sten[y]
            for x in range(xlo, xhi + 1):
                ux = np.uintp(x)
                row[ux] = (row[ux] & ~wm) | sval


@callee
def _fragment_run(r, y_lo, y_hi, f_xy, f_z, f_rgba, r_range, st, dv, tab,
                  front, back, zbuf, sten, tb, work):
    if dv[D_ZWRITE] != 0:
        tb[:, TB_VALID] = TB_UNKNOWN  # points and lines: forget the band's depth bounds
    if dv[D_STENCIL] != 0:
        tb[:, TB_SVALID] = TB_UNKNOWN  # and stencil bounds
    for f in range(r_range[r, 0], r_range[r, 1]):
        y = f_xy[f, 1]
        if y < y_lo or y > y_hi or y < st[S_SY0] or y > st[S_SY1]:
            continue
        x = f_xy[f, 0]
        if x < st[S_SX0] or x > st[S_SX1]:
            continue
        work[WORK_FRAGMENTS] += 1
        fragment(x, y, np.int64(f_z[f]), np.int64(f_rgba[f]), st, dv, tab,
                 front, back, zbuf, sten)


@inline_ir
def _bands_body(
    tid, nthreads, starts, items, band_shift, height,
    p_kind, p_ref,
    t_edge, t_box, t_z, t_zlim, t_col, t_state,
    frags,
    c_vals, c_state,
    states, derived, tables,
    front, back, zbuf, sten,
    switches, work, tex,
):
    # The body of :func:`render_bands`, inlined into each entry point; ``frags``
    # and ``switches`` are tuples (an inlined call of more than 30 arguments
    # compiles to CALL_FUNCTION_EX, which Numba cannot inline).
    f_xy, f_z, f_rgba, r_range, r_state = frags
    (edge_mode, general_only, skip_tiles, cover_blocks, tight_tiles, step_spans, vector_pack,
     small_path, block_update, lit_spans, lit_lanes, fill_spans, zpass_spans,
     prefetch_planes, span_zwrite, stencil_bounds, sided_bounds) = switches
    band_h = 1 << band_shift
    nbands = starts.shape[0] - 1
    ntiles = (front.shape[1] + TILE_W - 1) >> TILE_SHIFT
    # Tile bounds of one band: (band_h / TILE_H) tile rows of ntiles tiles.
    tb_own = np.zeros((ntiles * max(1, band_h >> TILE_H_SHIFT), TB_SIZE), np.int64)
    runs_own = np.zeros((ntiles, RUN_SIZE), np.int64)
    spans_own = np.zeros((band_h, 2), np.int64)  # a triangle's row spans in one band
    # Borrowed (kernels/borrow.py): no counted references in the inlined helpers;
    # the scratch arrays are kept alive to the end (keep_alive below).
    tb, runs, spans = borrow(tb_own), borrow(runs_own), borrow(spans_own)
    for b in range(tid, nbands, nthreads):
        y_lo = b * band_h
        y_hi = min(y_lo + band_h, height) - 1
        tb[:, TB_VALID] = TB_UNKNOWN  # bounds are found again in each band, on first use
        tb[:, TB_SVALID] = TB_UNKNOWN
        bw = borrow(work[b])  # (views borrowed too: ``work`` outlives them)
        # The state's rows, taken again only when the state changes (runs of
        # primitives share a state).
        cur = -1
        st = borrow(states[0])
        dv = borrow(derived[0])
        tab = borrow(tables[0])
        end = starts[b + 1]
        for i in range(starts[b], end):
            if prefetch_planes and i + PREFETCH_DISTANCE < end:
                q = items[i + PREFETCH_DISTANCE]
                if p_kind[q] == KIND_TRIANGLE:
                    u = p_ref[q]
                    prefetch_box(u, t_state[u], y_lo, y_hi, t_box, states, derived, front,
                                 back, zbuf, sten)
            p = items[i]
            kind = p_kind[p]
            ref = p_ref[p]
            if kind == KIND_TRIANGLE:
                s = t_state[ref]
                if s != cur:
                    cur = s
                    st = borrow(states[s])
                    dv = borrow(derived[s])
                    tab = borrow(tables[s])
                _triangle_rows(
                    ref, y_lo, y_hi, t_edge, t_box, t_z, t_zlim, t_col,
                    st, dv, tab,
                    front, back, zbuf, sten, edge_mode, general_only, skip_tiles,
                    cover_blocks, tight_tiles, step_spans, vector_pack, small_path, block_update,
                    (lit_spans, lit_lanes, fill_spans, zpass_spans, span_zwrite,
                     stencil_bounds, sided_bounds), tb, runs,
                    spans, bw,
                    tex,
                )
            elif kind == KIND_FRAGMENTS:
                if _FULL:  # (lean_fits: a lean batch has no fragment runs)
                    s = r_state[ref]
                    _fragment_run(ref, y_lo, y_hi, f_xy, f_z, f_rgba, r_range,
                                  states[s], derived[s], tables[s],
                                  front, back, zbuf, sten, tb, bw)
            else:
                s = c_state[ref]
                _clear_rows(ref, y_lo, y_hi, c_vals, states[s], derived[s],
                            front, back, zbuf, sten, tb)
    keep_alive(tb_own, runs_own, spans_own)


@jit
def render_bands(
    tid, nthreads, starts, items, band_shift, height,
    p_kind, p_ref,
    t_edge, t_box, t_z, t_zlim, t_col, t_state,
    f_xy, f_z, f_rgba, r_range, r_state,
    c_vals, c_state,
    states, derived, tables,
    front, back, zbuf, sten,
    edge_mode, general_only, skip_tiles, cover_blocks, tight_tiles, step_spans, vector_pack,
    small_path, block_update, lit_spans, lit_lanes, fill_spans, zpass_spans, prefetch_planes,
    span_zwrite, stencil_bounds, sided_bounds, work, tex,
):
    """Render every ``nthreads``-th band, starting with band ``tid``.

    Called once per worker thread (the kernels release the GIL); bands are
    disjoint rows, so threads never touch the same pixel, and inside a band the
    primitives run in their original order.  Interleaving the bands balances load
    on scenes whose depth complexity is uneven.

    Parameters
    ----------
    tid, nthreads : int
        This worker and the number of workers.
    starts, items : ndarray, int64
        Output of :func:`bin_primitives`.
    band_shift : int
        Bands are ``2**band_shift`` rows.
    height : int
        Window height.
    p_kind, p_ref : ndarray, shape (P,), int64
        Primitive kind (KIND_*) and index into that kind's arrays.
    t_edge, t_box, t_z, t_zlim, t_col, t_state : ndarray
        Set-up triangles (see :func:`vgxsim.kernels.setup.setup_triangles`).
    f_xy, f_z, f_rgba : ndarray, shapes (F, 2) int64, (F,) int64, (F,) int64
        Fragments of points and lines; ``r_range`` (R, 2) int64 gives each run's
        ``[start, end)`` and ``r_state`` (R,) its state.
    c_vals : ndarray, shape (C, 4), int64
        Clears: plane bits, packed colour, z, stencil; ``c_state`` (C,) their states.
    states, derived, tables : ndarray
        State rows, :func:`derive_states` output.
    front, back : ndarray, shape (H, W), uint32
        Colour buffers (a (1, 1) dummy when absent).
    zbuf : ndarray, shape (H, W), int32; sten : ndarray, shape (H, W), uint8
        Depth and stencil planes (a (1, 1) dummy when absent).
    edge_mode, general_only : bool
        Test switches: edge-function rasterizer instead of spans; the general
        per-fragment path instead of the fast span loops.
    skip_tiles, cover_blocks : bool
        Exact work skipping (:mod:`.tiles`): tiles whose depth bounds decide the z
        test; tiles fully inside a triangle (switches, on by default).
    tight_tiles : bool
        Classify tiles over a triangle's own pixels in the band (its row spans,
        solved first and kept), not its bounding box (a switch, on by default).
    step_spans, vector_pack : bool
        Row spans stepped exactly (:mod:`.spans`); colour and z converted through
        int32 in the lit-pass and z+stencil loops (switches, on by default; same
        planes).
    small_path : bool
        Triangles at most ``kernels.small.NARROW`` pixels wide whose tiles are not
        classified run in one pass over their box (:mod:`.small`; a switch, on by
        default; same planes).
    block_update : bool
        With ``cover_blocks``: rows of fully covered tiles where the z test is known
        to pass run without it (:mod:`.blocks`; a switch, on by default).
    lit_spans : bool
        With ``vector_pack``: long spans of the lit and ambient passes (z test,
        replace or ONE+ONE) run the out-of-line loop of :mod:`.lit` (a switch, on by
        default; same planes).
    lit_lanes : bool
        With ``lit_spans``: those spans, and the block update's lit and ambient
        rows, on 32-bit lanes where every plane's values are bounded
        (:func:`.lit.lit_span_lanes`; a switch, on by default; same planes).
    fill_spans : bool
        With ``vector_pack``: spans of at least ``FILL_MIN_SPAN`` pixels of the
        z+stencil pass with arithmetic ops and of the depth-only pass run the
        out-of-line loops of :mod:`.fill` (a switch, on by default; same planes).
    zpass_spans : bool
        With ``block_update``: the row spans of partly covered tiles whose depth
        bounds prove the z test passes run the block update's loop too
        (``TILE_ZPASS_SPAN``, :mod:`.tiles`; a switch, on by default; same planes).
    prefetch_planes : bool
        Prefetch the plane rows of the small triangle ``PREFETCH_DISTANCE`` entries
        ahead (:mod:`.prefetch`; a hint: a switch, on by default; same planes).
    span_zwrite : bool
        With ``block_update``: depth-writing colour passes ask for no z-passed tiles
        (their z-tested span loop costs about what the block rows do, and z-passed
        runs cut each row; a switch, on by default; same planes).
    stencil_bounds : bool
        Stencil-testing colour passes classify their tiles by the tiles' stencil
        bounds too: skipped where the test fails for every stored value, run without
        the per-fragment stencil test where it passes for every one (:mod:`.tiles`;
        a switch, on by default; same planes).
    sided_bounds : bool
        Z writes under a zfunction without the "greater" (or "less") outcome leave
        the tiles' upper (lower) depth bound as it was instead of widening it
        (:func:`.tiles.note_z_written`; a switch, on by default; same planes).
    work : ndarray, shape (nbands, WORK_SIZE), int64
        Work counters (WORK_*), one row per band, added to.
    tex : tuple
        (t_tex (T, 3, 3) float64 texture-coordinate planes, info (K, X_SIZE) int64,
        env_colour (K, 4) float64, texels (N,) uint32): the texture stage
        (:mod:`.texture`, vgxsim.state.textures.pack_bindings).

    The arrays may be plain or borrowed (:func:`render_bands_borrowed`).
    """
    _bands_body(
        tid, nthreads, starts, items, band_shift, height, p_kind, p_ref, t_edge, t_box, t_z,
        t_zlim, t_col, t_state, (f_xy, f_z, f_rgba, r_range, r_state), c_vals, c_state,
        states, derived, tables, front, back, zbuf, sten,
        (edge_mode, general_only, skip_tiles, cover_blocks, tight_tiles, step_spans,
         vector_pack, small_path, block_update, lit_spans, lit_lanes, fill_spans,
         zpass_spans, prefetch_planes, span_zwrite, stencil_bounds, sided_bounds),
        work, tex)


@jit
def render_bands_borrowed(
    tid, nthreads, starts, items, band_shift, height,
    p_kind, p_ref,
    t_edge, t_box, t_z, t_zlim, t_col, t_state,
    f_xy, f_z, f_rgba, r_range, r_state,
    c_vals, c_state,
    states, derived, tables,
    front, back, zbuf, sten,
    edge_mode, general_only, skip_tiles, cover_blocks, tight_tiles, step_spans, vector_pack,
    small_path, block_update, lit_spans, lit_lanes, fill_spans, zpass_spans, prefetch_planes,
    span_zwrite, stencil_bounds, sided_bounds, work, tex,
):
    """:func:`render_bands` on borrowed arrays (kernels/borrow.py,
    CommandBatch.borrow_arrays; the same arguments): the helpers it inlines per
    triangle bind their array arguments without counted references.  The caller
    holds every argument for the whole call.  (The body is inlined here, not
    called: a call links the callee's code into this one's, and Numba optimizes
    the linked module again: seconds of a cold start for the band kernel.)"""
    _bands_body(
        tid, nthreads, borrow(starts), borrow(items), band_shift, height,
        borrow(p_kind), borrow(p_ref),
        borrow(t_edge), borrow(t_box), borrow(t_z), borrow(t_zlim), borrow(t_col),
        borrow(t_state),
        (borrow(f_xy), borrow(f_z), borrow(f_rgba), borrow(r_range), borrow(r_state)),
        borrow(c_vals), borrow(c_state),
        borrow(states), borrow(derived), borrow(tables),
        borrow(front), borrow(back), borrow(zbuf), borrow(sten),
        (edge_mode, general_only, skip_tiles, cover_blocks, tight_tiles, step_spans,
         vector_pack, small_path, block_update, lit_spans, lit_lanes, fill_spans,
         zpass_spans, prefetch_planes, span_zwrite, stencil_bounds, sided_bounds),
        borrow(work), (borrow(tex[0]), borrow(tex[1]), borrow(tex[2]), borrow(tex[3])))


def lean_fits(derived: np.ndarray, nruns: int, edge_mode: bool, general_only: bool) -> bool:
    """Whether :data:`render_bands_lean` draws a batch as :func:`render_bands` does.

    True when no primitive can reach a path the lean copy leaves out: no fragment
    runs, neither test switch, and every state's derived mode one of the span loops
    (:func:`_triangle_rows`), with MODE_COLOUR only where the z test is on and the
    blend is replace or ONE+ONE (not general: :func:`_colour_span_slow`; not
    SA+MSA: :func:`_alpha_span`).  States of the table
    that no primitive uses count too (a safe over-approximation).

    Parameters
    ----------
    derived : ndarray, shape (S, D_SIZE), int64
        :func:`vgxsim.state.derive.derive_states` rows of the batch's states.
    nruns : int
        Fragment runs (points and lines) queued.
    edge_mode, general_only : bool
        The batch's test switches.
    """
    if nruns or edge_mode or general_only:
        return False
    mode = derived[:, D_MODE]
    colour = mode == MODE_COLOUR
    slow = colour & ((derived[:, D_ZTEST] == 0) | (derived[:, D_CBLEND] == CBLEND_GENERAL)
                     | (derived[:, D_CBLEND] == CBLEND_SA_MSA))
    spans = ((mode == MODE_ZSTENCIL_ADD) | (mode == MODE_ZSTENCIL) | (mode == MODE_ZONLY)
             | colour)
    return bool(spans.all() and not slow.any())


def _lean_copy(kernel, globs: dict, name: str):
    """The Python function of ``kernel`` (a dispatcher, or the function itself under
    NUMBA_DISABLE_JIT) reading its globals from ``globs``, named ``name`` (Numba's
    cache files are named after the qualified name: the copy gets its own)."""
    f = getattr(kernel, "py_func", kernel)
    copy = _types.FunctionType(f.__code__, globs, name, f.__defaults__, f.__closure__)
    copy.__qualname__ = name
    copy.__doc__ = f.__doc__
    return copy


# The lean copy: the same code objects with _FULL False in their globals, so Numba's
# dead-branch pruning drops the rare calls before type inference and never compiles
# them; the inlined helpers are copied too, as the inliner reads their own globals.
_LEAN_GLOBALS = dict(globals(), _FULL=False)
_LEAN_GLOBALS["_colour_span"] = inline_ir(_lean_copy(_colour_span, _LEAN_GLOBALS,
                                                     "_colour_span_lean"))
_LEAN_GLOBALS["_triangle_rows"] = inline_ir(_lean_copy(_triangle_rows, _LEAN_GLOBALS,
                                                       "_triangle_rows_lean"))
_LEAN_GLOBALS["_bands_body"] = inline_ir(_lean_copy(_bands_body, _LEAN_GLOBALS,
                                                    "_bands_body_lean"))
#: :func:`render_bands` without the paths :func:`lean_fits` rules out (same arguments).
render_bands_lean = jit(_lean_copy(render_bands, _LEAN_GLOBALS, "render_bands_lean"))
#: :func:`render_bands_borrowed` calling :data:`render_bands_lean`.
render_bands_lean_borrowed = jit(_lean_copy(render_bands_borrowed, _LEAN_GLOBALS,
                                            "render_bands_lean_borrowed"))
