"""Exact work skipping per tile: depth bounds and fully covered blocks.

A band of rows (:mod:`.render`) is cut into tiles of ``TILE_W`` columns.  For each
tile the band keeps bounds ``[lo, hi]`` of the z values stored in it, found by one
scan when first asked for and then kept up to date by the primitives that write z
(a triangle's written depths lie inside its vertex depth range ``t_zlim``, a clear
writes one value).  Before a large triangle is rasterized, every tile it touches
gets a class:

* ``TILE_SKIP``: the triangle's depths over the tile, ``[zlo, zhi]``, cannot pass the
  z test against any depth in ``[lo, hi]``, and a fragment failing the z test changes
  nothing (``D_ZFAIL_NOOP``: no stencil op on z fail).  The tile is not visited:
  Heidmann's shadow-volume faces behind the scene (z-pass, ST_KEEP on z fail) and
  the lit pass's hidden faces (zfunction(ZF_EQUAL)) cost nothing there.
* ``TILE_FULL``: the four corners of the tile's rectangle are inside all three edges,
  so (the triangle being convex) every pixel is: rows need no span solve and the
  edge-function rasterizer no per-pixel tests.
* ``TILE_ZPASS``: fully covered, and the triangle's depths over the tile pass the z
  test against every depth in ``[lo, hi]`` (the "block update": asked for with
  ``zpass``): rows run a loop without the per-fragment z compare
  (kernels/blocks.py), the stencil update, colour and z write of a passing fragment
  only.  Heidmann's volume faces in front of the scene and the lit pass's visible
  faces take it.
* ``TILE_ZPASS_SPAN``: not fully covered, but the depth bounds prove the z test
  passes as for ``TILE_ZPASS`` (asked for with ``zspan``): the triangle's row spans
  in the tile run the block update's loop.  The bounds hold for the triangle's own
  pixels in the tile as for all of them: the plane's extremes over the rectangle
  bound every depth inside it.  The diagonal of a full-screen quad and the tiles
  along a shadow face's edges take it (without it, the z-tested span loop).
* ``TILE_PARTIAL``: everything else, rasterized as before.

Exactness (docs/numeric_model.md, "Work skipping"): a fragment's depth is
``round_z((z0 + dzdy*(y - y0)) + dzdx*(x - x0))``; IEEE addition and multiplication
round monotonically, ``x - x0`` and ``y - y0`` are exact, so over a rectangle that
expression is monotone in x and in y and takes its extremes at the corners, which
are evaluated with the same expression.  Corners beyond +-4e18 (where the float to
int64 conversion stops being monotone) and non-finite planes never skip.
"""

from __future__ import annotations

import numpy as np

from vgxsim.state.codes import (
    CMP_EQUAL,
    CMP_GREATER_BIT,
    CMP_LESS_BIT,
    S_ZFUNC,
    WORK_BLOCKS_COVERED,
    WORK_BLOCKS_Z_PASSED,
    WORK_STENCIL_PASSED,
    WORK_STENCIL_SCANNED,
    WORK_STENCIL_SKIPPED,
    WORK_TILES_SCANNED,
    WORK_TILES_SKIPPED,
    Z24_MASK,
)

from .fragment import cmp_bits, round_z, write_z
from .options import callee, inline
from .raster import covers

