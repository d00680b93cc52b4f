"""Per-fragment operations in IRIS GL order (docs/numeric_model.md section 6).

alpha test -> stencil test -> z test -> stencil op (fail / pass / zpass) -> z write
-> blend or logicop -> write mask -> colour write, for each enabled draw buffer.

Stencil logic is table driven: for every state the batch precomputes, per 8-bit
stencil value s, the new value when the z test passes (or z is off) ``tab[0, s]``,
when it fails ``tab[1, s]``, and whether the stencil test passes ``tab[2, s]``.  The
ops, the reference, the masks, the INCR/DECR clamps and IRIS's rule that ``pass``
applies when z-buffering is off are all folded into those 768 bytes (built by
:mod:`vgxsim.state.derive`), so the inner loops never branch on the op.  Codes and
column indices come from :mod:`vgxsim.state.codes`.
"""

from __future__ import annotations

import numpy as np

from vgxsim.state.codes import (
    CMP_EQUAL_BIT,
    CMP_GREATER_BIT,
    CMP_LESS_BIT,
    D_COLOUR,
    D_STENCIL,
    D_ZMASK,
    D_ZTEST,
    D_ZWRITE,
    LO_SRC,
    S_AFUNC,
    S_AREF,
    S_BLEND_DF,
    S_BLEND_SF,
    S_DRAW_BACK,
    S_DRAW_FRONT,
    S_LOGICOP,
    S_WMPACK,
    S_ZFUNC,
    Z24_MASK,
)

from .options import inline, inline_ir


@inline
def cmp_bits(func):
    """The three outcome bits of a comparison code, for :func:`cmp_select`."""
    return ((func & CMP_LESS_BIT) != 0, (func & CMP_EQUAL_BIT) != 0,
            (func & CMP_GREATER_BIT) != 0)


@inline
def cmp_select(lt, eq, gt, lhs, rhs):
    """``lhs FUNC rhs`` from the bits of :func:`cmp_bits`: branch-free, so span loops
    that test z (or stencil) on every pixel vectorize (docs/numeric_model.md s. 6)."""
    return (lt & (lhs < rhs)) | (eq & (lhs == rhs)) | (gt & (lhs > rhs))


@inline
def cmp_pass(func, lhs, rhs):
    """``lhs FUNC rhs`` for one SF_/ZF_/AF_ code (the per-fragment form)."""
    lt, eq, gt = cmp_bits(func)
    return cmp_select(lt, eq, gt, lhs, rhs)


@inline
def _factor(f, is_src, s, d, sa, da):
    """One blend factor in 0..255 for a component (s, d) with alphas (sa, da)."""
    if f == 0:
        return 0
    if f == 1:
        return 255
    if f == 2:
        return d if is_src else s
    if f == 3:
        return 255 - (d if is_src else s)
    if f == 4:
        return sa
    if f == 5:
        return 255 - sa
    if f == 6:
        return da
    if f == 7:
        return 255 - da
    if f == 8:
        return min(sa, 255 - da)
    return 255


@inline
def _logic(op, s, d):
    r = 0
    if op & 1:
        r |= s & d
    if op & 2:
        r |= s & ~d
    if op & 4:
        r |= ~s & d
    if op & 8:
        r |= ~s & ~d
    return r & 0xFFFFFFFF


@inline
def combine(src, dst, sf, df, logicop, wm):
    """Blend (or logicop) a packed source word onto a packed destination word."""
    if logicop != LO_SRC:
        out = _logic(logicop, src, dst)
    elif sf == 1 and df == 0:
        out = src
    else:
        sa = (src >> 24) & 0xFF
        da = (dst >> 24) & 0xFF
        out = 0
        for sh in range(0, 32, 8):
            s = (src >> sh) & 0xFF
            d = (dst >> sh) & 0xFF
            if sh == 24 and sf == 8:
                fs = 255  # BF_MIN_SA_MDA scales only r, g, b
            else:
                fs = _factor(sf, True, s, d, sa, da)
            fd = _factor(df, False, s, d, sa, da)
            v = (s * fs + d * fd + 127) // 255
            if v > 255:
                v = 255
            out |= v << sh
    return (dst & ~wm & 0xFFFFFFFF) | (out & wm)


@inline
def add_sat(src, dst):
    """Per-byte saturating add of two packed words (blendfunction(BF_ONE, BF_ONE))."""
    out = 0
    for sh in range(0, 32, 8):
        v = ((src >> sh) & 0xFF) + ((dst >> sh) & 0xFF)
        out |= min(v, 255) << sh
    return out


@inline
def round_z(z, zmin, zmax):
    zi = np.int64(np.floor(z + 0.5))
    if zi < zmin:
        zi = zmin
    if zi > zmax:
        zi = zmax
    return zi


@inline
def round_c(c):
    v = np.int64(np.floor(c + 0.5))
    if v < 0:
        v = 0
    if v > 255:
        v = 255
    return v


@inline
def wrap_z24(zi):
    """A full-mask z write: the low 24 bits, as a signed 24-bit value."""
    return ((zi + 0x800000) & Z24_MASK) - 0x800000


@inline
def channel(c):
    """:func:`round_c` in a form span loops vectorize: ``floor(c + 0.5)`` clamped in
    float64 before the conversion.  Equal to ``round_c`` for every input, NaN and
    values beyond int64 included (there the x86 conversion gives INT64_MIN, so 0)."""
    f = np.floor(c + 0.5)
    f = f if (f > 0.0) & (f < 9.2e18) else 0.0  # '&', not 'and': no branch, so it vectorizes
    f = 255.0 if f > 255.0 else f
    return np.int64(f)


