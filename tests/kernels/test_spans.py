"""Row spans carried from row to row (kernels/spans.py) and records copied into band
order (CommandBatch.band_records) change nothing drawn.

The stepped spans are checked against :func:`vgxsim.kernels.raster.row_span` (one
floor division per edge per row) on every row of triangles of every kind, far
from the origin included; whole scenes of small triangles and of long slivers are
rendered with each switch on and off and compared plane by plane, and against the
naive reference.
"""

import numba
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
from test_watertight import random_triangles, setup_edges

import vgxsim.batch as batch_module
from vgxsim.batch import CommandBatch
from vgxsim.kernels.raster import row_span
from vgxsim.kernels.spans import edge_next, edge_start, span_from
from vgxsim.state.raster import BF_ONE, CMP_EQUAL, CMP_LEQUAL, CMP_LESS, OP_DECR, OP_INCR


@numba.njit(cache=False)
def _stepped_and_solved(edge, y0, y1, xlo, xhi):
    """Rows y0..y1: (stepped xl, xr, solved xl, xr)."""
    out = np.empty((y1 - y0 + 1, 4), np.int64)
    s0, q0, r0, d0, bq0, br0 = edge_start(edge[0, 0], edge[0, 1], edge[0, 2], y0)
    s1, q1, r1, d1, bq1, br1 = edge_start(edge[1, 0], edge[1, 1], edge[1, 2], y0)
    s2, q2, r2, d2, bq2, br2 = edge_start(edge[2, 0], edge[2, 1], edge[2, 2], y0)
    for y in range(y0, y1 + 1):
        a, b = span_from(s0, q0, s1, q1, s2, q2, xlo, xhi)
        c, d = row_span(edge, y, xlo, xhi)
        out[y - y0, 0] = a
        out[y - y0, 1] = b
        out[y - y0, 2] = c
        out[y - y0, 3] = d
        q0, r0 = edge_next(q0, r0, d0, bq0, br0)
        q1, r1 = edge_next(q1, r1, d1, bq1, br1)
        q2, r2 = edge_next(q2, r2, d2, bq2, br2)
    return out


def test_stepped_spans_equal_solved_spans():
    rng = np.random.default_rng(4242)
    tri = random_triangles(rng, 3000)
    kept = setup_edges(tri)
    rows = nonempty = 0
    for i, (edge, box) in kept.items():
        x0, x1, y0, y1 = (int(v) for v in box)
        # Start a few rows above the box (empty rows step too) and stop at most
        # 3000 rows on; huge triangles far from the origin are stepped all the same.
        y0 -= int(rng.integers(0, 3))
        y1 = min(y1 + 2, y0 + 3000)
        got = _stepped_and_solved(edge, y0, y1, x0 - 1, x1 + 1)
        empty_s = got[:, 0] > got[:, 1]
        empty_r = got[:, 2] > got[:, 3]
        np.testing.assert_array_equal(empty_s, empty_r, err_msg=f"triangle {i}")
        np.testing.assert_array_equal(got[~empty_s, :2], got[~empty_s, 2:],
                                      err_msg=f"triangle {i}")
        rows += got.shape[0]
        nonempty += int((~empty_s).sum())
    assert rows > 100_000 and nonempty > 50_000


def test_stepped_spans_by_hand():
    """Triangle (0, 0), (8, 0), (0, 4) in pixels, counter-clockwise.  Pixel centres
    on the bottom edge (dy = 0, dx > 0) and the left edge (dy < 0) are inside, those
    on the hypotenuse x = 8 - 2y (dy > 0) are not (numeric_model.md's tie rule), so
    row y covers 0 <= x < 8 - 2y: widths 8, 6, 4, 2 and an empty apex row."""
    one = 256
    edge, _ = setup_edges(np.array([[[0, 0], [8 * one, 0], [0, 4 * one]]]))[0]
    got = _stepped_and_solved(edge, -1, 5, -3, 12)
    assert [tuple(r) for r in got[1:5, :2]] == [(0, 7), (0, 5), (0, 3), (0, 1)]
    assert got[0, 0] > got[0, 1] and got[5, 0] > got[5, 1] and got[6, 0] > got[6, 1]
    np.testing.assert_array_equal(got[:5, :2], got[:5, 2:])


