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

:func:`lit_span_lanes` (CommandBatch.lit_lanes) is the same loop on 32-bit lanes
(eight pixels per AVX2 vector where the int64 forms fill four), for spans whose
planes :func:`lanes_ok` bounds: no NaN or range tests (every value is finite and
below 9.2e18 there), colour clamped before a truncating conversion instead of
floored, the stencil and z compares on int32, one loop per (z write, blend)
pair, and the colour store through masks (a branch or a select on the loaded
word became a masked store, vpmaskmovd, microcoded on AMD).  Its asm (numba
inspect_asm): one 8-pixel body of ~150 instructions for Heidmann's lit pass
against ~250 per 8 pixels for :func:`lit_span`, whose stencil compare ran on
int64 lanes and packed the masks down again.
"""

from __future__ import annotations

import numpy as np

from .fragment import cmp_select, pack_rgba_i32, round_z_i32, wrap_z24
from .options import callee, inline, inline_ir

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


# Planes whose every value over a span stays below 2**61 in magnitude: |a| < 2**60
# and |dadx| < 2**28 with |x - x0| < 2**31 (the caller's window).  There every
# intermediate of ``(a + dadx*dx) + 0.5`` is finite and below 9.2e18, the range
# where channel_i32 and round_z_i32 reduce to a plain clamp (see lit_span_lanes).
LANES_A = 2.0 ** 60
LANES_D = 2.0 ** 28


@inline
def lanes_plane_ok(a, d):
    """``a``, ``d`` finite and within the bounds of :func:`lit_span_lanes`."""
    return (abs(a) < LANES_A) & (abs(d) < LANES_D)


@inline
def lanes_ok(xl, xr, x0, za, dzdx, zmin, zmax, ra, ga, ba, aa, rdx, gdx, bdx, adx):
    """Whether a span may run :func:`lit_span_lanes`: every plane within
    :func:`lanes_plane_ok`, ``|x - x0| < 2**31`` over ``[xl, xr]`` and the depth
    clamp within int32 (a few scalar tests per span)."""
    return (lanes_plane_ok(za, dzdx) & lanes_plane_ok(ra, rdx) & lanes_plane_ok(ga, gdx)
            & lanes_plane_ok(ba, bdx) & lanes_plane_ok(aa, adx)
            & (abs(np.float64(xl) - x0) < 2.0 ** 30) & (abs(np.float64(xr) - x0) < 2.0 ** 30)
            & (zmin >= -2147483648) & (zmax <= 2147483647))


@inline
def channel_clamp(c):
    """:func:`.fragment.channel_i32` for a finite ``c`` with ``|c + 0.5| < 9.2e18``,
    as an int32.  There ``floor(c + 0.5)`` is kept when in 1..255: ``c + 0.5``
    clamped above to 255 in float64, truncated to int32 (the floor of a
    non-negative value; ``[255, 256)`` and above give 255; a value below
    -2**31 gives INT32_MIN), then clamped below to 0 in int32 (negative values
    and (-1, 1) give 0, as the floor's do).  No NaN test, no floor, and the low
    clamp on eight lanes instead of four."""
    return max(np.int32(min(c + 0.5, 255.0)), np.int32(0))


@inline
def pack_lanes(dx, ra, ga, ba, aa, rdx, gdx, bdx, adx):
    """The packed 0xAABBGGRR source word at column offset ``dx`` (uint32)."""
    return np.uint32(np.uint32(channel_clamp(ra + rdx * dx))
                     | np.uint32(np.uint32(channel_clamp(ga + gdx * dx)) << 8)
                     | np.uint32(np.uint32(channel_clamp(ba + bdx * dx)) << 16)
                     | np.uint32(np.uint32(channel_clamp(aa + adx * dx)) << 24))


@inline
def add_sat_swar32(s, d):
    """:func:`add_sat_swar` on uint32 words, every step truncated to 32 bits."""
    low = np.uint32(np.uint32(s & np.uint32(0x7F7F7F7F)) + np.uint32(d & np.uint32(0x7F7F7F7F)))
    total = np.uint32(low ^ np.uint32(np.uint32(s ^ d) & np.uint32(0x80808080)))
    carry = np.uint32(np.uint32(np.uint32(s & d) | np.uint32(np.uint32(s | d) & ~total))
                      & np.uint32(0x80808080))
    return np.uint32(total | np.uint32(np.uint32(carry << 1) - np.uint32(carry >> 7)))


@inline
def mix_sa32(s, d, a):
    """:func:`.fragment.mix_sa` on int32 lanes: at most (255*255 + 127) * 32897 =
    2143305344 < 2**31, so no product overflows."""
    return np.int32(np.int32(np.int32(np.int32(s * a) + np.int32(d * np.int32(255 - a))
                                      + np.int32(127)) * np.int32(32897)) >> 23)


@inline
def blend_sa_msa32(src, dst):
    """blendfunction(BF_SA, BF_MSA) of two packed words on int32 lanes (the values of
    :func:`.fragment.blend_sa_msa`, whose components are those of ``src``)."""
    a = np.int32(src >> 24)
    out = np.uint32(mix_sa32(np.int32(src & np.uint32(0xFF)), np.int32(dst & np.uint32(0xFF)), a))
    for sh in (8, 16):
        out |= np.uint32(np.uint32(mix_sa32(np.int32((src >> sh) & np.uint32(0xFF)),
                                            np.int32((dst >> sh) & np.uint32(0xFF)), a)) << sh)
    return np.uint32(out | np.uint32(np.uint32(mix_sa32(a, np.int32(dst >> 24), a)) << 24))


@inline
def blend_lanes(ok, src, dst, add, wm32):
    """The word a pixel of :func:`lit_span_lanes` stores: ``(dst & ~wm) | (out &
    wm)`` where the tests passed (``out`` the source; ``add`` 1: its saturating sum
    with ``dst``; 2: blendfunction(BF_SA, BF_MSA)), else ``dst``, by masks only: the
    mask ``wm & -ok`` hides the select from LLVM, which would otherwise store
    through a masked store (vpmaskmovd: microcoded and slow on AMD)."""
    if add == 2:
        out = blend_sa_msa32(src, dst)
    elif add == 1:
        out = add_sat_swar32(src, dst)
    else:
        out = src
    mm = np.uint32(wm32 & np.uint32(np.uint32(0) - np.uint32(ok)))
    return np.uint32(np.uint32(dst & ~mm) | np.uint32(out & mm))


@inline
def z_keep(zmask):
    """The 24-bit z write mask ``zmask`` widened to 32 bits (``| 0xFF000000``): -1
    for the full mask that every z-writing state of these loops has
    (vgxsim/state/derive.py).  A value LLVM cannot fold to a constant: and-ed into
    a pass mask, it keeps the masked z store a plain store of a merged word."""
    return np.int32(np.int32(zmask) | np.int32(-16777216))


@inline_ir
def lanes_row(uy, xl, xr, za, dzdx, x0, zlo, zhi, ra, ga, ba, aa, rdx, gdx, bdx, adx,
              lt, eq, gt, zwrite, slt, seq, sgt, sm, sr, add, wms, cbuf, zbuf, sten):
    """One row of :func:`lit_span_lanes` (``zwrite``, ``add``: constants in each
    call, so each call is its own loop with no branch on them; ``add`` as in
    :func:`blend_lanes`; ``wms`` = (colour write mask as uint32, :func:`z_keep`'s
    -1): one argument, as an inlined call of more than 30 arguments compiles to
    CALL_FUNCTION_EX, which Numba cannot inline)."""
    wm32, zkeep = wms
    for x in range(xl, xr + 1):
        ux = np.uintp(x)
        dx = np.float64(np.int32(x)) - x0
        sok = cmp_select(slt, seq, sgt, sr, np.int32(sten[uy, ux] & sm))
        zi = np.int32(min(max(np.floor(za + dzdx * dx + 0.5), zlo), zhi))
        zb = zbuf[uy, ux]
        ok = sok & cmp_select(lt, eq, gt, zi, zb)
        if zwrite:
            # By masks, as the colour (blend_lanes): ``zw if ok else zb`` is a select
            # on the loaded word, which LLVM stores by vpmaskmovd (microcoded on
            # AMD); and-ing the run-time ``zkeep`` into the mask hides it.
            mz = np.int32(np.int32(np.int32(0) - np.int32(ok)) & zkeep)
            zw = np.int32(np.int32(np.int32(zi + np.int32(0x800000)) & np.int32(0xFFFFFF))
                          - np.int32(0x800000))
            zbuf[uy, ux] = np.int32(np.int32(zw & mz) | np.int32(zb & ~mz))
        src = pack_lanes(dx, ra, ga, ba, aa, rdx, gdx, bdx, adx)
        cbuf[uy, ux] = blend_lanes(ok, src, cbuf[uy, ux], add, wm32)


@callee
def lit_span_lanes(uy, xl, xr, za, dzdx, x0, zmin, zmax, ra, ga, ba, aa, rdx, gdx, bdx, adx,
                   lt, eq, gt, zwrite, stest, slt, seq, sgt, smask, sref, add, wm, zmask,
                   cbuf, zbuf, sten):
    """:func:`lit_span` on 32-bit lanes, for planes within :func:`lanes_plane_ok`
    (the caller checks, with ``|x - x0| < 2**31`` and zmin, zmax within int32);
    ``zmask`` the state's z write mask (D_ZMASK: the full 24 bits where ``zwrite``)."""
    zlo = np.float64(zmin)
    zhi = np.float64(zmax)
    wm32 = np.uint32(wm)
    wms = (wm32, z_keep(zmask))
    # The stencil test on int32 lanes: a byte's ``s & smask`` is ``s & (smask &
    # 0xFF)``, and a reference beyond 0..255 compares with every byte as -1 or 256
    # do.  Without the test, one that always passes: ``0 == (s & 0)``.
    sm = np.int32(smask & 0xFF if stest else 0)
    sr = np.int32(min(max(sref, -1), 256) if stest else 0)
    if not stest:
        slt, seq, sgt = False, True, False
    z0 = np.int32(0)
    if not stest and zwrite:
        # No stencil test (the ambient pass), or one known to pass (a lit pass over
        # tiles whose stencil bounds pass: kernels/tiles.py): the test's operands as
        # literals, so LLVM folds ``s & 0`` and the loop reads no stencil at all.
        if add:
            lanes_row(uy, xl, xr, za, dzdx, x0, zlo, zhi, ra, ga, ba, aa, rdx, gdx, bdx, adx,
                      lt, eq, gt, True, False, True, False, z0, z0, 1, wms, cbuf, zbuf, sten)
        else:
            lanes_row(uy, xl, xr, za, dzdx, x0, zlo, zhi, ra, ga, ba, aa, rdx, gdx, bdx, adx,
                      lt, eq, gt, True, False, True, False, z0, z0, 0, wms, cbuf, zbuf, sten)
    elif not stest and add and (not lt) and eq and (not gt):
        # Heidmann's lit pass at zfunction(ZF_EQUAL) where the stencil test passes.
        lanes_row(uy, xl, xr, za, dzdx, x0, zlo, zhi, ra, ga, ba, aa, rdx, gdx, bdx, adx,
                  False, True, False, False, False, True, False, z0, z0, 1, wms,
                  cbuf, zbuf, sten)
    elif zwrite:
        if add:
            lanes_row(uy, xl, xr, za, dzdx, x0, zlo, zhi, ra, ga, ba, aa, rdx, gdx, bdx, adx,
                      lt, eq, gt, True, slt, seq, sgt, sm, sr, 1, wms, cbuf, zbuf, sten)
        else:
            lanes_row(uy, xl, xr, za, dzdx, x0, zlo, zhi, ra, ga, ba, aa, rdx, gdx, bdx, adx,
                      lt, eq, gt, True, slt, seq, sgt, sm, sr, 0, wms, cbuf, zbuf, sten)
    elif add and (not lt) and eq and (not gt) and (not slt) and seq and (not sgt):
        # Heidmann's lit pass (zfunction(ZF_EQUAL), stencil EQUAL, ONE+ONE) with its
        # comparison codes as constants: one compare each instead of three and the
        # masks of their outcome bits (the same values).
        lanes_row(uy, xl, xr, za, dzdx, x0, zlo, zhi, ra, ga, ba, aa, rdx, gdx, bdx, adx,
                  False, True, False, False, False, True, False, sm, sr, 1, wms,
                  cbuf, zbuf, sten)
    elif add:
        lanes_row(uy, xl, xr, za, dzdx, x0, zlo, zhi, ra, ga, ba, aa, rdx, gdx, bdx, adx,
                  lt, eq, gt, False, slt, seq, sgt, sm, sr, 1, wms, cbuf, zbuf, sten)
    else:
        lanes_row(uy, xl, xr, za, dzdx, x0, zlo, zhi, ra, ga, ba, aa, rdx, gdx, bdx, adx,
                  lt, eq, gt, False, slt, seq, sgt, sm, sr, 0, wms, cbuf, zbuf, sten)


@callee
def alpha_span_lanes(uy, xl, xr, za, dzdx, x0, zmin, zmax, ra, ga, ba, aa, rdx, gdx, bdx, adx,
                     lt, eq, gt, zwrite, stest, slt, seq, sgt, smask, sref, wm, zmask, cbuf,
                     zbuf, sten):
    """render._alpha_span (blendfunction(BF_SA, BF_MSA), z test on) on 32-bit lanes,
    for spans :func:`lanes_ok` allows: the loop of :func:`lit_span_lanes` with the
    alpha blend of :func:`blend_sa_msa32`."""
    zlo = np.float64(zmin)
    zhi = np.float64(zmax)
    wm32 = np.uint32(wm)
    wms = (wm32, z_keep(zmask))
    sm = np.int32(smask & 0xFF if stest else 0)
    sr = np.int32(min(max(sref, -1), 256) if stest else 0)
    if not stest:
        slt, seq, sgt = False, True, False
    if zwrite:
        lanes_row(uy, xl, xr, za, dzdx, x0, zlo, zhi, ra, ga, ba, aa, rdx, gdx, bdx, adx,
                  lt, eq, gt, True, slt, seq, sgt, sm, sr, 2, wms, cbuf, zbuf, sten)
    else:
        lanes_row(uy, xl, xr, za, dzdx, x0, zlo, zhi, ra, ga, ba, aa, rdx, gdx, bdx, adx,
                  lt, eq, gt, False, slt, seq, sgt, sm, sr, 2, wms, cbuf, zbuf, sten)
