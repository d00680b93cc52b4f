"""Triangle setup: facing, culling, watertight edge equations, interpolation planes.

Implements docs/numeric_model.md sections 3 and 4.  Everything is computed once per
triangle from fixed-point integer coordinates:

* ``area2`` (exact int64) decides facing and culling; zero-area triangles vanish;
* three edge inequalities ``A*X + B*Y + K >= 0`` whose constant already holds the
  tie-rule bias, so both rasterizers (scanline and edge-function) test the same thing;
* depth and colour plane equations set up from the vertices in canonical order
  (sorted by (y, x)), so a face drawn twice -- scene pass and shadow cap, or with its
  vertices permuted -- gets bit-identical depth.
"""

from __future__ import annotations

import numpy as np

from vgxsim.state.codes import CULL_BACK, CULL_FRONT

from .borrow import borrow
from .clip import ONE
from .options import inline, inline_ir, jit


@inline
def _edge(xi, yi, xj, yj, t_edge, n, e):
    """Edge i->j of a counter-clockwise triangle into t_edge[n, e] = (A, B, K).
    (Written in place, not through a view of record n: a view costs two atomic
    reference-count updates, which set-up on two threads would contend for.)"""
    dx = xj - xi
    dy = yj - yi
    inclusive = dy < 0 or (dy == 0 and dx > 0)
    bias = 1 if inclusive else 0
    t_edge[n, e, 0] = -dy * ONE
    t_edge[n, e, 1] = dx * ONE
    t_edge[n, e, 2] = dy * xi - dx * yi + bias - 1


DEAD_Y0 = 1 << 40  # first row of a dead record: beyond any band


@inline_ir
def canonical_order(xf, yf, a, b, c):
    """Vertex indices a, b, c in ascending (y, x) of their fixed-point positions
    (inlined at the IR level: it takes the position arrays, once per triangle).

    The first is the origin of every interpolation plane (depth, colour here,
    texture coordinates in kernels/texture.py), so the set-up and the texture stage
    take it from this one rule."""
    if (yf[b] < yf[a]) or (yf[b] == yf[a] and xf[b] < xf[a]):
        a, b = b, a
    if (yf[c] < yf[b]) or (yf[c] == yf[b] and xf[c] < xf[b]):
        b, c = c, b
        if (yf[b] < yf[a]) or (yf[b] == yf[a] and xf[b] < xf[a]):
            a, b = b, a
    return a, b, c


@inline
def plane_frame(ax, ay, bx, by, cx, cy, det2):
    """The frame a plane is solved in, in pixels: (x0, y0) the canonical first vertex,
    the offsets of the other two from it and the determinant (``det2`` is twice the
    signed area in fixed point, ONE units a pixel)."""
    fx0 = ax / ONE
    fy0 = ay / ONE
    return (fx0, fy0, bx / ONE - fx0, by / ONE - fy0, cx / ONE - fx0, cy / ONE - fy0,
            det2 / (ONE * ONE))


@inline
def _dead(t_box, t_state, n, state):
    t_box[n, 0] = 1
    t_box[n, 1] = 0
    t_box[n, 2] = DEAD_Y0
    t_box[n, 3] = -1
    t_state[n] = state


