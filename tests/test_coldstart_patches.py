"""The start-up edits to Numba (kernels/inline_copy.py, kernels/lazy_refresh.py)
change nothing but time.

Each runs in fresh processes with its switch on and off: the linear IR copy must
give byte-identical LLVM IR, the lazy refresh must load the same kernels and draw
the same planes, and each must really be in force when on (a broken install would
otherwise pass as "identical to stock").
"""

from __future__ import annotations

import json
import os
import subprocess
import sys

import pytest

from vgxsim.kernels import inline_copy, lazy_refresh

# A kernel with a multi-block inline='always' callee used twice (what the band
# kernel does with _triangle_rows and _colour_span) and one allocation (NRT);
# outside kernels/, so Numba's own cache locator stores it.
_KERNEL = '''
import math

import numpy as np
from vgxsim.kernels.options import inline_ir, jit

@inline_ir
def _clamp_row(a, i, lo, hi):
    s = 0
    for j in range(a.shape[1]):
        v = a[i, j]
        if v < lo:
            v = lo
        elif v > hi:
            v = hi
        a[i, j] = v
        s += v
    return s

@jit
def kernel(a, lo, hi):
    out = np.zeros(a.shape[0], np.int64)
    for i in range(a.shape[0]):
        out[i] = _clamp_row(a, i, lo, hi) - _clamp_row(a, i, lo + 1, hi)
    s = 0.0
    for i in range(a.shape[0]):
        for j in range(a.shape[1]):
            s += math.sqrt(abs(a[i, j]))
    return out, s
'''

_RUN_KERNEL = '''
import json, sys
sys.path.insert(0, sys.argv[1])
import numpy as np
import tinykernel
from numba.core import ir
from numba.core.caching import Cache
from numba.core.inline_closurecall import InlineWorker
# Count the scope copies (the quadratic part of the stock inliner's IR copy).
scope_copies = [0]
def _count(self, protocol):
    scope_copies[0] += 1
    return object.__reduce_ex__(self, protocol)
ir.Scope.__reduce_ex__ = _count
a = (np.arange(24, dtype=np.int64).reshape(4, 6) * 7) % 19
out, s = tinykernel.kernel(a, 3, 15)
print(json.dumps({
    "ir": [tinykernel.kernel.inspect_llvm(sig) for sig in tinykernel.kernel.signatures]
          if sys.argv[2] == "ir" else [],
    "scope_copies": scope_copies[0], "out": out.tolist(), "sum": s, "a": a.tolist(),
    "hits": sum(tinykernel.kernel.stats.cache_hits.values()),
    # the edited methods in force (each keeps the stock one as __wrapped__)
    "inline": hasattr(InlineWorker.inline_ir, "__wrapped__"),
    "lazy": hasattr(Cache.load_overload, "__wrapped__"),
    "linalg_imported": "numba.np.linalg" in sys.modules,
}))
'''


def _run(code: str, env_extra: dict, *args: str, timeout: int = 600) -> dict:
    env = dict(os.environ, VGXSIM_PARALLEL_COMPILE="0", **env_extra)
    proc = subprocess.run([sys.executable, "-c", code, *args], env=env,
                          capture_output=True, text=True, timeout=timeout)
    assert proc.returncode == 0, proc.stderr[-3000:]
    return json.loads(proc.stdout.strip().splitlines()[-1])


@pytest.fixture
def tiny(tmp_path):
    (tmp_path / "tinykernel.py").write_text(_KERNEL)
    return tmp_path


def test_linear_inline_gives_the_same_llvm_ir(tiny, tmp_path):
    runs = {}
    for switch in ("1", "0"):
        cache = tmp_path / f"cache{switch}"  # empty: each process compiles
        runs[switch] = _run(_RUN_KERNEL, {"VGXSIM_LINEAR_INLINE": switch,
                                          "NUMBA_CACHE_DIR": str(cache)}, str(tiny), "ir")
    on, off = runs["1"], runs["0"]
    assert on["inline"] and not off["inline"]
    assert on["ir"] and on["ir"] == off["ir"]
    # the scope is copied a few times per IR copy, not once per block
    assert 0 < 4 * on["scope_copies"] <= off["scope_copies"]
    assert (on["out"], on["sum"], on["a"]) == (off["out"], off["sum"], off["a"])


