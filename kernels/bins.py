"""Tile bins inside a band: runs of small triangles in tile order.

A band (kernels/render.py) is as wide as the window; random small triangles drawn
in submission order hop over all of it, so every triangle's pixels, and the
colour, z and stencil words under them, miss the first-level cache and TLB (a
band of 256 rows of 1280 pixels is about 3 MB of planes, a row of each plane a
page of its own).  Sorted into the tiles of kernels/tiles.py (``TILE_W`` columns
by ``TILE_H`` rows, about 18 KB of planes), one tile's planes stay in cache while
its triangles run.

Exactness (the per-pixel order of fragments is part of the semantics, IRIS GL
stencil and blend): a band's primitive list is cut at every primitive that is not
a *small* triangle (a big triangle, a clear, a line or point run); inside each run
of small triangles the entries are sorted by tile with a stable counting sort, and
a triangle whose bounding box crosses into a neighbouring tile gets one entry per
tile, each with its box clipped to that tile.  A pixel lies in exactly one tile,
so the fragments hitting it are still generated in primitive order, and the
clipped boxes together cover the same pixels as the whole box (spans and edge
tests are clipped to the box; the planes of the record are untouched).

A small triangle's box is narrower than a tile and lower than a tile row (so it
touches at most 2 x 2 tiles) and holds fewer than ``TILE_MIN_PIXELS`` pixels: the
band kernel never classifies its tiles (kernels/render.py _triangle_rows), clipped
or not, so the work skipping is the same either way.
"""

from __future__ import annotations

import numpy as np

from vgxsim.state.codes import KIND_TRIANGLE

from .options import inline, jit
from .tiles import TILE_H, TILE_H_SHIFT, TILE_MIN_PIXELS, TILE_SHIFT, TILE_W

NO_TILE = -1  # an entry that keeps its whole bounding box
MIN_RUN = 8  # shorter runs of small triangles stay in primitive order (nothing to gain)
PLACES = 4  # entries of one triangle in a band at most (2 x 2 tiles)


@inline
def _tiles(p, p_kind, p_ref, t_box, width, y_lo, y_hi):
    """Tile columns ``c0..c1`` and global tile rows ``r0..r1`` that small triangle
    ``p`` touches inside band rows ``[y_lo, y_hi]``; ``c1 < c0`` when ``p`` is not a
    small triangle."""
    if p_kind[p] != KIND_TRIANGLE:
        return 0, -1, 0, -1
    t = p_ref[p]
    x0 = t_box[t, 0]
    x1 = t_box[t, 1]
    y0 = t_box[t, 2]
    y1 = t_box[t, 3]
    if (x0 < 0 or x1 >= width or x1 - x0 >= TILE_W or y1 - y0 >= TILE_H
            or (x1 - x0 + 1) * (y1 - y0 + 1) >= TILE_MIN_PIXELS):
        return 0, -1, 0, -1
    # Binned by its rows, so it overlaps the band (a dead record is never binned).
    return (x0 >> TILE_SHIFT, x1 >> TILE_SHIFT, max(y0, y_lo) >> TILE_H_SHIFT,
            min(y1, y_hi) >> TILE_H_SHIFT)


@jit
def bin_tiles(starts, items, p_kind, p_ref, t_box, width, height, band_shift):
    """Reorder each band's entries (output of :func:`render.bin_primitives`) so that
    runs of at least ``MIN_RUN`` small triangles go tile by tile.

    Parameters
    ----------
    starts, items : ndarray, int64
        Band bins: ``items[starts[b]:starts[b + 1]]`` are band b's primitives.
    p_kind, p_ref : ndarray, shape (P,), int64
        Primitive kinds and references.
    t_box : ndarray, shape (T, 4), int64
        Triangle bounding boxes (x0, x1, y0, y1), pixels.
    width, height : int
        Window size.
    band_shift : int
        Bands are ``2**band_shift`` rows (at least ``TILE_H``).

    Returns
    -------
    new_starts : ndarray, shape (nbands + 1,), int64
        Where each band's entries start after the reordering (a triangle crossing a
        tile edge in a run has one entry per tile).
    place : ndarray, shape (N, PLACES, 3), int64
        Per entry of ``items``: up to ``PLACES`` (new slot, tile column, global
        tile row) its box is clipped to (column ``NO_TILE``: not clipped; slot -1:
        unused), for :func:`vgxsim.kernels.render.gather_band_records`.
    """
    nbands = starts.shape[0] - 1
    ncols = (width + TILE_W - 1) >> TILE_SHIFT
    nrows = 1 << (band_shift - TILE_H_SHIFT)  # tile rows per band
    # Pass 1: how many entries each band gets (one more per extra tile of a
    # triangle in a long enough run).
    new_starts = np.zeros(nbands + 1, np.int64)
    for b in range(nbands):
        y_lo = b << band_shift
        y_hi = min(y_lo + (1 << band_shift), height) - 1
        n = starts[b + 1] - starts[b]
        i = starts[b]
        while i < starts[b + 1]:
            j = i
            extra = 0
            while j < starts[b + 1]:
                c0, c1, r0, r1 = _tiles(items[j], p_kind, p_ref, t_box, width, y_lo, y_hi)
                if c1 < c0:
                    break
                extra += (c1 - c0 + 1) * (r1 - r0 + 1) - 1
                j += 1
            if j - i >= MIN_RUN:
                n += extra
            i = j + 1 if j == i else j
        new_starts[b + 1] = new_starts[b] + n
    place = np.full((items.shape[0], PLACES, 3), -1, np.int64)
    fill = np.zeros(nrows * ncols + 1, np.int64)
    # Pass 2: the slots; runs through a stable counting sort by tile.
    for b in range(nbands):
        y_lo = b << band_shift
        y_hi = min(y_lo + (1 << band_shift), height) - 1
        row0 = y_lo >> TILE_H_SHIFT
        o = new_starts[b]
        i = starts[b]
        while i < starts[b + 1]:
            j = i
            while j < starts[b + 1]:
                c0, c1, r0, r1 = _tiles(items[j], p_kind, p_ref, t_box, width, y_lo, y_hi)
                if c1 < c0:
                    break
                j += 1
            if j - i < MIN_RUN:
                # A short run (or none) and the primitive that ends it, as they are.
                end = min(j + 1, starts[b + 1])
                for k in range(i, end):
                    place[k, 0, 0] = o
                    o += 1
                i = end
                continue
            fill[:] = 0
            for k in range(i, j):
                c0, c1, r0, r1 = _tiles(items[k], p_kind, p_ref, t_box, width, y_lo, y_hi)
                for r in range(r0, r1 + 1):
                    for c in range(c0, c1 + 1):
                        fill[(r - row0) * ncols + c + 1] += 1
            fill[0] = o
            for c in range(nrows * ncols):
                fill[c + 1] += fill[c]
            for k in range(i, j):
                c0, c1, r0, r1 = _tiles(items[k], p_kind, p_ref, t_box, width, y_lo, y_hi)
                e = 0
                for r in range(r0, r1 + 1):
                    for c in range(c0, c1 + 1):
                        tile = (r - row0) * ncols + c
                        place[k, e, 0] = fill[tile]
                        place[k, e, 1] = c
                        place[k, e, 2] = r
                        fill[tile] += 1
                        e += 1
            o = fill[nrows * ncols - 1]
            i = j
    return new_starts, place