@inline
def _ceil_div_one(v):
    return -((-v) // ONE)


@jit
def setup_triangles(
    xf, yf, zw, col, tris, src, flat_col, state, cull, flat, want_colour,
    t_edge, t_box, t_z, t_zlim, t_col, t_state, offset,
):
    """Set up triangles into the batch arrays starting at ``offset``.

    Parameters
    ----------
    xf, yf : ndarray, shape (Nv,), int64
        Fixed-point window coordinates.
    zw : ndarray, shape (Nv,), float64
        Window depth.
    col : ndarray, shape (Nv, 4), float64
        Vertex RGBA in [0, 1] (Gouraud); ignored when ``flat`` or not ``want_colour``.
    tris : ndarray, shape (Nt, 3), int64
        Vertex indices, in drawing order.
    src : ndarray, shape (Nt,), int64
        Source primitive of each triangle (indexes ``flat_col``).
    flat_col : ndarray, shape (Ns, 4), float64
        Colour of each source primitive's last vertex (flat shading).
    state : int
        State-table index shared by all these triangles.
    cull : int
        Bit 0 culls clockwise (backface), bit 1 counter-clockwise (frontface).
    flat, want_colour : bool
        Shading model and whether colour is written at all (no colour, no planes).
    t_edge, t_box, t_z, t_zlim, t_col, t_state : ndarray
        Batch arrays, shapes (C, 3, 3) int64, (C, 4) int64, (C, 5) float64,
        (C, 2) int64, (C, 4, 3) float64, (C,) int32.
    offset : int
        First free slot.

    Returns
    -------
    int
        New number of used slots: ``offset + Nt``.  Every input triangle gets its
        slot (so chunks of one call can be set up by different threads); a culled,
        zero-area or pixel-less triangle gets a dead record (``DEAD_Y0`` > its last
        row) that binning never places in a band.
    """
    n = offset
    for t in range(tris.shape[0]):
        _setup_one(xf, yf, zw, col, tris, src, flat_col, state, cull, flat, want_colour,
                   t_edge, t_box, t_z, t_zlim, t_col, t_state, t, n)
        n += 1
    return n


@jit
def setup_triangles_states(
    xf, yf, zw, col, tris, src, flat_col, states, culls, flat, want_colour,
    t_edge, t_box, t_z, t_zlim, t_col, t_state, offset,
):
    """:func:`setup_triangles` with a state-table index and a cull mode per triangle
    (``states``, ``culls``: shape (Nt,), int64): one call sets up triangles drawn
    with different fragment state (the 1991 code changes stencil() before every
    shadow face, nothing else).  Also compiled for borrowed arrays
    (:func:`setup_triangles_borrowed`)."""
    n = offset
    for t in range(tris.shape[0]):
        _setup_one(xf, yf, zw, col, tris, src, flat_col, states[t], culls[t], flat,
                   want_colour, t_edge, t_box, t_z, t_zlim, t_col, t_state, t, n)
        n += 1
    return n


@jit
def setup_triangles_borrowed(
    xf, yf, zw, col, tris, src, flat_col, states, culls, flat, want_colour,
    t_edge, t_box, t_z, t_zlim, t_col, t_state, offset,
):
    """:func:`setup_triangles_states` on borrowed arrays (kernels/borrow.py;
    CommandBatch.borrow_arrays): the inlined ``_setup_one`` binds its array
    arguments once a triangle, and on plain arrays each binding is a counted
    reference (40 to 46 out-of-line calls a triangle in the loop's assembly); on
    borrowed ones there is no counting at all.  The records are the same.  The
    caller holds every argument for the whole call."""
    return setup_triangles_states(
        borrow(xf), borrow(yf), borrow(zw), borrow(col), borrow(tris), borrow(src),
        borrow(flat_col), borrow(states), borrow(culls), flat, want_colour,
        borrow(t_edge), borrow(t_box), borrow(t_z), borrow(t_zlim), borrow(t_col),
        borrow(t_state), offset)


@jit
def setup_triangles_slots(
    xf, yf, zw, col, tris, src, flat_col, states, culls, flat, want_colour,
    t_edge, t_box, t_z, t_zlim, t_col, t_state, offset, slot,
):
    """:func:`setup_triangles_states` writing triangle ``t``'s record to slot
    ``offset + slot[t]`` (``slot``: shape (Nt,), int64; kernels/band_order.py
    band_slots groups a call's records by band, CommandBatch.band_slots).  The
    records are the same, in other slots."""
    for t in range(tris.shape[0]):
        _setup_one(xf, yf, zw, col, tris, src, flat_col, states[t], culls[t], flat,
                   want_colour, t_edge, t_box, t_z, t_zlim, t_col, t_state, t,
                   offset + slot[t])
    return offset + tris.shape[0]


@jit
def setup_triangles_slots_borrowed(
    xf, yf, zw, col, tris, src, flat_col, states, culls, flat, want_colour,
    t_edge, t_box, t_z, t_zlim, t_col, t_state, offset, slot,
):
    """:func:`setup_triangles_slots` on borrowed arrays (as
    :func:`setup_triangles_borrowed`)."""
    return setup_triangles_slots(
        borrow(xf), borrow(yf), borrow(zw), borrow(col), borrow(tris), borrow(src),
        borrow(flat_col), borrow(states), borrow(culls), flat, want_colour,
        borrow(t_edge), borrow(t_box), borrow(t_z), borrow(t_zlim), borrow(t_col),
        borrow(t_state), offset, borrow(slot))


@inline_ir
def _setup_one(xf, yf, zw, col, tris, src, flat_col, state, cull, flat, want_colour,
               t_edge, t_box, t_z, t_zlim, t_col, t_state, t, n):
    """Set up triangle ``t`` into slot ``n`` (a dead record if it draws nothing)."""
    i0, i1, i2 = tris[t, 0], tris[t, 1], tris[t, 2]
    x0, y0, x1, y1, x2, y2 = xf[i0], yf[i0], xf[i1], yf[i1], xf[i2], yf[i2]
    area2 = (x1 - x0) * (y2 - y0) - (x2 - x0) * (y1 - y0)
    if (area2 == 0 or (area2 < 0 and (cull & CULL_BACK) != 0)
            or (area2 > 0 and (cull & CULL_FRONT) != 0)):
        _dead(t_box, t_state, n, state)
        return
    a, b, c = canonical_order(xf, yf, i0, i1, i2)
    ax, ay, bx, by, cx, cy = xf[a], yf[a], xf[b], yf[b], xf[c], yf[c]
    det2 = (bx - ax) * (cy - ay) - (cx - ax) * (by - ay)
    # Edges of the counter-clockwise version.
    if det2 > 0:
        _edge(ax, ay, bx, by, t_edge, n, 0)
        _edge(bx, by, cx, cy, t_edge, n, 1)
        _edge(cx, cy, ax, ay, t_edge, n, 2)
    else:
        _edge(ax, ay, cx, cy, t_edge, n, 0)
        _edge(cx, cy, bx, by, t_edge, n, 1)
        _edge(bx, by, ax, ay, t_edge, n, 2)
    xmin = min(ax, min(bx, cx))
    xmax = max(ax, max(bx, cx))
    t_box[n, 0] = _ceil_div_one(xmin)
    t_box[n, 1] = xmax // ONE
    t_box[n, 2] = ay // ONE + (1 if ay % ONE != 0 else 0)
    t_box[n, 3] = cy // ONE
    if t_box[n, 0] > t_box[n, 1] or t_box[n, 2] > t_box[n, 3]:
        _dead(t_box, t_state, n, state)  # no pixel centre inside the bounding box
        return
    fx0, fy0, dxb, dyb, dxc, dyc, det = plane_frame(ax, ay, bx, by, cx, cy, det2)
    za, zb, zc = zw[a], zw[b], zw[c]
    t_z[n, 0] = za
    t_z[n, 1] = fx0
    t_z[n, 2] = fy0
    t_z[n, 3] = ((zb - za) * dyc - (zc - za) * dyb) / det
    t_z[n, 4] = (dxb * (zc - za) - dxc * (zb - za)) / det
    ra = np.floor(za + 0.5)
    rb = np.floor(zb + 0.5)
    rc = np.floor(zc + 0.5)
    t_zlim[n, 0] = np.int64(min(ra, min(rb, rc)))
    t_zlim[n, 1] = np.int64(max(ra, max(rb, rc)))
    if want_colour:
        if flat:
            s = src[t]
            for ch in range(4):
                t_col[n, ch, 0] = flat_col[s, ch] * 255.0
                t_col[n, ch, 1] = 0.0
                t_col[n, ch, 2] = 0.0
        else:
            for ch in range(4):
                ca = col[a, ch] * 255.0
                cb = col[b, ch] * 255.0
                cc = col[c, ch] * 255.0
                t_col[n, ch, 0] = ca
                t_col[n, ch, 1] = ((cb - ca) * dyc - (cc - ca) * dyb) / det
                t_col[n, ch, 2] = (dxb * (cc - ca) - dxc * (cb - ca)) / det
    t_state[n] = state

