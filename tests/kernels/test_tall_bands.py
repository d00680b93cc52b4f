"""Tall bands for flushes of small triangles (CommandBatch.tall_bands) change nothing
drawn and count the same work.

A flush of many small triangles takes one band per thread (one band on one thread)
instead of bands of at most 256 rows, eight a thread.  Scenes of small triangles
(most a few pixels, some slivers and a few wide ones crossing bands, dead ones:
culled and zero-area), clears, points and lines, under states switched between
primitives (z only, z + stencil INCR/DECR, a stencil test with ONE+ONE blending,
culling, a scissor) are rendered with the switch on and off on one, two and three
threads (a window height that is not a power of two: the last band is short; on
three threads the tall bands' records are copied into band order, on fewer they
are read in place) and with band_records on and off; planes and the work
counters of fragments and tiles must be identical, the planes equal to the naive
reference's, and the tall path must have been taken.
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

from vgxsim import batch as batch_mod
from vgxsim import threads
from vgxsim.state.raster import (
    BF_ONE,
    CMP_LESS,
    CMP_NOTEQUAL,
    CULL_BACK,
    OP_DECR,
    OP_INCR,
)

W, H = 90, 300  # tall: one band of 512 rows on one thread, 256 + 44 rows on two,
# 128 + 128 + 44 on three


def _states():
    return [
        full_state(W, H, zbuffer=True),
        full_state(W, H, zbuffer=True, zfunc=CMP_LESS, wmpack=0),
        full_state(W, H, zbuffer=True, zwritemask=0, wmpack=0, stencil=True,
                   szpass=OP_INCR, spass=OP_DECR),
        full_state(W, H, zbuffer=True, stencil=True, sfunc=CMP_NOTEQUAL, sref=1,
                   blend_sf=BF_ONE, blend_df=BF_ONE),
        full_state(W, H, zbuffer=True, cull=CULL_BACK),
        full_state(W, H, zbuffer=True, scissor=(10, 70, 40, 250)),
    ]


def _scene(rng, n):
    states = _states()
    cmds = [("clear", {"color", "z", "stencil"},
             {"color": 0x40302010, "z": 0x7FFFFF, "stencil": 1}, full_state(W, H))]
    rs = states[0]
    for k in range(n):
        u = rng.random()
        if u < 0.1:
            rs = states[int(rng.integers(len(states)))]
        if k == n // 2:
            cmds.append(("clear", {"stencil"}, {"stencil": 2}, full_state(W, H)))
        if u > 0.995:
            x, y = (float(v) for v in rng.uniform([0, 0], [W, H]))
            cmds.append(("point", (x, y, 0.0, (1.0, 0.5, 0.0, 1.0)), rs))
            continue
        if u > 0.99:
            a = tuple(float(v) for v in rng.uniform([0, 0], [W, H]))
            b = tuple(float(v) for v in rng.uniform([0, 0], [W, H]))
            cmds.append(("line", [(a[0], a[1], 0.0, (0.0, 1.0, 0.0, 1.0)),
                                  (b[0], b[1], 0.0, (0.0, 1.0, 0.0, 1.0))], rs))
            continue
        # Mostly a few pixels; 1 % wide (crossing the two-thread bands' edge at row
        # 256), 1 % zero-size.
        side = 80.0 if u < 0.01 else (0.0 if u < 0.02 else float(rng.uniform(1.0, 4.0)))
        c = rng.uniform([0, 0], [W, H])
        z = float(rng.uniform(-4000, 4000))
        tri = tuple((float(x), float(y), z + float(rng.uniform(-500, 500)),
                     tuple(float(v) for v in rng.uniform(0, 1, 4)))
                    for x, y in c + rng.uniform(-side, side, (3, 2)))
        cmds.append(("triangle", tri, rs))
    return cmds


def _render(cmds, nthreads, **switches):
    threads.set_threads(nthreads)
    try:
        fb = kernel_framebuffer(W, H, double=True, zbits=24, stencil=8)
        batch = kernel_batch(fb)
        for k, v in switches.items():
            setattr(batch, k, v)
        queue_commands(batch, cmds)
        batch.flush()
        return planes_of(fb), batch.work()
    finally:
        threads.set_threads(None)  # follow numba again (not an override of its count)


def _drawn(work):
    """The counters of work done on fragments and tiles; not ``tiles_scanned``, the
    bookkeeping of depth bounds read from the z plane, which are kept per band and
    so are read again where bands cut tiles otherwise (as between thread counts)."""
    return {k: v for k, v in work.items() if k != "tiles_scanned"}


@pytest.mark.parametrize("nthreads", [1, 2, 3])
def test_tall_bands_change_no_plane_and_no_counter(monkeypatch, nthreads):
    monkeypatch.setattr(batch_mod, "TALL_MIN", 64)
    monkeypatch.setattr(batch_mod, "GATHER_MIN", 64)
    taken = []
    shift_of = batch_mod.band_shift

    def spy(height, n, tall=False):
        taken.append(tall)
        return shift_of(height, n, tall)

    monkeypatch.setattr(batch_mod, "band_shift", spy)
    cmds = _scene(np.random.default_rng(40 + nthreads), 2500)
    want, want_work = _render(cmds, nthreads, tall_bands=False)
    assert taken and not any(taken)
    for records in (True, False):
        taken.clear()
        got, work = _render(cmds, nthreads, tall_bands=True, band_records=records)
        assert taken and all(taken)  # the scene is one of small triangles
        what = f"tall_bands, band_records={records}, {nthreads} thread(s)"
        assert_planes_equal(got, want, what)
        assert _drawn(work) == _drawn(want_work), what
    assert want_work["fragments"] > 5000
    if nthreads == 2:
        naive = render_naive(cmds, W, H, double=True, zbits=24, stencil=8)
        assert_planes_equal(want, naive, "naive reference")


def test_tall_band_heights_cover_the_window_with_one_band_per_thread():
    for height in (1, 31, 32, 33, 300, 1000, 1024, 1025):
        for n in (1, 2, 3, 8):
            shift = batch_mod.band_shift(height, n, tall=True)
            rows = 1 << shift
            nbands = -(-height // rows)
            assert rows >= 32  # tile rows (kernels/tiles.py TILE_H) never cut
            assert nbands <= n and nbands * rows >= height, (height, n)
