"""Borrowed arrays: the band kernel's and the set-up's arrays without reference
counting (CommandBatch.borrow_arrays).

Numba counts references to an array's memory (its "meminfo") out of line
(NRT_incref / NRT_decref, atomic).  Every helper the band kernel and the set-up
inline at the IR level (kernels/options.py ``inline_ir``: ``_triangle_rows``,
``small_triangle``, ``_setup_one``, ...) binds its array arguments to new
variables, and each binding costs one increment and, on every way out, one
decrement; LLVM's reference-count pruning cannot pair them across the helpers'
branches.  Sampled on 200k 10-pixel triangles (perf, 1 thread), a third of a
flush's time sat on those atomic instructions: about twenty array arguments a
triangle, each counted up and down.

A first form of this module made views with a null meminfo: the counting
functions then return at once, but each binding still costs a call (they are
``noinline`` so that pruning can see them): the set-up loop kept 40 to 46 calls a
triangle (its assembly, 200k 10-pixel triangles).  :func:`borrow` now gives a
value of its own type, :class:`BorrowedArray`: the same layout as an array, but
its data model declares no meminfo, so Numba emits no counting at all for it --
not a call, not a compare (200k 10-pixel triangles, 1 thread, 7 alternating
pairs of runs, CPU ns a triangle: set-up 89 -> 46, band kernel 190 -> 124, the
whole draw 421 -> 324; on 2 threads 559 -> 389; the dense scene's frame 112 ->
92 ms CPU).  Everything an array does (indexing, shapes, views)
works on it unchanged: it is a ``types.Array`` subclass, and a view of one is a
plain array whose meminfo is null.

Such a value must not outlive the array it borrows from: a kernel borrows its
arguments (the caller holds them for the whole call) and its own scratch arrays,
which it keeps alive to its end with :func:`keep_alive`.  Nothing is copied and no
value changes; the switch exists because every fast path has one
(tests/kernels/test_borrow.py).  A variable must hold either borrowed or plain
arrays, never both (Numba would unify them to a plain array, counted again): the
kernels take the borrowed path through their own entry points
(kernels/setup.py ``setup_triangles_borrowed``, kernels/render.py
``render_bands_borrowed``), each compiled only when first used.
"""

from __future__ import annotations

from numba.core import cgutils, types
from numba.core.datamodel import models, register_default
from numba.extending import intrinsic


class BorrowedArray(types.Array):
    """An array type whose values carry no counted meminfo (see the module
    docstring).  Its views (``copy``) are plain arrays with a null meminfo."""

    def __init__(self, dtype, ndim, layout, readonly=False, aligned=True):
        kind = "borrowed readonly" if readonly else "borrowed"
        super().__init__(dtype, ndim, layout, readonly=readonly, aligned=aligned,
                         name=f"{kind}({dtype}, {ndim}d, {layout})")


@register_default(BorrowedArray)
class BorrowedArrayModel(models.StructModel):
    """numba's ArrayModel layout with the meminfo as a plain pointer: the same
    LLVM struct, but nothing the reference counting finds."""

    def __init__(self, dmm, fe_type):
        ndim = fe_type.ndim
        members = [
            ("meminfo", types.voidptr),
            ("parent", types.pyobject),
            ("nitems", types.intp),
            ("itemsize", types.intp),
            ("data", types.CPointer(fe_type.dtype)),
            ("shape", types.UniTuple(types.intp, ndim)),
            ("strides", types.UniTuple(types.intp, ndim)),
        ]
        super().__init__(dmm, fe_type, members)


@intrinsic
def borrow(typingctx, arr):
    """``arr`` as a :class:`BorrowedArray` of the same data, shape and strides, with
    a null meminfo and parent (valid while ``arr`` is alive; never return or store
    it)."""
    if not isinstance(arr, types.Array):
        return None
    out = BorrowedArray(arr.dtype, arr.ndim, arr.layout, readonly=not arr.mutable,
                        aligned=arr.aligned)

    def codegen(context, builder, signature, args):
        src = context.make_array(signature.args[0])(context, builder, args[0])
        dst = context.make_array(signature.return_type)(context, builder)
        dst.meminfo = cgutils.get_null_value(dst.meminfo.type)
        dst.parent = cgutils.get_null_value(dst.parent.type)
        dst.nitems = src.nitems
        dst.itemsize = src.itemsize
        dst.data = src.data
        dst.shape = src.shape
        dst.strides = src.strides
        return dst._getvalue()

    return out(arr), codegen


@intrinsic
def keep_alive(typingctx, a, b, c):
    """A use of ``a``, ``b`` and ``c`` that emits no code: called after the last use
    of views borrowed from them, it keeps Numba from releasing them earlier (it
    releases a variable after its last use)."""
    def codegen(context, builder, signature, args):
        return context.get_dummy_value()

    return types.void(a, b, c), codegen