TILE_SHIFT = 6
TILE_W = 1 << TILE_SHIFT  # columns per tile
TILE_H_SHIFT = 5
TILE_H = 1 << TILE_H_SHIFT  # rows per tile (bands are at least this tall, batch.py)
TILE_SKIP, TILE_PARTIAL, TILE_FULL, TILE_ZPASS = 0, 1, 2, 3  # ZPASS: full, z passes too
TILE_ZPASS_SPAN = 4  # partly covered, z passes everywhere in it (zpass_spans)
# Triangles with fewer pixels than this in a band are not classified tile by tile:
# the corner tests would cost more than they save (the result is the same).
TILE_MIN_PIXELS = 512
# The same for the rectangle of a triangle's own pixels in one tile row (spans
# solved first, kernels/render.py): it is close to the work itself, so one tile's
# test (a few dozen operations) pays off over far fewer pixels.
TILE_ROW_MIN_PIXELS = 64
ZMIN24, ZMAX24 = -0x800000, 0x7FFFFF
_PLANE_LIMIT = 1e30  # |z0|, |gradients| below this: corner sums cannot overflow
_CORNER_LIMIT = 4e18  # float depths below this convert to int64 monotonically
# Columns of a band's tile-bounds array (ntiles, TB_SIZE) int64.  TB_VALID says what
# [TB_LO, TB_HI] is: TB_UNKNOWN (nothing), TB_LOOSE (contains every stored depth, but
# widened by z writes since the last scan) or TB_EXACT (the stored minimum and
# maximum).  TB_DEBT: pixels of skip-eligible triangles that met the tile's loose
# bounds without being skipped since they last became loose (when it reaches the
# tile's size, one exact scan has been paid for: ski-rental, so rescans can at most
# double the work they try to save).
TB_VALID, TB_LO, TB_HI, TB_DEBT = 0, 1, 2, 3
# Stencil bounds (stencil_bounds): TB_SVALID is TB_UNKNOWN or TB_EXACT, [TB_SLO,
# TB_SHI] the stored minimum and maximum stencil values.  Found by one scan when a
# stencil-testing colour pass first asks, forgotten by every primitive that may write
# stencil there (never widened: the shadow faces that write stencil change it by
# many small steps, the lit pass that reads it comes after all of them).
TB_SVALID, TB_SLO, TB_SHI = 4, 5, 6
TB_SIZE = 7
TB_UNKNOWN, TB_LOOSE, TB_EXACT = 0, 1, 2
# A run's column 3 in ``runs`` (classify_tiles): 1 where the stencil test is known
# to pass for every fragment of the run (its tiles' stencil bounds), else 0.
RUN_SFREE = 3
RUN_SIZE = 4
# A loose tile is scanned again once faces it kept cover 1 / 2**RESCAN_SHIFT of it:
# a scan reads a tile once, but exact bounds serve every later face (a shadow pass
# draws many faces over the same tiles), so paying for it early is the better bet.
RESCAN_SHIFT = 3


@inline
def _plane_at(z0, dzdx, dzdy, x0, y0, x, y):
    """Unrounded depth at pixel (x, y), the span loops' expression and order."""
    za = z0 + dzdy * (y - y0)
    return za + dzdx * (x - x0)


@inline
def _plane_bounds(plane, tx, y_lo, y_hi):
    """(min, max) of ``plane`` over tile column ``tx``, rows ``[y_lo, y_hi]``.

    On the stored values themselves, indexed in place: for the int32 z plane
    vpminsd / vpmaxsd on eight lanes (AVX2 has no packed int64 min or max), for the
    stencil bytes vpminub / vpmaxub on 32; no row view (whose reference count costs
    two atomic updates per row)."""
    x0 = tx << TILE_SHIFT
    x1 = min(x0 + TILE_W, plane.shape[1]) - 1
    lo = plane[y_lo, x0]
    hi = lo
    for y in range(y_lo, y_hi + 1):
        uy = np.uintp(y)
        for x in range(x0, x1 + 1):
            v = plane[uy, np.uintp(x)]
            lo = min(lo, v)
            hi = max(hi, v)
    return lo, hi


@callee
def scan_tile(zbuf, tx, y_lo, y_hi, tb, i):
    """Exact depth bounds of tile column ``tx`` over rows ``[y_lo, y_hi]`` into ``tb[i]``."""
    lo, hi = _plane_bounds(zbuf, tx, y_lo, y_hi)
    tb[i, TB_VALID] = TB_EXACT
    tb[i, TB_LO] = lo
    tb[i, TB_HI] = hi
    tb[i, TB_DEBT] = 0


