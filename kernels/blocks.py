"""Z-passed block rows: the "block update" of fully covered tiles.

When a tile is fully inside a triangle and the tile's depth bounds prove that the
triangle's every depth over the tile passes the z test against every stored depth
(:func:`.tiles.z_passes_everywhere`, class ``TILE_ZPASS``), the per-fragment z
compare is known to succeed: a fragment does exactly what a passing one does in
the span loops of :mod:`.render` (docs/numeric_model.md s. 6 and s. 11) and
nothing else.  The rows of such tiles run here:

* the z+stencil pass with arithmetic ops (``MODE_ZSTENCIL_ADD``: stencil(3G) func
  SF_ALWAYS, ops ST_KEEP / ST_INCR / ST_DECR): the z-pass op only, on the 8-bit
  stencil values themselves, so the loop runs on byte lanes (no z read at all);
* the z+stencil pass with any other ops (``MODE_ZSTENCIL``): the z-pass column of
  the stencil table;
* the depth-only pass (``MODE_ZONLY``): the z write without the z read;
* the lit and ambient passes (``MODE_COLOUR``, blend replace or ONE+ONE): the
  stencil test, the colour and, when z writes are on, the z write, without the z
  read and compare.

Compiled out of line (called once per row run of at least a tile's width): keeps
the band kernel's compile short and its loops unchanged.
"""

from __future__ import annotations

import numpy as np

from vgxsim.state.codes import (
    CBLEND_ADD,
    D_CBLEND,
    D_DZPASS,
    D_MODE,
    D_SMAX,
    D_STENCIL,
    D_ZMASK,
    D_ZWRITE,
    MODE_COLOUR,
    MODE_ZONLY,
    MODE_ZSTENCIL,
    MODE_ZSTENCIL_ADD,
    S_SFUNC,
    S_SMASK,
    S_SREF,
    S_WMPACK,
)

from .fragment import (
    add_sat,
    cmp_bits,
    cmp_select,
    colour_row,
    pack_rgba,
    pack_rgba_i32,
    round_z,
    round_z_i32,
    wrap_z24,
)
from .lit import lanes_ok, lit_span_lanes
from .options import callee, inline


@inline
def add_op_bytes(dpass, smax):
    """The arithmetic stencil op ``min(max(s + dpass, 0), smax)`` (``dpass`` in -1,
    0, 1) as ``uint8(min(max(s, lo), hi) + d)`` on a byte ``s`` (the add wraps
    modulo 256): INCR ``min(s, smax - 1) + 1``, DECR ``min(max(s, 1), smax + 1) - 1``,
    KEEP ``min(s, smax)``.  Equal for every byte ``s`` (values above ``smax``
    included) and ``smax`` in 1..255; every step stays inside a byte, so the loop
    runs on byte lanes.  Returns ``(lo, hi, d)`` as uint8."""
    if dpass > 0:
        return np.uint8(0), np.uint8(smax - 1), np.uint8(1)
    if dpass < 0:
        return np.uint8(1), np.uint8(min(smax + 1, 255)), np.uint8(255)
    return np.uint8(0), np.uint8(smax), np.uint8(0)


@callee
def z_passed_row(t, uy, xl, xr, za, dzdx, x0, y0, zmin, zmax, t_col, st, dv, tab, cbuf,
                 zbuf, sten, vector_pack, lit_lanes, sfree):
    """Row ``uy``, columns ``[xl, xr]`` of triangle ``t``, all inside a TILE_ZPASS
    run: every fragment passes the z test.  ``za`` is the row's depth at column
    ``x0`` (the span loops' expression); ``cbuf`` the one colour buffer
    MODE_COLOUR draws.  The values written are those of the span loops in
    :mod:`.render` for a passing fragment (``lit_lanes``: MODE_COLOUR rows on
    32-bit lanes where :func:`.lit.lanes_ok` allows; ``sfree``: their stencil test
    is known to pass, from the tiles' stencil bounds)."""
    mode = dv[D_MODE]
    if mode == MODE_ZSTENCIL_ADD:
        lo, hi, d = add_op_bytes(dv[D_DZPASS], dv[D_SMAX])
        if d == 0 and hi == 255:
            return  # ST_KEEP on 8 planes: nothing changes
        for x in range(xl, xr + 1):
            ux = np.uintp(x)
            sten[uy, ux] = np.uint8(min(max(sten[uy, ux], lo), hi) + d)
    elif mode == MODE_ZSTENCIL:
        for x in range(xl, xr + 1):
            ux = np.uintp(x)
            sten[uy, ux] = tab[0, sten[uy, ux]]
    elif mode == MODE_ZONLY:
        if vector_pack and zmin >= -2147483648 and zmax <= 2147483647:
            for x in range(xl, xr + 1):
                zbuf[uy, np.uintp(x)] = wrap_z24(round_z_i32(za + dzdx * (x - x0), zmin, zmax))
        else:
            for x in range(xl, xr + 1):
                zbuf[uy, np.uintp(x)] = wrap_z24(round_z(za + dzdx * (x - x0), zmin, zmax))
    elif mode == MODE_COLOUR:
        _colour_passed(t, uy, xl, xr, za, dzdx, x0, y0, zmin, zmax, t_col, st, dv, cbuf,
                       zbuf, sten, vector_pack, lit_lanes, sfree)


