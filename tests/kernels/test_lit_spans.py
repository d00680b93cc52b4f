"""The lit and ambient passes' out-of-line span loop (kernels/lit.py,
CommandBatch.lit_spans) changes nothing drawn.

:func:`add_sat_swar` is checked against ``add_sat`` on every pair of byte values
in every byte position and on random words; scenes of lit and ambient passes
(every zfunction, stencil test or not, stencil planes or none, z writes on and
off, replace and ONE+ONE, write masks, front or back buffer, spans from a few
pixels to the whole window, so both sides of ``LIT_MIN_SPAN``) are rendered with
the switch on and off (1 and 2 threads, block update on and off) and compared plane
by plane and counter by counter, and against the naive reference; so is the
Heidmann frame.
"""

import dataclasses

import numba
import numpy as np
import pytest
from kernel_helpers import (
    assert_planes_equal,
    full_state,
    heidmann_images,
    random_planes,
    render_naive,
    render_switched,
)

from vgxsim.kernels.fragment import add_sat
from vgxsim.kernels.lit import LIT_MIN_SPAN, add_sat_swar
from vgxsim.state.raster import (
    BF_MSA,
    BF_ONE,
    BF_SA,
    BF_ZERO,
    CMP_ALWAYS,
    CMP_EQUAL,
    CMP_GEQUAL,
    CMP_GREATER,
    CMP_LEQUAL,
    CMP_LESS,
    CMP_NEVER,
    CMP_NOTEQUAL,
    OP_INCR,
)

W, H = 160, 96


@numba.njit(cache=False)
def _adds(s, d):
    out = np.empty((s.shape[0], 2), np.int64)
    for i in range(s.shape[0]):
        out[i, 0] = add_sat(s[i], d[i])
        out[i, 1] = add_sat_swar(s[i], d[i])
    return out


def test_add_sat_swar_equals_add_sat():
    rng = np.random.default_rng(11)
    a, b = np.meshgrid(np.arange(256, dtype=np.int64), np.arange(256, dtype=np.int64))
    a, b = a.ravel(), b.ravel()
    for shift in (0, 8, 16, 24):  # every byte pair, random neighbours
        other = rng.integers(0, 1 << 32, (2, a.size), dtype=np.int64)
        keep = ~(0xFF << shift) & 0xFFFFFFFF
        s = (other[0] & keep) | (a << shift)
        d = (other[1] & keep) | (b << shift)
        got = _adds(s, d)
        assert (got[:, 1] == got[:, 0]).all(), shift
        want = np.minimum(a + b, 255)  # by hand: the byte saturates at 255
        assert ((got[:, 1] >> shift) & 0xFF == want).all()
    s, d = rng.integers(0, 1 << 32, (2, 1_000_000), dtype=np.int64)
    got = _adds(s, d)
    assert (got[:, 1] == got[:, 0]).all()


def _render(cmds, cfg, init, nthreads=1, **switches):
    return render_switched(cmds, W, H, cfg=cfg, init=init, nthreads=nthreads, **switches)


def assert_switch_changes_no_plane(scene, switch, seed, rounds, naive_rounds):
    """``rounds`` random scenes of ``scene(rng)`` (``(cfg, init, cmds)``) rendered with
    ``CommandBatch.<switch>`` off and on (1 or 2 threads, block update on or off in
    turn): identical planes and work counters, fragments tested; the first
    ``naive_rounds`` scenes against the naive reference too."""
    rng = np.random.default_rng(seed)
    for i in range(rounds):
        cfg, init, cmds = scene(rng)
        n = 2 if i % 3 == 2 else 1
        block = i % 2 == 0
        want, off = _render(cmds, cfg, init, n, **{switch: False}, block_update=block)
        got, on = _render(cmds, cfg, init, n, **{switch: True}, block_update=block)
        assert_planes_equal(got, want, f"{switch} scene {i} threads={n} block_update={block}")
        assert on == off and on["fragments"] > 0
        if i < naive_rounds:
            assert_planes_equal(got, render_naive(cmds, W, H, init=init, **cfg), "naive")


def _tri(rng, size, zlo, zhi):
    c = rng.uniform([0, 0], [W, H])
    return tuple((float(c[0] + rng.uniform(-size, size)), float(c[1] + rng.uniform(-size, size)),
                  float(rng.uniform(zlo, zhi)), tuple(float(v) for v in rng.uniform(-0.2, 1.2, 4)))
                 for _ in range(3))


def _scene(rng):
    cfg = dict(double=bool(rng.integers(2)), zbits=24, stencil=int(rng.choice([8, 8, 2, 0])))
    smax = (1 << cfg["stencil"]) - 1
    cmds = [("clear", {"color", "z"} | ({"stencil"} if cfg["stencil"] else set()),
             {"color": int(rng.integers(0, 1 << 32)), "z": int(rng.choice([0x7FFFFF, 0])),
              "stencil": int(rng.integers(0, smax + 1))}, full_state(W, H))]
    depth = full_state(W, H, zbuffer=True, zfunc=CMP_LEQUAL)
    for _ in range(3):
        cmds.append(("triangle", _tri(rng, 150, -3000, 3000), depth))
    if cfg["stencil"]:
        vol = full_state(W, H, zbuffer=True, zfunc=CMP_LESS, zwritemask=0, wmpack=0,
                         stencil=True, szpass=OP_INCR)
        for _ in range(3):
            cmds.append(("triangle", _tri(rng, 120, -5000, 5000), vol))
    for _ in range(int(rng.integers(6, 14))):
        sf, df = [(BF_ONE, BF_ONE), (BF_ONE, BF_ONE), (BF_ONE, BF_ZERO), (BF_SA, BF_MSA)][
            int(rng.integers(4))]
        rs = full_state(
            W, H, zbuffer=True,
            zfunc=int(rng.choice([CMP_EQUAL, CMP_EQUAL, CMP_LEQUAL, CMP_LESS, CMP_GREATER,
                                  CMP_GEQUAL, CMP_NOTEQUAL, CMP_ALWAYS, CMP_NEVER])),
            zwritemask=int(rng.choice([0, 0xFFFFFF])),
            stencil=bool(cfg["stencil"]) and bool(rng.integers(2)),
            sfunc=int(rng.choice([CMP_EQUAL, CMP_NOTEQUAL, CMP_LESS, CMP_ALWAYS])),
            sref=int(rng.integers(0, smax + 1)), smask=int(rng.choice([0xFF, 0x1])),
            blend_sf=sf, blend_df=df,
            wmpack=int(rng.choice([0xFFFFFFFF, 0xFFFFFFFF, 0x00FF00FF, 0xFF000000])),
            shademodel=int(rng.integers(2)))
        if cfg["double"]:
            front = bool(rng.integers(2))
            rs = dataclasses.replace(rs, draw_front=front, draw_back=not front)
        size = float(rng.choice([4.0, LIT_MIN_SPAN / 2, LIT_MIN_SPAN, 40.0, 200.0]))
        cmds.append(("triangle", _tri(rng, size, -3000, 3000), rs))
    init = random_planes(rng, W, H, **cfg) if rng.random() < 0.3 else None
    return cfg, init, cmds


def test_lit_spans_change_no_plane():
    assert_switch_changes_no_plane(_scene, "lit_spans", 8801, rounds=30, naive_rounds=4)


@pytest.mark.parametrize("nthreads", [1, 2])
def test_heidmann_frame_is_identical(monkeypatch, nthreads):
    images = heidmann_images(monkeypatch, "lit_spans", nthreads)
    np.testing.assert_array_equal(images[True], images[False])
    assert images[True].any()
