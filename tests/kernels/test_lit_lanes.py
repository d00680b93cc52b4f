"""The lit and ambient span loop on 32-bit lanes (kernels/lit.py lit_span_lanes,
CommandBatch.lit_lanes) changes nothing drawn.

The lanes loop computes each value by the same float64 operations as
``lit_span`` but drops the NaN and range tests (the caller checks the planes'
bounds, :func:`lanes_ok`), clamps colour before the truncating conversion
instead of taking the floor, and compares and selects on 32-bit words.  It is
checked row by row against ``lit_span`` (every zfunction and stencil function,
stencil references and masks beyond a byte, z writes, replace and ONE+ONE, write
masks, planes whose values sit on the rounding boundaries, within and beyond
the bounds), :func:`channel_clamp` against ``channel_i32`` on the boundary
values, and whole scenes of lit and ambient passes with the switch on and off (1
and 2 threads, block update on and off), against the naive reference and on the
Heidmann frame.
"""

import numba
import numpy as np
import pytest
from kernel_helpers import heidmann_images
from test_lit_spans import _scene, assert_switch_changes_no_plane

from vgxsim.kernels.fragment import channel_i32, cmp_bits
from vgxsim.kernels.lit import (
    LANES_A,
    LANES_D,
    alpha_span_lanes,
    channel_clamp,
    lanes_ok,
    lit_span,
    lit_span_lanes,
)
from vgxsim.kernels.render import _alpha_span
from vgxsim.state.codes import Z24_MASK

W, H = 160, 96


@numba.njit(cache=False)
def _channels(c):
    out = np.empty((c.shape[0], 2), np.int64)
    for i in range(c.shape[0]):
        out[i, 0] = channel_i32(c[i])
        out[i, 1] = channel_clamp(c[i])
    return out


def test_channel_clamp_equals_channel_i32():
    rng = np.random.default_rng(5)
    ints = np.arange(-300, 600, dtype=np.float64)
    special = np.concatenate([
        ints, ints - 0.5, ints + 0.5, np.nextafter(ints - 0.5, -np.inf),
        np.nextafter(ints - 0.5, np.inf), [254.5, 255.5, 256.0, -0.5, -1.5, 2.0**31, -2.0**31,
                                           2.0**62, -2.0**62, LANES_A * 1.5, -LANES_A * 1.5],
        rng.uniform(-1000, 1000, 200_000), rng.uniform(-1e18, 1e18, 10_000)])
    got = _channels(special)
    assert (got[:, 0] == got[:, 1]).all()


@numba.njit(cache=False)
def _rows(p, fz, zw, st, ad, wms, zbuf0, sten0, cbuf0, lanes):
    n, w = zbuf0.shape
    cbuf = cbuf0.copy()
    zbuf = zbuf0.copy()
    sten = sten0.copy()
    taken = 0
    for r in range(n):
        uy = np.uintp(r)
        xl = int(p[r, 11])
        xr = int(p[r, 12])
        lt, eq, gt = cmp_bits(fz[r, 0])
        slt, seq, sgt = cmp_bits(fz[r, 1])
        smask = fz[r, 2]
        sref = fz[r, 3] & smask
        wm = wms[r]
        zmin, zmax = fz[r, 4], fz[r, 5]
        args_ok = lanes_ok(xl, xr, p[r, 10], p[r, 0], p[r, 1], zmin, zmax, p[r, 2], p[r, 3],
                           p[r, 4], p[r, 5], p[r, 6], p[r, 7], p[r, 8], p[r, 9])
        if ad[r] == 2 and lanes and args_ok:
            taken += 1
            alpha_span_lanes(uy, xl, xr, p[r, 0], p[r, 1], p[r, 10], zmin, zmax, p[r, 2],
                             p[r, 3], p[r, 4], p[r, 5], p[r, 6], p[r, 7], p[r, 8], p[r, 9], lt,
                             eq, gt, zw[r], st[r], slt, seq, sgt, smask, sref, wm, Z24_MASK,
                             cbuf, zbuf, sten)
        elif ad[r] == 2:
            _alpha_span(uy, xl, xr, p[r, 0], p[r, 1], p[r, 10], zmin, zmax, p[r, 2], p[r, 3],
                        p[r, 4], p[r, 5], p[r, 6], p[r, 7], p[r, 8], p[r, 9], lt, eq, gt, zw[r],
                        st[r], slt, seq, sgt, smask, sref, wm, ~wm & 0xFFFFFFFF, cbuf, zbuf,
                        sten)
        elif lanes and args_ok:
            taken += 1
            lit_span_lanes(uy, xl, xr, p[r, 0], p[r, 1], p[r, 10], zmin, zmax, p[r, 2],
                           p[r, 3], p[r, 4], p[r, 5], p[r, 6], p[r, 7], p[r, 8], p[r, 9], lt, eq,
                           gt, zw[r], st[r], slt, seq, sgt, smask, sref, ad[r] == 1, wm,
                           Z24_MASK, cbuf, zbuf, sten)
        else:
            lit_span(uy, xl, xr, p[r, 0], p[r, 1], p[r, 10], zmin, zmax, p[r, 2], p[r, 3],
                     p[r, 4], p[r, 5], p[r, 6], p[r, 7], p[r, 8], p[r, 9], lt, eq, gt, zw[r],
                     st[r], slt, seq, sgt, smask, sref, ad[r] == 1, wm, ~wm & 0xFFFFFFFF, cbuf,
                     zbuf, sten)
    return cbuf, zbuf, sten, taken


