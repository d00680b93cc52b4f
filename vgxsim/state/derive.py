"""Derived per-state data for the kernels: fragment mode and stencil tables.

Computed once per distinct state (cached across flushes), in numpy: a state table
holds a handful of distinct snapshots, so this is cheap, and keeping it out of
Numba removes a kernel from every cold start.  Columns (``S_*`` in, ``D_*`` out) and
codes come from :mod:`vgxsim.state.codes`.  The kernels that read these records are
checked pixel for pixel against the naive reference (tests/kernels), which derives
nothing: it applies the RasterState fields directly (docs/numeric_model.md s. 6).
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np

from . import codes as C

_S = np.arange(256, dtype=np.int64)


def _cmp(func: int, lhs, rhs):
    code = (lhs >= rhs).astype(np.int64) + (lhs > rhs).astype(np.int64)
    return ((func >> code) & 1) != 0


_CBLEND = {(C.BF_ONE, C.BF_ZERO): C.CBLEND_REPLACE, (C.BF_ONE, C.BF_ONE): C.CBLEND_ADD,
           (C.BF_SA, C.BF_MSA): C.CBLEND_SA_MSA}  # blends with a vectorized span loop
_ADD_OPS = (C.OP_KEEP, C.OP_INCR, C.OP_DECR)  # ops that are "add -1, 0 or +1, clamped"


def _op(op: int, s: np.ndarray, ref: int, smax: int) -> np.ndarray:
    if op == C.OP_ZERO:
        return np.zeros_like(s)
    if op == C.OP_REPLACE:
        return np.full_like(s, ref & smax)
    if op == C.OP_INCR:
        return np.minimum(s + 1, smax)
    if op == C.OP_DECR:
        return np.maximum(s - 1, 0)
    if op == C.OP_INVERT:
        return (~s) & smax
    return s


def _delta(op: int) -> int:
    return 1 if op == C.OP_INCR else (-1 if op == C.OP_DECR else 0)


@lru_cache(maxsize=8192)
def _derive_one(row: tuple, planes: int, has_colour: bool, has_z: bool):
    st = row
    d = np.zeros(C.D_SIZE, np.int64)
    smax = (1 << planes) - 1
    ztest = has_z and st[C.S_ZBUFFER] != 0
    zmask = st[C.S_ZWRITEMASK] & C.Z24_MASK
    zwrite = ztest and zmask != 0
    sten = planes > 0 and st[C.S_STENCIL] != 0
    colour = has_colour and (st[C.S_WMPACK] & 0xFFFFFFFF) != 0 and (
        st[C.S_DRAW_FRONT] != 0 or st[C.S_DRAW_BACK] != 0)
    alpha_always = st[C.S_AFUNC] == C.CMP_ALWAYS
    d[C.D_COLOUR] = colour
    d[C.D_ZTEST] = ztest
    d[C.D_ZWRITE] = zwrite
    d[C.D_STENCIL] = sten
    d[C.D_BLEND] = ((st[C.S_BLEND_SF] != C.BF_ONE or st[C.S_BLEND_DF] != C.BF_ZERO)
                  or st[C.S_LOGICOP] != C.LO_SRC)
    d[C.D_ZMASK] = zmask
    d[C.D_SWM] = st[C.S_SWRITEMASK] & smax
    d[C.D_RGBA] = colour or not alpha_always  # the alpha test reads alpha
    d[C.D_SMAX] = smax
    d[C.D_ZFAIL_NOOP] = not sten  # refined below from the stencil table
    add_ok = (sten and st[C.S_SFUNC] == C.CMP_ALWAYS and (st[C.S_SWRITEMASK] & smax) == smax
              and st[C.S_SZPASS] in _ADD_OPS and st[C.S_SPASS] in _ADD_OPS)
    if (not colour) and ztest and sten and (not zwrite) and alpha_always:
        d[C.D_MODE] = C.MODE_ZSTENCIL_ADD if add_ok else C.MODE_ZSTENCIL
        d[C.D_DZPASS] = _delta(st[C.S_SZPASS])
        d[C.D_DZFAIL] = _delta(st[C.S_SPASS])
    elif (not colour) and ztest and (not sten) and zmask == C.Z24_MASK and alpha_always:
        d[C.D_MODE] = C.MODE_ZONLY
    else:
        d[C.D_MODE] = C.MODE_GENERAL
    if (d[C.D_MODE] == C.MODE_GENERAL and colour and alpha_always
            and st[C.S_LOGICOP] == C.LO_SRC
            and (st[C.S_DRAW_FRONT] != 0) != (st[C.S_DRAW_BACK] != 0)
            and ((not ztest) or (not zwrite) or zmask == C.Z24_MASK)):
        d[C.D_MODE] = C.MODE_COLOUR
        sf, df = st[C.S_BLEND_SF], st[C.S_BLEND_DF]
        d[C.D_CBLEND] = _CBLEND.get((sf, df), C.CBLEND_GENERAL)
    if st[C.S_TEXTURE] != 0 and colour:
        d[C.D_MODE] = C.MODE_GENERAL  # the texture stage runs in the general path only
    tab = np.empty((3, 256), np.uint8)
    if not sten:
        tab[0] = _S
        tab[1] = _S
        tab[2] = 1
    else:
        ref, mask, wm = st[C.S_SREF], st[C.S_SMASK], st[C.S_SWRITEMASK] & smax
        passed = _cmp(st[C.S_SFUNC], ref & mask, _S & mask)
        fail = _op(st[C.S_SFAIL], _S, ref, smax)
        r0 = np.where(passed, _op(st[C.S_SZPASS] if ztest else st[C.S_SPASS], _S, ref, smax),
                      fail)
        r1 = np.where(passed, _op(st[C.S_SPASS], _S, ref, smax), fail)
        tab[0] = (_S & ~wm) | (r0 & wm)
        tab[1] = (_S & ~wm) | (r1 & wm)
        tab[2] = passed
        # A z-failing fragment applies tab[1] (the pass op, or fail when the stencil
        # test fails too); when that changes no value, failing the z test is a no-op.
        d[C.D_ZFAIL_NOOP] = bool((tab[1] == _S).all())
        if d[C.D_MODE] == C.MODE_COLOUR and (
                (tab[0, :smax + 1] != _S[:smax + 1]).any()
                or (tab[1, :smax + 1] != _S[:smax + 1]).any()):
            d[C.D_MODE] = C.MODE_GENERAL
    d.flags.writeable = False
    tab.flags.writeable = False
    return d, tab


def derive_states(states: np.ndarray, stencil_planes: int, has_colour: bool, has_z: bool):
    """Derived rows and stencil tables of a state table.

    Parameters
    ----------
    states : ndarray, shape (S, R), int64
    stencil_planes : int
    has_colour, has_z : bool

    Returns
    -------
    derived : ndarray, shape (S, D_SIZE), int64
    tables : ndarray, shape (S, 3, 256), uint8
    """
    rows = [_derive_one(tuple(int(v) for v in r), int(stencil_planes), bool(has_colour),
                        bool(has_z)) for r in states]
    return (np.ascontiguousarray(np.stack([r[0] for r in rows])),
            np.ascontiguousarray(np.stack([r[1] for r in rows])))
