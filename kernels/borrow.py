"""Borrowed array views: the band kernel's arrays without reference counting
(CommandBatch.borrow_arrays).

Numba counts references to an array's memory (its "meminfo") with atomic
increments and decrements, out of line (NRT_incref / NRT_decref).  Every helper the
band kernel inlines at the IR level (kernels/options.py ``inline_ir``:
``_triangle_rows``, ``small_triangle``, ...) binds its array arguments to new
variables, and each binding costs one atomic increment and, on every way out, one
decrement; LLVM's reference-count pruning cannot pair them across the helpers'
branches.  Sampled on 200k 10-pixel triangles (perf, 1 thread), a third of a
flush's time sat on those two atomic instructions: about twenty array arguments a
triangle, each counted up and down.

A view made here shares the array's data, shape and strides but has no meminfo
(and no parent object): Numba's counting functions return at once for a null
meminfo, so the same bindings cost a call and a compare.  Such a view must not
outlive the array it borrows from: the band kernel borrows its arguments (the
caller holds them for the whole call) and its own scratch arrays, which it keeps
alive to its end with :func:`keep_alive`.  Nothing is copied and no value
changes; the switch exists because every fast path has one
(tests/kernels/test_borrow.py).
"""

from __future__ import annotations

from numba.core import cgutils, types
from numba.extending import intrinsic


@intrinsic
def borrow(typingctx, arr):
    """``arr`` as a view of the same type with a null meminfo and parent (see the
    module docstring: valid while ``arr`` is alive; never return or store it)."""
    if not isinstance(arr, types.Array):
        return None

    def codegen(context, builder, signature, args):
        aryty = signature.args[0]
        src = context.make_array(aryty)(context, builder, args[0])
        dst = context.make_array(aryty)(context, builder)
        dst.meminfo = cgutils.get_null_value(dst.meminfo.type)
        dst.parent = cgutils.get_null_value(dst.parent.type)
        dst.nitems = src.nitems
        dst.itemsize = src.itemsize
        dst.data = src.data
        dst.shape = src.shape
        dst.strides = src.strides
        return dst._getvalue()

    return arr(arr), codegen


@intrinsic
def keep_alive(typingctx, a, b, c):
    """A use of ``a``, ``b`` and ``c`` that emits no code: called after the last use
    of views borrowed from them, it keeps Numba from releasing them earlier (it
    releases a variable after its last use)."""
    def codegen(context, builder, signature, args):
        return context.get_dummy_value()

    return types.void(a, b, c), codegen
