"""kernels/decode.py assemble_triangles against vgxsim.geometry.assembly, the
per-primitive Python assembly (polygon fans, tmesh with swaptmesh, qstrips), on
random runs of primitives."""

import numpy as np

from vgxsim.geometry import assembly
from vgxsim.kernels.decode import assemble_triangles
from vgxsim.stream.opcodes import (
    P_KIND,
    P_SWAP0,
    P_SWAP1,
    P_V0,
    P_V1,
    PMV,
    POLYGON,
    PRIM_COLUMNS,
    QSTRIP,
    TMESH,
)


def _expected(block, base, swaps):
    tris, prov, recs = [], [], []
    for r, row in enumerate(block.tolist()):
        kind, v0, v1 = row[P_KIND], row[P_V0], row[P_V1]
        n = v1 - v0
        if kind in (POLYGON, PMV):
            t = assembly.polygon_fan(n)
            pv = np.full(t.shape[0], n - 1)
        elif kind == TMESH:
            t = assembly.tmesh_triangles(n, swaps[row[P_SWAP0]:row[P_SWAP1]].tolist())
            pv = t[:, 2]
        else:
            t = assembly.qstrip_triangles(n)
            pv = t.max(axis=1) if t.shape[0] else np.zeros(0, np.int64)
        off = v0 - base
        tris += (t + off).tolist()
        prov += (np.asarray(pv, np.int64) + off).tolist()
        recs += [r] * t.shape[0]
    return (np.array(tris, np.int64).reshape(-1, 3), np.array(prov, np.int64),
            np.array(recs, np.int64))


def test_assemble_triangles_matches_the_python_assembly():
    rng = np.random.default_rng(1991)
    for _ in range(200):
        rows, swaps = [], []
        base = int(rng.integers(0, 5))
        v = base
        for _ in range(int(rng.integers(0, 8))):
            kind = int(rng.choice([POLYGON, PMV, TMESH, QSTRIP]))
            n = int(rng.integers(0, 12))
            s0 = len(swaps)
            if kind == TMESH:
                swaps += sorted(rng.integers(0, n + 1, int(rng.integers(0, 4))).tolist())
            row = [0] * PRIM_COLUMNS
            row[P_KIND], row[P_V0], row[P_V1] = kind, v, v + n
            row[P_SWAP0], row[P_SWAP1] = s0, len(swaps)
            rows.append(row)
            v += n
        block = np.array(rows, np.int64).reshape(-1, PRIM_COLUMNS)
        sw = np.array(swaps, np.int64)
        got = assemble_triangles(block, base, sw)
        for g, w in zip(got, _expected(block, base, sw), strict=True):
            np.testing.assert_array_equal(g, w)
