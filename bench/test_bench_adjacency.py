"""Edge adjacency (the role of the 1991 .pdat precomputation) at >= 1 M triangles.

README of ``shadows``: "for some models this time was getting up around 30 seconds".
``python -m pytest bench/test_bench_adjacency.py --benchmark-enable`` times the Numba
kernel alone and the whole :func:`polyhedron_from_polygons` (kernel, Newell normals,
fan triangles) on a 1,000,000-triangle torus, and the cache read that replaces it.
"""

from __future__ import annotations

import numpy as np
import pytest
import trimesh

from vgxsim.formats.cache import read_cache, write_cache
from vgxsim.kernels.adjacency import ADJ_OK, edge_adjacency
from vgxsim.shadow.scene import _polygon_arrays, polyhedron_from_polygons


@pytest.fixture(scope="module")
def million():
    mesh = trimesh.creation.torus(1.0, 0.3, major_sections=1000, minor_sections=500)
    assert len(mesh.faces) == 1_000_000
    edge_adjacency(*_polygon_arrays(mesh.faces[:2]))  # compile outside the timing
    return mesh


def test_adjacency_kernel_1m_triangles(benchmark, million):
    start, flat = _polygon_arrays(np.asarray(million.faces))
    edges, faces, status, _ = benchmark(edge_adjacency, start, flat)
    assert status == ADJ_OK and len(edges) == 1_500_000


def test_polyhedron_build_1m_triangles(benchmark, million):
    poly = benchmark.pedantic(polyhedron_from_polygons, (million.vertices, million.faces, "t"),
                              rounds=3, iterations=1)
    assert poly.is_closed


def test_cache_read_1m_triangles(benchmark, million, tmp_path):
    poly = polyhedron_from_polygons(million.vertices, million.faces, "t")
    write_cache(tmp_path / "t.npz", poly, "0" * 64)
    back, _ = benchmark.pedantic(read_cache, (tmp_path / "t.npz", "t"), rounds=3, iterations=1)
    assert np.array_equal(back.edges, poly.edges)
