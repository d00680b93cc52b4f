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
    band_scene,
    band_states,
    render_naive,
    render_switched,
)

from vgxsim import batch as batch_mod
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
    return band_states(W, H, CULL_BACK, (OP_INCR, OP_DECR), (CMP_LESS, CMP_NOTEQUAL), BF_ONE)


def _scene(rng, n):
    return band_scene(rng, n, W, H, _states(), switch_below=0.1, point_above=0.99,
                      line_above=0.98, wide_below=0.05, dead_below=0.06, wide=90.0,
                      small=6.0)


def _render(cmds, nthreads, **switches):
    return render_switched(cmds, W, H, nthreads=nthreads, **switches)


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
