"""One-sided widening of the tiles' depth bounds (CommandBatch.sided_bounds,
kernels/tiles.py note_z_written) changes nothing drawn.

A z write under ZF_LESS / ZF_LEQUAL only lowers stored depths (ZF_GREATER /
ZF_GEQUAL only raises them), so the bound on the other side still holds.  Random
layered scenes (depth passes under every zfunction, volume faces, lit passes,
clears, lines; every rasterizer path, 1 and 2 threads) and the Heidmann frame are
rendered with the switch on and off and compared plane by plane; a hand-counted
quad shows the kept upper bound deciding a face behind it without a scan.
"""

import numpy as np
from kernel_helpers import (
    assert_planes_equal,
    full_state,
    heidmann_images,
    render_naive,
    render_switched,
)
from test_work_skipping import layered_scene

from vgxsim.state.raster import CMP_GEQUAL, CMP_GREATER, CMP_LEQUAL, CMP_LESS, OP_INCR


def _render(cmds, w, h, cfg, init, on, mode="span", nthreads=1):
    return render_switched(cmds, w, h, cfg=cfg, init=init, nthreads=nthreads, mode=mode,
                           sided_bounds=on)


def test_sided_bounds_change_no_plane_on_layered_scenes():
    rng = np.random.default_rng(3131)
    w, h = 200, 150
    fewer = 0
    for i in range(30):
        cfg, init, cmds = layered_scene(rng, w, h)
        # A second depth pass under another zfunction writes over the first's depths.
        zf = int(rng.choice([CMP_LESS, CMP_LEQUAL, CMP_GREATER, CMP_GEQUAL]))
        depth = full_state(w, h, zbuffer=True, zfunc=zf)
        cmds = cmds + [("triangle", c[1], depth) for c in cmds if c[0] == "triangle"][:4] \
            + [c for c in cmds if c[0] == "triangle"]
        n = 2 if i % 3 == 2 else 1
        modes = ("span", "general", "edge") if i % 5 == 0 else ("span",)
        for mode in modes:
            want, off = _render(cmds, w, h, cfg, init, False, mode, n)
            got, on = _render(cmds, w, h, cfg, init, True, mode, n)
            assert_planes_equal(got, want, f"scene {i} mode={mode} threads={n}")
            if mode == "span":
                fewer += (on["tiles_scanned"] < off["tiles_scanned"]
                          or on["fragments"] < off["fragments"])
        if i < 3:
            assert_planes_equal(got, render_naive(cmds, w, h, init=init, **cfg), "naive")
    assert fewer > 3  # the scenes reach the switch: fewer scans or fragments


def test_a_lequal_write_keeps_the_upper_bound():
    """128 x 64, z cleared to 1000 (every tile exactly [1000, 1000]).  A ZF_LEQUAL
    quad from z = 500 at the left to 3000 at the right writes where it is in front
    (its right tiles are skipped: behind the cleared depth);
    a volume quad at z = 2000 (ZF_LESS, ST_INCR) is then behind every stored depth.
    With the switch the tiles' upper bound stays 1000 and the volume quad is skipped
    without a scan; without it the bound was pushed to 3000 and the tiles are
    scanned again before the skip.  Same planes, same fragments."""
    w, h = 128, 64
    cfg = dict(double=False, zbits=24, stencil=8)
    clear = full_state(w, h)
    depth = full_state(w, h, zbuffer=True, zfunc=CMP_LEQUAL, wmpack=0)
    vol = full_state(w, h, zbuffer=True, zfunc=CMP_LESS, zwritemask=0, wmpack=0,
                     stencil=True, szpass=OP_INCR)
    white = (1.0, 1.0, 1.0, 1.0)

    def quad(zl, zr, rs):
        q = [(x - 0.5, y - 0.5, zl if x == 0 else zr, white)
             for x, y in ((0, 0), (w, 0), (w, h), (0, h))]
        return [("triangle", (q[0], q[1], q[2]), rs), ("triangle", (q[0], q[2], q[3]), rs)]

    cmds = ([("clear", {"z", "stencil"}, {"z": 1000, "stencil": 0}, clear)]
            + quad(500.0, 3000.0, depth) + quad(2000.0, 2000.0, vol))
    want, off = _render(cmds, w, h, cfg, None, False)
    got, on = _render(cmds, w, h, cfg, None, True)
    assert_planes_equal(got, want, "lequal quad")
    assert not got["stencil"].any()
    # The depth quad's left tiles only (its right half, z > 1750, is behind the
    # cleared depth and skipped either way); none of the volume quad.
    assert on["fragments"] == off["fragments"] == 64 * h
    assert on["tiles_skipped"] == off["tiles_skipped"] > 0
    # With the switch only the depth quad's second triangle scans, the two left tiles
    # its first triangle made loose; without it the volume quad scans too.
    assert on["tiles_scanned"] == 2 < off["tiles_scanned"]


def test_heidmann_frame_is_identical(monkeypatch):
    for n in (1, 2):
        images = heidmann_images(monkeypatch, "sided_bounds", n)
        np.testing.assert_array_equal(images[True], images[False])
