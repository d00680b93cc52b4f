"""The z+stencil and depth passes' out-of-line span loops (kernels/fill.py,
CommandBatch.fill_spans) change nothing drawn.

Scenes of depth-only passes (z test and z write, colour masked) and z+stencil
passes with arithmetic stencil ops (ST_INCR / ST_DECR / ST_KEEP on z pass and z
fail, as z-pass and z-fail shadow volumes use them; 8 and 2 stencil planes, so
the clamps at 255 and 3) under every zfunction, with spans from a few pixels to
the whole window (both sides of ``FILL_MIN_SPAN``), steep planes beyond the
bounds of the loops' unchecked depth form, and random initial planes, are
rendered with the switch on and off (1 and 2 threads, block update on and off)
and compared plane by plane and counter by counter, and against the naive
reference; so is the Heidmann frame.
"""

import dataclasses

import numpy as np
import pytest
from kernel_helpers import full_state, heidmann_images, random_planes
from test_lit_spans import _tri, assert_switch_changes_no_plane

from vgxsim.kernels.fill import FILL_MIN_SPAN
from vgxsim.state.raster import (
    CMP_ALWAYS,
    CMP_EQUAL,
    CMP_GEQUAL,
    CMP_GREATER,
    CMP_LEQUAL,
    CMP_LESS,
    CMP_NEVER,
    CMP_NOTEQUAL,
    OP_DECR,
    OP_INCR,
    OP_KEEP,
)

W, H = 160, 96
ZFUNCS = [CMP_LESS, CMP_LEQUAL, CMP_EQUAL, CMP_GREATER, CMP_GEQUAL, CMP_NOTEQUAL, CMP_ALWAYS,
          CMP_NEVER]


def _steep(rng):
    """A quad over 16 pixel centres of each row (x .. x + 15) whose depth crosses
    +-2.1e9 over 15.5 pixels: a depth gradient above 2**28 per pixel, so the loops'
    checked depth form (kernels/fill.py z_bounded false), with the depth range inside
    int32 and spans of FILL_MIN_SPAN pixels (so the span loops of kernels/fill.py
    still take it); drawn with subpixel(TRUE), which keeps its quarter pixels."""
    x = float(rng.integers(0, W - 20))
    y = float(rng.integers(0, H - 40))
    lo, hi = -2.1e9, 2.1e9
    col = (0.5, 0.5, 0.5, 1.0)
    x0, x1 = x - 0.25, x + 15.25
    a, b, c, d = (x0, y, lo, col), (x1, y, hi, col), (x1, y + 30, hi, col), (
        x0, y + 30, lo, col)
    return [(a, b, c), (a, c, d)]


def _scene(rng):
    cfg = dict(double=False, zbits=24, stencil=int(rng.choice([8, 8, 2])))
    cmds = [("clear", {"color", "z", "stencil"},
             {"color": 0, "z": int(rng.choice([0x7FFFFF, 0, -0x800000])),
              "stencil": int(rng.integers(0, (1 << cfg["stencil"])))}, full_state(W, H))]
    for _ in range(int(rng.integers(8, 16))):
        zfunc = int(rng.choice(ZFUNCS))
        if rng.random() < 0.4:
            rs = full_state(W, H, zbuffer=True, zfunc=zfunc, wmpack=0)  # depth only
        else:
            rs = full_state(W, H, zbuffer=True, zfunc=zfunc, zwritemask=0, wmpack=0,
                            stencil=True, sfunc=CMP_ALWAYS,
                            szpass=int(rng.choice([OP_INCR, OP_DECR, OP_KEEP])),
                            spass=int(rng.choice([OP_INCR, OP_DECR, OP_KEEP])))
        if rng.random() < 0.15:
            steep = dataclasses.replace(rs, subpixel=True)  # keep the quarter pixels
            for tri in _steep(rng):
                cmds.append(("triangle", tri, steep))
        else:
            size = float(rng.choice([4.0, FILL_MIN_SPAN / 2, FILL_MIN_SPAN, 40.0, 200.0]))
            cmds.append(("triangle", _tri(rng, size, -8e6, 8e6), rs))
    init = random_planes(rng, W, H, **cfg) if rng.random() < 0.4 else None
    return cfg, init, cmds


def test_fill_spans_change_no_plane():
    assert_switch_changes_no_plane(_scene, "fill_spans", 4242, rounds=30, naive_rounds=6)


@pytest.mark.parametrize("nthreads", [1, 2])
def test_heidmann_frame_is_identical(monkeypatch, nthreads):
    images = heidmann_images(monkeypatch, "fill_spans", nthreads)
    np.testing.assert_array_equal(images[True], images[False])
    assert images[True].any()