@callee
def scan_stencil(sten, tx, y_lo, y_hi, tb, i):
    """Exact stencil bounds of tile column ``tx`` over rows ``[y_lo, y_hi]`` into
    ``tb[i]``."""
    lo, hi = _plane_bounds(sten, tx, y_lo, y_hi)
    tb[i, TB_SVALID] = TB_EXACT
    tb[i, TB_SLO] = lo
    tb[i, TB_SHI] = hi


@inline
def stencil_passes_in(tab, lo, hi):
    """How many stored stencil values in ``[lo, hi]`` pass the state's stencil test:
    ``tab[2]`` is its table of outcomes by stored value (vgxsim/state/derive.py: the
    test with the state's function, reference and mask, the table the general path
    reads), so masks need no interval reasoning."""
    n = 0
    for v in range(lo, hi + 1):
        n += tab[2, v] != 0
    return n


@inline
def note_stencil_written(tb, xlo, xhi, ylo, yhi, y_lo, ntx):
    """After a primitive that may write stencil in columns ``[xlo, xhi]``, rows
    ``[ylo, yhi]`` of the band starting at row ``y_lo``: forget those tiles'
    stencil bounds."""
    for ty in range((ylo - y_lo) >> TILE_H_SHIFT, ((yhi - y_lo) >> TILE_H_SHIFT) + 1):
        for tx in range(xlo >> TILE_SHIFT, (xhi >> TILE_SHIFT) + 1):
            tb[ty * ntx + tx, TB_SVALID] = TB_UNKNOWN


@inline
def z_fails_everywhere(zfunc, zlo, zhi, blo, bhi):
    """No fragment depth in ``[zlo, zhi]`` passes ``zfunc`` against any stored depth
    in ``[blo, bhi]`` (the outcome bits of the ZF_* code none of which can occur)."""
    lt, eq, gt = cmp_bits(zfunc)
    can_lt = zlo < bhi
    can_eq = zlo <= bhi and zhi >= blo
    can_gt = zhi > blo
    return not ((lt and can_lt) or (eq and can_eq) or (gt and can_gt))


@inline
def z_passes_everywhere(zfunc, zlo, zhi, blo, bhi):
    """Every fragment depth in ``[zlo, zhi]`` passes ``zfunc`` against every stored
    depth in ``[blo, bhi]``: each outcome (less, equal, greater) that can occur is
    one the ZF_* code accepts (the outcomes that can occur are over-estimated from
    the intervals, which errs on the side of testing)."""
    lt, eq, gt = cmp_bits(zfunc)
    can_lt = zlo < bhi
    can_eq = zlo <= bhi and zhi >= blo
    can_gt = zhi > blo
    return (lt or not can_lt) and (eq or not can_eq) and (gt or not can_gt)


