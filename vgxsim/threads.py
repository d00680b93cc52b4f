"""Worker threads for band-parallel rendering.

The kernels are compiled with ``nogil=True``, so ordinary Python threads run them in
parallel.  The thread count defaults to ``numba.config.NUMBA_NUM_THREADS`` (the
NUMBA_NUM_THREADS environment variable, else the number of CPUs) and follows
``numba.set_num_threads`` so existing Numba habits keep working; ``set_threads``
overrides it.  Output never depends on the count: bands are disjoint rows.
"""

from __future__ import annotations

from collections.abc import Sequence
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


def run_each(n: int, fn, items: Sequence) -> None:
    """``fn(item)`` for every item, on ``n`` threads: the caller and ``n - 1`` pool
    workers, each taking the next item not yet taken (in the order given) until none
    is left.

    The caller works instead of waiting, and each worker is one pool task however
    many items there are: a flush's bands cost no future, queue hand-off or thread
    wake-up each (measured: bench/flush_overhead.py).  Items must be independent
    (the bands of a flush are disjoint rows).  The first exception raised is
    re-raised in the caller once every thread has stopped.
    """
    it = iter(items)  # a list iterator's next() is atomic under the GIL

    def work() -> None:
        for item in it:
            fn(item)

    futures = [pool(n).submit(work) for _ in range(min(n, len(items)) - 1)]
    try:
        work()
    finally:
        for f in futures:
            f.result()
