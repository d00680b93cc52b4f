"""Accumulation-buffer operations, acbuf(3G) (docs/numeric_model.md section 9).

The VGX accumulation buffer holds 16-bit signed components; colour enters as 0..255
integers, so 32 accumulated images of 255 (8160) fit with room to spare
(Haeberli and Akeley 1990).  Rows are independent, so rows run in parallel.
"""

from __future__ import annotations

import numba
import numpy as np

from vgxsim.state.codes import (
    AC_ACCUMULATE,
    AC_ADD,
    AC_CLEAR,
    AC_CLEAR_ACCUMULATE,
    AC_MULT,
    AC_RETURN,
)

from .options import inline, parallel_jit


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


@parallel_jit
def accumulate(acc, colour, op, value, x0, x1, y0, y1, wm):
    """Apply one acbuf operation to the rectangle [x0, x1] x [y0, y1].

    Parameters
    ----------
    acc : ndarray, shape (H, W, 4), int16
        Accumulation buffer, RGBA.
    colour : ndarray, shape (H, W), uint32
        The colour buffer read (AC_ACCUMULATE, AC_CLEAR_ACCUMULATE) or written
        (AC_RETURN, through the packed write mask ``wm``).
    op : int
        AC_* code.
    value : float
        The operation's value.
    """
    for y in numba.prange(y0, y1 + 1):
        for x in range(x0, x1 + 1):
            if op == AC_RETURN:
                out = 0
                for ch in range(4):
                    v = _round(value * acc[y, x, ch])
                    v = min(max(v, 0), 255)
                    out |= v << (8 * ch)
                old = np.int64(colour[y, x])
                colour[y, x] = (old & ~wm & 0xFFFFFFFF) | (out & wm)
                continue
            c = np.int64(colour[y, x])
            for ch in range(4):
                a = np.int64(acc[y, x, ch])
                comp = (c >> (8 * ch)) & 0xFF
                if op == AC_CLEAR:
                    a = _round(value)
                elif op == AC_ACCUMULATE:
                    a = a + _round(value * comp)
                elif op == AC_CLEAR_ACCUMULATE:
                    a = _round(value * comp)
                elif op == AC_MULT:
                    a = _round(value * a)
                elif op == AC_ADD:
                    a = a + _round(value)
                acc[y, x, ch] = _sat16(a)
