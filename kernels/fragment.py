"""Per-fragment operations in IRIS GL order (docs/numeric_model.md section 6).

alpha test -> stencil test -> z test -> stencil op (fail / pass / zpass) -> z write
-> blend or logicop -> write mask -> colour write, for each enabled draw buffer.

Stencil logic is table driven: for every state the batch precomputes, per 8-bit
stencil value s, the new value when the z test passes (or z is off) ``tab[0, s]``,
when it fails ``tab[1, s]``, and whether the stencil test passes ``tab[2, s]``.  The
ops, the reference, the masks, the INCR/DECR clamps and IRIS's rule that ``pass``
applies when z-buffering is off are all folded into those 768 bytes, so the inner
loops never branch on the op.
"""

from __future__ import annotations

import numpy as np

from .options import inline, jit

# Column indices of a state row; they must match vgxsim/state/raster.py ROW (checked
# by tests/kernels/test_state_layout.py).
S_ZBUFFER, S_ZFUNC, S_ZWRITEMASK, S_STENCIL = 0, 1, 2, 3
S_SREF, S_SFUNC, S_SMASK, S_SFAIL, S_SPASS, S_SZPASS, S_SWRITEMASK = 4, 5, 6, 7, 8, 9, 10
S_BLEND_SF, S_BLEND_DF, S_LOGICOP, S_WMPACK, S_AFUNC, S_AREF = 11, 12, 13, 14, 15, 16
S_SHADEMODEL, S_SUBPIXEL, S_CULL, S_DRAW_FRONT, S_DRAW_BACK = 17, 18, 19, 20, 21
S_LINEWIDTH, S_LINESTYLE, S_LSREPEAT, S_PNTSIZE = 22, 23, 24, 25
S_SX0, S_SX1, S_SY0, S_SY1 = 26, 27, 28, 29

# Derived per-state columns computed by derive_states().
D_MODE, D_COLOUR, D_ZTEST, D_ZWRITE, D_STENCIL, D_BLEND, D_ZMASK = 0, 1, 2, 3, 4, 5, 6
D_SWM, D_RGBA = 7, 8  # stencil write mask limited to the planes; colour needed at all
D_DZPASS, D_DZFAIL, D_SMAX = 9, 10, 11  # arithmetic stencil form (MODE_ZSTENCIL_ADD)
D_CBLEND = 12  # MODE_COLOUR blend kind: 0 replace, 1 add (ONE, ONE), 2 general
D_SIZE = 13
MODE_GENERAL = 0
MODE_ZSTENCIL = 1  # shadow-volume pass: z test, stencil update, no colour, no z write
MODE_ZONLY = 2  # depth-only pass: z test and full z write, no colour, no stencil
# Shadow-volume pass whose stencil ops are KEEP/INCR/DECR with an always-passing
# stencil test and a full write mask (Heidmann's case): the new value is
# clamp(s + delta, 0, smax), branch-free and vectorizable, instead of a table look-up.
MODE_ZSTENCIL_ADD = 3
# Colour pass with no stencil writes (stencil off, or a test whose ops change
# nothing), alpha test off, no logicop, one draw buffer: the lit pass of Heidmann's
# algorithm (stencil EQUAL, blend ONE+ONE) and ordinary shaded drawing.
MODE_COLOUR = 4

LO_SRC = 3
Z24_MASK = 0xFFFFFF


@inline
def cmp_pass(func, lhs, rhs):
    """SF_/ZF_/AF_ codes are bit masks of less (1), equal (2), greater (4)."""
    return ((func >> ((lhs >= rhs) + (lhs > rhs))) & 1) != 0


@inline
def _stencil_op(op, s, ref, smax):
    if op == 0:
        return s
    if op == 1:
        return 0
    if op == 2:
        return ref & smax
    if op == 3:
        return s + 1 if s < smax else smax
    if op == 4:
        return s - 1 if s > 0 else 0
    if op == 5:
        return (~s) & smax
    return s


@inline
def _op_delta(op):
    if op == 3:
        return 1
    if op == 4:
        return -1
    return 0


