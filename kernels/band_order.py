"""Records into band order by one pass in drawing order (CommandBatch.scatter_bins).

The band kernel (kernels/render.py render_bands) reads each band's primitives
front to back when their set-up records are copied into band order first.  The
copy used to be a gather (kernels/render.py gather_band_records): entry by entry
of each band, the record of a scattered primitive, so every band's pass read the
whole record arrays again, a few records per cache line (200k 10-pixel
triangles, 1280x1024: 99 ns a triangle on 4 bands, 154 on 16).  Here the
primitives are walked once, in drawing order, and each record is written to the
next free slot of every band it touches: the reads are sequential, the writes
one sequential stream per band (60 and 87 ns in the same test).

Chunks of primitives may run on different threads: each starts from its own free
slot per band (the bands' starts plus the entries the chunks before it put
there, :func:`band_counts`), so every band's entries stay in drawing order, as
kernels/render.py bin_primitives lists them.
"""

from __future__ import annotations

import numpy as np

from vgxsim.state.codes import KIND_TRIANGLE

from .clip import ONE
from .options import inline_ir, jit


@jit
def band_counts(py0, py1, lo, hi, band_shift, nbands, counts):
    """Add to ``counts[b]`` how many of primitives ``lo .. hi - 1`` touch band ``b``
    (rows ``py0 .. py1``, the bands of bin_primitives).

    Parameters
    ----------
    py0, py1 : ndarray, shape (P,), int64
    lo, hi : int
    band_shift, nbands : int
    counts : ndarray, shape (nbands,), int64
    """
    for p in range(lo, hi):
        b0 = max(py0[p], 0) >> band_shift
        b1 = min(py1[p] >> band_shift, nbands - 1)
        for b in range(b0, b1 + 1):
            counts[b] += 1


@jit
def band_slots(yf, tris, band_shift, nbands, max_rows, slot):
    """Where each triangle of a call writes its set-up record (CommandBatch.band_slots):
    grouped by the band of its first row, in drawing order within a band (a stable
    counting sort), so that a band reads its triangles' records front to back
    without the flush copying them.

    The key is the first row of the triangle's set-up box (kernels/setup.py:
    ``ceil(min y)``); it only places records, so a key that differs from the rows
    the flush bins by (a scissor, a dead triangle, another band height by then)
    changes where a record sits, never what is drawn.

    Parameters
    ----------
    yf : ndarray, shape (Nv,), int64
        Fixed-point window y of the vertices.
    tris : ndarray, shape (Nt, 3), int64
    band_shift, nbands : int
        Bands of ``2**band_shift`` rows (vgxsim/batch.py band_shift).
    max_rows : float
        The most rows the call's triangles may span on average (their y extent
        plus one) for it to be placed: tall bands are for small triangles
        (vgxsim/batch.py ``TALL_ROWS``), a flush of others copies records anyway.
    slot : ndarray, shape (Nt,), int64
        Output: triangle ``t``'s record offset from the call's first record (a
        permutation of ``0 .. Nt - 1``); unspecified when not placed.

    Returns
    -------
    bool
        Whether the call is placed (else its records go in drawing order).
    """
    n = tris.shape[0]
    counts = np.zeros(nbands + 1, np.int64)
    rows = 0.0
    for t in range(n):
        y0, y1, y2 = yf[tris[t, 0]], yf[tris[t, 1]], yf[tris[t, 2]]
        y = min(y0, min(y1, y2))
        rows += (max(y0, max(y1, y2)) - y) / ONE + 1.0
        b = min(max(-((-y) // ONE), 0) >> band_shift, nbands - 1)
        slot[t] = b  # the key, for the second pass
        counts[b + 1] += 1
    if rows > max_rows * max(n, 1):
        return False
    for b in range(nbands):
        counts[b + 1] += counts[b]
    for t in range(n):
        b = slot[t]
        slot[t] = counts[b]
        counts[b] += 1
    return True


@jit
def mean_rows(py0, py1, nprims, height):
    """Mean number of window rows (``0 .. height - 1``) of primitives ``0 .. nprims - 1``
    (rows ``py0 .. py1``; none for a dead one), for the choice of band height
    (vgxsim/batch.py ``tall_bands``).

    Parameters
    ----------
    py0, py1 : ndarray, shape (P,), int64
    nprims, height : int

    Returns
    -------
    float
    """
    total = 0
    for p in range(nprims):
        total += max(min(py1[p], height - 1) - max(py0[p], 0) + 1, 0)
    return total / max(nprims, 1)


@inline_ir
def _copy_record(s, i, t_edge, t_box, t_z, t_zlim, t_col, t_state, g_edge, g_box, g_z,
                 g_zlim, g_col, g_state):
    """Record ``s`` of the ``t_*`` arrays to slot ``i`` of the ``g_*`` arrays."""
    for e in range(3):
        for c in range(3):
            g_edge[i, e, c] = t_edge[s, e, c]
    for c in range(4):
        g_box[i, c] = t_box[s, c]
    for c in range(5):
        g_z[i, c] = t_z[s, c]
    g_zlim[i, 0] = t_zlim[s, 0]
    g_zlim[i, 1] = t_zlim[s, 1]
    for ch in range(4):
        for c in range(3):
            g_col[i, ch, c] = t_col[s, ch, c]
    g_state[i] = t_state[s]


@jit
def scatter_records(lo, hi, py0, py1, band_shift, nbands, fill, p_kind, p_ref, t_edge, t_box,
                    t_z, t_zlim, t_col, t_state, g_kind, g_ref, g_edge, g_box, g_z, g_zlim,
                    g_col, g_state):
    """Primitives ``lo .. hi - 1`` (set up already) into band order.

    Parameters
    ----------
    lo, hi : int
    py0, py1 : ndarray, shape (P,), int64
        Rows of each primitive.
    band_shift, nbands : int
    fill : ndarray, shape (nbands,), int64
        Next free slot of each band; advanced.
    p_kind, p_ref : ndarray, shape (P,), int64
    t_edge, t_box, t_z, t_zlim, t_col, t_state : ndarray
        The batch's set-up records (kernels/setup.py).
    g_kind, g_ref, g_edge, g_box, g_z, g_zlim, g_col, g_state : ndarray
        Band-ordered entries: a triangle's kind, its own slot as reference and its
        record there; other kinds their reference unchanged (as
        kernels/render.py gather_band_records).
    """
    for p in range(lo, hi):
        b0 = max(py0[p], 0) >> band_shift
        b1 = min(py1[p] >> band_shift, nbands - 1)
        k = p_kind[p]
        for b in range(b0, b1 + 1):
            i = fill[b]
            fill[b] = i + 1
            g_kind[i] = k
            if k != KIND_TRIANGLE:
                g_ref[i] = p_ref[p]
                continue
            g_ref[i] = i
            _copy_record(p_ref[p], i, t_edge, t_box, t_z, t_zlim, t_col, t_state, g_edge,
                         g_box, g_z, g_zlim, g_col, g_state)
