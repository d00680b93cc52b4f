"""Prefetching the plane rows of coming small triangles (kernels/prefetch.py,
CommandBatch.prefetch_planes) changes nothing drawn and counts the same work.

The prefetch reads the box and state of the triangle a few entries ahead in the
band kernel's walk: scenes mix small triangles (the prefetched ones), wide ones (not
prefetched), clears and lines between them, states switched between triangles
(colour to the front or the back buffer, z only, the shadow-volume z + stencil
counts, a stencil-tested lit pass), boxes crossing the window edges; small flushes
(records read in place) and large ones (records in band order), one and two
threads.  Planes and work counters must equal those with the switch off, and the
naive reference's planes.
"""

from __future__ import annotations

import numpy as np
import pytest
from kernel_helpers import (
    assert_planes_equal,
    full_state,
    render_naive,
    render_switched,
)

from vgxsim.batch import GATHER_MIN
from vgxsim.state.raster import (
    BF_ONE,
    CMP_EQUAL,
    CMP_LESS,
    CMP_NOTEQUAL,
    OP_DECR,
    OP_INCR,
)

W, H = 150, 300  # two bands of rows on one thread


def _states():
    return [
        full_state(W, H, zbuffer=True),  # colour to the back buffer
        full_state(W, H, zbuffer=True, draw_front=True, draw_back=False),
        full_state(W, H, zbuffer=True, zfunc=CMP_LESS, wmpack=0),  # z only
        full_state(W, H, zbuffer=True, zwritemask=0, wmpack=0, stencil=True,
                   szpass=OP_INCR, spass=OP_DECR),  # shadow-volume counts
        full_state(W, H, zbuffer=True, zfunc=CMP_EQUAL, zwritemask=0, stencil=True,
                   sfunc=CMP_NOTEQUAL, sref=0, blend_sf=BF_ONE, blend_df=BF_ONE),  # lit
        full_state(W, H, blend_sf=BF_ONE, blend_df=BF_ONE),  # no z test
    ]


def _tri(rng, c, size):
    p = c + rng.uniform(-size, size, (3, 2))
    z = float(rng.uniform(-5000, 5000))
    return tuple((float(x), float(y), z + float(rng.uniform(-900, 900)),
                  tuple(float(v) for v in rng.uniform(0, 1, 4))) for x, y in p)


def _scene(rng, n):
    states = _states()
    cmds = [("clear", {"color", "z", "stencil"}, {"color": 0x10203040, "z": 0x7FFFFF,
                                                  "stencil": 0}, full_state(W, H))]
    rs = states[0]
    for _ in range(n):
        u = rng.random()
        if u < 0.02:
            rs = states[int(rng.integers(len(states)))]
        if u < 0.001:
            cmds.append(("clear", {"z"}, {"z": 0x7FFFFF}, full_state(W, H)))
        elif u < 0.003:
            cmds.append(("line", ((float(rng.uniform(0, W)), float(rng.uniform(0, H)), 0.0,
                                   (1.0, 0.5, 0.2, 1.0)),
                                  (float(rng.uniform(0, W)), float(rng.uniform(0, H)), 0.0,
                                   (0.2, 0.5, 1.0, 1.0))), rs))
        # Clustered, so that triangles pile on the same pixels; some over the edges.
        c = rng.uniform([-4, -4], [W + 4, H + 4])
        size = 40.0 if u > 0.99 else float(rng.uniform(0.6, 3.5))
        cmds.append(("triangle", _tri(rng, c, size), rs))
    return cmds


def _render(cmds, nthreads, prefetch):
    return render_switched(cmds, W, H, nthreads=nthreads, prefetch_planes=prefetch)


@pytest.mark.parametrize("count", [900, GATHER_MIN + 1500])
@pytest.mark.parametrize("nthreads", [1, 2])
def test_prefetch_changes_no_plane(count, nthreads):
    cmds = _scene(np.random.default_rng(count + nthreads), count)
    want, want_work = _render(cmds, nthreads, False)
    got, got_work = _render(cmds, nthreads, True)
    assert_planes_equal(got, want, f"prefetch_planes, {nthreads} thread(s), {count}")
    assert got_work == want_work and got_work["fragments"] > 1000
    assert np.count_nonzero(want["stencil"]) > 100  # the counting pass drew
    if nthreads == 1:
        naive = render_naive(cmds, W, H, double=True, zbits=24, stencil=8)
        assert_planes_equal(got, naive, "naive reference")
