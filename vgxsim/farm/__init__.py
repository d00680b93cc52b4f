"""Render farms: sweeps, spins and soft-shadow samples on Dask distributed.

Tasks (:mod:`.tasks`) are pure functions of scene, settings and a frame or sample
index; the scene is shipped to each worker once; results come back as arrays and are
put back in job order, so a farm run is bit-identical to the in-process run.  Soft
shadows are summed in accumulation-buffer units and reduced exactly
(:mod:`.exact`).  Dask is optional (``pip install vgxsim[dask]``) and imported only
when a :class:`DaskExecutor` is opened; :class:`LocalExecutor` runs the same tasks
in-process.
"""

from .exact import ReductionError, reduce_partials, resolve
from .executor import DaskExecutor, LocalExecutor, open_executor
from .jobs import FarmTaskError, soft_shadows, spin
from .tasks import TaskResult, Timing

__all__ = ["DaskExecutor", "FarmTaskError", "LocalExecutor", "ReductionError", "TaskResult",
           "Timing", "open_executor", "reduce_partials", "resolve", "soft_shadows", "spin"]
