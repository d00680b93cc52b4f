"""Tall bands for flushes of small triangles (CommandBatch.tall_bands) change nothing
drawn and count the same work.

A flush of many small triangles takes one band per thread (one band on one thread)
instead of bands of at most 256 rows, eight a thread.  Scenes of small triangles
(most a few pixels, some slivers and a few wide ones crossing bands, dead ones:
culled and zero-area), clears, points and lines, under states switched between
primitives (z only, z + stencil INCR/DECR, a stencil test with ONE+ONE blending,
culling, a scissor) are rendered with the switch on and off on one, two and three
threads (a window height that is not a power of two: the last band is short; on
two threads the records are placed by band and read in place, else copied into
band order) and with band_records and band_slots on and off; planes and the work
counters of fragments and tiles must be identical, the planes equal to the naive
reference's, and the tall path must have been taken.
"""

import numpy as np
import pytest
from kernel_helpers import (
    assert_planes_equal,
    band_scene,
    band_states,
    full_state,
    render_naive,
    render_switched,
)

from vgxsim import batch as batch_mod
from vgxsim import threads
from vgxsim.geometry.transform import perspective
from vgxsim.pipeline.context import Context
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
    return band_states(W, H, CULL_BACK, (OP_INCR, OP_DECR), (CMP_LESS, CMP_NOTEQUAL),
                       BF_ONE) + [
        full_state(W, H),  # no z test: the last triangle drawn on a pixel is its colour
    ]


def _scene(rng, n, group=1):
    # Mostly a few pixels; 1 % wide (crossing the two-thread bands' edge at row
    # 256), 1 % zero-size.
    return band_scene(rng, n, W, H, _states(), switch_below=0.1 / group,
                      point_above=0.995, line_above=0.99, wide_below=0.01,
                      dead_below=0.02, wide=80.0, small=4.0)


def _render(cmds, nthreads, **switches):
    return render_switched(cmds, W, H, nthreads=nthreads, **switches)


def _drawn(work):
    """The counters of fragments drawn.  The tile counters depend on the band
    height (as between thread counts): a triangle is classified by tiles where its
    part in a band is large enough, and depth and stencil bounds are kept per band
    (with stencil_bounds on, fragments and stencil writes depend on it too)."""
    return {k: work[k] for k in ("fragments", "stencil_writes")}


@pytest.mark.parametrize("nthreads", [1, 2, 3])
def test_tall_bands_change_no_plane_and_no_counter(monkeypatch, nthreads):
    monkeypatch.setattr(batch_mod, "TALL_MIN", 16)
    monkeypatch.setattr(batch_mod, "GATHER_MIN", 64)
    taken = []
    shift_of = batch_mod.band_shift

    def spy(height, n, tall=False):
        taken.append(tall)
        return shift_of(height, n, tall)

    monkeypatch.setattr(batch_mod, "band_shift", spy)
    placed = []
    slots_of = batch_mod.band_slots
    monkeypatch.setattr(batch_mod, "band_slots", lambda *a: placed.append(slots_of(*a))
                        or placed[-1])
    # Long runs of one state: calls of many triangles, whose records are placed.
    cmds = _scene(np.random.default_rng(40 + nthreads), 2500, group=20)
    # Stencil bounds skip whole tiles, and tiles lie in bands: with them the count
    # of fragments drawn depends on the band height too, so the drawn counters are
    # compared with stencil_bounds off, the planes with it on and off.
    for bounds in (True, False):
        taken.clear()
        want, want_work = _render(cmds, nthreads, tall_bands=False, stencil_bounds=bounds)
        assert taken and not any(taken) and not placed
        tall_work = None
        for records, slots in ((True, True), (False, True), (True, False)):
            taken.clear()
            placed.clear()
            got, work = _render(cmds, nthreads, tall_bands=True, band_records=records,
                                band_slots=slots, stencil_bounds=bounds)
            assert taken and all(taken)  # the scene is one of small triangles
            # Records are placed by band where two tall bands read them in place.
            assert any(placed) == (slots and nthreads == 2)
            what = (f"tall_bands, band_records={records}, band_slots={slots}, "
                    f"stencil_bounds={bounds}, {nthreads} thread(s)")
            assert_planes_equal(got, want, what)
            if not bounds:
                assert _drawn(work) == _drawn(want_work), what
            tall_work = tall_work or work
            assert work == tall_work, what  # the same bands: every counter the same
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


def _draw_arrays(obj, col, tris, nthreads, zbuffer, monkeypatch, **switches):
    monkeypatch.setattr(batch_mod, "PARALLEL_FRONT", 8)  # split every call into chunks
    for k, v in switches.items():
        monkeypatch.setattr(batch_mod.CommandBatch, k, v)
    threads.set_threads(nthreads)
    try:
        ctx = Context(W, H, rgb=True, double=False)
        ctx.matrices.load_projection(perspective(700, W / H, 0.5, 25.0))
        ctx.raster.set(zbuffer=zbuffer)
        ctx.draw_arrays("triangles", obj, col, indices=tris)
        ctx.flush()
        return ctx.fb.front.copy(), ctx.fb.z.copy(), ctx.batch.work()
    finally:
        threads.set_threads(None)


@pytest.mark.parametrize("nthreads", [1, 2])
@pytest.mark.parametrize("zbuffer", [True, False])
def test_band_slots_of_the_array_path_change_no_plane(monkeypatch, nthreads, zbuffer):
    """The fused front end (Context.draw_arrays, CommandBatch.add_object_triangles)
    with its records placed by band: small triangles in perspective, some crossing
    the near plane (clipped: several records a triangle), some behind the eye
    (rejected: none), a few wide ones crossing the bands' edge; with the z test, and
    without (the last triangle drawn on a pixel gives its colour: drawing order)."""
    monkeypatch.setattr(batch_mod, "TALL_MIN", 16)
    placed = []
    slots_of = batch_mod.band_slots
    monkeypatch.setattr(batch_mod, "band_slots", lambda *a: placed.append(slots_of(*a))
                        or placed[-1])
    rng = np.random.default_rng(3)
    n = 3000
    centre = rng.uniform([-1.2, -6, -24], [1.2, 6, -1], (n, 1, 3))
    size = np.where(rng.random((n, 1, 1)) < 0.01, 0.6, 0.05)
    obj = (centre + rng.normal(size=(n, 3, 3)) * size).reshape(-1, 3)
    obj[: 3 * 40, 2] += rng.uniform(0, 30, 3 * 40)  # near-plane crossings, behind the eye
    col = rng.random((obj.shape[0], 4))
    tris = np.arange(obj.shape[0]).reshape(-1, 3)
    want = _draw_arrays(obj, col, tris, nthreads, zbuffer, monkeypatch, tall_bands=False)
    unplaced = _draw_arrays(obj, col, tris, nthreads, zbuffer, monkeypatch, tall_bands=True,
                            band_slots=False)
    assert not placed
    got = _draw_arrays(obj, col, tris, nthreads, zbuffer, monkeypatch, tall_bands=True,
                       band_slots=True)
    assert any(placed) == (nthreads == 2)
    for name, a, b, c in zip(("colour", "z"), got[:2], unplaced[:2], want[:2], strict=True):
        np.testing.assert_array_equal(a, b, err_msg=name)
        np.testing.assert_array_equal(a, c, err_msg=name)
    assert got[2] == unplaced[2]
    assert _drawn(got[2]) == _drawn(want[2])
    assert want[2]["fragments"] > 2000
