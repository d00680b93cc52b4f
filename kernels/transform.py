"""Vertex transform ``points @ m`` with a fixed, row-independent rounding order.

BLAS may round a row differently depending on how many rows share the call, so the
same vertex could get a different clip position drawn alone or inside a mesh; the
numeric model needs bit-identical results for both (docs/numeric_model.md s. 4).
Each output is ``((p0*m0j + p1*m1j) + p2*m2j) + p3*m3j`` (no fused multiply-add).
"""

from __future__ import annotations

import numpy as np

from .options import jit


@jit
def transform_points(p, m):
    """Row vectors times a matrix.

    Parameters
    ----------
    p : ndarray, shape (N, K), float64
    m : ndarray, shape (K, J), float64

    Returns
    -------
    ndarray, shape (N, J), float64
    """
    n, k = p.shape
    j = m.shape[1]
    out = np.empty((n, j), dtype=np.float64)
    if k == 4 and j == 4:
        # The usual 4x4 case, unrolled (same order of operations as below).
        for i in range(n):
            p0, p1, p2, p3 = p[i, 0], p[i, 1], p[i, 2], p[i, 3]
            for c in range(4):
                out[i, c] = ((p0 * m[0, c] + p1 * m[1, c]) + p2 * m[2, c]) + p3 * m[3, c]
        return out
    for i in range(n):
        for c in range(j):
            acc = p[i, 0] * m[0, c]
            for r in range(1, k):
                acc = acc + p[i, r] * m[r, c]
            out[i, c] = acc
    return out
