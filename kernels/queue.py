"""Queueing set-up triangles as batch primitives: kind, reference and rows.

A batch bins each primitive by the rows it can touch (``p_y0 .. p_y1``;
vgxsim/batch.py, kernels/render.py ``bin_primitives``).  For triangles those rows
come from their set-up box (kernels/setup.py ``t_box``), cut to the raster
rectangle (scissor(3G)), so that bands outside a light's scissor rectangle never
see them.  One pass over the new records writes the primitive columns in place:
the numpy form (``np.maximum`` / ``np.minimum`` / a mask over the whole call)
allocated five temporaries per call, whose first touch (page faults) cost more
than the arithmetic for a call of many small triangles.
"""

from __future__ import annotations

from vgxsim.state.codes import KIND_TRIANGLE

from .options import jit


@jit
def queue_triangles(t_box, start, end, slot, rec0, clip, sx0, sx1, sy0, sy1, p_kind, p_ref,
                    p_y0, p_y1, at):
    """Records ``start .. end - 1`` as primitives ``at .. at + end - start - 1``.

    Parameters
    ----------
    t_box : ndarray, shape (C, 4), int64
        Set-up boxes (x0, x1, y0, y1; a dead record has an empty one).
    start, end : int
        The records to queue.
    slot : ndarray, shape (end - start,) or (0,), int64
        Where these triangles put their records (kernels/band_order.py band_slots,
        offsets from the call's first record ``rec0``): primitive ``at + k`` is
        record ``rec0 + slot[k]``; empty: record ``start + k``.
    rec0 : int
    clip : bool
        Cut the rows to the scissor ``sx0 .. sx1, sy0 .. sy1`` (inclusive) and give
        a triangle whose box misses it, or is empty, no row (``p_y1 = -1``).  False:
        the box rows as they are (a dead record's are already empty).
    p_kind, p_ref, p_y0, p_y1 : ndarray, shape (P,), int64
        The batch's primitive columns, written at ``at ..``.
    """
    placed = slot.shape[0] > 0
    for r in range(start, end):
        p = at + r - start
        t = rec0 + slot[r - start] if placed else r
        p_kind[p] = KIND_TRIANGLE
        p_ref[p] = t
        y0 = t_box[t, 2]
        y1 = t_box[t, 3]
        if clip:
            y0 = max(y0, sy0)
            y1 = min(y1, sy1)
            if (y0 > y1 or t_box[t, 0] > sx1 or t_box[t, 1] < sx0
                    or t_box[t, 0] > t_box[t, 1]):
                y1 = -1
        p_y0[p] = y0
        p_y1[p] = y1
