"""Where farm tasks run: in-process, on an embedded LocalCluster, or on a cluster.

Both executors take a list of jobs ``(fn, *args)`` and yield :class:`TaskResult` in
completion order; callers put results back by ``index``, so nothing downstream sees
which worker finished first.

Dask is imported only by :class:`DaskExecutor`: the package works without it.
"""

from __future__ import annotations

import os
import sys
import uuid
from collections.abc import Iterator, Mapping, Sequence
from typing import Any

from .tasks import TaskResult, Timing, run_measured, warm_up

RETRIES = 2  # re-runs of a task whose worker was lost (Dask's retries= per future)


def machine_cores() -> int:
    """CPUs this process may use (the LocalCluster's default worker count)."""
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # not Linux
        return os.cpu_count() or 1


def _bar(total: int, desc: str, enabled: bool):
    from tqdm import tqdm

    # disable=None: a bar only when stderr is a terminal
    return tqdm(total=total, desc=desc, unit="task", file=sys.stderr,
                disable=None if enabled else True)


class LocalExecutor:
    """Run jobs one after another in this process (``--local``)."""

    name = "in-process"

    def __init__(self, progress: bool = False) -> None:
        self.progress = progress
        self.workers = ["in-process"]

    def put(self, obj: Any) -> Any:
        """Make ``obj`` available to tasks (here: itself)."""
        return obj

    def warm_up(self, settings_list: Sequence[Mapping[str, Any]]) -> dict[str, float]:
        """Compile every kernel the settings use; seconds per worker."""
        return {"in-process": warm_up(list(settings_list))}

    def map(self, jobs: Sequence[tuple], desc: str = "tasks") -> Iterator[TaskResult]:
        """Run ``jobs`` (each ``(fn, *args)``); results in completion order."""
        with _bar(len(jobs), desc, self.progress) as bar:
            for i, (fn, *args) in enumerate(jobs):
                yield run_measured(i, fn, *args)
                bar.update(1)

    def close(self) -> None:
        """Nothing to release."""

    def __enter__(self) -> LocalExecutor:
        return self

    def __exit__(self, *exc) -> None:
        self.close()


class DaskExecutor:
    """Run jobs on Dask distributed.

    Parameters
    ----------
    scheduler : str, optional
        A scheduler address (``tcp://host:8786``).  None: start an embedded
        LocalCluster of ``n_workers`` single-threaded workers.
    n_workers : int, optional
        LocalCluster workers (default: the machine's cores).
    processes : bool
        LocalCluster workers as processes (True) or threads of this process (False:
        quick to start, but IRIS GL has one current window per process, so thread
        workers render one at a time -- the same pixels, no speed-up).
    threads : int
        Numba threads per task (1: one worker per core does the parallelism).
    retries : int
        Times Dask re-runs a task whose worker died.
    progress : bool
        Show a tqdm bar (on a terminal) as tasks complete.
    """

    def __init__(self, scheduler: str | None = None, n_workers: int | None = None,
                 processes: bool = True, threads: int = 1, retries: int = RETRIES,
                 progress: bool = False) -> None:
        from distributed import Client, LocalCluster

        self.threads = int(threads)
        self.retries = int(retries)
        self.progress = progress
        self.cluster = None
        if scheduler is None:
            n = n_workers or machine_cores()
            kw: dict[str, Any] = {}
            if processes:
                # NUMBA_NUM_THREADS must be set before numba is imported in the worker.
                kw["env"] = {"NUMBA_NUM_THREADS": str(self.threads),
                             "OMP_NUM_THREADS": "1"}
            self.cluster = LocalCluster(n_workers=n, threads_per_worker=1,
                                        processes=processes, dashboard_address=None,
                                        silence_logs=40, **kw)
            self.client = Client(self.cluster)
        else:
            self.client = Client(scheduler)
        self.name = "dask " + (f"LocalCluster ({n} {'processes' if processes else 'threads'})"
                               if self.cluster is not None else scheduler)

    @property
    def workers(self) -> list[str]:
        """Addresses of the workers now connected."""
        return sorted(self.client.scheduler_info()["workers"])

    def put(self, obj: Any):
        """Ship ``obj`` (a scene) for tasks: the returned future stands for it.

        Not ``client.scatter``: a scattered key that only lost workers held cannot be
        recovered, and the scheduler's active memory manager trims the replicas of a
        broadcast (a worker killed mid-sweep then failed every task that needed the
        scene: tests/farm/test_processes.py).  A task that returns ``obj`` is held by
        one worker, copied once to each worker whose tasks need it, and re-run from
        its spec (kept by the scheduler) if every holder dies."""
        return self.client.submit(_keep, obj, pure=False,
                                  key=f"{type(obj).__name__}-{uuid.uuid4().hex}")

    def warm_up(self, settings_list: Sequence[Mapping[str, Any]]) -> dict[str, float]:
        """One warm-up task pinned to each worker, run in the worker's executor thread
        (where tasks run) rather than its event loop, so a slow first compile does not
        stall heartbeats.  Returns seconds per worker."""
        settings = list(settings_list)
        futures = {w: self.client.submit(warm_up, settings, self.threads, workers=[w],
                                         allow_other_workers=False, pure=False,
                                         key=f"warm-up-{uuid.uuid4().hex}")
                   for w in self.workers}
        return {w: f.result() for w, f in futures.items()}

    def map(self, jobs: Sequence[tuple], desc: str = "tasks") -> Iterator[TaskResult]:
        """Submit ``jobs`` (each ``(fn, *args)``); results in completion order.

        A task that raised comes back as a :class:`TaskResult` with ``error`` (see
        :func:`run_measured`); a task Dask gave up on (its workers kept dying past
        ``retries``) too, so one bad job never ends the run."""
        from distributed import as_completed

        if not jobs:
            return
        tag = uuid.uuid4().hex[:8]
        index = {}
        futures = []
        for i, (fn, *args) in enumerate(jobs):
            fut = self.client.submit(run_measured, i, fn, *args, threads=self.threads,
                                     retries=self.retries, pure=False,
                                     key=f"{fn.__name__}-{tag}-{i}")
            index[fut.key] = i
            futures.append(fut)
        del fut  # as_completed holds the futures now; each is dropped once read
        with _bar(len(jobs), desc, self.progress) as bar:
            done = as_completed(futures)
            futures = []
            for fut in done:
                try:
                    result = fut.result()
                except Exception as exc:  # KilledWorker past the retries, lost data ...
                    result = TaskResult(index[fut.key], None, Timing("lost", 0.0, 0.0, -1),
                                        f"{type(exc).__name__}: {exc}")
                bar.update(1)
                yield result

    def close(self) -> None:
        """Close the client (and the embedded cluster)."""
        self.client.close()
        if self.cluster is not None:
            self.cluster.close()

    def __enter__(self) -> DaskExecutor:
        return self

    def __exit__(self, *exc) -> None:
        self.close()


def _keep(obj: Any) -> Any:
    """The shipped object itself (see :meth:`DaskExecutor.put`)."""
    return obj


def open_executor(scheduler: str | None = None, local: bool = False,
                  n_workers: int | None = None, processes: bool = True,
                  progress: bool = False):
    """The executor a command asked for: ``local`` in-process, else Dask (a scheduler
    address, or an embedded LocalCluster)."""
    if local:
        return LocalExecutor(progress=progress)
    return DaskExecutor(scheduler, n_workers=n_workers, processes=processes,
                        progress=progress)
