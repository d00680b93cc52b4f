"""Derived per-state data for the kernels: fragment mode and stencil tables.

Computed once per distinct state (cached across flushes), in numpy: a state table
holds a handful of distinct snapshots, so this is cheap, and keeping it out of
Numba removes a kernel from every cold start.  The rules are those of
:func:`vgxsim.kernels.fragment.derive_states`, the compiled reference it is tested
against; the column layout is the kernels' (``D_*``).
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np

from vgxsim.kernels import fragment as F

_S = np.arange(256, dtype=np.int64)


def _cmp(func: int, lhs, rhs):
    code = (lhs >= rhs).astype(np.int64) + (lhs > rhs).astype(np.int64)
    return ((func >> code) & 1) != 0


def _op(op: int, s: np.ndarray, ref: int, smax: int) -> np.ndarray:
    if op == 1:
        return np.zeros_like(s)
    if op == 2:
        return np.full_like(s, ref & smax)
    if op == 3:
        return np.minimum(s + 1, smax)
    if op == 4:
        return np.maximum(s - 1, 0)
    if op == 5:
        return (~s) & smax
    return s


def _delta(op: int) -> int:
    return 1 if op == 3 else (-1 if op == 4 else 0)


@lru_cache(maxsize=8192)
def _derive_one(row: tuple, planes: int, has_colour: bool, has_z: bool):
    st = row
    d = np.zeros(F.D_SIZE, np.int64)
    smax = (1 << planes) - 1
    ztest = has_z and st[F.S_ZBUFFER] != 0
    zmask = st[F.S_ZWRITEMASK] & F.Z24_MASK
    zwrite = ztest and zmask != 0
    sten = planes > 0 and st[F.S_STENCIL] != 0
    colour = has_colour and (st[F.S_WMPACK] & 0xFFFFFFFF) != 0 and (
        st[F.S_DRAW_FRONT] != 0 or st[F.S_DRAW_BACK] != 0)
    alpha_always = st[F.S_AFUNC] == 7
    d[F.D_COLOUR] = colour
    d[F.D_ZTEST] = ztest
    d[F.D_ZWRITE] = zwrite
    d[F.D_STENCIL] = sten
    d[F.D_BLEND] = (st[F.S_BLEND_SF] != 1 or st[F.S_BLEND_DF] != 0) or st[F.S_LOGICOP] != F.LO_SRC
    d[F.D_ZMASK] = zmask
    d[F.D_SWM] = st[F.S_SWRITEMASK] & smax
    d[F.D_RGBA] = colour or not alpha_always  # the alpha test reads alpha
    d[F.D_SMAX] = smax
    add_ok = (sten and st[F.S_SFUNC] == 7 and (st[F.S_SWRITEMASK] & smax) == smax
              and st[F.S_SZPASS] in (0, 3, 4) and st[F.S_SPASS] in (0, 3, 4))
    if (not colour) and ztest and sten and (not zwrite) and alpha_always:
        d[F.D_MODE] = F.MODE_ZSTENCIL_ADD if add_ok else F.MODE_ZSTENCIL
        d[F.D_DZPASS] = _delta(st[F.S_SZPASS])
        d[F.D_DZFAIL] = _delta(st[F.S_SPASS])
    elif (not colour) and ztest and (not sten) and zmask == F.Z24_MASK and alpha_always:
        d[F.D_MODE] = F.MODE_ZONLY
    else:
        d[F.D_MODE] = F.MODE_GENERAL
    if (d[F.D_MODE] == F.MODE_GENERAL and colour and alpha_always
            and st[F.S_LOGICOP] == F.LO_SRC
            and (st[F.S_DRAW_FRONT] != 0) != (st[F.S_DRAW_BACK] != 0)
            and ((not ztest) or (not zwrite) or zmask == F.Z24_MASK)):
        d[F.D_MODE] = F.MODE_COLOUR
        sf, df = st[F.S_BLEND_SF], st[F.S_BLEND_DF]
        d[F.D_CBLEND] = 0 if (sf, df) == (1, 0) else (1 if (sf, df) == (1, 1) else 2)
    tab = np.empty((3, 256), np.uint8)
    if not sten:
        tab[0] = _S
        tab[1] = _S
        tab[2] = 1
    else:
        ref, mask, wm = st[F.S_SREF], st[F.S_SMASK], st[F.S_SWRITEMASK] & smax
        passed = _cmp(st[F.S_SFUNC], ref & mask, _S & mask)
        fail = _op(st[F.S_SFAIL], _S, ref, smax)
        r0 = np.where(passed, _op(st[F.S_SZPASS] if ztest else st[F.S_SPASS], _S, ref, smax),
                      fail)
        r1 = np.where(passed, _op(st[F.S_SPASS], _S, ref, smax), fail)
        tab[0] = (_S & ~wm) | (r0 & wm)
        tab[1] = (_S & ~wm) | (r1 & wm)
        tab[2] = passed
        if d[F.D_MODE] == F.MODE_COLOUR and (
                (tab[0, :smax + 1] != _S[:smax + 1]).any()
                or (tab[1, :smax + 1] != _S[:smax + 1]).any()):
            d[F.D_MODE] = F.MODE_GENERAL
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