@callee
def classify_tiles(t, xlo, xhi, ylo, yhi, y_lo, y_hi, base, t_edge, t_z, t_zlim, st, zbuf,
                   tb, runs, skip, cover, merge, zpass, zspan, work, sbounds, tab, sten):
    """Classify the tiles of triangle ``t``'s rectangle in one tile row of a band;
    write the runs of adjacent non-skipped tiles of one class into ``runs``.

    Parameters
    ----------
    t : int
        Triangle record.
    xlo, xhi, ylo, yhi : int
        A rectangle holding the triangle's pixels in this tile row (bounding box,
        scissor, band, tile row; or its own pixels' rectangle).
    y_lo, y_hi : int
        The tile row's rows (the tiles' extent in y).
    base : int
        Index in ``tb`` of the tile row's first tile.
    t_edge, t_z, t_zlim : ndarray
        Set-up records (see :func:`vgxsim.kernels.setup.setup_triangles`).
    st : ndarray, shape (ROW_SIZE,), int64
        State row.
    zbuf : ndarray, shape (H, W), int32
    tb : ndarray, shape (n, TB_SIZE), int64
        The band's tile bounds (TB_*), filled in on first use.
    runs : ndarray, shape (ntiles, RUN_SIZE), int64
        Output: ``(x first, x last, class, stencil free)`` per run: class TILE_ZPASS,
        TILE_ZPASS_SPAN, TILE_FULL or TILE_PARTIAL; column RUN_SFREE 1 where the
        stencil test is known to pass everywhere in the run (with ``sbounds``).
    skip, cover : bool
        Whether to test depth bounds (the caller has checked that the z test is on
        and z failure is a no-op) and whether to test full coverage.
    merge : bool
        Merge adjacent full and partial tiles into one (partial) run: for the span
        rasterizer, which solves each row once; the edge-function rasterizer keeps
        full runs apart to leave out their per-pixel tests.  Z-passed runs are
        never merged with the other classes (they run another loop).
    zpass : bool
        Also test whether fully covered tiles pass the z test everywhere
        (``TILE_ZPASS``; the caller has checked that the z test is on, that ``cover``
        is set and that the state has a z-passed row loop).
    zspan : bool
        With ``zpass``: tiles not fully covered whose bounds prove the same get
        ``TILE_ZPASS_SPAN`` (counted in no work counter: the class changes which
        loop runs, not the work); runs of z-passed tiles of both classes merge into
        one ``TILE_ZPASS_SPAN`` run (its rows clip to the row's span).
    work : ndarray, shape (WORK_SIZE,), int64
        Work counters of this band.
    sbounds : bool
        Also decide the stencil test from the tiles' stencil bounds (the caller has
        checked that the state is a colour pass, MODE_COLOUR, with the stencil test
        on: a fragment failing it changes nothing).  A tile where no stored value
        passes is skipped (WORK_STENCIL_SKIPPED); one where every value passes runs
        without the per-fragment stencil test (RUN_SFREE, WORK_STENCIL_PASSED).
    tab : ndarray, shape (3, 256), uint8
        The state's stencil tables (derive.py); ``tab[2]``: the stencil test's
        outcome by stored value.
    sten : ndarray, shape (H, W), uint8
        The stencil plane (read by the scans of ``sbounds``).

    Returns
    -------
    int
        Number of runs (0: the triangle touches nothing in this band).
    """
    edge = t_edge[t]
    z0, x0, y0, dzdx, dzdy = t_z[t, 0], t_z[t, 1], t_z[t, 2], t_z[t, 3], t_z[t, 4]
    zmin = t_zlim[t, 0]
    zmax = t_zlim[t, 1]
    plane_ok = (abs(z0) < _PLANE_LIMIT and abs(dzdx) < _PLANE_LIMIT
                and abs(dzdy) < _PLANE_LIMIT)
    bounds = (skip or zpass) and plane_ok
    zfunc = st[S_ZFUNC]
    tile_px = TILE_W * (y_hi - y_lo + 1)
    nruns = 0
    for tx in range(xlo >> TILE_SHIFT, (xhi >> TILE_SHIFT) + 1):
        cx0 = max(xlo, tx << TILE_SHIFT)
        cx1 = min(xhi, (tx << TILE_SHIFT) + TILE_W - 1)
        cls = TILE_PARTIAL
        passes = False
        if bounds:
            a = _plane_at(z0, dzdx, dzdy, x0, y0, cx0, ylo)
            b = _plane_at(z0, dzdx, dzdy, x0, y0, cx1, ylo)
            c = _plane_at(z0, dzdx, dzdy, x0, y0, cx0, yhi)
            d = _plane_at(z0, dzdx, dzdy, x0, y0, cx1, yhi)
            flo = min(min(a, b), min(c, d))
            fhi = max(max(a, b), max(c, d))
            if flo > -_CORNER_LIMIT and fhi < _CORNER_LIMIT:
                i = base + tx
                if tb[i, TB_VALID] == TB_UNKNOWN:
                    scan_tile(zbuf, tx, y_lo, y_hi, tb, i)
                    work[WORK_TILES_SCANNED] += 1
                # round_z is monotone: rounding the extremes gives the extremes.
                rlo = round_z(flo, zmin, zmax)
                rhi = round_z(fhi, zmin, zmax)
                fails = skip and z_fails_everywhere(zfunc, rlo, rhi, tb[i, TB_LO],
                                                    tb[i, TB_HI])
                if skip and not fails and tb[i, TB_VALID] == TB_LOOSE:
                    # Loose bounds (widened by z writes) may be what keeps the tile;
                    # scan again once the faces they kept have paid for a scan.
                    tb[i, TB_DEBT] += (cx1 - cx0 + 1) * (yhi - ylo + 1)
                    if tb[i, TB_DEBT] >= tile_px >> RESCAN_SHIFT:
                        scan_tile(zbuf, tx, y_lo, y_hi, tb, i)
                        work[WORK_TILES_SCANNED] += 1
                        fails = z_fails_everywhere(zfunc, rlo, rhi, tb[i, TB_LO],
                                                   tb[i, TB_HI])
                if fails:
                    cls = TILE_SKIP
                    work[WORK_TILES_SKIPPED] += 1
                elif zpass:
                    passes = z_passes_everywhere(zfunc, rlo, rhi, tb[i, TB_LO], tb[i, TB_HI])
        sfree = 0
        if sbounds and cls != TILE_SKIP:
            i = base + tx
            if tb[i, TB_SVALID] == TB_UNKNOWN:
                scan_stencil(sten, tx, y_lo, y_hi, tb, i)
                work[WORK_STENCIL_SCANNED] += 1
            slo = tb[i, TB_SLO]
            shi = tb[i, TB_SHI]
            npass = stencil_passes_in(tab, slo, shi)
            if npass == 0:
                cls = TILE_SKIP
                work[WORK_STENCIL_SKIPPED] += 1
            elif npass == shi - slo + 1:
                sfree = 1
                work[WORK_STENCIL_PASSED] += 1
        if cls == TILE_PARTIAL and cover and covers(edge, cx0, ylo) and covers(
                edge, cx1, ylo) and covers(edge, cx0, yhi) and covers(edge, cx1, yhi):
            cls = TILE_FULL
            work[WORK_BLOCKS_COVERED] += 1
            if passes:
                cls = TILE_ZPASS
                work[WORK_BLOCKS_Z_PASSED] += 1
        elif cls == TILE_PARTIAL and passes and zspan:
            cls = TILE_ZPASS_SPAN
        if cls == TILE_SKIP:
            continue
        prev = runs[nruns - 1, 2] if nruns > 0 else TILE_SKIP
        zp = cls == TILE_ZPASS or cls == TILE_ZPASS_SPAN
        zp_prev = prev == TILE_ZPASS or prev == TILE_ZPASS_SPAN
        if nruns > 0 and runs[nruns - 1, 1] == cx0 - 1 and (prev == cls or (zp and zp_prev) or (
                merge and not zp_prev and not zp)):
            # Span rows solve their edges once per row anyway: one long run (a long
            # vectorized loop) beats a run per class; it is full only if all tiles are
            # (z-passed runs of both kinds: a z-passed run clipped to the row's span),
            # and free of the stencil test only if all tiles are (a run per tile
            # costs a span call each, more than the test saves over a tile's row).
            runs[nruns - 1, 1] = cx1
            runs[nruns - 1, RUN_SFREE] &= sfree
            if cls != prev:
                runs[nruns - 1, 2] = TILE_ZPASS_SPAN if zp else TILE_PARTIAL
        else:
            runs[nruns, 0] = cx0
            runs[nruns, 1] = cx1
            runs[nruns, 2] = cls
            runs[nruns, RUN_SFREE] = sfree
            nruns += 1
    return nruns