@jit
def derive_states(states, stencil_planes, has_colour, has_z):
    """Per-state derived data: fragment mode flags and stencil tables.

    Parameters
    ----------
    states : ndarray, shape (S, R), int64
        State-table rows (vgxsim/state/raster.py layout).
    stencil_planes : int
        Configured stencil planes (0-8).
    has_colour, has_z : bool
        Whether a colour buffer / z buffer is allocated.

    Returns
    -------
    derived : ndarray, shape (S, D_SIZE), int64
    tables : ndarray, shape (S, 3, 256), uint8
    """
    ns = states.shape[0]
    derived = np.zeros((ns, D_SIZE), dtype=np.int64)
    tables = np.zeros((ns, 3, 256), dtype=np.uint8)
    smax = (1 << stencil_planes) - 1
    for i in range(ns):
        st = states[i]
        ztest = has_z and st[S_ZBUFFER] != 0
        zmask = st[S_ZWRITEMASK] & Z24_MASK
        zwrite = ztest and zmask != 0
        sten = stencil_planes > 0 and st[S_STENCIL] != 0
        colour = has_colour and (st[S_WMPACK] & 0xFFFFFFFF) != 0 and (
            st[S_DRAW_FRONT] != 0 or st[S_DRAW_BACK] != 0
        )
        blend = (st[S_BLEND_SF] != 1 or st[S_BLEND_DF] != 0) or st[S_LOGICOP] != LO_SRC
        derived[i, D_COLOUR] = colour
        derived[i, D_ZTEST] = ztest
        derived[i, D_ZWRITE] = zwrite
        derived[i, D_STENCIL] = sten
        derived[i, D_BLEND] = blend
        derived[i, D_ZMASK] = zmask
        derived[i, D_SWM] = st[S_SWRITEMASK] & smax
        # Colour is interpolated only when written or when the alpha test reads it.
        derived[i, D_RGBA] = colour or st[S_AFUNC] != 7
        alpha_always = st[S_AFUNC] == 7
        derived[i, D_SMAX] = smax
        add_ok = (sten and st[S_SFUNC] == 7 and (st[S_SWRITEMASK] & smax) == smax
                  and st[S_SZPASS] in (0, 3, 4) and st[S_SPASS] in (0, 3, 4))
        if (not colour) and ztest and sten and (not zwrite) and alpha_always:
            derived[i, D_MODE] = MODE_ZSTENCIL_ADD if add_ok else MODE_ZSTENCIL
            derived[i, D_DZPASS] = _op_delta(st[S_SZPASS])
            derived[i, D_DZFAIL] = _op_delta(st[S_SPASS])
        elif (not colour) and ztest and (not sten) and zmask == Z24_MASK and alpha_always:
            derived[i, D_MODE] = MODE_ZONLY
        else:
            derived[i, D_MODE] = MODE_GENERAL
        if derived[i, D_MODE] == MODE_GENERAL and colour and alpha_always and (
                st[S_LOGICOP] == LO_SRC) and (st[S_DRAW_FRONT] != 0) != (st[S_DRAW_BACK] != 0) and (
                (not ztest) or (not zwrite) or zmask == Z24_MASK):
            derived[i, D_MODE] = MODE_COLOUR
            if st[S_BLEND_SF] == 1 and st[S_BLEND_DF] == 0:
                derived[i, D_CBLEND] = 0
            elif st[S_BLEND_SF] == 1 and st[S_BLEND_DF] == 1:
                derived[i, D_CBLEND] = 1
            else:
                derived[i, D_CBLEND] = 2
        ref = st[S_SREF]
        mask = st[S_SMASK]
        wm = st[S_SWRITEMASK] & smax
        for s in range(256):
            if not sten:
                tables[i, 0, s] = s
                tables[i, 1, s] = s
                tables[i, 2, s] = 1
                continue
            passed = cmp_pass(st[S_SFUNC], ref & mask, s & mask)
            if passed:
                r0 = _stencil_op(st[S_SZPASS] if ztest else st[S_SPASS], s, ref, smax)
                r1 = _stencil_op(st[S_SPASS], s, ref, smax)
            else:
                r0 = _stencil_op(st[S_SFAIL], s, ref, smax)
                r1 = r0
            tables[i, 0, s] = (s & ~wm) | (r0 & wm)
            tables[i, 1, s] = (s & ~wm) | (r1 & wm)
            tables[i, 2, s] = 1 if passed else 0
        if derived[i, D_MODE] == MODE_COLOUR and sten:
            for s in range(smax + 1):
                if tables[i, 0, s] != s or tables[i, 1, s] != s:
                    derived[i, D_MODE] = MODE_GENERAL
                    break
    return derived, tables


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
