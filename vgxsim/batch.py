"""The command batch: primitives accumulate here and render in one kernel call.

Every primitive carries the index of its raster-state snapshot, so state changes
between primitives (the 1991 code changes ``stencil()`` before every shadow face)
cost one dictionary look-up, not a flush.  The batch is flushed on readback,
swapbuffers, acbuf, reconfiguration, or when it is full.  Clears are queued as
primitives too: a band of rows then stays in cache from the clear through every
pass of a frame.
"""

from __future__ import annotations

import numpy as np

from vgxsim import coldstart, threads
from vgxsim.kernels.band_order import band_counts, band_slots, mean_rows, scatter_records
from vgxsim.kernels.clip import snap_window
from vgxsim.kernels.front import front_assemble, front_slots, front_vertices
from vgxsim.kernels.queue import queue_triangles
from vgxsim.kernels.render import (
    bin_primitives,
    gather_band_records,
    lean_fits,
    render_bands,
    render_bands_borrowed,
    render_bands_lean,
    render_bands_lean_borrowed,
)
from vgxsim.kernels.setup import (
    setup_triangles_borrowed,
    setup_triangles_slots,
    setup_triangles_slots_borrowed,
    setup_triangles_states,
)
from vgxsim.kernels.texture import setup_texture_planes
from vgxsim.state.codes import (
    CLEAR_COLOUR,
    CLEAR_STENCIL,
    CLEAR_Z,
    FLAT,
    KIND_CLEAR,
    KIND_FRAGMENTS,
    ROW_SIZE,
    S_DRAW_BACK,
    S_DRAW_FRONT,
    S_TEXTURE,
    WORK_BLOCKS_COVERED,
    WORK_BLOCKS_Z_PASSED,
    WORK_FRAGMENTS,
    WORK_SIZE,
    WORK_STENCIL_PASSED,
    WORK_STENCIL_SCANNED,
    WORK_STENCIL_SKIPPED,
    WORK_STENCIL_WRITES,
    WORK_TILES_SCANNED,
    WORK_TILES_SKIPPED,
)
from vgxsim.state.derive import derive_states
from vgxsim.state.planes import Framebuffer
from vgxsim.state.raster import RasterState
from vgxsim.state.textures import pack_bindings

__all__ = ["CommandBatch", "CLEAR_COLOUR", "CLEAR_Z", "CLEAR_STENCIL", "WORK_NAMES"]

#: Names of the work counters, in the order of ``CommandBatch.counters``.
WORK_NAMES = tuple(name for _, name in sorted([
    (WORK_FRAGMENTS, "fragments"), (WORK_TILES_SKIPPED, "tiles_skipped"),
    (WORK_BLOCKS_COVERED, "blocks_covered"), (WORK_STENCIL_WRITES, "stencil_writes"),
    (WORK_TILES_SCANNED, "tiles_scanned"), (WORK_BLOCKS_Z_PASSED, "blocks_z_passed"),
    (WORK_STENCIL_SCANNED, "stencil_scanned"), (WORK_STENCIL_SKIPPED, "stencil_skipped"),
    (WORK_STENCIL_PASSED, "stencil_untested")]))

# Bands are 2**shift rows, 32 to 256.  Tall bands keep the triangle records a band
# reads dense in memory (many small triangles are latency-bound on those reads);
# with several threads, more bands balance the load.
MIN_BAND_SHIFT, MAX_BAND_SHIFT = 5, 8


