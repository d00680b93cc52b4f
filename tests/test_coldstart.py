"""The cold-start helper (vgxsim/coldstart.py) compiles what it promises.

It fails quietly by design (drawing never waits on it), so a broken helper only
shows as a slow first image: these tests run its script in a fresh process with an
empty Numba cache and read the cache it leaves.
"""

from __future__ import annotations

import os
import subprocess
import sys

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
