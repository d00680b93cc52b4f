"""Numba decorator options for every vgxsim kernel, in one place.

* ``cache=True``: compiled code is reused across processes (cold vs warm start is
  benchmarked in bench/).
* ``fastmath`` is never set: raster and fragment code must be exact (no reassociation,
  no fused multiply-add, NaN/inf checks kept), see docs/numeric_model.md section 4.
* ``error_model='numpy'``: no Python exception checks for division in inner loops;
  every divisor is checked explicitly by the caller.
* ``nogil=True`` so that library users may render from several Python threads.
* Helpers (:func:`inline`) compile once per argument *type*: Numba types a constant
  argument by its value (``Literal[int](0)``), so ``_edge(..., 0)``, ``_edge(..., 1)``
  and ``_edge(..., 2)`` would be three compiles of the same code; LLVM inlines the
  helper into its caller and propagates the constant there anyway (cold start,
  bench/startup.py --compiles).  Nor do they get the wrappers that let Python call a
  compiled function (``no_cpython_wrapper``, ``no_cfunc_wrapper``): only kernels
  call them, and the wrappers (argument unboxing for every array) cost more compile
  time than many helpers themselves.
"""

from __future__ import annotations

import numba
from numba.core import types
from numba.core.registry import CPUDispatcher

JIT_OPTIONS = {"cache": True, "nogil": True, "error_model": "numpy", "fastmath": False}


def jit(func=None, **overrides):
    """Serial kernel: ``numba.njit`` with the project's options."""
    opts = dict(JIT_OPTIONS, **overrides)
    if func is None:
        return lambda f: numba.njit(**opts)(f)
    return numba.njit(**opts)(func)


def parallel_jit(func=None, **overrides):
    """Parallel kernel (``prange`` over disjoint screen regions)."""
    opts = dict(JIT_OPTIONS, parallel=True, **overrides)
    if func is None:
        return lambda f: numba.njit(**opts)(f)
    return numba.njit(**opts)(func)


class _TypeDispatcher(CPUDispatcher):
    """A dispatcher whose callers' constant arguments are typed as their values'
    types (int64, bool, ...), not as literal values: one compile per signature."""

    def get_call_template(self, args, kws):
        args = tuple(types.unliteral(a) for a in args)
        kws = {k: types.unliteral(v) for k, v in kws.items()}
        return super().get_call_template(args, kws)

    def __call__(self, *args, **kws):
        # Compiled without a Python wrapper: a call from Python would jump to a null
        # address.  Kernels call it through Numba's typing, never through here.
        raise TypeError(f"{self.py_func.__qualname__} is a kernel helper: call it from a "
                        "Numba kernel (or set NUMBA_DISABLE_JIT=1), not from Python")


def _kernel_only(func, cache: bool):
    """``func`` compiled for calls from kernels only (see :class:`_TypeDispatcher`)."""
    if numba.config.DISABLE_JIT:  # as numba.njit does: the plain Python function
        return func
    opts = {k: v for k, v in JIT_OPTIONS.items() if k != "cache"}
    opts.update(nopython=True, boundscheck=None, no_cpython_wrapper=True,
                no_cfunc_wrapper=True)
    disp = _TypeDispatcher(py_func=func, locals={}, targetoptions=opts)
    if cache:
        disp.enable_caching()
    return disp


def inline(func):
    """Small scalar helper: compiled into each caller, where LLVM inlines it.

    (Numba's IR-level ``inline='always'`` is kept for :func:`inline_ir` only: it
    multiplies compile time, and LLVM inlines small scalar functions anyway.)
    Not cached on its own (it lives in its callers' cache entries), compiled once
    per argument types whatever constants it is called with, and callable from
    kernels only (no Python wrapper).
    """
    return _kernel_only(func, cache=False)


def callee(func):
    """A kernel that only other kernels call (a rare path compiled out of line):
    cached like :func:`jit`, but without the Python wrapper (as :func:`inline`)."""
    return _kernel_only(func, cache=True)


def inline_ir(func):
    """Inline at the Numba IR level: for helpers that take many arrays, where a real
    call would pay reference-count updates on every array argument."""
    return numba.njit(inline="always", **{k: v for k, v in JIT_OPTIONS.items() if k != "cache"})(
        func
    )