@inline
def mix_sa(s, d, sa):
    """blendfunction(BF_SA, BF_MSA) on one component: ``(s*sa + d*(255 - sa) + 127)
    // 255`` (s. 6) by a multiply and shift, exact over the whole range 0..65152."""
    return ((s * sa + d * (255 - sa) + 127) * 32897) >> 23


@inline_ir
def blend_sa_msa(dx, ra, ga, ba, aa, rdx, gdx, bdx, adx, dst):
    """The interpolated colour at column offset ``dx``, alpha-blended onto ``dst``.
    (Inlined in Numba's IR: too large for LLVM's inliner, and a call per pixel would
    stop the span loop from vectorizing.)"""
    a = channel(aa + adx * dx)
    out = mix_sa(channel(ra + rdx * dx), dst & 0xFF, a)
    out |= mix_sa(channel(ga + gdx * dx), (dst >> 8) & 0xFF, a) << 8
    out |= mix_sa(channel(ba + bdx * dx), (dst >> 16) & 0xFF, a) << 16
    return out | (mix_sa(a, (dst >> 24) & 0xFF, a) << 24)


@inline
def round_z_i32(z, zmin, zmax):
    """:func:`round_z` with the conversion in int32 (vectorizes on AVX2), for
    ``zmin``, ``zmax`` within int32 (the caller checks).  NaN and values outside
    [-2**63, 2**63) give INT64_MIN in ``round_z``'s int64 conversion (x86), so
    ``zmin``; everything else is clamped to [zmin, zmax] in float64 (exact: both
    bounds are integers below 2**53) before converting."""
    f = np.floor(z + 0.5)
    lo = np.float64(zmin)
    hi = np.float64(zmax)
    f = f if (f > -9223372036854775808.0) & (f < 9223372036854775808.0) else lo
    f = lo if f < lo else f
    f = hi if f > hi else f
    return np.int64(np.int32(f))


@inline
def channel_i32(c):
    """:func:`round_c` with the float->int conversion done in int32 after a float64
    clamp: AVX2 has a packed float64->int32 conversion (vcvttpd2dq) but none to
    int64, so span loops using this form vectorize the conversion.  Equal to
    ``round_c`` for every input: NaN and values from 2**63 up (where the int64
    conversion gives INT64_MIN, so 0) map to 0, everything else is clamped to
    0..255 before converting."""
    f = np.floor(c + 0.5)
    f = f if (f > 0.0) & (f < 9223372036854775808.0) else 0.0
    f = 255.0 if f > 255.0 else f
    return np.int64(np.int32(f))


@inline
def pack_rgba_i32(r, g, b, a):
    """:func:`pack_rgba` through :func:`channel_i32` (same words; vectorizes)."""
    return (channel_i32(r) | (channel_i32(g) << 8) | (channel_i32(b) << 16)
            | (channel_i32(a) << 24))


@inline
def pack_rgba(r, g, b, a):
    """Rounded, clamped 0..255 components packed as 0xAABBGGRR (cpack order)."""
    return round_c(r) | (round_c(g) << 8) | (round_c(b) << 16) | (round_c(a) << 24)


@inline
def colour_row(t_col, t, dy):
    """Colour planes of triangle ``t`` at row offset ``dy``: the four values at the
    plane origin's column and their x gradients (docs/numeric_model.md s. 4)."""
    return (t_col[t, 0, 0] + t_col[t, 0, 2] * dy, t_col[t, 1, 0] + t_col[t, 1, 2] * dy,
            t_col[t, 2, 0] + t_col[t, 2, 2] * dy, t_col[t, 3, 0] + t_col[t, 3, 2] * dy,
            t_col[t, 0, 1], t_col[t, 1, 1], t_col[t, 2, 1], t_col[t, 3, 1])


@inline
def write_z(old, zi, zmask):
    """Masked 24-bit two's-complement z write, sign-extended back to int32."""
    u = ((old & ~zmask) | (zi & zmask)) & Z24_MASK
    if u & 0x800000:
        u -= 0x1000000
    return u


@inline
def fragment(x, y, zi, rgba, st, dv, tab, front, back, zbuf, sten):
    """The general per-fragment path (one pixel, any state).

    Returns True when the fragment passed every test.  Indices are made unsigned:
    coordinates are inside the raster rectangle, and Numba then skips its
    negative-index wraparound code.
    """
    x = np.uintp(x)
    y = np.uintp(y)
    if st[S_AFUNC] != 7:
        if not cmp_pass(st[S_AFUNC], (rgba >> 24) & 0xFF, st[S_AREF]):
            return False
    s = 0
    if dv[D_STENCIL]:
        s = np.int64(sten[y, x])
        if tab[2, s] == 0:
            sten[y, x] = tab[0, s]
            return False
    if dv[D_ZTEST]:
        zb = np.int64(zbuf[y, x])
        if not cmp_pass(st[S_ZFUNC], zi, zb):
            if dv[D_STENCIL]:
                sten[y, x] = tab[1, s]
            return False
        if dv[D_ZWRITE]:
            zbuf[y, x] = write_z(zb, zi, dv[D_ZMASK])
    if dv[D_STENCIL]:
        sten[y, x] = tab[0, s]
    if dv[D_COLOUR]:
        wm = st[S_WMPACK] & 0xFFFFFFFF
        if st[S_DRAW_BACK]:
            back[y, x] = combine(
                rgba, np.int64(back[y, x]), st[S_BLEND_SF], st[S_BLEND_DF], st[S_LOGICOP], wm
            )
        if st[S_DRAW_FRONT]:
            front[y, x] = combine(
                rgba, np.int64(front[y, x]), st[S_BLEND_SF], st[S_BLEND_DF], st[S_LOGICOP], wm
            )
    return True
