"""kernels.accum.accumulate against naive.accum for every acbuf operation
(docs/numeric_model.md section 9), on random buffers, values and rectangles."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from vgxsim.kernels.accum import accumulate
from vgxsim.reference.naive import (
    AC_ACCUMULATE,
    AC_ADD,
    AC_CLEAR,
    AC_CLEAR_ACCUMULATE,
    AC_MULT,
    AC_RETURN,
    NaiveFramebuffer,
    accum,
)

W, H = 13, 9
OPS = [AC_CLEAR, AC_ACCUMULATE, AC_CLEAR_ACCUMULATE, AC_RETURN, AC_MULT, AC_ADD]

values = st.one_of(
    st.sampled_from([0.0, 1.0, -1.0, 0.5, -0.5, 1 / 32, 2.0, 255.0, 1 / 255, 0.25, 1.5]),
    st.floats(-4, 4), st.floats(-40000, 40000), st.integers(-300, 300).map(lambda v: v / 2),
)


def _buffers(seed, extreme):
    rng = np.random.default_rng(seed)
    colour = rng.integers(0, 1 << 32, (H, W), dtype=np.uint64).astype(np.uint32)
    if extreme:
        acc = rng.choice(np.array([-32768, -32767, -1, 0, 1, 255, 32766, 32767]), (H, W, 4))
    else:
        acc = rng.integers(-32768, 32768, (H, W, 4))
    return colour, acc.astype(np.int16)


def run_both(op, value, colour, acc, rect, wm):
    x0, x1, y0, y1 = rect
    k_acc, k_col = acc.copy(), colour.copy()
    accumulate(k_acc, k_col, op, float(value), x0, x1, y0, y1,
               wm if op == AC_RETURN else 0xFFFFFFFF)
    h, w = colour.shape
    fb = NaiveFramebuffer(w, h, stencil_planes=0, zbits=0, double=False)
    fb.front[...] = colour
    n_acc = acc.copy()
    accum(fb, n_acc, op, value, rect, wm, "front")
    return (k_acc, k_col), (n_acc, fb.front)


@settings(max_examples=150, deadline=None)
@given(op=st.sampled_from(OPS), value=values, seed=st.integers(0, 2**32 - 1),
       extreme=st.booleans(),
       rect=st.tuples(st.integers(0, W - 1), st.integers(0, W - 1),
                      st.integers(0, H - 1), st.integers(0, H - 1)),
       wm=st.one_of(st.just(0xFFFFFFFF), st.just(0), st.integers(0, 0xFFFFFFFF)))
def test_accumulate_matches_naive(op, value, seed, extreme, rect, wm):
    x0, x1, y0, y1 = rect
    rect = (min(x0, x1), max(x0, x1), min(y0, y1), max(y0, y1))
    colour, acc = _buffers(seed, extreme)
    (k_acc, k_col), (n_acc, n_col) = run_both(op, value, colour, acc, rect, wm)
    np.testing.assert_array_equal(k_acc, n_acc)
    np.testing.assert_array_equal(k_col, n_col)


@pytest.mark.parametrize("op", OPS)
def test_every_op_changes_exactly_the_rectangle(op):
    colour, acc = _buffers(3, False)
    rect = (2, 9, 1, 6)
    (k_acc, k_col), (n_acc, n_col) = run_both(op, 0.75, colour, acc, rect, 0x00FFFFFF)
    np.testing.assert_array_equal(k_acc, n_acc)
    np.testing.assert_array_equal(k_col, n_col)
    outside = np.ones((H, W), bool)
    outside[1:7, 2:10] = False
    np.testing.assert_array_equal(k_acc[outside], acc[outside])
    np.testing.assert_array_equal(k_col[outside], colour[outside])
    changed = (k_acc != acc).any() or (k_col != colour).any()
    assert changed


def test_hand_computed_sequence():
    """acbuf(AC_CLEAR, 0); 3 x AC_ACCUMULATE 1/3 of colour 90; AC_RETURN 1."""
    colour = np.full((1, 1), 0xFF5A5A5A, np.uint32)  # r = g = b = 90, a = 255
    acc = np.zeros((1, 1, 4), np.int16)
    accumulate(acc, colour, AC_CLEAR, 0.0, 0, 0, 0, 0, 0xFFFFFFFF)
    for _ in range(3):
        accumulate(acc, colour, AC_ACCUMULATE, 1 / 3, 0, 0, 0, 0, 0xFFFFFFFF)
    # round(90/3) = 30 three times; round(255/3) = 85 three times.
    assert acc[0, 0].tolist() == [90, 90, 90, 255]
    accumulate(acc, colour, AC_MULT, 0.5, 0, 0, 0, 0, 0xFFFFFFFF)
    assert acc[0, 0].tolist() == [45, 45, 45, 128]  # round(127.5) = 128
    accumulate(acc, colour, AC_ADD, -50.0, 0, 0, 0, 0, 0xFFFFFFFF)
    assert acc[0, 0].tolist() == [-5, -5, -5, 78]
    accumulate(acc, colour, AC_RETURN, 1.0, 0, 0, 0, 0, 0xFFFFFFFF)
    assert int(colour[0, 0]) == 0x4E000000  # clamp(-5) = 0, a = 78
    accumulate(acc, colour, AC_ADD, 40000.0, 0, 0, 0, 0, 0xFFFFFFFF)
    assert acc[0, 0].tolist() == [32767] * 4


@pytest.mark.parametrize("op", [AC_MULT, AC_ADD, AC_CLEAR, AC_ACCUMULATE,
                                AC_CLEAR_ACCUMULATE])
def test_enormous_values_saturate(op):
    colour = np.full((1, 2), 0xFF808080, np.uint32)
    acc = np.array([[[100, 100, 100, 100], [-100, -100, -100, -100]]], np.int16)
    (k_acc, _), (n_acc, _) = run_both(op, 1e20, colour, acc, (0, 1, 0, 0), 0xFFFFFFFF)
    np.testing.assert_array_equal(k_acc, n_acc)


def test_hand_computed_clear_and_clear_accumulate():
    """AC_CLEAR stores round(value) in every component; AC_CLEAR_ACCUMULATE replaces the
    old contents with round(value * component)."""
    colour = np.array([[0x80FF0A01, 0x00000000]], np.uint32)  # r 1, g 10, b 255, a 128
    acc = np.full((1, 2, 4), 1234, np.int16)
    accumulate(acc, colour, AC_CLEAR, -2.5, 0, 1, 0, 0, 0xFFFFFFFF)
    assert acc.tolist() == [[[-2] * 4, [-2] * 4]]  # floor(-2.5 + 0.5) = -2
    accumulate(acc, colour, AC_CLEAR_ACCUMULATE, 1.5, 0, 0, 0, 0, 0xFFFFFFFF)
    # round(1.5), round(15), round(382.5) = 383, round(192); the second pixel keeps -2.
    assert acc.tolist() == [[[2, 15, 383, 192], [-2] * 4]]
    accumulate(acc, colour, AC_ACCUMULATE, 200.0, 0, 0, 0, 0, 0xFFFFFFFF)
    assert acc[0, 0].tolist() == [202, 2015, 32767, 25792]  # 383 + 51000 saturates


def test_hand_computed_return_through_write_mask():
    """AC_RETURN clamps round(value * acc) to 0..255 and writes only the mask's bits."""
    colour = np.array([[0x11223344]], np.uint32)
    acc = np.array([[[100, -7, 300, 51]]], np.int16)
    accumulate(acc, colour, AC_RETURN, 0.5, 0, 0, 0, 0, 0x0F00FF00)
    # r 50 -> 0x32 (not written), g -3 -> 0x00, b 150 -> 0x96 (not written), a 25.5 -> 26.
    # Written bits: all of green, the low nibble of alpha (26 = 0x1A, so 0xA).
    assert int(colour[0, 0]) == 0x1A220044
    assert acc.tolist() == [[[100, -7, 300, 51]]]