def _row_cases(rng, n, w):
    p = np.empty((n, 13))
    # Depth: values around the stored ones (so EQUAL passes often), on the
    # rounding boundaries (x0 and gradients in multiples of 1/2 and 1/256).
    p[:, 0] = rng.integers(-40, 40, n) + rng.choice([0.0, 0.5, -0.5, 0.25, 1e-9], n)
    p[:, 1] = rng.choice([0.0, 0.5, -0.25, 1.0 / 256], n) * rng.integers(-2, 3, n)
    for c in range(4):
        p[:, 2 + c] = rng.choice([rng.uniform(-60, 320), 127.5, 254.5, 255.5, -0.5, 0.0], n)
        p[:, 6 + c] = rng.choice([0.0, 0.5, -0.5, 1.0, rng.uniform(-5, 5), 3.0 / 256], n)
    p[:, 10] = rng.integers(-4 * 256, (w + 4) * 256, n) / 256.0  # x0, 8 fraction bits
    xl = rng.integers(0, w, n)
    p[:, 11] = xl
    p[:, 12] = np.minimum(w - 1, xl + rng.integers(0, w, n))
    # Some rows beyond the lanes' bounds or not finite: they take lit_span.
    bad = rng.random(n) < 0.1
    p[bad, rng.integers(0, 10, bad.sum())] = rng.choice(
        [np.nan, np.inf, -np.inf, LANES_A * 2, LANES_D * 2, 1e300], bad.sum())
    fz = np.empty((n, 6), np.int64)
    # Every code, and EQUAL for both often (the lit pass's own loop).
    fz[:, 0] = np.where(rng.random(n) < 0.4, 2, rng.integers(0, 8, n))
    fz[:, 1] = np.where(rng.random(n) < 0.4, 2, rng.integers(0, 8, n))
    fz[:, 2] = rng.choice([0xFF, 0x1, 0x0F, 0xFFFF, 0x100, -1], n)
    fz[:, 3] = rng.choice([0, 1, 7, 255, 256, 1000, rng.integers(0, 256)], n)
    zlim = rng.choice([0, 1, 2], n)
    fz[:, 4] = np.where(zlim == 0, -0x800000, np.where(zlim == 1, -30, -2**31))
    fz[:, 5] = np.where(zlim == 0, 0x7FFFFF, np.where(zlim == 1, 30, 2**31 - 1))
    zw = rng.random(n) < 0.5
    st = rng.random(n) < 0.7
    ad = rng.choice([0, 1, 1, 2], n)  # replace, ONE+ONE, SA+MSA
    wms = rng.choice([0xFFFFFFFF, 0x00FF00FF, 0xFF000000, 0x0F0FF0F0, 0], n).astype(np.int64)
    return p, fz, zw, st, ad, wms


def test_lanes_rows_equal_lit_span():
    rng = np.random.default_rng(77)
    n, w = 400, 96
    p, fz, zw, st, ad, wms = _row_cases(rng, n, w)
    zbuf = rng.integers(-40, 40, (n, w)).astype(np.int32)
    sten = rng.integers(0, 256, (n, w)).astype(np.uint8)
    sten[:, ::3] = rng.integers(0, 4, (n, (w + 2) // 3))  # small values: EQUAL passes
    cbuf = rng.integers(0, 1 << 32, (n, w), dtype=np.uint64).astype(np.uint32)
    want = _rows(p, fz, zw, st, ad, wms, zbuf, sten, cbuf, False)
    got = _rows(p, fz, zw, st, ad, wms, zbuf, sten, cbuf, True)
    assert got[3] > n // 2  # most rows take the lanes loop
    for a, b, name in zip(got[:3], want[:3], ("colour", "z", "stencil"), strict=True):
        np.testing.assert_array_equal(a, b, err_msg=name)
    assert (got[0] != cbuf).any() and (got[1] != zbuf).any()


def test_alpha_rows_reach_every_mix():
    # SA+MSA rows over every (source, destination, alpha) byte triple's corner
    # cases: flat planes with alpha 0, 255 and between, destinations 0 and 255.
    rng = np.random.default_rng(78)
    n, w = 64, 96
    p, fz, zw, st, ad, wms = _row_cases(rng, n, w)
    p[:, 0:10] = 0.0
    p[:, 2:6] = rng.choice([0.0, 255.0, 127.6, 1.0, 254.4], (n, 4))
    p[:, 6:10] = rng.choice([0.0, 2.7, -2.7], (n, 4))
    fz[:, 0] = 7
    ad[:] = 2
    zbuf = np.zeros((n, w), np.int32)
    sten = np.zeros((n, w), np.uint8)
    cbuf = rng.choice(np.array([0, 0xFFFFFFFF, 0x80808080, 0x01FE7F00], np.uint32), (n, w))
    want = _rows(p, fz, zw, st, ad, wms, zbuf, sten, cbuf, False)
    got = _rows(p, fz, zw, st, ad, wms, zbuf, sten, cbuf, True)
    assert got[3] == n
    np.testing.assert_array_equal(got[0], want[0])


def test_lit_lanes_change_no_plane():
    assert_switch_changes_no_plane(_scene, "lit_lanes", 9902, rounds=24, naive_rounds=4)


@pytest.mark.parametrize("nthreads", [1, 2])
def test_heidmann_frame_is_identical(monkeypatch, nthreads):
    images = heidmann_images(monkeypatch, "lit_lanes", nthreads)
    np.testing.assert_array_equal(images[True], images[False])
    assert images[True].any()
