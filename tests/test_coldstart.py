"""The cold-start helper (vgxsim/coldstart.py) compiles what it promises.

It fails quietly by design (drawing never waits on it), so a broken helper only
shows as a slow first image: these tests run its script in a fresh process with an
empty Numba cache and read the cache it leaves.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import types as _types

import pytest

from vgxsim import coldstart
from vgxsim.geometry import pipeline


def _cached_kernels(cache: str) -> set[str]:
    """'module.function' of every kernel with a cache index under ``cache``."""
    names = set()
    for _, _, files in os.walk(cache):
        for f in files:
            if f.endswith(".nbi"):
                names.add(f.split("-")[0])
    return names


@pytest.mark.slow
def test_helper_caches_the_geometry_kernels_and_not_the_band_kernel(tmp_path):
    env = dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path), VGXSIM_PARALLEL_COMPILE="0")
    proc = subprocess.run([sys.executable, "-c", coldstart._GEOMETRY], env=env,
                          capture_output=True, text=True, timeout=1200)
    assert proc.returncode == 0, proc.stderr[-2000:]
    cached = _cached_kernels(str(tmp_path))
    # Context.draw_arrays and the IRIS GL calls: transform, clip, project, set-up;
    # the GL calls also decode a command stream; the tetrahedron's adjacency.  With
    # the fused front end (on by default) array-drawn triangles are transformed by
    # its one vertex pass instead of transform_points.
    transform = ("front.front_vertices" if pipeline.FUSED_FRONT
                 else "transform.transform_points")
    for name in (transform, "clip.clip_triangles", "clip.project_snap",
                 "setup.setup_triangles_states", "decode.decode_stream",
                 "adjacency.edge_adjacency", "adjacency.newell_normals"):
        assert name in cached, (name, sorted(cached))
    assert not any(n.startswith("render.") for n in cached), sorted(cached)


def test_switch_off_starts_no_helper(monkeypatch):
    started = []
    monkeypatch.setenv("VGXSIM_PARALLEL_COMPILE", "0")
    monkeypatch.setattr(coldstart, "_started", False)
    monkeypatch.setattr(coldstart.subprocess, "Popen", lambda *a, **k: started.append(a))
    coldstart.prepare(object)
    assert started == []


class _FakeKernel:
    """What the check reads of a dispatcher: its loaded signatures, its index path."""

    def __init__(self, signatures, index_path):
        self.signatures = signatures
        self._cache = _types.SimpleNamespace(
            _cache_file=_types.SimpleNamespace(_index_path=index_path))


@pytest.mark.parametrize("lean", [True, False])
@pytest.mark.parametrize("borrowed", [True, False])
def test_helper_starts_by_the_cache_of_the_kernel_the_batch_uses(monkeypatch, tmp_path,
                                                                 lean, borrowed):
    """The check reads the band kernel of the batch's own switches (lean_kernel,
    borrow_arrays: four copies, four cache entries).  It once read the plain lean
    copy while batches drew with the borrowed one, whose index it never found: every
    warm start ran the helper (a second process importing everything) and waited."""
    index = tmp_path / "kernel.nbi"
    asked, started = [], []

    class Batch:  # the in-process compile of a cold start does nothing here
        lean_kernel = lean
        borrow_arrays = borrowed
        kernel = None

        def __init__(self, fb):
            pass

        def add_clear(self, *args):
            pass

        def flush(self):
            pass

        @staticmethod
        def band_kernel(lean_, borrowed_):
            asked.append((lean_, borrowed_))
            return Batch.kernel

    class Helper:
        def __init__(self, *args, **kwargs):
            started.append(args)

        def wait(self, timeout=None):
            return 0

    monkeypatch.delenv("VGXSIM_PARALLEL_COMPILE", raising=False)
    monkeypatch.setattr(coldstart.os, "cpu_count", lambda: 2)
    monkeypatch.setattr(coldstart.subprocess, "Popen", Helper)
    for signatures, on_disk, helper in (([], False, 1), (["sig"], False, 0), ([], True, 0)):
        if on_disk:
            index.write_bytes(b"")
        Batch.kernel = _FakeKernel(signatures, str(index))
        started.clear()
        monkeypatch.setattr(coldstart, "_started", False)
        coldstart.prepare(Batch)
        assert len(started) == helper, (signatures, on_disk)
    assert set(asked) == {(lean, borrowed)}


@pytest.mark.parametrize("borrowed", [True, False])
def test_band_kernel_is_the_one_flush_calls(monkeypatch, borrowed):
    from vgxsim.batch import CommandBatch
    from vgxsim.state.planes import Framebuffer, PlaneConfig
    from vgxsim.state.raster import RasterState

    monkeypatch.setenv("VGXSIM_PARALLEL_COMPILE", "0")
    calls = []
    batch = CommandBatch(Framebuffer(PlaneConfig(8, 8, stencil=8)))
    batch.borrow_arrays = borrowed
    want = CommandBatch.band_kernel(True, borrowed)
    monkeypatch.setattr(CommandBatch, "band_kernel",
                        staticmethod(lambda lean, b: calls.append((lean, b)) or want))
    batch.add_clear(7, 0, 0, 0, RasterState(scissor=(0, 7, 0, 7)))
    batch.flush()
    assert calls == [(True, borrowed)]
    assert want.signatures  # the copy flush called was this one


# A cold `vgxsim shadows` with the helper: the kernels this process compiles, by
# tree (the kernel called from Python whose compile it was part of), on stdout; run
# again warm, the processes it started.
_MAIN_COMPILES = r"""
import json, subprocess, sys
_started = []
class _Popen(subprocess.Popen):
    def __init__(self, *a, **k):
        _started.append(a[0])
        super().__init__(*a, **k)