@inline
def note_z_written(tb, xlo, xhi, ylo, yhi, y_lo, ntx, zlo, zhi, zmask, zfunc, sided):
    """After a primitive wrote depths in ``[zlo, zhi]`` (unwrapped) through
    ``zmask`` somewhere in columns ``[xlo, xhi]``, rows ``[ylo, yhi]`` of the band
    starting at row ``y_lo`` (``ntx`` tiles a tile row): widen the valid bounds of
    those tiles (they become loose: the old extreme may be overwritten), or forget
    them when the stored value is not simply the written one (a partial mask, or a
    depth that wraps to 24 bits).  Under zfunction(ZF_EQUAL) a fragment writes only
    where its depth equals the stored one, so a full-mask write of a 24-bit value
    leaves the plane, and any bounds within 24 bits, unchanged.  With ``sided``
    (CommandBatch.sided_bounds): a zfunction without the "greater" outcome
    (ZF_LESS, ZF_LEQUAL) writes only depths at most the stored ones, so no value
    rises and ``hi`` still bounds the tile; without "less" (ZF_GREATER, ZF_GEQUAL)
    ``lo`` does (Heidmann's ambient and lit passes, ZF_LEQUAL: a lit triangle's
    far corners no longer push ``hi`` out, which kept its hidden faces' tiles)."""
    full = zmask == Z24_MASK
    exact = full and zlo >= ZMIN24 and zhi <= ZMAX24
    for ty in range((ylo - y_lo) >> TILE_H_SHIFT, ((yhi - y_lo) >> TILE_H_SHIFT) + 1):
        for tx in range(xlo >> TILE_SHIFT, (xhi >> TILE_SHIFT) + 1):
            i = ty * ntx + tx
            if tb[i, TB_VALID] == TB_UNKNOWN:
                continue
            if full and zfunc == CMP_EQUAL and tb[i, TB_LO] >= ZMIN24 and (
                    tb[i, TB_HI] <= ZMAX24):
                continue
            if exact:
                # Bounds still contain every depth, but the old extreme may be gone.
                if not (sided and (zfunc & CMP_LESS_BIT) == 0):
                    tb[i, TB_LO] = min(tb[i, TB_LO], zlo)
                if not (sided and (zfunc & CMP_GREATER_BIT) == 0):
                    tb[i, TB_HI] = max(tb[i, TB_HI], zhi)
                if tb[i, TB_VALID] == TB_EXACT:
                    tb[i, TB_VALID] = TB_LOOSE
                    tb[i, TB_DEBT] = 0
            else:
                tb[i, TB_VALID] = TB_UNKNOWN


