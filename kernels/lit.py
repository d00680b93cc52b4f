"""The lit and ambient passes' span loop, compiled on its own (CommandBatch.lit_spans).

Heidmann's lit pass (Gouraud colour, zfunction(ZF_EQUAL), a stencil test,
blendfunction(BF_ONE, BF_ONE)) and the ambient pass (z test, replace) run the
branch-free span loop of :func:`.render._colour_span`.  Inside the band kernel
that loop vectorizes but runs at a third of its own speed: the kernel is one huge
function, and its other loops keep so many values live that LLVM spills the
loop's two dozen invariants (colour planes, masks, comparison bits) to the stack
and reloads them in every iteration (bench/fill_ab.py lit_spans).  Here the loop
is a function of its own, called once per row span of at least
:data:`LIT_MIN_SPAN` pixels (a call costs a few reference-count updates), and
two of its steps are cheaper, with the same values:

* the column offset ``x - x0`` converts ``x`` through int32 (``vcvtdq2pd``: AVX2
  has no packed int64 to float64 conversion, so the int64 form took four scalar
  conversions per vector); exact, as every column is below 2**31, so
  ``float64(int32(x)) == float64(x)``;
* blendfunction(BF_ONE, BF_ONE) adds the four bytes at once (:func:`add_sat_swar`)
  instead of byte by byte.

No branch on state inside the loop: the stencil test picks one of two loops, the
z write and the blend are selects on loop invariants, which LLVM takes out of the
loop (loop unswitching).
"""

from __future__ import annotations

import numpy as np

from .fragment import cmp_select, pack_rgba_i32, round_z_i32, wrap_z24
from .options import callee, inline

LIT_MIN_SPAN = 16  # shorter spans run the band kernel's own loop (no call)


@inline
def add_sat_swar(s, d):
    """Per-byte saturating add of two packed words ``s``, ``d`` in [0, 2**32), four
    bytes at once: equal to :func:`.fragment.add_sat`.  The low seven bits of each
    byte add without carrying into the next byte; the top bit is added by xor; a
    byte overflows when both top bits are set, or one is and the sum's is not (the
    carry out of bit 7); ``(carry << 1) - (carry >> 7)`` is 0xFF in each byte that
    did (no borrow crosses a byte)."""
    low = (s & 0x7F7F7F7F) + (d & 0x7F7F7F7F)
    total = low ^ ((s ^ d) & 0x80808080)
    carry = ((s & d) | ((s | d) & ~total)) & 0x80808080
    return total | ((carry << 1) - (carry >> 7))


@callee
def lit_span(uy, xl, xr, za, dzdx, x0, zmin, zmax, ra, ga, ba, aa, rdx, gdx, bdx, adx,
             lt, eq, gt, zwrite, stest, slt, seq, sgt, smask, sref, add, wm, keep, cbuf,
             zbuf, sten):
    """Row ``uy``, columns ``[xl, xr]``: stencil test (when ``stest``), z test
    (bits ``lt, eq, gt``), z write (``zwrite``), colour replace or ONE+ONE
    (``add``) through the write mask ``wm`` into ``cbuf``; ``zmin``, ``zmax``
    within int32 (the caller checks).  The values of render._colour_span's loop."""
    if stest:
        for x in range(xl, xr + 1):
            ux = np.uintp(x)
            dx = np.float64(np.int32(x)) - x0
            sok = cmp_select(slt, seq, sgt, sref, np.int64(sten[uy, ux]) & smask)
            zi = round_z_i32(za + dzdx * dx, zmin, zmax)
            zb = np.int64(zbuf[uy, ux])
            ok = sok & cmp_select(lt, eq, gt, zi, zb)
            zbuf[uy, ux] = wrap_z24(zi) if (ok & zwrite) else zb
            src = pack_rgba_i32(ra + rdx * dx, ga + gdx * dx, ba + bdx * dx, aa + adx * dx)
            dst = np.int64(cbuf[uy, ux])
            out = add_sat_swar(src, dst) if add else src
            cbuf[uy, ux] = ((dst & keep) | (out & wm)) if ok else dst
    else:  # no stencil test (and maybe no stencil plane: sten is a dummy, never read)
        for x in range(xl, xr + 1):
            ux = np.uintp(x)
            dx = np.float64(np.int32(x)) - x0
            zi = round_z_i32(za + dzdx * dx, zmin, zmax)
            zb = np.int64(zbuf[uy, ux])
            ok = cmp_select(lt, eq, gt, zi, zb)
            zbuf[uy, ux] = wrap_z24(zi) if (ok & zwrite) else zb
            src = pack_rgba_i32(ra + rdx * dx, ga + gdx * dx, ba + bdx * dx, aa + adx * dx)
            dst = np.int64(cbuf[uy, ux])
            out = add_sat_swar(src, dst) if add else src
            cbuf[uy, ux] = ((dst & keep) | (out & wm)) if ok else dst