@callee
def _colour_passed(t, uy, xl, xr, za, dzdx, x0, y0, zmin, zmax, t_col, st, dv, cbuf, zbuf,
                   sten, vector_pack, lit_lanes, sfree):
    """MODE_COLOUR (blend replace or ONE+ONE) with the z test known to pass: the
    branch-free loop of render._colour_span without the z read and compare."""
    zwrite = dv[D_ZWRITE] != 0
    stest = dv[D_STENCIL] != 0 and not sfree
    add = dv[D_CBLEND] == CBLEND_ADD
    wm = st[S_WMPACK] & 0xFFFFFFFF
    keep = ~wm & 0xFFFFFFFF
    smask = st[S_SMASK]
    sref = st[S_SREF] & smask
    slt, seq, sgt = cmp_bits(st[S_SFUNC])
    y = np.int64(uy)
    ra, ga, ba, aa, rdx, gdx, bdx, adx = colour_row(t_col, t, y - y0)
    if vector_pack and lit_lanes and lanes_ok(xl, xr, x0, za, dzdx, zmin, zmax, ra, ga, ba,
                                              aa, rdx, gdx, bdx, adx):
        # The lit span loop on 32-bit lanes with the z test ZF_ALWAYS: it passes
        # here, so the fragment does what this function's loops do.
        lit_span_lanes(uy, xl, xr, za, dzdx, x0, zmin, zmax, ra, ga, ba, aa, rdx, gdx, bdx, adx,
                       True, True, True, zwrite, stest, slt, seq, sgt, smask, sref, add, wm,
                       dv[D_ZMASK], cbuf, zbuf, sten)
    elif not (vector_pack and zmin >= -2147483648 and zmax <= 2147483647):
        # The reference form (vector_pack off): int64 conversions, branches.
        for x in range(xl, xr + 1):
            ux = np.uintp(x)
            if stest and not cmp_select(slt, seq, sgt, sref, np.int64(sten[uy, ux]) & smask):
                continue
            if zwrite:
                zbuf[uy, ux] = wrap_z24(round_z(za + dzdx * (x - x0), zmin, zmax))
            dx = x - x0
            src = pack_rgba(ra + rdx * dx, ga + gdx * dx, ba + bdx * dx, aa + adx * dx)
            dst = np.int64(cbuf[uy, ux])
            out = add_sat(src, dst) if add else src
            cbuf[uy, ux] = (dst & keep) | (out & wm)
    elif stest and zwrite:
        for x in range(xl, xr + 1):
            ux = np.uintp(x)
            ok = cmp_select(slt, seq, sgt, sref, np.int64(sten[uy, ux]) & smask)
            zi = round_z_i32(za + dzdx * (x - x0), zmin, zmax)
            zbuf[uy, ux] = wrap_z24(zi) if ok else zbuf[uy, ux]
            dx = x - x0
            src = pack_rgba_i32(ra + rdx * dx, ga + gdx * dx, ba + bdx * dx, aa + adx * dx)
            dst = np.int64(cbuf[uy, ux])
            out = add_sat(src, dst) if add else src
            cbuf[uy, ux] = ((dst & keep) | (out & wm)) if ok else dst
    elif stest:
        for x in range(xl, xr + 1):
            ux = np.uintp(x)
            ok = cmp_select(slt, seq, sgt, sref, np.int64(sten[uy, ux]) & smask)
            dx = x - x0
            src = pack_rgba_i32(ra + rdx * dx, ga + gdx * dx, ba + bdx * dx, aa + adx * dx)
            dst = np.int64(cbuf[uy, ux])
            out = add_sat(src, dst) if add else src
            cbuf[uy, ux] = ((dst & keep) | (out & wm)) if ok else dst
    else:
        for x in range(xl, xr + 1):
            ux = np.uintp(x)
            if zwrite:
                zbuf[uy, ux] = wrap_z24(round_z_i32(za + dzdx * (x - x0), zmin, zmax))
            dx = x - x0
            src = pack_rgba_i32(ra + rdx * dx, ga + gdx * dx, ba + bdx * dx, aa + adx * dx)
            dst = np.int64(cbuf[uy, ux])
            out = add_sat(src, dst) if add else src
            cbuf[uy, ux] = (dst & keep) | (out & wm)
