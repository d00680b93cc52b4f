"""Exact soft-shadow reduction in the VGX's accumulation units.

:func:`vgxsim.shadow.program.accumulate` sums its ``N`` jittered frames with
``acbuf(AC_CLEAR_ACCUMULATE, 1.0)`` / ``acbuf(AC_ACCUMULATE, 1.0)`` and shows
``acbuf(AC_RETURN, 1.0 / N)`` (Haeberli and Akeley 1990).  Here each worker sums its
own samples with the same acbuf kernel (:func:`vgxsim.kernels.accum.accumulate`, 16-bit
signed per component, docs/numeric_model.md section 9) and the partial sums are added
in sample order.

Why the result cannot depend on the split.  With value 1.0, ``round(1.0 * c) = c``:
every addend is a colour component, an integer in 0..255, never negative.  acbuf
saturates after every step, ``a <- min(a + c, 32767)``; for non-negative addends that
running saturation equals one saturation of the exact sum,
``min(c_1 + ... + c_N, 32767)`` (once a prefix reaches 32767 every later step stays
there, and before that nothing was clipped).  The same holds for a partial sum that
saturated: ``min(min(a, M) + b, M) = min(a + b, M)`` for ``a, b >= 0``.  So the
partials are summed in int64 (no overflow below 3.6e16 samples) and saturated once,
which is bit-identical to the sequential acbuf for every ``N`` and every split --
without intermediate saturation trivially, with it by the identity above.  The
16-bit range is reached only past 128 samples of a full-intensity component
(``128 * 255 = 32640``); the program's default maximum is 64.

What would break associativity: a negative contribution (``acbuf(AC_ACCUMULATE, w)``
with ``w < 0``, or ``AC_ADD`` of a negative value) between saturations, e.g.
``32767 + 1 - 1`` is 32766 step by step but 32767 summed at once; or weights other than
1.0 applied to partial sums instead of per frame (the per-frame rounding of
``round(w * c)`` would differ).  The farm accumulates with weight 1.0 only, and
:func:`reduce_partials` refuses a negative partial rather than return an image that a
sequential run would not give.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from vgxsim.kernels.accum import AC_ACCUMULATE, AC_CLEAR_ACCUMULATE, AC_RETURN
from vgxsim.kernels.accum import accumulate as acbuf_kernel

ACC_MAX = 32767  # 16-bit signed components (numeric_model.md section 9)
ALL_PLANES = 0xFFFFFFFF


class ReductionError(ValueError):
    """Partial sums that do not cover the samples exactly once, or a negative sum."""


def pack_rgba(colour: np.ndarray) -> np.ndarray:
    """(H, W, 4) uint8 RGBA -> (H, W) uint32 with R in the low byte (cpack order)."""
    c = np.asarray(colour, np.uint32)
    return c[..., 0] | (c[..., 1] << 8) | (c[..., 2] << 16) | (c[..., 3] << 24)


def unpack_rgba(packed: np.ndarray) -> np.ndarray:
    """(H, W) uint32 -> (H, W, 4) uint8 RGBA (inverse of :func:`pack_rgba`)."""
    return np.stack([(packed >> (8 * ch)) & 0xFF for ch in range(4)], -1).astype(np.uint8)


def accumulate_frames(colours: Sequence[np.ndarray]) -> np.ndarray:
    """Sum frames as acbuf does: AC_CLEAR_ACCUMULATE for the first, AC_ACCUMULATE after.

    Parameters
    ----------
    colours : sequence of ndarray, each (H, W, 4) uint8
        Frames in sample order (at least one).

    Returns
    -------
    ndarray, shape (H, W, 4), int16
    """
    if not colours:
        raise ValueError("accumulate_frames: no frames")
    h, w = colours[0].shape[:2]
    acc = np.zeros((h, w, 4), np.int16)
    for k, colour in enumerate(colours):
        op = AC_CLEAR_ACCUMULATE if k == 0 else AC_ACCUMULATE
        acbuf_kernel(acc, pack_rgba(colour), op, 1.0, 0, w - 1, 0, h - 1, ALL_PLANES)
    return acc


def reduce_partials(partials: Sequence, total: int) -> np.ndarray:
    """Add partial accumulation buffers in sample order and saturate once.

    Parameters
    ----------
    partials : sequence of :class:`~vgxsim.farm.tasks.Partial`
        Any order; together they must cover samples ``0 .. total - 1`` exactly once.
    total : int

    Returns
    -------
    ndarray, shape (H, W, 4), int16
        Equal to the sequential acbuf sum of all samples (module docstring).

    Raises
    ------
    ReductionError
        A gap, an overlap or a negative component.
    """
    ordered = sorted(partials, key=lambda p: p.start)
    edge = 0
    for p in ordered:
        if p.start != edge or p.stop <= p.start:
            spans = [(q.start, q.stop) for q in ordered]
            raise ReductionError(f"partial sums cover samples {spans}, not 0..{total - 1} "
                                 "exactly once")
        edge = p.stop
    if edge != total:
        raise ReductionError(f"partial sums end at sample {edge}, not {total}")
    acc = np.zeros(ordered[0].acc.shape, np.int64)
    for p in ordered:
        if (p.acc < 0).any():
            raise ReductionError(f"samples {p.start}..{p.stop - 1}: a negative accumulated "
                                 "component; saturating sums would depend on the split")
        acc += p.acc
    return np.minimum(acc, ACC_MAX).astype(np.int16)


def resolve(acc: np.ndarray, frames: int) -> np.ndarray:
    """``acbuf(AC_RETURN, 1.0 / frames)`` of ``acc`` into a fresh RGBA image.

    Parameters
    ----------
    acc : ndarray, shape (H, W, 4), int16
    frames : int

    Returns
    -------
    ndarray, shape (H, W, 4), uint8
    """
    h, w = acc.shape[:2]
    out = np.zeros((h, w), np.uint32)
    acbuf_kernel(np.ascontiguousarray(acc), out, AC_RETURN, 1.0 / frames, 0, w - 1, 0, h - 1,
                 ALL_PLANES)
    return unpack_rgba(out)
