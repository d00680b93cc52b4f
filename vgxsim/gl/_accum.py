"""IRIS GL accumulation buffer: acbuf (acsize lives with the window configuration).

acbuf(op, value) works on the raster rectangle, reading the buffer readsource
selects and writing (AC_RETURN) the enabled draw buffers through wmpack
(docs/numeric_model.md section 9; the arithmetic is IGL's reading, the manual page
was not reached).

Choice: acbuf with no accumulation planes (acsize 0, or before gconfig) raises
GLUsageError rather than doing nothing -- a program that meant to average images
would otherwise silently show the last one.  Accumulation is RGB only, so acbuf in
cmode is an error too.
"""

from __future__ import annotations

import math

from ._core import (
    GLUsageError,
    GLValueError,
    as_float,
    check_token,
    current,
    describe,
    gl_function,
)

__all__ = ["acbuf"]


@gl_function()
def acbuf(op: int, value: float) -> None:
    """Operate on the accumulation buffer (acbuf(3G)).

    Parameters
    ----------
    op : int
        AC_CLEAR (acc = value), AC_ACCUMULATE (acc += value * colour),
        AC_CLEAR_ACCUMULATE (acc = value * colour), AC_RETURN (colour =
        value * acc, clamped to 0..255), AC_MULT (acc *= value) or AC_ADD
        (acc += value); colour in 0..255 units, results saturate to 16 bits.
    value : float
        The operand (finite).

    Raises
    ------
    GLValueError
        Unknown op or a non-finite value.
    GLUsageError
        No accumulation planes configured, or cmode.
    """
    args = (op, value)
    ctx = current("acbuf", args)
    o = check_token("acbuf", args, "op", op, range(6), "AC_")
    v = as_float("acbuf", args, "value", value)
    if not math.isfinite(v):
        raise GLValueError(f"{describe('acbuf', args)}: value must be a finite number")
    if not ctx.config.rgb:
        raise GLUsageError(f"{describe('acbuf', args)}: the accumulation buffer needs "
                           "RGBmode")
    if ctx.fb.accum is None:
        raise GLUsageError(f"{describe('acbuf', args)}: no accumulation buffer (call "
                           "acsize(16) and gconfig() first)")
    ctx.acbuf(o, v)
