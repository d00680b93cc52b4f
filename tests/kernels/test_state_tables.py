"""CommandBatch.cache_tables: a flush's state table and its derived rows kept per
list of state snapshots and reused by later flushes of the same list.  Planes and
work counters must be those of tables made afresh at every flush, and those of the
naive oracle; a list in another order or with other snapshots must not reuse them."""

import numpy as np
import pytest
from kernel_helpers import (
    assert_planes_equal,
    full_state,
    kernel_batch,
    kernel_framebuffer,
    planes_of,
    queue_commands,
    random_planes,
    render_naive,
)
from test_threads import heavy_scene

from vgxsim.batch import CommandBatch
from vgxsim.state.raster import BF_ONE, CMP_EQUAL, OP_INCR


def _frames(rng, w, h):
    """Three 'frames' of the same snapshots, each flushed several times, plus one
    frame of the same snapshots first used in another order."""
    cmds = heavy_scene(rng, w, h, 250)
    return cmds + [("flush",)] + cmds + [("flush",)] + cmds[::-1]


@pytest.mark.parametrize("double", [True, False])
def test_cache_tables_on_off_identical_and_naive(monkeypatch, double):
    w, h = 80, 120
    rng = np.random.default_rng(11)
    cmds = _frames(rng, w, h)
    cfg = dict(double=double, zbits=24, stencil=8)
    init = random_planes(rng, w, h, **cfg)
    got = {}
    for on in (False, True):
        monkeypatch.setattr(CommandBatch, "cache_tables", on)
        fb = kernel_framebuffer(w, h, init=init, **cfg)
        batch = kernel_batch(fb)
        queue_commands(batch, cmds)
        batch.flush()
        got[on] = (planes_of(fb), batch.counters.copy(), batch.flushes,
                   len(batch._tables_memo))
    assert_planes_equal(got[True][0], got[False][0], "cache_tables on vs off")
    np.testing.assert_array_equal(got[True][1], got[False][1])
    assert got[True][2] == got[False][2] > 6
    assert got[False][3] == 0
    # Fewer distinct tables than flushes: later flushes did reuse them.
    assert 0 < got[True][3] < got[True][2]
    assert_planes_equal(got[True][0], render_naive(cmds, w, h, init=init, **cfg), "naive")


def test_cache_tables_keyed_on_the_snapshots_and_their_order(monkeypatch):
    monkeypatch.setattr(CommandBatch, "cache_tables", True)
    w, h = 32, 32
    fb = kernel_framebuffer(w, h, double=True, zbits=24, stencil=8)
    batch = kernel_batch(fb)
    a = full_state(w, h, zbuffer=True, stencil=True, szpass=OP_INCR)
    b = full_state(w, h, zbuffer=True, stencil=True, sfunc=CMP_EQUAL, blend_sf=BF_ONE,
                   blend_df=BF_ONE)
    tri = ("triangle", ((0.0, 0.0, 0.0, (1, 0, 0, 1)), (30.0, 0.0, 0.0, (1, 0, 0, 1)),
                        (0.0, 30.0, 0.0, (1, 0, 0, 1))))
    tables = []
    for order in ((a, b), (a, b), (b, a), (a,)):
        queue_commands(batch, [(*tri, rs) for rs in order])
        tables.append(batch._state_tables()[2])
        batch.flush()
    assert tables[1] is tables[0]  # the same snapshots in the same order: reused
    assert tables[2] is not tables[0]  # another order: other table indices
    np.testing.assert_array_equal(tables[2][::-1], tables[0])
    assert tables[3].shape[0] == 1
