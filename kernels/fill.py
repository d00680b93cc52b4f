"""The z+stencil and depth-only passes' span loops, compiled on their own
(CommandBatch.fill_spans).

Heidmann's shadow-volume pass (z test, stencil(3G) ST_INCR / ST_DECR / ST_KEEP, no
colour, no z write: ``MODE_ZSTENCIL_ADD``) and the depth pass (z test and z write
only: ``MODE_ZONLY``) run a span loop per row.  Inside the band kernel those loops
vectorize but run several times slower than on their own (bench/fill_ab.py
fill_spans): as for the lit pass (:mod:`.lit`), the kernel is one huge function whose
other loops keep so many values live that LLVM spills the span loops' invariants
and reloads them on every vector.  Here each loop is a function of its own, called
once per row span of at least :data:`FILL_MIN_SPAN` pixels (shorter spans, the
edges of small triangles, keep the band kernel's own loop: no call).

The values are those of the band kernel's loops (``kernels/render.py``), with
every step on 32-bit lanes (eight pixels per AVX2 vector where int64 forms fill
four):

* the column offset ``x - x0`` converts ``x`` through int32 (exact: every column
  is below 2**31, so ``float64(int32(x)) == float64(x)``);
* the depth is :func:`.fragment.round_z_i32` (its NaN and range tests kept: the
  planes are not bounded here), compared with the stored int32 depth as int32
  (both within int32: the caller checks ``zmin``, ``zmax``);
* the arithmetic stencil op ``min(max(s + d, 0), smax)`` with ``d`` the z-pass or
  z-fail delta in -1..1 and ``s`` a byte: every value fits an int32 lane;
* the depth pass stores every pixel of the span, the new depth where the test
  passed and the loaded one elsewhere, through masks (``m = -passed``): a branch or
  a select on the loaded word becomes a masked store (vpmaskmovd), microcoded and
  slow on AMD.  Threads own disjoint rows, so storing a pixel's own value back
  changes nothing.
"""

from __future__ import annotations

import numpy as np

from .fragment import round_z_i32
from .lit import LANES_A, LANES_D, z_keep
from .options import callee, inline

FILL_MIN_SPAN = 16  # shorter spans run the band kernel's own loop (no call)


@inline
def cmp_mask(mlt, meq, mgt, a, b):
    """``a FUNC b`` on int32 lanes as a mask (-1 passes, 0 fails), from the outcome
    masks ``mlt, meq, mgt`` (-1 where the ZF_/SF_ code accepts less, equal,
    greater): the outcome of :func:`.fragment.cmp_select`, with each compare's
    mask used as it is (vpcmpgtd gives -1 / 0) instead of packed to bytes and back."""
    return np.int32(np.int32(np.int32(mlt & np.int32(-np.int32(a < b)))
                             | np.int32(meq & np.int32(-np.int32(a == b))))
                    | np.int32(mgt & np.int32(-np.int32(a > b))))


@inline
def z_bounded(za, dzdx, xl, xr, x0):
    """Whether ``za + dzdx*(x - x0) + 0.5`` is finite and below 2**61 in magnitude
    over ``[xl, xr]`` (the bounds of :func:`.lit.lanes_ok`): there
    :func:`.fragment.round_z_i32` is a plain clamp, without its NaN and range tests."""
    return ((abs(za) < LANES_A) & (abs(dzdx) < LANES_D) & (abs(np.float64(xl) - x0) < 2.0 ** 30)
            & (abs(np.float64(xr) - x0) < 2.0 ** 30))


@inline
def _masks(lt, eq, gt):
    """The outcome masks of :func:`cmp_mask` from :func:`.fragment.cmp_bits`."""
    return np.int32(-np.int32(lt)), np.int32(-np.int32(eq)), np.int32(-np.int32(gt))


@inline
def _stencil_add(s, passed, dp, df, sm):
    """``min(max(s + (dp if passed else df), 0), sm)`` on int32 lanes as a byte
    (``passed`` a mask of :func:`cmp_mask`)."""
    d = np.int32(np.int32(dp & passed) | np.int32(df & ~passed))
    return np.uint8(min(max(np.int32(np.int32(s) + d), np.int32(0)), sm))


