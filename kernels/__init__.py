"""Numba kernels of vgxsim (installed as ``vgxsim.kernels``).

Kernels see only numpy arrays and integers, never Python objects; all validation
happens in the layers above.  Stage by stage:

* :mod:`.options`   -- the one place that sets Numba decorator options;
* :mod:`.transform` -- vertex transform with a row-independent rounding order;
* :mod:`.clip`      -- homogeneous clipping, divide, viewport and fixed-point snap;
* :mod:`.setup`     -- triangle setup: facing, culling, edges, interpolation planes;
* :mod:`.raster`    -- exact span (scanline) and edge-function coverage;
* :mod:`.lines`     -- points and lines expanded to fragments;
* :mod:`.fragment`  -- per-fragment operations in IRIS GL order;
* :mod:`.render`    -- binning and the band kernel that runs a whole batch (worker
  threads, see vgxsim/threads.py, each take bands of rows);
* :mod:`.accum`     -- accumulation-buffer operations;
* :mod:`.bvh`       -- bounding-volume hierarchy over triangles (the ray-cast oracle);
* :mod:`.raycast`   -- exact float64 ray casting: nearest hit, shadow segments and
  shadow-face crossing counts (:mod:`vgxsim.shadow.raycast` drives them).

Only relative imports are used here: this folder must never be importable as a
top-level ``kernels`` module (a different PyPI package has that name).
"""

# Before any kernel module is imported (their dispatchers pick a cache locator when
# decorated): every cached kernel is keyed by the content of all kernel sources.
# Then the start-up edits to Numba, each behind its own switch: the inliner copies
# IR in linear time (cold start, kernels/inline_copy.py), cache loads skip the
# registry refresh (warm start, kernels/lazy_refresh.py).
from . import cache_stamp as _cache_stamp
from . import inline_copy as _inline_copy
from . import lazy_refresh as _lazy_refresh

_cache_stamp.install()
_inline_copy.install()
_lazy_refresh.install()
