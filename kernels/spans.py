"""Row spans by stepping: the span of every row of a triangle without a division per row.

:func:`.raster.row_span` solves each edge inequality ``A*x + (B*y + K) >= 0`` of a
row for x with one floor division per edge.  Over the rows of a triangle the
constant ``k(y) = B*y + K`` grows by ``B`` per row, so the quotient
``q = floor(k / |A|)`` can be carried from row to row with its remainder
``r = k - q*|A|`` in ``[0, |A|)``: adding ``B = bq*|A| + br`` (``0 <= br < |A|``) adds
``bq`` to q and ``br`` to r, and one more to q when r reaches ``|A|``.  That is exact
integer arithmetic (Bresenham's idea), so every row gets bit for bit the span
``row_span`` gives (tests/kernels/test_spans.py), for two divisions per edge per
triangle instead of one per edge per row.  Long thin triangles (shadow-volume faces:
hundreds of rows of one or two pixels) spent most of their time in those divisions.

An edge with ``A == 0`` is horizontal: its row test ``k >= 0`` does not depend on
x; it is carried the same way with divisor 1 (so q is k itself).
"""

from __future__ import annotations

from .options import inline
from .raster import floor_div


@inline
def edge_start(a, b, k, y):
    """Stepping state of one edge at row ``y``: ``(sign of A, q, r, |A| or 1, bq, br)``."""
    s = 1 if a > 0 else (-1 if a < 0 else 0)
    d = a if a > 0 else (-a if a < 0 else 1)
    kk = b * y + k
    q = floor_div(kk, d)
    bq = floor_div(b, d)
    return s, q, kk - q * d, d, bq, b - bq * d


@inline
def edge_start_at(t_edge, t, e, y):
    """:func:`edge_start` of edge ``e`` of set-up record ``t`` (``t_edge`` (T, 3, 3)
    int64), read in place: no array view, so no reference-count update."""
    return edge_start(t_edge[t, e, 0], t_edge[t, e, 1], t_edge[t, e, 2], y)


@inline
def edge_next(q, r, d, bq, br):
    """The edge's ``(q, r)`` one row further down."""
    r += br
    c = r >= d
    return q + bq + c, r - d * c


@inline
def span_from(s0, q0, s1, q1, s2, q2, xlo, xhi):
    """Inclusive span ``[xl, xr]`` of the row whose edge quotients are ``q0..q2``,
    clipped to ``[xlo, xhi]``; empty (``xl > xr``) when a horizontal edge excludes it."""
    xl = xlo
    xr = xhi
    empty = False
    if s0 > 0:
        xl = max(xl, -q0)
    elif s0 < 0:
        xr = min(xr, q0)
    else:
        empty = q0 < 0
    if s1 > 0:
        xl = max(xl, -q1)
    elif s1 < 0:
        xr = min(xr, q1)
    else:
        empty = empty or q1 < 0
    if s2 > 0:
        xl = max(xl, -q2)
    elif s2 < 0:
        xr = min(xr, q2)
    else:
        empty = empty or q2 < 0
    if empty:
        return xlo, xlo - 1
    return xl, xr