def _small_scene(rng, w, h, n):
    """n small triangles (1..30 pixels) and slivers over a depth pass, a volume-like
    stencil pass and an EQUAL lit pass (the dense benchmark scene in miniature)."""
    depth = full_state(w, h, zbuffer=True, zfunc=CMP_LEQUAL)
    vol = full_state(w, h, zbuffer=True, zfunc=CMP_LESS, zwritemask=0, wmpack=0,
                     stencil=True, szpass=OP_INCR, cull=1)
    vol_b = full_state(w, h, zbuffer=True, zfunc=CMP_LESS, zwritemask=0, wmpack=0,
                       stencil=True, szpass=OP_DECR, cull=2)
    lit = full_state(w, h, zbuffer=True, zfunc=CMP_EQUAL, stencil=True, sfunc=CMP_EQUAL,
                     blend_sf=BF_ONE, blend_df=BF_ONE)

    def tri(small):
        c = rng.uniform([0, 0], [w, h])
        if small:
            p = c + rng.uniform(-4, 4, (3, 2))
        else:  # a sliver: long, one or two pixels wide
            d = rng.uniform(-h, h, 2)
            p = np.array([c, c + d, c + d * rng.uniform(0.2, 0.9) + rng.uniform(-2, 2, 2)])
        return tuple((float(x), float(y), float(rng.uniform(-5000, 5000)),
                      tuple(float(v) for v in rng.uniform(0, 1, 4))) for x, y in p)

    scene = [tri(rng.random() < 0.8) for _ in range(n)]
    vols = [tri(rng.random() < 0.3) for _ in range(n // 4)]
    cmds = [("clear", {"color", "z", "stencil"}, {"color": 0, "z": 0x7FFFFF, "stencil": 0},
             full_state(w, h))]
    cmds += [("triangle", t, depth) for t in scene]
    cmds += [("triangle", t, vol) for t in vols] + [("triangle", t, vol_b) for t in vols]
    cmds += [("triangle", t, lit) for t in scene]
    return cmds


def _render(cmds, w, h, mode="span", **switches):
    fb = kernel_framebuffer(w, h, double=False, zbits=24, stencil=8)
    batch = kernel_batch(fb, mode)
    for k, v in switches.items():
        setattr(batch, k, v)
    queue_commands(batch, cmds)
    batch.flush()
    return planes_of(fb)


@pytest.mark.parametrize("seed", range(3))
def test_switches_change_no_plane_on_small_triangles(monkeypatch, seed):
    monkeypatch.setattr(batch_module, "GATHER_MIN", 16)  # band order from 16 triangles
    rng = np.random.default_rng(310 + seed)
    w, h = 160, 300  # several bands on any thread count
    cmds = _small_scene(rng, w, h, 600)
    want = _render(cmds, w, h, step_spans=False, band_records=False)
    for step in (True, False):
        for gather in (True, False):
            got = _render(cmds, w, h, step_spans=step, band_records=gather)
            assert_planes_equal(got, want, f"step_spans={step} band_records={gather}")
    assert_planes_equal(_render(cmds, w, h, "edge"), want, "edge-function rasterizer")
    if seed == 0:
        assert_planes_equal(render_naive(cmds, w, h, double=False, zbits=24, stencil=8),
                            want, "naive reference")


def test_band_order_is_taken_and_counts_alike(monkeypatch):
    """The copy really happens (records in band order), and the work counters agree."""
    monkeypatch.setattr(batch_module, "GATHER_MIN", 16)
    rng = np.random.default_rng(77)
    w, h = 128, 400
    cmds = _small_scene(rng, w, h, 200)
    calls = []
    real = CommandBatch._band_order
    monkeypatch.setattr(CommandBatch, "_band_order",
                        lambda self, *a: calls.append(1) or real(self, *a))
    works = []
    for gather in (True, False):
        fb = kernel_framebuffer(w, h, double=False, zbits=24, stencil=8)
        batch = CommandBatch(fb)
        batch.band_records = gather
        batch.scatter_bins = False  # the gather copy (_band_order) is what this test spies on
        queue_commands(batch, cmds)
        batch.flush()
        works.append(batch.work())
    assert len(calls) == 1
    assert works[0] == works[1] and works[0]["fragments"] > 0
