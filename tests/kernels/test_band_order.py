"""Records written into band order in one pass in drawing order
(kernels/band_order.py, CommandBatch.scatter_bins) change nothing drawn.

Flushes of triangles (small, slivers, big ones crossing bands, dead ones: culled
and zero-area), clears, points and lines, under states switched between
primitives (z only, z + stencil INCR/DECR, a stencil test with ONE+ONE blending,
culling, a scissor), are rendered with the records scattered into band order, with
them gathered band by band (kernels/render.py gather_band_records) and with no
copy at all (band_records off), on one and two threads (two bands, then more, so
that chunks of primitives fill the same band); planes and work counters must be
identical, and the planes equal to the naive reference's.
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
from vgxsim.kernels.band_order import band_counts
from vgxsim.kernels.render import bin_primitives
from vgxsim.state.raster import (
    BF_ONE,
    CMP_LESS,
    CMP_NOTEQUAL,
    CULL_BACK,
    OP_DECR,
    OP_INCR,
)

W, H = 90, 300  # two bands on one thread, ten on two


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
    clear_all = ("clear", {"color", "z", "stencil"},
                 {"color": 0x40302010, "z": 0x7FFFFF, "stencil": 1}, full_state(W, H))
    cmds = [clear_all]
    rs = states[0]
    for k in range(n):
        u = rng.random()
        if u < 0.1:
            rs = states[int(rng.integers(len(states)))]
        if k == n // 2:
            cmds.append(("clear", {"stencil"}, {"stencil": 2}, full_state(W, H)))
        if u > 0.99:
            x, y = (float(v) for v in rng.uniform([0, 0], [W, H]))
            cmds.append(("point", (x, y, 0.0, (1.0, 0.5, 0.0, 1.0)), rs))
            continue
        if u > 0.98:
            a = tuple(float(v) for v in rng.uniform([0, 0], [W, H]))
            b = tuple(float(v) for v in rng.uniform([0, 0], [W, H]))
            cmds.append(("line", [(a[0], a[1], 0.0, (0.0, 1.0, 0.0, 1.0)),
                                  (b[0], b[1], 0.0, (0.0, 1.0, 0.0, 1.0))], rs))
            continue
        side = 90.0 if u < 0.05 else (0.0 if u < 0.06 else float(rng.uniform(1.0, 6.0)))
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


@pytest.mark.parametrize("nthreads", [1, 2])
def test_scattered_band_order_changes_no_plane_and_no_counter(monkeypatch, nthreads):
    monkeypatch.setattr(batch_mod, "GATHER_MIN", 64)
    cmds = _scene(np.random.default_rng(21 + nthreads), 1500)
    want, want_work = _render(cmds, nthreads, band_records=False)
    for scatter in (True, False):
        got, work = _render(cmds, nthreads, scatter_bins=scatter)
        what = f"scatter_bins={scatter}, {nthreads} thread(s)"
        assert_planes_equal(got, want, what)
        assert work == want_work, what
    assert want_work["fragments"] > 5000
    if nthreads == 2:
        naive = render_naive(cmds, W, H, double=True, zbits=24, stencil=8)
        assert_planes_equal(want, naive, "naive reference")


def test_band_counts_in_chunks_add_up_to_the_bins():
    """Counts per chunk of primitives sum to bin_primitives' band sizes."""
    rng = np.random.default_rng(4)
    n = 500
    y0 = rng.integers(-20, 300, n)
    y1 = y0 + rng.integers(-3, 90, n)  # some empty (y1 < y0), some across bands
    y0[::17] = 1 << 40  # dead records
    y1[::17] = -1
    starts, _ = bin_primitives(y0, y1, n, 5, 10)
    counts = np.zeros(10, np.int64)
    for lo, hi in ((0, 123), (123, 124), (124, n)):
        band_counts(y0, y1, lo, hi, 5, 10, counts)
    np.testing.assert_array_equal(counts, np.diff(starts))
