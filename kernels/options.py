"""Numba decorator options for every vgxsim kernel, in one place.

* ``cache=True``: compiled code is reused across processes (cold vs warm start is
  benchmarked in bench/).
* ``fastmath`` is never set: raster and fragment code must be exact (no reassociation,
  no fused multiply-add, NaN/inf checks kept), see docs/numeric_model.md section 4.
* ``error_model='numpy'``: no Python exception checks for division in inner loops;
  every divisor is checked explicitly by the caller.
* ``nogil=True`` so that library users may render from several Python threads.
"""

from __future__ import annotations

import numba

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


def inline(func):
    """Small scalar helper: compiled into each caller, where LLVM inlines it.

    (Numba's IR-level ``inline='always'`` is kept for :func:`inline_ir` only: it
    multiplies compile time, and LLVM inlines small scalar functions anyway.)
    """
    return numba.njit(**{k: v for k, v in JIT_OPTIONS.items() if k != "cache"})(func)


def inline_ir(func):
    """Inline at the Numba IR level: for helpers that take many arrays, where a real
    call would pay reference-count updates on every array argument."""
    return numba.njit(inline="always", **{k: v for k, v in JIT_OPTIONS.items() if k != "cache"})(
        func
    )
