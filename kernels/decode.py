"""Decode the command stream into vertex and primitive arrays (one pass).

The stream (vgxsim/stream/opcodes.py) carries vertices and attribute changes the way
the VGX command FIFO did: a colour or normal call changes the current attribute and
every vertex after it takes that attribute.  This pass resolves the attributes of
every vertex and cuts the primitives, so that what follows (transform, lighting,
clipping, set-up) works on whole arrays.
"""

from __future__ import annotations

import numpy as np

from vgxsim.kernels.options import jit
from vgxsim.stream.opcodes import (
    BGN,
    CLEAR,
    CLEAR_KIND,
    CM,
    CRAW,
    CSKIP,
    END,
    P_CLEAR,
    P_KIND,
    P_LMCOLOR_SET,
    P_STATE,
    P_SWAP0,
    P_SWAP1,
    P_V0,
    P_V1,
    PRIM_COLUMNS,
    QSTRIP,
    STATE,
    SWAP,
    SYNC,
    TMESH,
    C,
    N,
    T,
    V,
)


@jit
def decode_stream(ops, nops, fl, attrs):
    """Resolve per-vertex attributes and cut primitives.

    Parameters
    ----------
    ops : ndarray, shape (>= nops,), int64
        Opcodes and their integer payloads.
    nops : int
        How many entries of ``ops`` are used.
    fl : ndarray, float64
        Float payloads, in stream order.
    attrs : ndarray, shape (11,), float64
        In: the attributes current at the start of the stream (r, g, b, a, nx, ny,
        nz, sent_normal, lmcolor_set, state, open kind or -1); out: at its end.

    Returns
    -------
    pos : ndarray, shape (V, 4), float64
    col : ndarray, shape (V, 4), float64
    nrm : ndarray, shape (V, 3), float64
    sent : ndarray, shape (V,), bool
        Whether the normal was sent after the last colour (lmcolor(3G)).
    prims : ndarray, shape (P, 7), int64
        Kind, first vertex, end vertex, state record, lmcolor_set, swap range (a
        CLEAR row: CLEAR_KIND, no vertices, its clear index in P_CLEAR).
    swaps : ndarray, shape (S,), int64
        swaptmesh positions (vertex counts from the primitive's first vertex).
    """
    nv = 0
    npr = 0
    nsw = 0
    i = 0
    while i < nops:  # first pass: sizes
        op = ops[i]
        if op == V:
            nv += 1
        elif op == END or op == CLEAR:
            npr += 1
        elif op == SWAP:
            nsw += 1
        i += 1 + _int_payload(op)
    pos = np.empty((nv, 4))
    col = np.empty((nv, 4))
    nrm = np.empty((nv, 3))
    sent = np.empty(nv, np.bool_)
    prims = np.empty((npr, PRIM_COLUMNS), np.int64)
    swaps = np.empty(nsw, np.int64)
    r, g, b, a = attrs[0], attrs[1], attrs[2], attrs[3]
    nx, ny, nz = attrs[4], attrs[5], attrs[6]
    sn = attrs[7] != 0.0
    lms = attrs[8] != 0.0
    state = int(attrs[9])
    kind = int(attrs[10])
    v0 = 0
    sw0 = 0
    iv = 0
    ip = 0
    isw = 0
    f = 0
    i = 0
    while i < nops:
        op = ops[i]
        if op == V:
            pos[iv, 0] = fl[f]
            pos[iv, 1] = fl[f + 1]
            pos[iv, 2] = fl[f + 2]
            pos[iv, 3] = fl[f + 3]
            col[iv, 0] = r
            col[iv, 1] = g
            col[iv, 2] = b
            col[iv, 3] = a
            nrm[iv, 0] = nx
            nrm[iv, 1] = ny
            nrm[iv, 2] = nz
            sent[iv] = sn
            iv += 1
            f += 4
        elif op == SYNC:
            r, g, b, a = fl[f], fl[f + 1], fl[f + 2], fl[f + 3]
            nx, ny, nz = fl[f + 4], fl[f + 5], fl[f + 6]
            sn = ops[i + 1] != 0
            lms = ops[i + 2] != 0
            f += 7
        elif op == C or op == CM or op == CSKIP or op == CRAW:
            if op == C:
                r, g, b, a = fl[f], fl[f + 1], fl[f + 2], fl[f + 3]
                sn = False
            elif op == CM:
                r, g, b, a = fl[f], fl[f + 1], fl[f + 2], fl[f + 3]
                lms = True
            f += 4
        elif op == N:
            nx, ny, nz = fl[f], fl[f + 1], fl[f + 2]
            sn = True
            f += 3
        elif op == BGN:
            kind = ops[i + 1]
            v0 = iv
            sw0 = isw
        elif op == END:
            prims[ip, P_KIND] = kind
            prims[ip, P_V0] = v0
            prims[ip, P_V1] = iv
            prims[ip, P_STATE] = state
            prims[ip, P_LMCOLOR_SET] = 1 if lms else 0
            prims[ip, P_SWAP0] = sw0
            prims[ip, P_SWAP1] = isw
            ip += 1
            kind = -1
        elif op == SWAP:
            swaps[isw] = iv - v0
            isw += 1
        elif op == STATE:
            state = ops[i + 1]
        elif op == CLEAR:
            # In drawing order among the primitives (a clear inside an open
            # primitive comes before it, which is drawn at its END).
            prims[ip, P_KIND] = CLEAR_KIND
            prims[ip, P_V0] = iv
            prims[ip, P_V1] = iv
            prims[ip, P_STATE] = state
            prims[ip, P_LMCOLOR_SET] = 0
            prims[ip, P_CLEAR] = ops[i + 1]
            prims[ip, P_SWAP1] = 0
            ip += 1
        elif op == T:
            f += 2  # texture coordinate: kernels/texture.py decode_texcoords reads it
        i += 1 + _int_payload(op)
    attrs[0], attrs[1], attrs[2], attrs[3] = r, g, b, a
    attrs[4], attrs[5], attrs[6] = nx, ny, nz
    attrs[7] = 1.0 if sn else 0.0
    attrs[8] = 1.0 if lms else 0.0
    attrs[9] = state
    attrs[10] = kind
    return pos, col, nrm, sent, prims, swaps


