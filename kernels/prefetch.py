"""Software prefetch of the plane rows a coming small triangle touches
(CommandBatch.prefetch_planes).

A band of a full window is larger than the second-level cache (1280 x 256 rows of
z and colour: 2.6 MB), and a flush of small triangles lands all over it: each
triangle's first read of a z and a colour row misses.  Sampled on 200k 10-pixel
triangles (perf, 1 thread), two thirds of the band kernel's time sat on the
instructions after those two loads.  The band kernel walks its primitives in
drawing order from records in band order, so it can read the box of the triangle
``PREFETCH_DISTANCE`` entries ahead and ask for its lines now: by the time that
triangle is drawn, its rows are on their way or in cache.

A prefetch is only a hint (LLVM's ``llvm.prefetch``: no fault, no value, no
ordering), so the planes cannot change; the switch exists to measure it and
because every fast path has one (tests/kernels/test_prefetch.py).
"""

from __future__ import annotations

from llvmlite import ir
from numba.core import cgutils, types
from numba.extending import intrinsic

from vgxsim.state.codes import D_RGBA, D_STENCIL, D_ZTEST, S_DRAW_BACK

from .options import inline_ir

PREFETCH_DISTANCE = 24  # entries ahead: several triangles' time covers a miss to memory
PREFETCH_MAX_ROWS = 8  # rows of a box prefetched (small triangles: the point of it)
PREFETCH_MAX_WIDTH = 32  # boxes wider than this are streamed by the hardware prefetcher


@intrinsic
def prefetch_item(typingctx, arr, y, x):
    """Hint that ``arr[y, x]`` (a 2-D array) will be read and written soon: LLVM's
    ``llvm.prefetch`` (write intent, high locality, data cache).  No bounds check
    and no access: the caller keeps ``y, x`` inside the array."""
    if not (isinstance(arr, types.Array) and arr.ndim == 2):
        return None
    sig = types.void(arr, y, x)

    def codegen(context, builder, signature, args):
        aryty = signature.args[0]
        ary = context.make_array(aryty)(context, builder, args[0])
        iy = context.cast(builder, args[1], signature.args[1], types.intp)
        ix = context.cast(builder, args[2], signature.args[2], types.intp)
        ptr = cgutils.get_item_pointer(context, builder, aryty, ary, [iy, ix],
                                       wraparound=False)
        i32 = ir.IntType(32)
        i8p = ir.IntType(8).as_pointer()  # one declaration for every element type
        ptr = builder.bitcast(ptr, i8p)
        fnty = ir.FunctionType(ir.VoidType(), [i8p, i32, i32, i32])
        fn = cgutils.get_or_insert_function(builder.module, fnty, "llvm.prefetch.p0")
        # (address, rw = 1: write, locality = 3: keep in every level, 1: data cache)
        builder.call(fn, [ptr, ir.Constant(i32, 1), ir.Constant(i32, 3), ir.Constant(i32, 1)])
        return context.get_dummy_value()

    return sig, codegen


@inline_ir
def _rows(plane, xl, xr, ylo, yhi):
    """Prefetch the lines of ``plane[ylo:yhi + 1, xl:xr + 1]`` (first and last
    column of each row: a small box spans one or two lines a row)."""
    for y in range(ylo, yhi + 1):
        prefetch_item(plane, y, xl)
        prefetch_item(plane, y, xr)


@inline_ir
def prefetch_box(t, s, y_lo, y_hi, t_box, states, derived, front, back, zbuf, sten):
    """Prefetch the rows of band ``[y_lo, y_hi]`` that triangle ``t`` (record
    ``t_box``, state ``s`` of ``states``, ``derived``) may read: z when it tests
    depth, colour when it needs colour (the buffer it draws), stencil when it is on.
    Only for a box at most ``PREFETCH_MAX_WIDTH`` wide; at most
    ``PREFETCH_MAX_ROWS`` rows.  (State values are read by index, not through row
    views: a view costs reference-count updates.)"""
    xl = max(t_box[t, 0], 0)
    xr = min(t_box[t, 1], max(front.shape[1], zbuf.shape[1]) - 1)
    ylo = max(t_box[t, 2], y_lo)
    yhi = min(min(t_box[t, 3], y_hi), ylo + PREFETCH_MAX_ROWS - 1)
    if xl > xr or ylo > yhi or xr - xl >= PREFETCH_MAX_WIDTH:
        return
    # Absent planes are (1, 1) dummies: the box's rows are not theirs.
    if derived[s, D_ZTEST] != 0 and zbuf.shape[0] > yhi and zbuf.shape[1] > xr:
        _rows(zbuf, xl, xr, ylo, yhi)
    if derived[s, D_RGBA] != 0:
        if states[s, S_DRAW_BACK] != 0:
            if back.shape[0] > yhi and back.shape[1] > xr:
                _rows(back, xl, xr, ylo, yhi)
        elif front.shape[0] > yhi and front.shape[1] > xr:
            _rows(front, xl, xr, ylo, yhi)
    if derived[s, D_STENCIL] != 0 and sten.shape[0] > yhi and sten.shape[1] > xr:
        _rows(sten, xl, xr, ylo, yhi)