def band_shift(height: int, nthreads: int, tall: bool = False) -> int:
    """Rows per band (as a shift) for a window height and thread count: one thread
    takes tall bands; several threads get about eight bands each, handed out
    dynamically, so a scene whose work sits in a few rows still keeps them all busy.
    ``tall`` (a flush of small triangles, CommandBatch.tall_bands): at most one band
    per thread, of a power of two rows."""
    if tall:
        rows = -(-height // max(1, nthreads))
        return max(MIN_BAND_SHIFT, (rows - 1).bit_length())
    per = 1 if nthreads <= 1 else 8 * nthreads
    rows = max(1, height // per)
    return max(MIN_BAND_SHIFT, min(MAX_BAND_SHIFT, rows.bit_length() - 1))
PARALLEL_SETUP = 20_000  # triangles in one call above which set-up runs on all threads
PARALLEL_FRONT = 4_096  # the same for the fused front end (add_object_triangles)
MAX_PRIMITIVES = 1 << 21  # flush when this many primitives are queued
GATHER_MIN = 4096  # triangles in a flush from which records are copied into band order
GATHER_MAX = 1 << 20  # binned entries above which they are not (the copy's memory)
TABLES_MEMO = 64  # distinct state tables a batch keeps derived (cache_tables)
TALL_MIN = 4096  # triangles in a flush from which it may take tall_bands
TALL_ROWS = 16.0  # mean rows of a flush's primitives up to which it takes tall_bands
TALL_COPY_BANDS = 2  # tall bands up to which records are not copied into band order


def _cuts(n: int, parts: int) -> list[tuple[int, int]]:
    """``parts`` nearly equal, non-empty ranges covering 0 .. n - 1."""
    c = np.linspace(0, n, max(1, parts) + 1).astype(np.int64).tolist()
    return [(a, b) for a, b in zip(c[:-1], c[1:], strict=True) if b > a]


def _run_chunks(parallel: bool, nthreads: int, kernel, cuts, *args) -> None:
    """``kernel(*args, a, b)`` for every range of ``cuts``, on the worker threads when
    ``parallel`` (the kernels release the GIL and write disjoint rows)."""
    if not parallel or len(cuts) == 1:
        for a, b in cuts:
            kernel(*args, a, b)
        return
    pool = threads.pool(nthreads)
    for f in [pool.submit(kernel, *args, a, b) for a, b in cuts]:
        f.result()


def _grow(arr: np.ndarray, need: int) -> np.ndarray:
    if arr.shape[0] >= need:
        return arr
    cap = max(need, 2 * arr.shape[0], 64)
    out = np.zeros((cap,) + arr.shape[1:], dtype=arr.dtype)
    out[: arr.shape[0]] = arr
    return out


class CommandBatch:
    """Queued primitives of one framebuffer, with their state snapshots.

    Parameters
    ----------
    framebuffer : Framebuffer
        Where a flush renders to.

    Attributes
    ----------
    edge_mode, general_only : bool
        Test switches: the edge-function rasterizer; no fast span paths.
    skip_tiles, cover_blocks : bool
        Exact work skipping (vgxsim/kernels/tiles.py; on by default): skip tiles
        whose depth bounds fail the z test for a whole triangle; run tiles fully
        inside a triangle without edge tests.  Switching either off changes no pixel.
        Class attributes: set them on ``CommandBatch`` to switch every batch.
    tight_tiles : bool
        With spans stepped: a triangle's tiles are classified over its own pixels
        in each band (row spans solved first), not over its bounding box; on by
        default, a switch that changes no pixel.
    step_spans : bool
        Row spans of a triangle carried from row to row by exact integer steps
        (vgxsim/kernels/spans.py) instead of solved per row; on by default, the
        same spans either way (a class attribute like the two above).
    vector_pack : bool
        The stencil-tested Gouraud span loop (Heidmann's lit pass) and the
        z + stencil INCR/DECR loop (the shadow-volume pass) convert colour and z
        through int32 after a float clamp, which AVX2 vectorizes, instead of
        through int64 (kernels/fragment.py pack_rgba_i32, round_z_i32); on by
        default, the same values either way (a class attribute like the above).
    small_path : bool
        Triangles at most eight pixels wide (whose tiles are not classified) run in
        one pass over their bounding box with the edge values stepped per pixel
        and scalar fragment loops (kernels/small.py), instead of through stepped
        spans and the span loops, whose per-row set-up costs more than a small
        triangle's row of pixels; on by default, the same planes either way (a
        class attribute like the above).
    block_update : bool
        With ``cover_blocks``: fully covered tiles whose depth bounds prove that
        the z test passes for the whole triangle there run their rows without the
        per-fragment z compare (vgxsim/kernels/blocks.py; the z+stencil, z-only and
        lit passes); on by default, a switch that changes no pixel.
    lit_spans : bool
        With ``vector_pack``: row spans of at least 16 pixels of the lit and ambient
        passes (z test, replace or ONE+ONE blend) run a span loop compiled on its
        own (vgxsim/kernels/lit.py), which LLVM keeps in registers; on by default,
        the same planes either way.
    lit_lanes : bool
        With ``lit_spans``: those spans, and the block update's lit and ambient
        rows, run on 32-bit lanes (vgxsim/kernels/lit.py lit_span_lanes: no NaN
        tests, clamps without floor, int32 compares and selects by masks) where
        every plane's values over the span are bounded so that those forms give the
        same values; on by default, the same planes either way.
    fill_spans : bool
        With ``vector_pack``: row spans of at least 16 pixels of the z+stencil
        pass with an arithmetic stencil op and of the depth-only pass run span
        loops compiled on their own, on 32-bit lanes (vgxsim/kernels/fill.py: in
        the band kernel their invariants are spilled and reloaded per vector); on
        by default, the same planes either way.
    zpass_spans : bool
        With ``block_update``: in tiles only partly covered by a triangle whose
        depth bounds prove that its z test passes everywhere there, the triangle's
        row spans run the block update's loop as well (kernels/tiles.py
        TILE_ZPASS_SPAN: the diagonal of a full-screen quad, the tiles along a
        shadow face's edges); on by default, the same planes and work counters.
    band_records : bool
        Before a flush of many triangles (``GATHER_MIN``; at most ``GATHER_MAX``
        binned entries, which bounds the copy's memory) in several bands, copy
        their set-up records into band order so that each band reads its own
        front to back (kernels/render.py gather_band_records); on by default, a
        switch that changes nothing drawn.
    lean_kernel : bool
        Draw a batch whose triangles' states all take the span loops, without
        points or lines, with ``render_bands_lean``: the band kernel compiled
        without the general per-fragment path, the texture stage and the slow
        colour span (kernels/render.py lean_fits), so a cold start compiles only
        those kernels the first image runs; on by default, a switch that changes
        nothing drawn.
    band_workers : bool
        With several threads, a flush's bands are taken one after another by one
        loop per thread, the calling thread one of them (vgxsim/threads.py
        run_each), not submitted to the pool as one task each: the serial Python
        of a flush (a future, a queue hand-off and a wake-up per band) capped the
        2-thread speed-up of the fill passes; on by default, a switch that changes
        nothing drawn (bands are disjoint rows).
    cache_tables : bool
        A flush's state table, derived rows, stencil tables and lean-kernel check
        are kept per distinct list of state snapshots and reused by a later flush
        of the same list (untextured tables only; :meth:`_state_tables`); on by
        default, a switch that changes nothing drawn.
    scatter_bins : bool
        With ``band_records``: the primitives are binned and their records written
        into band order in one pass in drawing order, one sequential write stream
        per band (kernels/band_order.py), instead of listed per band and then
        gathered band by band (each band's pass re-reading the whole record arrays);
        on by default, a switch that changes nothing drawn.
    prefetch_planes : bool
        The band kernel prefetches the plane rows of the small triangle a few
        entries ahead of the one it draws (vgxsim/kernels/prefetch.py: a band of
        a full window does not fit the cache, and each small triangle's first z
        and colour reads missed); on by default, a hint that changes nothing drawn.
    borrow_arrays : bool
        The band kernel and set-up take their arrays borrowed
        (vgxsim/kernels/borrow.py: a type without a counted meminfo, through
        render_bands_borrowed and setup_triangles_borrowed): the array arguments of
        the helpers they inline per triangle cost no reference-count calls; on by
        default, a switch that changes nothing drawn.
    tall_bands : bool
        A flush of at least ``TALL_MIN`` triangles whose primitives span at most
        ``TALL_ROWS`` rows on average (small triangles) takes one band per thread
        (one band, nothing binned, on one thread) instead of bands of at most 256
        rows, eight a thread: binning and the copies into band order cost small
        triangles more than the band's cache locality saves them (200k 10-pixel
        triangles, 1 thread, CPU ns a triangle: 328 with 4 bands, 253 with one).
        Up to ``TALL_COPY_BANDS`` such bands read their records where they are
        when ``band_slots`` placed every one (``band_records`` then copies nothing).  On by
        default, a switch that changes nothing drawn (bands are disjoint rows, tile
        rows the same).
    band_slots : bool
        With ``tall_bands``: a call of at least ``TALL_MIN`` triangles, drawn where
        there would be two to ``TALL_COPY_BANDS`` tall bands (two threads), writes its
        set-up records grouped by the tall band of each triangle's first row, in
        drawing order within a band (kernels/band_order.py band_slots); the
        primitives stay in drawing order and point at them.  The bands, which read
        records in place, then read them front to back instead of every other one
        (200k 10-pixel triangles, 2 threads, CPU ms, 21 alternating runs: 65.3
        without, 56.2 with, 60.1 copying the records into band order); on by
        default, a switch that changes nothing drawn.
    span_zwrite : bool
        With ``block_update``: depth-writing colour passes (blend
        replace or ONE+ONE; Heidmann's ambient pass) do not ask for z-passed tiles:
        their vectorized z-tested span loop costs about what the block update's
        loop does, and z-passed tiles would cut each row into one run per class
        (kernels/render.py _triangle_rows); on by default, the same planes either way.
    stencil_bounds : bool
        Per tile, the bounds of the stored stencil values (found by one scan when a
        stencil-testing colour pass first asks, forgotten by every primitive that
        may write stencil there): that pass skips a tile where its stencil test
        fails for every value in the bounds and runs one where it passes for every
        value without the per-fragment stencil test (vgxsim/kernels/tiles.py;
        Heidmann's lit pass after the shadow faces); on by default, the same planes
        either way.
    sided_bounds : bool
        A triangle that writes z under ZF_LESS or ZF_LEQUAL (ZF_GREATER, ZF_GEQUAL)
        can only lower (raise) stored depths, so it widens only the lower (upper)
        depth bound of the tiles it wrote (vgxsim/kernels/tiles.py note_z_written;
        Heidmann's ambient and lit passes); on by default, the same planes either
        way (tighter bounds skip more tiles).
    counters : ndarray, shape (WORK_SIZE,), int64
        Work done since the batch was made or :meth:`reset_counters`, in the order
        of ``WORK_NAMES``: fragments tested, (triangle, tile) pairs skipped, tiles
        covered without edge tests, fragments of passes that may write stencil,
        tiles whose depth bounds were read from the z plane, of the covered tiles
        those run without z tests; tiles whose stencil bounds were read from the
        stencil plane, (triangle, tile) pairs skipped by them and run without the
        stencil test by them.  :meth:`work` gives them by name.
    """

    skip_tiles = True
    cover_blocks = True
    tight_tiles = True
    step_spans = True
    vector_pack = True
    small_path = True
    block_update = True
    lit_spans = True
    lit_lanes = True
    fill_spans = True
    zpass_spans = True
    band_records = True
    scatter_bins = True
    prefetch_planes = True
    borrow_arrays = True
    lean_kernel = True
    band_workers = True
    cache_tables = True
    span_zwrite = True
    stencil_bounds = True
    sided_bounds = True
    tall_bands = True
    band_slots = True

    def __init__(self, framebuffer: Framebuffer):
        self.fb = framebuffer
        self.edge_mode = False
        self.general_only = False
        self.counters = np.zeros(WORK_SIZE, np.int64)
        self.flushes = 0
        self._tables_memo: dict[tuple, tuple] = {}
        self._allocate()
        self._reset()
        coldstart.prepare(CommandBatch)  # first batch, empty cache: compile in parallel

    @staticmethod
    def band_kernel(lean: bool, borrowed: bool):
        """The band kernel :meth:`flush` calls: the lean copy (``lean``) or the full
        one, on borrowed arrays (``borrowed``, the ``borrow_arrays`` switch) or plain
        ones.  vgxsim/coldstart.py asks it which kernel's cache entry a first image
        needs: each of the four has its own."""
        if borrowed:
            return render_bands_lean_borrowed if lean else render_bands_borrowed
        return render_bands_lean if lean else render_bands

    def reset_counters(self) -> None:
        """Zero the work counters."""
        self.counters[:] = 0

    def work(self) -> dict[str, int]:
        """The work counters by name (see ``counters``)."""
        return {name: int(v) for name, v in zip(WORK_NAMES, self.counters, strict=True)}

    def _allocate(self) -> None:
        """The batch's arrays, grown on demand and kept across flushes (a frame of
        many small triangles would otherwise re-allocate and re-fault tens of MB)."""
        self.p_kind = np.zeros(64, np.int64)
        self.p_ref = np.zeros(64, np.int64)
        self.p_y0 = np.zeros(64, np.int64)
        self.p_y1 = np.zeros(64, np.int64)
        self.t_edge = np.zeros((64, 3, 3), np.int64)
        self.t_box = np.zeros((64, 4), np.int64)
        self.t_z = np.zeros((64, 5), np.float64)
        self.t_zlim = np.zeros((64, 2), np.int64)
        self.t_col = np.zeros((64, 4, 3), np.float64)
        self.t_state = np.zeros(64, np.int32)
        self.t_tex = np.zeros((64, 3, 3), np.float64)  # texture planes (kernels/texture.py)
        self.f_xy = np.zeros((64, 2), np.int64)
        self.f_z = np.zeros(64, np.int64)
        self.f_rgba = np.zeros(64, np.int64)
        self.r_range = np.zeros((16, 2), np.int64)
        self.r_state = np.zeros(16, np.int64)
        self.c_vals = np.zeros((16, 4), np.int64)
        self.c_state = np.zeros(16, np.int64)
        self.g_kind = np.zeros(0, np.int64)  # band-ordered copies (_band_order)
        self._kept: dict[str, np.ndarray] = {}  # per-call scratch (_scratch)

    def _scratch(self, name: str, n: int, shape: tuple = (), dtype=np.int64) -> np.ndarray:
        """A kept array of ``n`` rows (of ``shape``) for one call's intermediate values
        (vertex positions, per-triangle state columns): grown on demand and reused,
        because freshly allocated arrays of a call of many triangles cost their page
        faults on first touch, more than the work written into them."""
        arr = self._kept.get(name)
        if arr is None or arr.shape[0] < n:
            cap = max(n, 2 * (0 if arr is None else arr.shape[0]), 64)
            arr = self._kept[name] = np.empty((cap,) + shape, dtype)
        return arr[:n]

    def _iota(self, n: int) -> np.ndarray:
        """``np.arange(n)`` from a kept array (see :meth:`_scratch`)."""
        arr = self._kept.get("iota")
        if arr is None or arr.shape[0] < n:
            arr = self._kept["iota"] = np.arange(max(n, 64), dtype=np.int64)
        return arr[:n]

    def _repeat(self, name: str, n: int, value: int) -> np.ndarray:
        """``np.full(n, value, np.int64)`` in a kept array (see :meth:`_scratch`)."""
        arr = self._scratch(name, n)
        arr[:] = value
        return arr

    def _queue_triangles(self, start: int, end: int, scissor=None, slot=None) -> None:
        """Queue records ``start .. end - 1`` as triangle primitives, binned by their
        box rows, cut to ``scissor`` (x0, x1, y0, y1) when given
        (kernels/queue.py); ``slot``: where the call's triangles put their records
        (:meth:`_band_slots`), in drawing order."""
        n = end - start
        if n <= 0:
            return
        stop = self.nprims + n
        self.p_kind = _grow(self.p_kind, stop)
        self.p_ref = _grow(self.p_ref, stop)
        self.p_y0 = _grow(self.p_y0, stop)
        self.p_y1 = _grow(self.p_y1, stop)
        clip = scissor is not None
        sx0, sx1, sy0, sy1 = (int(v) for v in scissor) if clip else (0, 0, 0, 0)
        nthreads = threads.get_threads()
        at = self.nprims
        # Each record writes its own primitive: chunks run side by side, on the
        # worker threads for a call large enough to be worth the hand-off.
        cuts = _cuts(n, nthreads if nthreads > 1 and n >= PARALLEL_FRONT else 1)
        _run_chunks(len(cuts) > 1, nthreads, lambda a, b: queue_triangles(
            self.t_box, start + a, start + b, _NO_SLOTS if slot is None else slot[a:b], start,
            clip, sx0, sx1, sy0, sy1, self.p_kind, self.p_ref, self.p_y0, self.p_y1, at + a),
            cuts)
        self.nprims = stop

    def _band_slots(self, yf: np.ndarray, tris: np.ndarray) -> np.ndarray | None:
        """Per triangle of a call, its record's offset from the call's first, grouped
        by the tall band of its first row (``band_slots``; kernels/band_order.py), or
        None: records in drawing order (the switch off, or a call that tall bands
        would not read in place: under ``TALL_MIN`` triangles, of triangles of more
        than ``TALL_ROWS`` rows on average, one band, or more than
        ``TALL_COPY_BANDS``, whose flush copies records anyway)."""
        nt = tris.shape[0]
        if not (self.band_slots and self.tall_bands) or nt < TALL_MIN:
            return None
        height = self.fb.height
        shift = band_shift(height, max(1, threads.get_threads()), True)
        nbands = (height + (1 << shift) - 1) >> shift
        if nbands <= 1 or nbands > TALL_COPY_BANDS:
            return None
        slot = self._scratch("slot", nt)
        if not band_slots(yf, tris, shift, nbands, TALL_ROWS, slot):
            return None
        self.nplaced += nt
        return slot

    def _grow_records(self, end: int) -> None:
        """Grow the set-up record arrays to hold ``end`` records (capacity is kept
        across flushes)."""
        self.t_edge = _grow(self.t_edge, end)
        self.t_box = _grow(self.t_box, end)
        self.t_z = _grow(self.t_z, end)
        self.t_zlim = _grow(self.t_zlim, end)
        self.t_col = _grow(self.t_col, end)
        self.t_state = _grow(self.t_state, end)

    def _records(self) -> tuple:
        """The set-up record arrays, in the order the set-up kernels write them."""
        return (self.t_edge, self.t_box, self.t_z, self.t_zlim, self.t_col, self.t_state)

    def _band_order(self, items: np.ndarray, nthreads: int) -> tuple:
        """The binned primitives with their triangle records copied into band order
        (``band_records``): items ``0 .. n - 1``, the kinds and references, and the
        record arrays, for :func:`render_bands` in place of the batch's own."""
        n = items.shape[0]
        self._band_capacity(n)
        prims = (self.g_kind, self.g_ref)
        # Chunks of items are disjoint slots: they copy on the worker threads.
        _run_chunks(nthreads > 1, nthreads, _gather_range(items, self, prims),
                    _cuts(n, nthreads))
        return self.g_iota[:n], prims, self.g_records

    def _band_capacity(self, n: int) -> None:
        """Band-ordered arrays (``g_*``) for at least ``n`` entries."""
        if self.g_kind.shape[0] < n:
            cap = max(n, 2 * self.g_kind.shape[0], 64)
            self.g_iota = np.arange(cap, dtype=np.int64)
            self.g_kind = np.empty(cap, np.int64)
            self.g_ref = np.empty(cap, np.int64)
            self.g_records = tuple(np.empty((cap,) + a.shape[1:], a.dtype)
                                   for a in self._records())

    def _scatter(self, shift: int, nbands: int, nthreads: int):
        """Bin the primitives and write their records into band order in one pass in
        drawing order (``scatter_bins``, kernels/band_order.py): ``(starts, items,
        prims, records)`` for :func:`render_bands`, or None when the bins hold more
        than ``GATHER_MAX`` entries (nothing written).  Chunks of primitives run on
        the worker threads, each from its own free slot per band (the entries of
        the chunks before it counted first), so each band stays in drawing order."""
        n = self.nprims
        cuts = _cuts(n, nthreads)
        counts = np.zeros((len(cuts), nbands), np.int64)
        par = nthreads > 1 and len(cuts) > 1
        pool = threads.pool(nthreads) if par else None

        def each(job):
            if not par:
                for c in range(len(cuts)):
                    job(c)
                return
            for f in [pool.submit(job, c) for c in range(len(cuts))]:
                f.result()

        py0, py1 = self.p_y0, self.p_y1
        each(lambda c: band_counts(py0, py1, cuts[c][0], cuts[c][1], shift, nbands, counts[c]))
        per_band = counts.sum(axis=0)
        total = int(per_band.sum())
        if total > GATHER_MAX:
            return None
        starts = np.zeros(nbands + 1, np.int64)
        starts[1:] = np.cumsum(per_band)
        fills = starts[:nbands] + np.cumsum(counts, axis=0) - counts  # chunks before
        self._band_capacity(total)
        out = (self.g_kind, self.g_ref, *self.g_records)
        own = (self.p_kind, self.p_ref, *self._records())
        each(lambda c: scatter_records(cuts[c][0], cuts[c][1], py0, py1, shift, nbands,
                                       fills[c].copy(), *own, *out))
        return starts, self.g_iota[:total], (self.g_kind, self.g_ref), self.g_records

    def _reset(self) -> None:
        """Empty the batch (counters only; the arrays keep their capacity)."""
        self._state_index: dict[RasterState, int] = {}
        self._state_rows: list[np.ndarray] = []
        self.nprims = 0
        self.ntris = 0
        self.nplaced = 0  # records that band_slots placed (:meth:`_band_slots`)
        self.nfrags = 0
        self.nruns = 0
        self.nclears = 0

    # -- state ------------------------------------------------------------------
    def state_index(self, rs: RasterState) -> int:
        """Index of a snapshot in this batch's state table (added on first use)."""
        idx = self._state_index.get(rs)
        if idx is None:
            idx = len(self._state_rows)
            self._state_index[rs] = idx
            self._state_rows.append(rs.kept_row())  # (np.stack copies at the flush)
        return idx

    def _add_prims(self, kind: int, refs: np.ndarray, y0: np.ndarray, y1: np.ndarray) -> None:
        n = refs.shape[0]
        if n == 0:
            return
        end = self.nprims + n
        self.p_kind = _grow(self.p_kind, end)
        self.p_ref = _grow(self.p_ref, end)
        self.p_y0 = _grow(self.p_y0, end)
        self.p_y1 = _grow(self.p_y1, end)
        self.p_kind[self.nprims:end] = kind
        self.p_ref[self.nprims:end] = refs
        self.p_y0[self.nprims:end] = y0
        self.p_y1[self.nprims:end] = y1
        self.nprims = end

    def _maybe_flush(self) -> None:
        if self.nprims >= MAX_PRIMITIVES:
            self.flush()

    # -- primitives ---------------------------------------------------------------
    def add_triangles(self, xf, yf, zw, col, tris, src, flat_col, rs: RasterState,
                      tex=None) -> int:
        """Set up and queue triangles given in fixed-point window coordinates.

        Parameters
        ----------
        xf, yf : ndarray, shape (Nv,), int64
        zw : ndarray, shape (Nv,), float64
        col : ndarray, shape (Nv, 4), float64 or None
            Vertex RGBA in [0, 1]; None when colour is not written.
        tris : ndarray, shape (Nt, 3), int64
        src : ndarray, shape (Nt,), int64
            Source primitive of each triangle (indexes ``flat_col``).
        flat_col : ndarray, shape (Ns, 4), float64 or None
            Last-vertex colour of each source primitive (flat shading).
        rs : RasterState
        tex : ndarray, shape (Nv, 3), float64, optional
            s/w, t/w, 1/w per vertex when ``rs`` has a texture bound.

        Returns
        -------
        int
            Number of triangle slots used (culled and zero-area triangles keep a dead
            slot that is never rasterized).
        """
        nt = tris.shape[0]
        if nt == 0:
            return 0
        # One set-up kernel for one state and for many (setup_triangles_states, with
        # the state and cull repeated): the first image then compiles one, not two.
        idx = self._repeat("idx", nt, self.state_index(rs))
        culls = self._repeat("cull", nt, rs.cull)
        start, slot = self._set_up(xf, yf, zw, col, tris, src, flat_col, rs.shademodel, idx,
                                   culls, tex)
        # Bin by the rows the triangle can touch inside the raster rectangle, so bands
        # outside the scissor (a light's scissor rectangle) never see it.
        self._queue_triangles(start, self.ntris, rs.scissor, slot)
        self._maybe_flush()
        return self.ntris - start

    def _set_up(self, xf, yf, zw, col, tris, src, flat_col, shademodel, idx, culls,
                tex) -> tuple:
        """Set up triangles ``tris`` into new record slots (state table index ``idx``
        and cull mode ``culls`` per triangle) and their texture planes; returns the
        first slot and where each triangle's record went (:meth:`_band_slots`; None:
        in drawing order).  Every triangle owns its slot (dead records for culled
        ones), so chunks of one call set up in parallel and the drawing order is
        unchanged."""
        nt = tris.shape[0]
        want_colour = col is not None or flat_col is not None
        colv = col if col is not None else np.zeros((1, 4))
        flatv = flat_col if flat_col is not None else np.zeros((1, 4))
        flat = shademodel == FLAT or col is None
        start = self.ntris
        self._grow_records(start + nt)
        nthreads = threads.get_threads()
        cuts = _cuts(nt, nthreads if nthreads > 1 and nt >= PARALLEL_SETUP else 1)
        # Texture planes are written in drawing order: a textured call is not placed.
        slot = self._band_slots(yf, tris) if tex is None else None
        self._run_setup(cuts, nthreads, slot, xf, yf, zw, colv, tris, src, flatv, idx, culls,
                        flat, want_colour, start)
        self.ntris = start + nt
        self._texture_planes(xf, yf, tex, tris, start)
        return start, slot

    def _run_setup(self, cuts, nthreads, slot, xf, yf, zw, col, tris, src, flat_col, idx,
                   culls, flat, want_colour, start) -> None:
        """Set up ``tris`` at ``start``, in drawing order or to the offsets ``slot``
        (:meth:`_band_slots`), the ranges of ``cuts`` on the worker threads when
        there are several: every triangle owns its slot, so chunks run side by side
        (on borrowed arrays with ``borrow_arrays``)."""
        out = self._records()
        if slot is None:
            kernel = setup_triangles_borrowed if self.borrow_arrays else setup_triangles_states
        else:
            kernel = (setup_triangles_slots_borrowed if self.borrow_arrays
                      else setup_triangles_slots)
        _run_chunks(len(cuts) > 1, nthreads, lambda a, b: kernel(
            xf, yf, zw, col, tris[a:b], src[a:b], flat_col, idx[a:b], culls[a:b], flat,
            want_colour, *out, *((start + a,) if slot is None else (start, slot[a:b]))), cuts)

    def _texture_planes(self, xf, yf, tex, tris, start) -> None:
        """Texture-coordinate planes of the triangles just set up at ``start``."""
        if tex is None:
            return
        self.t_tex = _grow(self.t_tex, start + tris.shape[0])
        setup_texture_planes(xf, yf, np.ascontiguousarray(tex, np.float64), tris,
                             self.t_tex, start)

    def add_triangles_states(self, xf, yf, zw, col, tris, src, flat_col,
                             states: list[RasterState], tri_state: np.ndarray,
                             tex=None) -> int:
        """:meth:`add_triangles` for triangles of several raster states at once.

        Parameters
        ----------
        states : list of RasterState
            All alike except in what only the fragment stage reads (stencil, z and
            blend functions, masks, cull): one shading model, one subpixel mode.
        tri_state : ndarray, shape (Nt,), int64
            Index into ``states`` of each triangle.
        """
        nt = tris.shape[0]
        if nt == 0:
            return 0
        if type(self).add_triangles is not _ADD_TRIANGLES:
            # add_triangles is wrapped (vgxsim.reference.recorder captures every
            # triangle through it): feed it one state run at a time.
            cuts = np.flatnonzero(np.diff(tri_state)) + 1
            bounds = [0, *cuts.tolist(), nt]
            more = {} if tex is None else {"tex": tex}  # a wrapper may not know tex
            return sum(self.add_triangles(xf, yf, zw, col, tris[a:b], src[a:b], flat_col,
                                          states[int(tri_state[a])], **more)
                       for a, b in zip(bounds[:-1], bounds[1:], strict=True))
        rs = states[0]
        seen: dict[int, tuple[int, int]] = {}  # id -> (table index, cull): one look-up each
        rows = []
        for r in states:
            hit = seen.get(id(r))
            if hit is None:
                hit = seen[id(r)] = (self.state_index(r), r.cull)
            rows.append(hit)
        table = np.array(rows, np.int64).reshape(-1, 2)
        idx = np.ascontiguousarray(table[tri_state, 0])
        culls = np.ascontiguousarray(table[tri_state, 1])
        start, slot = self._set_up(xf, yf, zw, col, tris, src, flat_col, rs.shademodel, idx,
                                   culls, tex)
        self._queue_triangles(start, self.ntris, None, slot)
        self._maybe_flush()
        return self.ntris - start

    def add_object_triangles(self, obj, mvp, viewport, depth, guard, user_planes, attr, tris,
                             flat_col, states: list[RasterState], tri_state=None) -> int:
        """Transform, clip, project, snap, set up and queue triangles in one fused pass
        per chunk (vgxsim/kernels/front.py), chunks spread over the worker threads.

        Gives the set-up records :func:`vgxsim.geometry.pipeline.draw_triangles`
        builds through :meth:`add_triangles` / :meth:`add_triangles_states` (the
        rasterized triangles and their order are the same; a clipped triangle keeps
        ``CLIP_SLOTS`` records, the unused ones dead).

        Parameters
        ----------
        obj : ndarray, shape (Nv, 4) or (Nv, 3), float64
            Homogeneous object coordinates (w = 1 where there are three columns).
        mvp : ndarray, shape (4, 4), float64
        viewport : tuple of 4 int; depth : tuple of 2 float
            Inclusive viewport and lsetdepth range.
        guard : tuple of 2 float
            Guard band (vgxsim.geometry.pipeline._guard).
        user_planes : ndarray, shape (K, 4), float64
            User clip planes in clip space (clipplane(3G)).
        attr : ndarray, shape (Nv, 4), float64 or None
            Vertex colour in [0, 1]; None when colour is not written.
        tris : ndarray, shape (Nt, 3), int64
        flat_col : ndarray, shape (Nt, 4), float64 or None
            Per triangle, its flat-shading colour.
        states : list of RasterState
            One state, or (with ``tri_state``) the states of several that differ only
            in fragment state.
        tri_state : ndarray, shape (Nt,), int64, optional
            Index into ``states`` of each triangle.

        Returns
        -------
        int
            Set-up records used.
        """
        nt = tris.shape[0]
        nv = obj.shape[0]
        if nt == 0 or nv == 0:
            return 0
        rs = states[0]
        if tri_state is None:
            idx = self._repeat("idx", nt, self.state_index(rs))
            culls = self._repeat("cull", nt, rs.cull)
        else:
            rows = [(self.state_index(r), r.cull) for r in states]
            table = np.array(rows, np.int64).reshape(-1, 2)
            idx = np.ascontiguousarray(table[tri_state, 0])
            culls = np.ascontiguousarray(table[tri_state, 1])
        want_colour = attr is not None or flat_col is not None
        attrv = attr if attr is not None else np.zeros((nv, 0))
        flatv = flat_col if flat_col is not None else np.zeros((1, 4))
        flat = rs.shademodel == FLAT or attr is None
        l, r, b, t = (int(v) for v in viewport)
        znear, zfar = float(depth[0]), float(depth[1])
        gx, gy = guard
        sub = bool(rs.subpixel)
        code = self._scratch("code", nv, (), np.uint16)
        user = np.ascontiguousarray(user_planes, dtype=np.float64).reshape(-1, 4)
        xf = self._scratch("xf", nv)
        yf = self._scratch("yf", nv)
        zw = self._scratch("zw", nv, (), np.float64)
        nthreads = threads.get_threads()
        par = nthreads > 1 and nt >= PARALLEL_FRONT
        _run_chunks(par, nthreads, front_vertices, _cuts(nv, nthreads if par else 1), obj, mvp,
                    gx, gy, user, l, r, b, t, znear, zfar, sub, code, xf, yf, zw)
        slots = front_slots(code, tris)
        used = int(slots[nt])
        if used == nt and not (slots[1:] - slots[:-1] - 1).any():
            rec_tris, rec_src = tris, None  # the usual case: one record per triangle
        else:
            xf, yf, zw, attrv, rec_tris, rec_src = front_assemble(
                obj, mvp, code, xf, yf, zw, attrv, tris, slots, gx, gy, user, l, r, b, t, znear,
                zfar, sub)
            idx = np.ascontiguousarray(idx[rec_src])
            culls = np.ascontiguousarray(culls[rec_src])
        src = self._iota(used) if rec_src is None else rec_src
        colv = attrv if attr is not None else np.zeros((1, 4))
        start = self.ntris
        end = start + used
        self._grow_records(end)
        slot = self._band_slots(yf, rec_tris)
        self._run_setup(_cuts(used, nthreads if par else 1), nthreads, slot, xf, yf, zw, colv,
                        rec_tris, src, flatv, idx, culls, flat, want_colour, start)
        self.ntris = end
        # As add_triangles bins: by the rows inside the raster rectangle (one state).
        self._queue_triangles(start, end, rs.scissor if tri_state is None else None, slot)
        self._maybe_flush()
        return used

    def add_window_triangles(self, xw, yw, zw, col, tris, rs: RasterState, flat_col=None,
                             tex=None) -> int:
        """Queue triangles given in float IRIS window coordinates (library fast path).

        Non-finite vertices drop their triangles (documented behaviour for NaN/inf).
        ``tex`` (Nv, 3): s/w, t/w, 1/w per vertex when ``rs`` has a texture bound.
        """
        xw = np.asarray(xw, np.float64)
        yw = np.asarray(yw, np.float64)
        zw = np.asarray(zw, np.float64)
        tris = np.asarray(tris, np.int64).reshape(-1, 3)
        if flat_col is None and col is not None and rs.shademodel == FLAT:
            flat_col = np.asarray(col, np.float64)[tris[:, 2]]  # the last vertex's colour
        finite = np.isfinite(xw) & np.isfinite(yw) & np.isfinite(zw)
        keep = finite[tris].all(axis=1)
        src = np.nonzero(keep)[0].astype(np.int64)
        tris = tris[keep]
        xf, yf = snap_window(np.where(finite, xw, 0.0), np.where(finite, yw, 0.0), rs.subpixel)
        if tex is not None:
            return self.add_triangles(xf, yf, np.where(finite, zw, 0.0), col, tris, src,
                                      flat_col, rs, tex=tex)
        return self.add_triangles(xf, yf, np.where(finite, zw, 0.0), col, tris, src,
                                  flat_col, rs)

    def add_fragments(self, xy, z, rgba, rs: RasterState) -> None:
        """Queue one run of fragments (a point or a line) sharing one state.

        Parameters
        ----------
        xy : ndarray, shape (F, 2), int64
        z : ndarray, shape (F,), int64
        rgba : ndarray, shape (F,), int64 packed 0xAABBGGRR
        """
        n = xy.shape[0]
        if n == 0:
            return
        s = self.state_index(rs)
        end = self.nfrags + n
        self.f_xy = _grow(self.f_xy, end)
        self.f_z = _grow(self.f_z, end)
        self.f_rgba = _grow(self.f_rgba, end)
        self.f_xy[self.nfrags:end] = xy
        self.f_z[self.nfrags:end] = z
        self.f_rgba[self.nfrags:end] = rgba
        self.r_range = _grow(self.r_range, self.nruns + 1)
        self.r_state = _grow(self.r_state, self.nruns + 1)
        self.r_range[self.nruns] = (self.nfrags, end)
        self.r_state[self.nruns] = s
        self._add_prims(KIND_FRAGMENTS, np.array([self.nruns]), np.array([xy[:, 1].min()]),
                        np.array([xy[:, 1].max()]))
        self.nruns += 1
        self.nfrags = end
        self._maybe_flush()

    def add_clear(self, planes: int, colour: int, z: int, stencil: int, rs: RasterState) -> None:
        """Queue a clear of the raster rectangle of ``rs`` (planes: CLEAR_* bits)."""
        fb = self.fb
        if fb.z is None:
            planes &= ~CLEAR_Z
        if fb.stencil is None:
            planes &= ~CLEAR_STENCIL
        if planes == 0:
            return
        s = self.state_index(rs)
        self.c_vals = _grow(self.c_vals, self.nclears + 1)
        self.c_state = _grow(self.c_state, self.nclears + 1)
        self.c_vals[self.nclears] = (planes, colour & 0xFFFFFFFF, z, stencil)
        self.c_state[self.nclears] = s
        self._add_prims(KIND_CLEAR, np.array([self.nclears]), np.array([rs.scissor[2]]),
                        np.array([rs.scissor[3]]))
        self.nclears += 1
        self._maybe_flush()

    # -- flush ----------------------------------------------------------------------
    def _state_tables(self) -> tuple:
        """The flush's state table and what is derived from it: ``(states,
        tex_table, derived, tables, textured, all_lean)``, ``all_lean`` whether
        every state takes the lean kernel (lean_fits of the whole table).

        With ``cache_tables``, kept per distinct list of state rows (kept_row: one
        frozen array per snapshot, so their identities name the values) for an
        untextured table: a frame flushes the same few snapshots again, and the
        derivation is Python over every row (about 0.1 ms a flush).  Textured
        tables are made afresh (pack_bindings reads the current texel arrays)."""
        rows = self._state_rows
        fb = self.fb
        key = (tuple(map(id, rows)), fb.back is None, fb.config.stencil, fb.z is not None)
        if self.cache_tables:
            hit = self._tables_memo.get(key)
            if hit is not None and all(a is b for a, b in zip(hit[0], rows, strict=True)):
                return hit[1]
        states = np.stack(rows) if rows else np.zeros((1, ROW_SIZE), np.int64)
        if fb.back is None:
            # Single-buffered: frontbuffer/backbuffer select nothing; everything drawn
            # goes to the one colour buffer (and a dummy back plane is never indexed).
            states = states.copy()
            states[:, S_DRAW_FRONT] |= states[:, S_DRAW_BACK]
            states[:, S_DRAW_BACK] = 0
        textured = bool(states[:, S_TEXTURE].any())
        states, tex_table = _texture_table(states)
        derived, tables = derive_states(states, fb.config.stencil, True, fb.z is not None)
        all_lean = lean_fits(derived, 0, False, False)
        out = (states, tex_table, derived, tables, textured, all_lean)
        if self.cache_tables and not textured:
            if len(self._tables_memo) >= TABLES_MEMO:
                self._tables_memo.clear()
            self._tables_memo[key] = (tuple(rows), out)
        return out

    def flush(self) -> None:
        """Render everything queued, in order, and empty the batch."""
        if self.nprims == 0:
            return
        fb = self.fb
        states, tex_table, derived, tables, textured, all_lean = self._state_tables()
        front, back, z, st = fb.kernel_planes()
        height = fb.height
        nthreads = max(1, threads.get_threads())
        tall = (self.tall_bands and self.ntris >= TALL_MIN
                and mean_rows(self.p_y0, self.p_y1, self.nprims, height) <= TALL_ROWS)
        shift = band_shift(height, nthreads, tall)
        nbands = (height + (1 << shift) - 1) >> shift
        work = np.zeros((nbands, WORK_SIZE), np.int64)  # one row per band: no sharing
        # Tall bands whose records their calls placed by band (band_slots) read them
        # in place, front to back: a copy would cost more than it saves.  (Records
        # in drawing order are copied: read in place, every other one, they cost
        # the band kernel more than the copy.)
        placed = tall and nbands <= TALL_COPY_BANDS and self.nplaced == self.ntris
        ordered = (self.band_records and not textured and nbands > 1
                   and self.ntris >= GATHER_MIN and not placed)
        got = self._scatter(shift, nbands, nthreads) if ordered and self.scatter_bins else None
        if got is not None:
            starts, items, prims, records = got
        else:
            starts, items = bin_primitives(self.p_y0, self.p_y1, self.nprims, shift, nbands)
            if ordered and items.shape[0] <= GATHER_MAX:
                items, prims, records = self._band_order(items, nthreads)
            else:
                prims, records = (self.p_kind, self.p_ref), self._records()
        args = (
            starts, items, shift, height, *prims, *records,
            self.f_xy, self.f_z, self.f_rgba, self.r_range, self.r_state,
            self.c_vals, self.c_state, states, derived, tables,
            front, back, z, st, self.edge_mode, self.general_only,
            self.skip_tiles, self.cover_blocks, self.tight_tiles, self.step_spans,
            self.vector_pack, self.small_path, self.block_update, self.lit_spans, self.lit_lanes,
            self.fill_spans, self.zpass_spans,
            self.prefetch_planes, self.span_zwrite, self.stencil_bounds, self.sided_bounds,
            work,
            (self.t_tex, *tex_table),
        )
        nthreads = min(nthreads, nbands)
        lean = False
        if self.lean_kernel and all_lean and not (self.nruns or self.edge_mode
                                                  or self.general_only):
            lean = True  # every state of the table fits: so do those triangles use
        elif self.lean_kernel:
            used = np.zeros(len(derived), bool)  # the states triangles use
            used[self.t_state[:self.ntris]] = True
            lean = lean_fits(derived[used], self.nruns, self.edge_mode, self.general_only)
        kernel = self.band_kernel(lean, self.borrow_arrays)
        if nthreads == 1:
            kernel(0, 1, *args)
        else:
            # The kernel releases the GIL: plain threads give band parallelism without
            # Numba's parallel=True compile cost (a large part of cold start).
            # One task per band (render_bands(b, nbands) renders band b alone): the
            # pool hands bands to whichever thread is free, the busiest bands (most
            # primitives) first, so that a heavy band is not the last one started
            # while the other thread idles (bands are disjoint: order changes nothing).
            order = np.argsort(-np.diff(starts), kind="stable").tolist()
            if self.band_workers:
                threads.run_each(nthreads, lambda b: kernel(b, nbands, *args), order)
            else:
                pool = threads.pool(nthreads)
                futures = [pool.submit(kernel, b, nbands, *args) for b in order]
                for f in futures:
                    f.result()
        self.counters += work.sum(axis=0)
        self.flushes += 1
        self._reset()


_ADD_TRIANGLES = CommandBatch.add_triangles
_NO_SLOTS = np.zeros(0, np.int64)  # queue_triangles: records in drawing order


def _gather_range(items, batch: CommandBatch, prims):
    """``f(lo, hi)`` copying the records of ``items[lo:hi]`` (for _run_chunks)."""
    args = (batch.p_kind, batch.p_ref, *batch._records(), *prims, *batch.g_records)
    return lambda lo, hi: gather_band_records(items, lo, hi, *args)


def _texture_table(states: np.ndarray):
    """States with S_TEXTURE rewritten from binding ids to 1 + rows of the batch's
    texture table, and that table (vgxsim.state.textures.pack_bindings)."""
    col = states[:, S_TEXTURE]
    if not col.any():
        return states, pack_bindings([])
    ids = sorted({int(v) for v in col if v})
    states = states.copy()
    states[:, S_TEXTURE] = [0 if v == 0 else ids.index(int(v)) + 1 for v in col]
    return states, pack_bindings(ids)
