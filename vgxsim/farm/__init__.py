"""Render farms: sweeps, spins and soft-shadow samples on Dask distributed.

Tasks (:mod:`.tasks`) are pure functions of scene, settings and a frame or sample
index; the scene is shipped to each worker once; results come back as arrays and are
put back in job order, so a farm run is bit-identical to the in-process run.  Soft
shadows are summed in accumulation-buffer units and reduced exactly
(:mod:`.exact`).  Dask is optional (``pip install vgxsim[dask]``) and imported only
when a :class:`DaskExecutor` is opened; :class:`LocalExecutor` runs the same tasks
in-process.

The names below are imported on first use, so ``vgxsim --help`` (which builds the
parsers of :mod:`.command`) loads neither Numba nor Dask.
"""

from __future__ import annotations

import importlib

_WHERE = {
    "DaskExecutor": "executor", "LocalExecutor": "executor", "open_executor": "executor",
    "FarmTaskError": "jobs", "soft_shadows": "jobs", "spin": "jobs",
    "ReductionError": "exact", "reduce_partials": "exact", "resolve": "exact",
    "TaskResult": "tasks", "Timing": "tasks",
    "load_config": "sweep", "run_sweep": "sweep",
}
__all__ = sorted(_WHERE)


def __getattr__(name: str):
    if name not in _WHERE:
        raise AttributeError(f"module 'vgxsim.farm' has no attribute {name!r}")
    return getattr(importlib.import_module(f".{_WHERE[name]}", __name__), name)