@jit
def _int_payload(op):
    if op == SYNC:
        return 2
    if op == BGN or op == STATE or op == CLEAR:
        return 1
    return 0


@jit
def assemble_triangles(block, base, swaps):
    """Triangles of consecutive triangle primitives (rows of the decoded primitive
    table), as vgxsim.geometry.assembly assembles each kind: a polygon (or pmv) is
    fanned from its first vertex, (0, i, i + 1), its last vertex provoking
    (shademodel(3G)); a tmesh keeps two saved vertices, each new one replacing the
    older, swaptmesh exchanging them (and the winding parity, so a fan faces one way),
    its newest vertex provoking; a qstrip makes (q, q + 1, q + 3) and (q, q + 3, q + 2)
    per quad, q + 3 provoking.

    Parameters
    ----------
    block : ndarray, shape (P, PRIM_COLUMNS), int64
    base : int
        Vertex index the returned indices count from.
    swaps : ndarray, shape (S,), int64
        The stream's swaptmesh positions (rows name their range, nondecreasing).

    Returns
    -------
    tris : ndarray, shape (T, 3), int64
    prov : ndarray, shape (T,), int64
        The flat-shading vertex of each triangle.
    recs : ndarray, shape (T,), int64
        The row of ``block`` each triangle comes from.
    """
    n = 0
    for r in range(block.shape[0]):
        count = block[r, P_V1] - block[r, P_V0]
        kind = block[r, P_KIND]
        if kind == QSTRIP:
            if count >= 4:
                n += 2 * ((count - 4) // 2 + 1)
        elif count >= 3:
            n += count - 2
    tris = np.empty((n, 3), np.int64)
    prov = np.empty(n, np.int64)
    recs = np.empty(n, np.int64)
    t = 0
    for r in range(block.shape[0]):
        kind = block[r, P_KIND]
        off = block[r, P_V0] - base
        count = block[r, P_V1] - block[r, P_V0]
        if kind == TMESH:
            # The decoder writes a primitive's swaps in stream order, which is
            # vertex order: already sorted, as assembly.tmesh_triangles sorts them.
            t = _tmesh(tris, prov, recs, t, r, off, count,
                       swaps[block[r, P_SWAP0]:block[r, P_SWAP1]])
        elif kind == QSTRIP:
            for q in range(0, count - 3, 2):
                tris[t, 0], tris[t, 1], tris[t, 2] = off + q, off + q + 1, off + q + 3
                tris[t + 1, 0], tris[t + 1, 1], tris[t + 1, 2] = off + q, off + q + 3, off + q + 2
                prov[t] = prov[t + 1] = off + q + 3
                recs[t] = recs[t + 1] = r
                t += 2
        else:
            for i in range(1, count - 1):
                tris[t, 0], tris[t, 1], tris[t, 2] = off, off + i, off + i + 1
                prov[t] = off + count - 1
                recs[t] = r
                t += 1
    return tris, prov, recs


@jit
def _tmesh(tris, prov, recs, t, r, off, count, swap_at):
    """One tmesh's triangles into rows ``t ..``; returns the next free row."""
    s0, s1 = -1, -1  # s0 is replaced next
    replace_slot = 0
    si = 0
    for v in range(count):
        while si < swap_at.shape[0] and swap_at[si] == v:
            s0, s1 = s1, s0
            if s0 >= 0 and s1 >= 0:
                replace_slot ^= 1
            si += 1
        if s0 >= 0 and s1 >= 0:
            if replace_slot == 0:
                tris[t, 0], tris[t, 1] = off + s0, off + s1
            else:
                tris[t, 0], tris[t, 1] = off + s1, off + s0
            tris[t, 2] = off + v
            prov[t] = off + v
            recs[t] = r
            t += 1
        if s0 < 0:
            s0 = v
        elif s1 < 0:
            s1 = v
        else:
            s0 = s1
            s1 = v
            replace_slot ^= 1
    return t
