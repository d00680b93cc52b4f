"""Worker threads for band-parallel rendering.

The kernels are compiled with ``nogil=True``, so ordinary Python threads run them in
parallel.  The thread count defaults to ``numba.config.NUMBA_NUM_THREADS`` (the
NUMBA_NUM_THREADS environment variable, else the number of CPUs) and follows
``numba.set_num_threads`` so existing Numba habits keep working; ``set_threads``
overrides it.  Output never depends on the count: bands are disjoint rows.
"""

from __future__ import annotations

from concurrent.futures import ThreadPoolExecutor

import numba

_override: int | None = None
_pools: dict[int, ThreadPoolExecutor] = {}


def set_threads(n: int | None) -> None:
    """Use ``n`` render threads (None: follow numba.get_num_threads())."""
    global _override
    if n is not None and int(n) < 1:
        raise ValueError("set_threads: n must be at least 1")
    _override = None if n is None else int(n)


def get_threads() -> int:
    """Number of render threads in use."""
    return _override if _override is not None else numba.get_num_threads()


def pool(n: int) -> ThreadPoolExecutor:
    """A process-wide executor with ``n`` workers (created once per size)."""
    ex = _pools.get(n)
    if ex is None:
        ex = _pools[n] = ThreadPoolExecutor(max_workers=n, thread_name_prefix="vgxsim-band")
    return ex
