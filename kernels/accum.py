"""Accumulation-buffer operations, acbuf(3G) (docs/numeric_model.md section 9).

The VGX accumulation buffer holds 16-bit signed components; colour enters as 0..255
integers, so 32 accumulated images of 255 (8160) fit with room to spare
(Haeberli and Akeley 1990).

The operation is chosen once per call, outside the pixel loops, so that each loop is
a straight run of work the compiler vectorises: AC_ACCUMULATE and AC_CLEAR_ACCUMULATE
scale each component in floating point (one lane per component), AC_ADD and AC_CLEAR
add or store one rounded constant.  The kernel is serial: a full 1280x1024 call takes
a few milliseconds on one core, and on a loaded two-core machine it finished sooner
alone than split over the band threads or an OpenMP prange, whose threads wait for a
free core (measured for figure 6, bench/heidmann_claims.py).
"""

from __future__ import annotations

import numpy as np

from vgxsim.state.codes import (
    AC_ACCUMULATE,
    AC_ADD,
    AC_CLEAR,
    AC_CLEAR_ACCUMULATE,
    AC_MULT,
    AC_RETURN,
)

from .options import inline, jit


@inline
def _sat16(v):
    if v < -32768:
        return -32768
    if v > 32767:
        return 32767
    return v


@inline
def _round(v):
    """floor(v + 0.5), first limited to +-2**20 (NaN as 0) so the integer conversion
    cannot overflow; every result is saturated to 16 bits afterwards anyway."""
    if not (v == v):
        v = 0.0
    v = min(max(v, -1048576.0), 1048576.0)
    return np.int64(np.floor(v + 0.5))


@jit
def accumulate(acc, colour, op, value, x0, x1, y0, y1, wm):
    """Apply one acbuf operation to the rectangle [x0, x1] x [y0, y1].

    Parameters
    ----------
    acc : ndarray, shape (H, W, 4), int16, C-contiguous
        Accumulation buffer, RGBA.
    colour : ndarray, shape (H, W), uint32, C-contiguous
        The colour buffer read (AC_ACCUMULATE, AC_CLEAR_ACCUMULATE) or written
        (AC_RETURN, through the packed write mask ``wm``).
    op : int
        AC_* code.
    value : float
        The operation's value.
    x0, x1, y0, y1 : int
        Inclusive rectangle.
    wm : int
        Packed colour write mask (AC_RETURN).
    """
    h, w = colour.shape
    # Component k of pixel x is element 4x + k of a row in both planes: the packed
    # word 0xAABBGGRR is R, G, B, A in memory on the little-endian hosts vgxsim runs
    # on (lrectread(3G) data is little-endian words too).  Flat rows give the loops
    # below one index, unsigned so Numba drops its negative-index wraparound.
    acc_rows = acc.reshape((h, w * 4))
    col_rows = colour.view(np.uint8).reshape((h, w * 4))
    i0 = np.uintp(4 * x0)
    i1 = np.uintp(4 * x1 + 4)
    if op == AC_ACCUMULATE or op == AC_CLEAR_ACCUMULATE:
        keep = np.int32(1 if op == AC_ACCUMULATE else 0)
        for y in range(y0, y1 + 1):
            a_row = acc_rows[y]
            c_row = col_rows[y]
            for i in range(i0, i1):
                a = np.int32(a_row[i]) * keep + np.int32(_round(value * np.float64(c_row[i])))
                a_row[i] = np.int16(min(max(a, -32768), 32767))
    elif op == AC_CLEAR or op == AC_ADD:
        r = np.int32(_round(value))
        keep = np.int32(1 if op == AC_ADD else 0)
        for y in range(y0, y1 + 1):
            a_row = acc_rows[y]
            for i in range(i0, i1):
                a = np.int32(a_row[i]) * keep + r
                a_row[i] = np.int16(min(max(a, -32768), 32767))
    elif op == AC_MULT:
        for y in range(y0, y1 + 1):
            a_row = acc_rows[y]
            for i in range(i0, i1):
                a_row[i] = np.int16(_sat16(_round(value * np.float64(a_row[i]))))
    elif op == AC_RETURN:
        masks = np.empty(4, np.uint8)  # the write mask's byte for each component
        for ch in range(4):
            masks[ch] = np.uint8((wm >> (8 * ch)) & 0xFF)
        for y in range(y0, y1 + 1):
            a_row = acc_rows[y]
            c_row = col_rows[y]
            for x in range(np.uintp(x0), np.uintp(x1 + 1)):
                for ch in range(4):
                    i = np.uintp(4) * x + np.uintp(ch)
                    v = np.uint8(min(max(_round(value * np.float64(a_row[i])), 0), 255))
                    m = masks[ch]
                    c_row[i] = (c_row[i] & ~m) | (v & m)
