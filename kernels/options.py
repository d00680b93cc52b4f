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
    """Small helper inlined into its callers at the Numba IR level."""
    return numba.njit(inline="always", **{k: v for k, v in JIT_OPTIONS.items() if k != "cache"})(
        func
    )