@inline
def note_z_cleared(tb, xlo, xhi, ylo, yhi, y_lo, y_hi, width, zval, zmask):
    """After a z clear of columns ``[xlo, xhi]``, rows ``[ylo, yhi]`` of the band
    ``[y_lo, y_hi]``: tiles cleared whole with the full mask hold exactly one value."""
    v = write_z(0, zval, Z24_MASK)
    full = zmask == Z24_MASK
    ntx = (width + TILE_W - 1) >> TILE_SHIFT
    for ty in range((ylo - y_lo) >> TILE_H_SHIFT, ((yhi - y_lo) >> TILE_H_SHIFT) + 1):
        ty0 = y_lo + (ty << TILE_H_SHIFT)
        ty1 = min(ty0 + TILE_H - 1, y_hi)
        whole_rows = ylo <= ty0 and yhi >= ty1
        for tx in range(xlo >> TILE_SHIFT, (xhi >> TILE_SHIFT) + 1):
            i = ty * ntx + tx
            tx0 = tx << TILE_SHIFT
            tx1 = min(tx0 + TILE_W, width) - 1
            if full and whole_rows and xlo <= tx0 and xhi >= tx1:
                tb[i, TB_VALID] = TB_EXACT
                tb[i, TB_LO] = v
                tb[i, TB_HI] = v
                tb[i, TB_DEBT] = 0
            elif full and tb[i, TB_VALID] != TB_UNKNOWN:
                tb[i, TB_LO] = min(tb[i, TB_LO], v)
                tb[i, TB_HI] = max(tb[i, TB_HI], v)
                if tb[i, TB_VALID] == TB_EXACT:
                    tb[i, TB_VALID] = TB_LOOSE
                    tb[i, TB_DEBT] = 0
            else:
                tb[i, TB_VALID] = TB_UNKNOWN
