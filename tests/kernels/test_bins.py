"""Tile bins (kernels/bins.py, CommandBatch.tile_bins) change nothing drawn.

Runs of small triangles inside a band are reordered tile by tile; the planes must
come out bit-identical to primitive order.  The scenes put many triangles on the
same pixels across tile edges (a crossing triangle is drawn once per tile,
clipped), with order-dependent raster states between them (additive blending
without a z test, stencil increments, replace with z writes), big triangles,
clears and points in the middle of the runs, on one and two threads; they are
compared with the switch on and off, with the band copy off, and against the naive
reference.  The reordering itself is checked on a hand-made band.
"""

import numpy as np
import pytest
from kernel_helpers import (
    assert_planes_equal,
    full_state,
    kernel_batch,
    kernel_framebuffer,
    planes_of,
    queue_commands,
    render_naive,
)

import vgxsim.batch as batch_module
from vgxsim import threads
from vgxsim.kernels.bins import MIN_RUN, NO_TILE, bin_tiles
from vgxsim.state.codes import KIND_CLEAR, KIND_TRIANGLE
from vgxsim.state.raster import (
    BF_MSA,
    BF_ONE,
    BF_SA,
    CMP_ALWAYS,
    CMP_EQUAL,
    CMP_LEQUAL,
    CMP_LESS,
    OP_INCR,
    OP_REPLACE,
)

W, H = 300, 260  # five tile columns (64 pixels) and nine tile rows (32), partial ones


def _states():
    return [
        full_state(W, H, zbuffer=True, zfunc=CMP_LEQUAL),
        # Additive blend with no z test: the result depends on nothing but the
        # colour already there, so a swapped pair of fragments shows.
        full_state(W, H, blend_sf=BF_ONE, blend_df=BF_ONE),
        full_state(W, H, zbuffer=True, zfunc=CMP_LESS, zwritemask=0, wmpack=0,
                   stencil=True, szpass=OP_INCR, spass=OP_REPLACE, sref=7),
        full_state(W, H, zbuffer=True, zfunc=CMP_ALWAYS, blend_sf=BF_SA, blend_df=BF_MSA),
        full_state(W, H, zbuffer=True, zfunc=CMP_EQUAL, stencil=True, sfunc=CMP_EQUAL,
                   sref=1, blend_sf=BF_ONE, blend_df=BF_ONE),
        full_state(W, H, zbuffer=True, scissor=(70, 200, 30, 220)),
    ]


def _tri(rng, centre, size):
    p = centre + rng.uniform(-size, size, (3, 2))
    z = float(rng.uniform(-3000, 3000))
    return tuple((float(x), float(y), z + float(rng.uniform(-500, 500)),
                  tuple(float(v) for v in rng.uniform(0, 1, 4))) for x, y in p)


def _scene(rng, n):
    """Small triangles, most of them near tile edges (x = 64, 128, ...; y = 32, 64,
    ...), in runs of random states, with a big triangle, a clear or a point now and
    then."""
    states = _states()
    cmds = [("clear", {"color", "z", "stencil"}, {"color": 0x20304050, "z": 0x7FFFFF,
                                                  "stencil": 1}, full_state(W, H))]
    rs = states[0]
    for _ in range(n):
        u = rng.random()
        if u < 0.1:
            rs = states[int(rng.integers(len(states)))]
        if u < 0.01:
            cmds.append(("clear", {"stencil"}, {"stencil": 1}, full_state(W, H)))
        elif u < 0.02:
            cmds.append(("triangle", _tri(rng, rng.uniform([0, 0], [W, H]), 120.0), rs))
        elif u < 0.025:
            cmds.append(("point", (float(rng.uniform(0, W)), float(rng.uniform(0, H)), 0.0,
                                   (1.0, 0.0, 0.0, 1.0)), rs))
        else:
            x = 64 * int(rng.integers(1, 5)) + rng.normal(0, 3)
            y = 32 * int(rng.integers(1, 9)) + rng.normal(0, 3)
            c = np.array([x if rng.random() < 0.7 else rng.uniform(0, W),
                          y if rng.random() < 0.5 else rng.uniform(0, H)])
            cmds.append(("triangle", _tri(rng, c, float(rng.uniform(1, 5))), rs))
    return cmds