@callee
def zstencil_span(uy, xl, xr, za, dzdx, x0, zmin, zmax, lt, eq, gt, dpass, dfail, smax,
                  zbuf, sten):
    """Row ``uy``, columns ``[xl, xr]`` of the z+stencil pass with an arithmetic
    stencil op: z test (bits ``lt, eq, gt``) of ``round_z_i32(za + dzdx*(x - x0))``
    against ``zbuf``, then ``sten = min(max(sten + (dpass if passed else dfail), 0),
    smax)``; ``zmin``, ``zmax`` within int32 (the caller checks)."""
    mlt, meq, mgt = _masks(lt, eq, gt)
    dp = np.int32(dpass)
    df = np.int32(dfail)
    sm = np.int32(smax)
    if z_bounded(za, dzdx, xl, xr, x0):
        zlo = np.float64(zmin)
        zhi = np.float64(zmax)
        for x in range(xl, xr + 1):
            ux = np.uintp(x)
            dx = np.float64(np.int32(x)) - x0
            zi = np.int32(min(max(np.floor(za + dzdx * dx + 0.5), zlo), zhi))
            passed = cmp_mask(mlt, meq, mgt, zi, zbuf[uy, ux])
            sten[uy, ux] = _stencil_add(sten[uy, ux], passed, dp, df, sm)
    else:
        for x in range(xl, xr + 1):
            ux = np.uintp(x)
            dx = np.float64(np.int32(x)) - x0
            zi = np.int32(round_z_i32(za + dzdx * dx, zmin, zmax))
            passed = cmp_mask(mlt, meq, mgt, zi, zbuf[uy, ux])
            sten[uy, ux] = _stencil_add(sten[uy, ux], passed, dp, df, sm)


@inline
def _z_store(zi, zb, passed, zkeep):
    """The word the depth pass stores: :func:`.fragment.wrap_z24` of ``zi`` where
    ``passed`` (a mask), else the loaded ``zb``.  ``zkeep`` is :func:`.lit.z_keep`'s
    -1, a run-time value: and-ed into the mask, it keeps LLVM from seeing a select
    on the loaded word, which it stores by vpmaskmovd."""
    m = np.int32(passed & zkeep)
    zw = np.int32(np.int32(np.int32(zi + np.int32(0x800000)) & np.int32(0xFFFFFF))
                  - np.int32(0x800000))
    return np.int32(np.int32(zw & m) | np.int32(zb & ~m))


@callee
def zonly_span(uy, xl, xr, za, dzdx, x0, zmin, zmax, lt, eq, gt, zmask, zbuf):
    """Row ``uy``, columns ``[xl, xr]`` of the depth-only pass: z test (bits ``lt,
    eq, gt``) and, where it passes, the full-mask z write of
    :func:`.fragment.wrap_z24` of ``round_z_i32(za + dzdx*(x - x0))``; ``zmin``,
    ``zmax`` within int32 (the caller checks); ``zmask`` the state's z write mask
    (D_ZMASK: the full 24 bits in MODE_ZONLY)."""
    mlt, meq, mgt = _masks(lt, eq, gt)
    zkeep = z_keep(zmask)
    if z_bounded(za, dzdx, xl, xr, x0):
        zlo = np.float64(zmin)
        zhi = np.float64(zmax)
        for x in range(xl, xr + 1):
            ux = np.uintp(x)
            dx = np.float64(np.int32(x)) - x0
            zi = np.int32(min(max(np.floor(za + dzdx * dx + 0.5), zlo), zhi))
            zb = zbuf[uy, ux]
            zbuf[uy, ux] = _z_store(zi, zb, cmp_mask(mlt, meq, mgt, zi, zb), zkeep)
    else:
        for x in range(xl, xr + 1):
            ux = np.uintp(x)
            dx = np.float64(np.int32(x)) - x0
            zi = np.int32(round_z_i32(za + dzdx * dx, zmin, zmax))
            zb = zbuf[uy, ux]
            zbuf[uy, ux] = _z_store(zi, zb, cmp_mask(mlt, meq, mgt, zi, zb), zkeep)
