"""Small triangles in one pass over their bounding box (CommandBatch.small_path).

A 10-pixel triangle has four or five rows of two or three pixels.  The general
band path (kernels/render.py _triangle_rows) pays, per triangle, the set-up of
three stepped edges (kernels/spans.py: two divisions each) and, per row, a span
solve and the entry of a span loop built to vectorize over long spans (its
preamble and remainder handling cost more than two pixels of work).  For a
triangle at most ``NARROW`` pixels wide whose tiles are not classified, this path
instead walks the pixel centres of the box once, carrying the three edge values
by exact integer steps (``A`` per column, the value at the row's first column from
``A*x + B*y + K``: the same int64 sums as kernels/raster.py covers), and runs the
fragment operations of the state's span loop on the covered ones, scalar.

Exactness: the covered pixels are those of the edge-function test, which the span
rasterizer matches exactly (tests/kernels/test_spans.py); each fragment's depth
and colour are the span loops' expressions (``za = z0 + dzdy*(y - y0)`` then
``za + dzdx*(x - x0)``, colour_row then ``c + dc*(x - x0)``), rounded by the same
round_z / pack_rgba (the int64 forms, equal to vector_pack's int32 ones), and the
same comparisons and writes; writes the span loops make with unchanged values
are left out.  A pixel is visited once per triangle, so the order inside a
triangle changes nothing.  Modes: z only, z + stencil (table and saturating add),
and colour with the z test on and a replace or add blend, stencil test or not;
anything else takes the span path.
"""

from __future__ import annotations

import numpy as np

from vgxsim.state.codes import (
    CBLEND_ADD,
    CBLEND_REPLACE,
    D_CBLEND,
    D_DZFAIL,
    D_DZPASS,
    D_MODE,
    D_SMAX,
    D_STENCIL,
    D_ZTEST,
    D_ZWRITE,
    MODE_COLOUR,
    MODE_ZONLY,
    MODE_ZSTENCIL,
    MODE_ZSTENCIL_ADD,
    S_DRAW_BACK,
    S_SFUNC,
    S_SMASK,
    S_SREF,
    S_WMPACK,
    S_ZFUNC,
)

from .fragment import add_sat, cmp_bits, cmp_select, colour_row, pack_rgba, round_z, wrap_z24
from .options import inline, inline_ir

NARROW = 8  # boxes at most this many pixels wide (as kernels/render.py's narrow scan)


@inline
def small_mode(dv):
    """Whether the state's mode has a loop here (see the module docstring)."""
    mode = dv[D_MODE]
    if mode == MODE_ZONLY or mode == MODE_ZSTENCIL or mode == MODE_ZSTENCIL_ADD:
        return True
    blend = dv[D_CBLEND]
    return mode == MODE_COLOUR and dv[D_ZTEST] != 0 and (
        blend == CBLEND_REPLACE or blend == CBLEND_ADD)


@inline_ir
def small_triangle(t, xlo, xhi, ylo, yhi, t_edge, t_z, t_zlim, t_col, st, dv, tab, front,
                   back, zbuf, sten):
    """Rasterize triangle ``t`` over the box ``[xlo, xhi] x [ylo, yhi]`` (already
    clipped to band and scissor; ``xhi - xlo < NARROW``) in a mode
    :func:`small_mode` accepts.  Returns the number of fragments (covered pixels).
    """
    a0 = t_edge[t, 0, 0]
    b0 = t_edge[t, 0, 1]
    k0 = t_edge[t, 0, 2]
    a1 = t_edge[t, 1, 0]
    b1 = t_edge[t, 1, 1]
    k1 = t_edge[t, 1, 2]
    a2 = t_edge[t, 2, 0]
    b2 = t_edge[t, 2, 1]
    k2 = t_edge[t, 2, 2]
    z0 = t_z[t, 0]
    x0 = t_z[t, 1]
    y0 = t_z[t, 2]
    dzdx = t_z[t, 3]
    dzdy = t_z[t, 4]
    zmin = t_zlim[t, 0]
    zmax = t_zlim[t, 1]
    mode = dv[D_MODE]
    lt, eq, gt = cmp_bits(st[S_ZFUNC])
    zwrite = dv[D_ZWRITE] != 0
    stest = dv[D_STENCIL] != 0
    smask = st[S_SMASK]
    sref = st[S_SREF] & smask
    slt, seq, sgt = cmp_bits(st[S_SFUNC])
    add = dv[D_CBLEND] == CBLEND_ADD
    wm = st[S_WMPACK] & 0xFFFFFFFF
    keep = ~wm & 0xFFFFFFFF
    dpass = dv[D_DZPASS]
    dfail = dv[D_DZFAIL]
    smax = dv[D_SMAX]
    cbuf = back if st[S_DRAW_BACK] else front
    tested = 0
    for y in range(ylo, yhi + 1):
        e0 = a0 * xlo + b0 * y + k0
        e1 = a1 * xlo + b1 * y + k1
        e2 = a2 * xlo + b2 * y + k2
        uy = np.uintp(y)
        za = z0 + dzdy * (y - y0)
        ra = ga = ba = aa = rdx = gdx = bdx = adx = 0.0
        if mode == MODE_COLOUR:
            ra, ga, ba, aa, rdx, gdx, bdx, adx = colour_row(t_col, t, y - y0)
        for x in range(xlo, xhi + 1):
            inside = e0 >= 0 and e1 >= 0 and e2 >= 0
            e0 += a0
            e1 += a1
            e2 += a2
            if not inside:
                continue
            tested += 1
            ux = np.uintp(x)
            zi = round_z(za + dzdx * (x - x0), zmin, zmax)
            zpass = cmp_select(lt, eq, gt, zi, np.int64(zbuf[uy, ux]))
            if mode == MODE_COLOUR:
                if stest and not cmp_select(slt, seq, sgt, sref,
                                            np.int64(sten[uy, ux]) & smask):
                    continue
                if not zpass:
                    continue
                if zwrite:
                    zbuf[uy, ux] = wrap_z24(zi)
                dx = x - x0
                src = pack_rgba(ra + rdx * dx, ga + gdx * dx, ba + bdx * dx, aa + adx * dx)
                dst = np.int64(cbuf[uy, ux])
                out = add_sat(src, dst) if add else src
                cbuf[uy, ux] = (dst & keep) | (out & wm)
            elif mode == MODE_ZONLY:
                if zpass:
                    zbuf[uy, ux] = wrap_z24(zi)
            elif mode == MODE_ZSTENCIL_ADD:
                sv = np.int64(sten[uy, ux]) + (dpass if zpass else dfail)
                sten[uy, ux] = min(max(sv, 0), smax)
            else:  # MODE_ZSTENCIL
                sv = sten[uy, ux]
                sten[uy, ux] = tab[0, sv] if zpass else tab[1, sv]
    return tested