subprocess.Popen = _Popen
from numba.core import event
_stack, _roots = [], set()
class _Roots(event.Listener):
    def on_start(self, ev):
        f = ev.data["dispatcher"].py_func
        _stack.append(f.__module__ + "." + f.__qualname__)
    def on_end(self, ev):
        name = _stack.pop()
        if not _stack:
            _roots.add(name)
event.register("numba:compile", _Roots())
from vgxsim.cli import main
status = main(["shadows", "-o", sys.argv[1], "--size", "64x48"])
print("ROOTS " + json.dumps(sorted(_roots)))
print("STARTED " + json.dumps(len(_started)))
sys.exit(status)
"""


@pytest.mark.slow
@pytest.mark.skipif((os.cpu_count() or 1) < 2, reason="the helper needs two CPUs")
def test_cold_shadows_compiles_only_the_band_tree_in_process(tmp_path):
    """Everything but the band kernel (and the binning that feeds it) comes from the
    helper's cache: a kernel compiled here as well ran serially after the helper.
    Two did (docs/cold_start.md): light_transform_rows for the layout of a
    many-record flush, and the scene's edge adjacency, built before any batch."""
    env = dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path / "cache"))
    env.pop("VGXSIM_PARALLEL_COMPILE", None)
    proc = subprocess.run([sys.executable, "-c", _MAIN_COMPILES, str(tmp_path / "a.png")],
                          env=env, capture_output=True, text=True, timeout=1800)
    assert proc.returncode == 0, proc.stderr[-2000:]
    roots = json.loads(proc.stdout.split("ROOTS ")[-1].splitlines()[0])
    # The lean band kernel of the batch's array mode (CommandBatch.borrow_arrays):
    # compiled here, so the cache was cold indeed.
    from vgxsim.batch import CommandBatch

    lean = "render_bands_lean_borrowed" if CommandBatch.borrow_arrays else "render_bands_lean"
    assert "vgxsim.kernels.render." + lean in roots
    assert [r for r in roots if not r.startswith("vgxsim.kernels.render.")] == []
    assert json.loads(proc.stdout.split("STARTED ")[-1]) == 1  # the helper
    # Warm: every kernel loads from the cache, and no helper starts.
    proc = subprocess.run([sys.executable, "-c", _MAIN_COMPILES, str(tmp_path / "b.png")],
                          env=env, capture_output=True, text=True, timeout=600)
    assert proc.returncode == 0, proc.stderr[-2000:]
    assert json.loads(proc.stdout.split("ROOTS ")[-1].splitlines()[0]) == []
    assert json.loads(proc.stdout.split("STARTED ")[-1]) == 0


# The band kernel a first batch compiles (the one-clear flush of coldstart.prepare),
# alone, from an empty cache: every function compiled, with its CPU seconds.
_LEAN_COMPILES = r"""
import json, time
from numba.core import event
_rows, _stack = [], []
class _All(event.Listener):
    def on_start(self, ev):
        f = ev.data["dispatcher"].py_func
        _stack.append((f.__module__ + "." + f.__qualname__, time.process_time()))
    def on_end(self, ev):
        name, t = _stack.pop()
        _rows.append((name, time.process_time() - t))
event.register("numba:compile", _All())
from vgxsim.batch import CommandBatch
from vgxsim.state.planes import Framebuffer, PlaneConfig
from vgxsim.state.raster import RasterState
batch = CommandBatch(Framebuffer(PlaneConfig(8, 8, stencil=8)))
batch.add_clear(7, 0, 0, 0, RasterState(scissor=(0, 7, 0, 7)))
batch.flush()
print("COMPILES " + json.dumps(_rows))
"""


@pytest.mark.slow
def test_lean_band_kernel_compiles_none_of_the_paths_it_leaves_out(tmp_path):
    """render_bands_lean(_borrowed) prunes, before typing, every call lean_fits rules
    out.  A pruned call whose branch stays reachable (an `if not _FULL: pass` ahead
    of an elif chain) still compiles its callee: the SA+MSA spans did, ~2 s of CPU."""
    env = dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path), VGXSIM_PARALLEL_COMPILE="0")
    proc = subprocess.run([sys.executable, "-c", _LEAN_COMPILES], env=env,
                          capture_output=True, text=True, timeout=1200)
    assert proc.returncode == 0, proc.stderr[-2000:]
    names = {n for n, _ in json.loads(proc.stdout.split("COMPILES ")[-1])}
    assert "vgxsim.kernels.render.render_bands_lean_borrowed" in names  # a cold compile
    assert "vgxsim.kernels.tiles.classify_tiles" in names  # callees are listed
    left_out = ("render._general_row", "render._colour_span_slow", "render._fragment_run",
                "render._alpha_span", "lit.alpha_span_lanes", "texture.texture_fragment",
                "fragment.fragment", "fragment.blend_sa_msa")
    assert [n for n in names if n.split("kernels.")[-1] in left_out] == []