def _pile(rng, n):
    """``n`` triangles over the same few pixels around (128, 96), a tile corner,
    alternating states whose results depend on the order."""
    states = _states()
    cmds = [("clear", {"color", "z", "stencil"}, {"color": 0, "z": 0x7FFFFF, "stencil": 1},
             full_state(W, H))]
    for i in range(n):
        rs = states[(i // 3) % 4]
        cmds.append(("triangle", _tri(rng, np.array([128.0, 96.0]), 6.0), rs))
    return cmds


def _render(cmds, nthreads, mode="span", **switches):
    keep = threads.get_threads()
    threads.set_threads(nthreads)
    try:
        fb = kernel_framebuffer(W, H, double=False, zbits=24, stencil=8)
        batch = kernel_batch(fb, mode)
        for k, v in switches.items():
            setattr(batch, k, v)
        queue_commands(batch, cmds)
        batch.flush()
        return planes_of(fb)
    finally:
        threads.set_threads(keep)


@pytest.mark.parametrize("seed", range(3))
@pytest.mark.parametrize("nthreads", [1, 2])
def test_tile_bins_change_no_plane(monkeypatch, seed, nthreads):
    monkeypatch.setattr(batch_module, "GATHER_MIN", 16)  # band order from 16 triangles
    calls = []
    real = batch_module.bin_tiles
    monkeypatch.setattr(batch_module, "bin_tiles",
                        lambda *a: calls.append(1) or real(*a))
    rng = np.random.default_rng(900 + seed)
    cmds = _scene(rng, 700) if seed else _pile(rng, 400)
    want = _render(cmds, nthreads, tile_bins=False)
    assert not calls
    got = _render(cmds, nthreads, tile_bins=True)
    assert calls  # the bins were really made
    assert_planes_equal(got, want, f"tile_bins on, {nthreads} thread(s)")
    assert_planes_equal(_render(cmds, nthreads, band_records=False), want, "no band copy")
    assert_planes_equal(_render(cmds, nthreads, "edge", tile_bins=True), want,
                        "edge-function rasterizer, tile_bins on")
    if nthreads == 1:
        assert_planes_equal(render_naive(cmds, W, H, double=False, zbits=24, stencil=8),
                            want, "naive reference")


def test_bin_tiles_by_hand():
    """One band of two tile rows of 64-pixel tiles: a run of small triangles goes
    tile by tile in primitive order (a crossing one in every tile it touches), a
    big triangle and a clear end runs, and a run shorter than MIN_RUN stays as it
    is."""
    assert MIN_RUN <= 8
    # (x0, x1, y0, y1) of each triangle's box.  None: a clear.
    boxes = [(70, 75, 0, 3), (10, 12, 0, 3), (60, 66, 0, 3), (130, 131, 0, 3),
             (5, 9, 0, 3), (100, 101, 0, 3), (64, 64, 0, 3),
             (127, 128, 0, 3),         # run 1: eight small triangles (0..7)
             (0, 250, 0, 3),           # 8: big, ends the run
             (1, 2, 0, 3), (200, 201, 0, 3),  # 9, 10: a short run
             None,                     # 11: a clear
             (66, 67, 0, 3), (3, 4, 0, 3), (65, 66, 0, 3), (62, 63, 0, 3),
             (1, 1, 0, 3), (68, 69, 0, 3), (2, 2, 0, 3),
             (63, 64, 30, 33)]         # 19: four tiles
    kinds, refs, tb = [], [], []
    for b in boxes:
        if b is None:
            kinds.append(KIND_CLEAR)
            refs.append(0)
            continue
        kinds.append(KIND_TRIANGLE)
        refs.append(len(tb))
        tb.append(b)
    p_kind = np.array(kinds, np.int64)
    p_ref = np.array(refs, np.int64)
    t_box = np.array(tb, np.int64)
    n = len(boxes)
    starts = np.array([0, n], np.int64)
    items = np.arange(n, dtype=np.int64)
    new_starts, place = bin_tiles(starts, items, p_kind, p_ref, t_box, 256, 64, 6)
    slots = {}
    for i in range(n):
        for slot, col, row in place[i]:
            if slot >= 0:
                assert slot not in slots
                slots[int(slot)] = (int(items[i]), int(col), int(row))
    nc = NO_TILE
    want = [  # (primitive, tile column, tile row)
        (1, 0, 0), (2, 0, 0), (4, 0, 0),                        # tile (0, 0) in order
        (0, 1, 0), (2, 1, 0), (5, 1, 0), (6, 1, 0), (7, 1, 0),  # 2 and 7 cross
        (3, 2, 0), (7, 2, 0),
        (8, nc, -1), (9, nc, -1), (10, nc, -1), (11, nc, -1),
        (13, 0, 0), (15, 0, 0), (16, 0, 0), (18, 0, 0), (19, 0, 0),
        (12, 1, 0), (14, 1, 0), (17, 1, 0), (19, 1, 0),
        (19, 0, 1), (19, 1, 1),
    ]
    assert list(new_starts) == [0, len(want)]
    assert sorted(slots) == list(range(len(want)))
    assert [slots[k] for k in range(len(want))] == want
