"""Depth-writing colour passes without the block update (CommandBatch.span_zwrite,
kernels/render.py _triangle_rows) change nothing drawn.

The switch only stops such passes from asking for z-passed tiles, so every other
tile decision stays as it was: random scenes of lit and ambient passes (z writes on
and off, every zfunction, stencil tests, replace and ONE+ONE; 1 and 2 threads) are
rendered with it on and off and compared plane by plane, against the naive
reference, and counter by counter (all but ``blocks_z_passed``, which may only
drop); a two-pass quad shows the switch takes the z-passed tiles from the
depth-writing pass only; so is the Heidmann frame.
"""

import numpy as np
import pytest
from kernel_helpers import assert_planes_equal, full_state, heidmann_images, render_naive
from test_lit_spans import H, W, _render, _scene

from vgxsim.state.raster import BF_ONE, BF_ZERO, CMP_EQUAL, CMP_LEQUAL

_SAME = ("fragments", "tiles_skipped", "blocks_covered", "stencil_writes", "tiles_scanned")


def test_span_zwrite_changes_no_plane_on_random_scenes():
    rng = np.random.default_rng(5150)
    dropped = 0
    for i in range(24):
        cfg, init, cmds = _scene(rng)
        n = 2 if i % 3 == 2 else 1
        want, off = _render(cmds, cfg, init, n, span_zwrite=False)
        got, on = _render(cmds, cfg, init, n, span_zwrite=True)
        assert_planes_equal(got, want, f"span_zwrite scene {i} threads={n}")
        assert {k: on[k] for k in _SAME} == {k: off[k] for k in _SAME}
        assert on["fragments"] > 0 and on["blocks_z_passed"] <= off["blocks_z_passed"]
        dropped += off["blocks_z_passed"] - on["blocks_z_passed"]
        if i < 4:
            assert_planes_equal(got, render_naive(cmds, W, H, init=init, **cfg), "naive")
    assert dropped > 0  # the scenes do reach the switch


def _quad(z, rgba):
    a, b, c, d = ((-1.0, -1.0), (W + 1.0, -1.0), (W + 1.0, H + 1.0), (-1.0, H + 1.0))
    return [tuple((p[0], p[1], z, rgba) for p in tri) for tri in ((a, b, c), (a, c, d))]


def test_only_the_depth_writing_pass_loses_its_z_passed_tiles():
    # Heidmann's ambient pass (replace, z writes, over a cleared z buffer) then a lit
    # pass over it (zfunction(ZF_EQUAL), no z writes, ONE+ONE): every tile of both is
    # fully covered and proven to pass; with the switch only the lit pass's count.
    cfg = dict(double=False, zbits=24, stencil=0)
    ambient = full_state(W, H, zbuffer=True, zfunc=CMP_LEQUAL, blend_sf=BF_ONE,
                         blend_df=BF_ZERO)
    lit = full_state(W, H, zbuffer=True, zfunc=CMP_EQUAL, zwritemask=0, blend_sf=BF_ONE,
                     blend_df=BF_ONE)
    cmds = [("clear", {"color", "z"}, {"color": 0, "z": 0x7FFFFF, "stencil": 0},
             full_state(W, H))]
    cmds += [("triangle", t, ambient) for t in _quad(100.0, (0.2, 0.3, 0.4, 1.0))]
    cmds += [("triangle", t, lit) for t in _quad(100.0, (0.1, 0.1, 0.1, 1.0))]
    want, off = _render(cmds, cfg, None, span_zwrite=False)
    got, on = _render(cmds, cfg, None, span_zwrite=True)
    assert_planes_equal(got, want, "two-pass quad")
    assert_planes_equal(got, render_naive(cmds, W, H, **cfg), "naive")
    assert on["blocks_z_passed"] > 0  # the lit pass keeps its block update
    # The ambient pass's tiles are as many as the lit pass's: half of them are gone.
    assert off["blocks_z_passed"] == 2 * on["blocks_z_passed"]


@pytest.mark.parametrize("nthreads", [1, 2])
def test_heidmann_frame_is_identical(monkeypatch, nthreads):
    images = heidmann_images(monkeypatch, "span_zwrite", nthreads)
    np.testing.assert_array_equal(images[True], images[False])
    assert images[True].any()
