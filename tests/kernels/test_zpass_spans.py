"""Z-passed spans in partly covered tiles (kernels/tiles.py TILE_ZPASS_SPAN,
CommandBatch.zpass_spans) change nothing drawn and count the same work.

A tile that a triangle covers only in part, but whose depth bounds prove that the
triangle's depths there pass the z test against every stored depth, runs the
triangle's row spans in it through the block update's loop (no z compare).  The
scenes of tests/kernels/test_block_update.py (big triangles over a few tiles, z
clears and flat layers, volume faces in front of, behind and across the stored
depths under every z-pass op, depth and lit passes) and full-window quads whose
diagonals cross many tiles are rendered with the switch on and off (1 and 2 threads,
spans stepped or not, tight tiles or not, int32 packing or not, the out-of-line
fill spans or not): identical planes and work counters, and equal to the naive
reference.
"""

import numpy as np
from kernel_helpers import assert_planes_equal, full_state, random_planes, render_naive
from test_block_update import _render, _scene

from vgxsim.state.raster import CMP_EQUAL, CMP_LEQUAL, CMP_LESS, OP_DECR, OP_INCR

W, H = 200, 100  # test_block_update's window


def test_zpass_spans_change_no_plane_on_random_scenes():
    rng = np.random.default_rng(7311)
    variants = [dict(), dict(step_spans=False), dict(tight_tiles=False),
                dict(vector_pack=False), dict(nthreads=2), dict(fill_spans=False)]
    for i in range(36):
        cfg, init, cmds = _scene(rng)
        v = dict(variants[i % len(variants)])
        n = v.pop("nthreads", 1)
        want, off = _render(cmds, cfg, init, n, zpass_spans=False, **v)
        got, on = _render(cmds, cfg, init, n, zpass_spans=True, **v)
        assert_planes_equal(got, want, f"scene {i} {v} threads={n}")
        assert on == off, (i, on, off)
        if i < 5:
            assert_planes_equal(got, render_naive(cmds, W, H, init=init, **cfg), "naive")


def _slanted_quad(z0, z1, colour):
    """Two triangles over the whole window, depth from z0 (left) to z1 (right): the
    shared diagonal crosses a partly covered tile in every tile row of each."""
    q = [(-0.5, -0.5, z0, colour), (W - 0.5, -0.5, z1, colour), (W - 0.5, H - 0.5, z1, colour),
         (-0.5, H - 0.5, z0, colour)]
    return [(q[0], q[1], q[2]), (q[0], q[2], q[3])]


def test_diagonals_of_volume_and_lit_passes():
    """Heidmann's passes as full-window quads over a stored depth: volume faces in
    front of it (INCR) and across it (DECR), an ambient pass at LEQUAL writing z,
    the lit pass at EQUAL with ONE+ONE."""
    cfg = dict(double=False, zbits=24, stencil=8)
    init = random_planes(np.random.default_rng(3), W, H, **cfg)
    init["z"][:] = 4000
    init["stencil"][:] = np.random.default_rng(4).integers(0, 3, (H, W)).astype(np.uint8)
    vol_in = full_state(W, H, zbuffer=True, zfunc=CMP_LESS, zwritemask=0, wmpack=0,
                        stencil=True, szpass=OP_INCR)
    vol_dec = full_state(W, H, zbuffer=True, zfunc=CMP_LESS, zwritemask=0, wmpack=0,
                         stencil=True, szpass=OP_DECR)
    amb = full_state(W, H, zbuffer=True, zfunc=CMP_LEQUAL)
    lit = full_state(W, H, zbuffer=True, zfunc=CMP_EQUAL, zwritemask=0, stencil=True,
                     sfunc=CMP_EQUAL, sref=1, blend_sf=1, blend_df=1)
    cmds = []
    for t in _slanted_quad(-3000.0, 2000.0, (0.3, 0.2, 0.1, 1.0)):
        cmds.append(("triangle", t, vol_in))
    for t in _slanted_quad(-1000.0, 9000.0, (0.3, 0.2, 0.1, 1.0)):
        cmds.append(("triangle", t, vol_dec))
    for t in _slanted_quad(-500.0, 3000.0, (0.9, 0.4, 0.2, 0.5)):
        cmds.append(("triangle", t, amb))
    for t in _slanted_quad(-500.0, 3000.0, (0.1, 0.6, 0.3, 0.2)):
        cmds.append(("triangle", t, lit))
    for n in (1, 2):
        want, off = _render(cmds, cfg, init, n, zpass_spans=False)
        got, on = _render(cmds, cfg, init, n, zpass_spans=True)
        assert_planes_equal(got, want, f"threads={n}")
        assert on == off
        assert on["blocks_z_passed"] > 0
    assert_planes_equal(got, render_naive(cmds, W, H, init=init, **cfg), "naive")
    assert (got["stencil"] != init["stencil"]).any() and (got["front"] != init["front"]).any()
