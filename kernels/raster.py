"""Exact coverage: the scanline span and the per-pixel edge-function test.

Both read the edge inequalities ``A*X + B*Y + K >= 0`` prepared by :mod:`.setup`
(the tie-rule bias is already inside K), so they cover exactly the same pixels; the
test-suite checks that on every kind of triangle.  The span form solves the three
inequalities of a row once with floor division and leaves a branch-free inner loop.
"""

from __future__ import annotations

import numpy as np

from .options import inline, jit


@inline
def floor_div(k, a):
    """Exact ``k // a`` for ``a > 0`` without an integer division instruction.

    Integer division costs tens of cycles and a small triangle needs three per row;
    |k| < 2**52 and a < 2**34 here, so the float64 quotient is within one of the
    exact one and a single correction step each way makes it exact.
    """
    q = np.int64(np.floor(k / a))
    if q * a > k:
        q -= 1
    elif (q + 1) * a <= k:
        q += 1
    return q


@inline
def row_span(edge, y, xlo, xhi):
    """Inclusive pixel span ``[xl, xr]`` of row ``y`` clipped to ``[xlo, xhi]``.

    ``edge`` is a (3, 3) int64 array of (A, B, K); an empty span has ``xl > xr``.
    """
    xl = xlo
    xr = xhi
    for e in range(3):
        a = edge[e, 0]
        k = edge[e, 1] * y + edge[e, 2]
        if a > 0:
            lo = -floor_div(k, a)
            if lo > xl:
                xl = lo
        elif a < 0:
            hi = floor_div(k, -a)
            if hi < xr:
                xr = hi
        elif k < 0:
            return xlo, xlo - 1
    return xl, xr


@inline
def covers(edge, x, y):
    """Edge-function test of one pixel centre."""
    for e in range(3):
        if edge[e, 0] * x + edge[e, 1] * y + edge[e, 2] < 0:
            return False
    return True


@jit
def coverage_mask_scanline(edge, x0, x1, y0, y1):
    """Coverage of one triangle over a window, by spans.

    Parameters
    ----------
    edge : ndarray, shape (3, 3), int64
    x0, x1, y0, y1 : int
        Inclusive window of pixels to report.

    Returns
    -------
    ndarray, shape (y1 - y0 + 1, x1 - x0 + 1), bool
    """
    out = np.zeros((y1 - y0 + 1, x1 - x0 + 1), dtype=np.bool_)
    for y in range(y0, y1 + 1):
        xl, xr = row_span(edge, y, x0, x1)
        for x in range(xl, xr + 1):
            out[y - y0, x - x0] = True
    return out


@jit
def coverage_mask_edge(edge, x0, x1, y0, y1):
    """Coverage of one triangle over a window, testing every pixel centre."""
    out = np.zeros((y1 - y0 + 1, x1 - x0 + 1), dtype=np.bool_)
    for y in range(y0, y1 + 1):
        for x in range(x0, x1 + 1):
            out[y - y0, x - x0] = covers(edge, x, y)
    return out
