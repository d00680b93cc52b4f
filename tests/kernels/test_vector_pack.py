"""Colour and z converted through int32 in the lit-pass and z+stencil span loops
(CommandBatch.vector_pack) change nothing drawn.

:func:`vgxsim.kernels.fragment.channel_i32` is checked against ``round_c`` (the
numeric model's ``floor(c + 0.5)`` clamped to 0..255) on the awkward inputs (ties,
NaN, infinities, beyond int32 and int64) and on random values; random scenes with
INCR/DECR volume passes and an EQUAL/stencil-tested ONE+ONE lit pass (every plane
compared) and the Heidmann frame are rendered with
the switch on and off and compared plane by plane, and against the naive reference.
"""

import numba
import numpy as np
import pytest
from kernel_helpers import assert_planes_equal, render_naive
from test_spans import _render, _small_scene

from vgxsim.batch import CommandBatch
from vgxsim.kernels.fragment import (
    channel_i32,
    pack_rgba,
    pack_rgba_i32,
    round_c,
    round_z,
    round_z_i32,
)


@numba.njit(cache=False)
def _both(c):
    out = np.empty((c.shape[0], 2), np.int64)
    for i in range(c.shape[0]):
        out[i, 0] = round_c(c[i])
        out[i, 1] = channel_i32(c[i])
    return out


@numba.njit(cache=False)
def _packs(c):
    out = np.empty((c.shape[0], 2), np.int64)
    for i in range(c.shape[0]):
        out[i, 0] = pack_rgba(c[i, 0], c[i, 1], c[i, 2], c[i, 3])
        out[i, 1] = pack_rgba_i32(c[i, 0], c[i, 1], c[i, 2], c[i, 3])
    return out


def test_channel_i32_equals_round_c():
    edges = np.array([np.nan, np.inf, -np.inf, -0.5, -0.49999999999999994, 0.0, 0.49, 0.5,
                      254.5, 254.49999999999997, 255.0, 255.5, 1e9, 2.0**31, 2.0**31 + 1,
                      -2.0**31, -2.0**31 - 1, 9.2e18, 2.0**63 - 1024, 2.0**63, 1e300,
                      -1e300])
    got = _both(edges)
    # By hand: NaN, +-inf, 2**63 and up convert to INT64_MIN in round_c (x86), so 0.
    want = [0, 0, 0, 0, 0, 0, 0, 1, 255, 254, 255, 255, 255, 255, 255,
            0, 0, 255, 255, 0, 0, 0]
    assert list(got[:, 0]) == want
    assert list(got[:, 1]) == want
    rng = np.random.default_rng(5)
    c = np.concatenate([rng.uniform(-400, 700, 200_000),
                        np.floor(rng.uniform(-10, 270, 20_000)) + 0.5])
    got = _both(c)
    np.testing.assert_array_equal(got[:, 0], got[:, 1])
    p = _packs(rng.uniform(-100, 400, (50_000, 4)))
    np.testing.assert_array_equal(p[:, 0], p[:, 1])


@numba.njit(cache=False)
def _z_both(z, zmin, zmax):
    out = np.empty((z.shape[0], 2), np.int64)
    for i in range(z.shape[0]):
        out[i, 0] = round_z(z[i], zmin, zmax)
        out[i, 1] = round_z_i32(z[i], zmin, zmax)
    return out


def test_round_z_i32_equals_round_z():
    z = np.array([np.nan, np.inf, -np.inf, -100.5, -100.49, 99.5, 99.49999999999999,
                  1e10, -1e10, 2.0**63, -2.0**63, 1e300])
    got = _z_both(z, -100, 100)
    # By hand: NaN, +-inf, +-2**63 and 1e300 take INT64_MIN in round_z, so zmin.
    want = [-100, -100, -100, -100, -100, 100, 99, 100, -100, -100, -100, -100]
    assert list(got[:, 0]) == want
    assert list(got[:, 1]) == want
    rng = np.random.default_rng(6)
    z = rng.uniform(-2.0**24, 2.0**24, 200_000)
    for lo, hi in ((-0x800000, 0x7FFFFF), (-5000, 70_000), (-2**31, 2**31 - 1)):
        got = _z_both(z, lo, hi)
        np.testing.assert_array_equal(got[:, 0], got[:, 1])


@pytest.mark.parametrize("seed", range(2))
def test_vector_pack_changes_no_plane(seed):
    rng = np.random.default_rng(4410 + seed)
    w, h = 160, 200
    cmds = _small_scene(rng, w, h, 400)
    want = _render(cmds, w, h, vector_pack=False)
    assert_planes_equal(_render(cmds, w, h, vector_pack=True), want, "vector_pack")
    if seed == 0:
        assert_planes_equal(render_naive(cmds, w, h, double=False, zbits=24, stencil=8),
                            want, "naive reference")


def test_heidmann_frame_is_identical_with_vector_pack(monkeypatch):
    from vgxsim.examples import heidmann1991 as h91
    from vgxsim.gl._core import session

    imgs = []
    for on in (False, True):
        monkeypatch.setattr(CommandBatch, "vector_pack", on)
        session.reset()
        try:
            imgs.append(h91.render(320, 256))
        finally:
            session.reset()
    assert imgs[0].any()
    np.testing.assert_array_equal(imgs[1], imgs[0])