def test_lazy_refresh_loads_the_same_kernel_without_the_registries(tiny, tmp_path):
    cache = {"NUMBA_CACHE_DIR": str(tmp_path / "cache")}
    cold = _run(_RUN_KERNEL, cache, str(tiny), "-")
    assert cold["hits"] == 0
    on = _run(_RUN_KERNEL, dict(cache, VGXSIM_LAZY_REFRESH="1"), str(tiny), "-")
    off = _run(_RUN_KERNEL, dict(cache, VGXSIM_LAZY_REFRESH="0"), str(tiny), "-")
    assert on["hits"] == off["hits"] == 1  # loaded, not compiled again
    assert on["lazy"] and not off["lazy"]
    # On: Numba's implementation modules were never imported (the time it saves).
    assert not on["linalg_imported"] and off["linalg_imported"]
    for key in ("out", "sum", "a"):
        assert on[key] == off[key] == cold[key]


def test_a_numba_whose_source_differs_is_left_stock(monkeypatch):
    from numba.core import caching
    from numba.core import inline_closurecall as icc

    for mod, attr in ((inline_copy, "_STOCK_SHA256"), (lazy_refresh, "_LOAD_SHA256")):
        monkeypatch.setattr(mod, "_installed", False)
        monkeypatch.setattr(mod, attr, "0" * 64)
    before = (icc.InlineWorker.inline_ir, caching.Cache.load_overload)
    assert not inline_copy.install()
    assert not lazy_refresh.install()
    assert (icc.InlineWorker.inline_ir, caching.Cache.load_overload) == before


# The first image's kernels (band kernel and geometry), compiled from an empty cache
# with each switch on and off, then loaded warm with each switch on and off.
_FIRST_IMAGE = '''
import hashlib, json, sys
from numba.core.dispatcher import Dispatcher
from vgxsim.geometry.transform import orthographic
from vgxsim.pipeline.context import Context
ctx = Context(64, 48, stencil=8)
ctx.matrices.load_projection(orthographic(-0.5, 63.5, -0.5, 47.5, -1, 1))
ctx.raster.set(zbuffer=True)
ctx.clear_planes(7, 0xff000000)
ctx.draw_arrays("polygon", [[3, 2, 0.5], [60, 5, -0.25], [30, 45, 0]],
                [[1, 0, 0, 1], [0, 1, 0, 1], [0, 0, 1, 1]])
ctx.flush()
fb = ctx.fb
ir = {}
if sys.argv[1] == "ir":
    for name, mod in sorted(sys.modules.items()):
        if name.startswith("vgxsim"):
            for attr, obj in sorted(vars(mod).items()):
                if isinstance(obj, Dispatcher) and obj.py_func.__module__ == name:
                    for sig, cres in obj.overloads.items():
                        ir[f"{name}.{attr}{sig}"] = hashlib.sha256(
                            cres.library.get_llvm_str().encode()).hexdigest()
print(json.dumps({"ir": ir, "planes": [hashlib.sha256(p.tobytes()).hexdigest()
                                        for p in (fb.front, fb.z, fb.stencil)],
                  "counters": ctx.raw_batch.counters.tolist()}))
'''


@pytest.mark.slow
def test_first_image_kernels_same_ir_and_planes_on_and_off(tmp_path):
    runs = {}
    for switch in ("1", "0"):
        env = {"NUMBA_CACHE_DIR": str(tmp_path / f"cache{switch}"), "NUMBA_NUM_THREADS": "1",
               "VGXSIM_LINEAR_INLINE": switch, "VGXSIM_LAZY_REFRESH": switch}
        runs[switch] = _run(_FIRST_IMAGE, env, "ir", timeout=1200)
    on, off = runs["1"], runs["0"]
    assert any("render_bands" in k for k in on["ir"])
    assert on["ir"] == off["ir"]
    for switch in ("1", "0"):
        warm = _run(_FIRST_IMAGE, {"NUMBA_CACHE_DIR": str(tmp_path / "cache1"),
                                   "VGXSIM_LAZY_REFRESH": switch}, "-")
        assert (warm["planes"], warm["counters"]) == (on["planes"], on["counters"])
    assert (on["planes"], on["counters"]) == (off["planes"], off["counters"])
