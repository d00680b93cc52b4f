"""The adjacency cache and its Numba builder: pairs agree with an independent pairing,
the cache round-trips, and a stale cache is never used."""

from __future__ import annotations

import os

import numpy as np
import pytest
import trimesh

from vgxsim.formats import FormatError
from vgxsim.formats.cache import (
    cache_dir,
    file_sha256,
    load_model,
    read_cache,
    write_cache,
)
from vgxsim.formats.glo import GloModel, write_glo
from vgxsim.kernels.adjacency import (
    ADJ_NONMANIFOLD,
    ADJ_OK,
    ADJ_SAME_DIRECTION,
    edge_adjacency,
)
from vgxsim.shadow.scene import MeshError, _polygon_arrays, polyhedron_from_polygons


def python_pairs(polys) -> dict:
    """Independent pairing: {frozenset(a, b): {face traversing a->b, face b->a}}."""
    out: dict = {}
    for f, p in enumerate(polys):
        for i, a in enumerate(p):
            b = p[(i + 1) % len(p)]
            out.setdefault(frozenset((a, b)), []).append((f, a, b))
    return out


@pytest.mark.parametrize("mesh", [trimesh.creation.icosphere(subdivisions=3),
                                  trimesh.creation.torus(1.0, 0.3, 24, 12),
                                  trimesh.creation.box()])
def test_kernel_pairs_every_edge_with_its_two_faces(mesh):
    start, flat = _polygon_arrays(np.asarray(mesh.faces))
    edges, faces, status, where = edge_adjacency(start, flat)
    assert status == ADJ_OK and where == -1
    ref = python_pairs(mesh.faces.tolist())
    assert len(edges) == len(ref)
    for (a, b), (f, g) in zip(edges.tolist(), faces.tolist(), strict=True):
        sides = ref[frozenset((a, b))]
        assert (f, a, b) in sides and (g, b, a) in sides
    # trimesh's own count of unique edges
    assert len(edges) == len(mesh.edges_unique)


def test_kernel_open_mesh_and_errors():
    # two triangles sharing one edge: 5 edges, 4 on the boundary
    start, flat = _polygon_arrays(np.array([[0, 1, 2], [2, 1, 3]]))
    edges, faces, status, _ = edge_adjacency(start, flat)
    assert status == ADJ_OK and len(edges) == 5 and (faces[:, 1] < 0).sum() == 4
    # the second triangle wound the same way along the shared edge
    start, flat = _polygon_arrays(np.array([[0, 1, 2], [1, 2, 3]]))
    assert edge_adjacency(start, flat)[2] == ADJ_SAME_DIRECTION
    # three triangles on one edge
    start, flat = _polygon_arrays(np.array([[0, 1, 2], [1, 0, 3], [0, 1, 4]]))
    assert edge_adjacency(start, flat)[2] in (ADJ_NONMANIFOLD, ADJ_SAME_DIRECTION)
    start, flat = _polygon_arrays(np.array([[0, 1, 2], [1, 0, 3], [1, 0, 4]]))
    assert edge_adjacency(start, flat)[2] == ADJ_NONMANIFOLD
    with pytest.raises(MeshError, match="polygon 1"):
        polyhedron_from_polygons(np.zeros((4, 3)), [[0, 1, 2], [1, 2, 3]], "m")


def write_sphere(path) -> trimesh.Trimesh:
    mesh = trimesh.creation.icosphere(subdivisions=2)
    write_glo(path, GloModel.from_polygons(mesh.vertices, mesh.faces,
                                           vertex_normals=mesh.vertex_normals))
    return mesh


def same_polyhedron(a, b) -> bool:
    return all(np.array_equal(getattr(a, k), getattr(b, k)) for k in
               ("vertices", "polygons", "normals", "edges", "edge_faces", "triangles",
                "triangle_face", "vertex_normals"))


def test_cache_round_trip(tmp_path):
    glo = tmp_path / "ball.glo"
    write_sphere(glo)
    built = load_model(glo, use_cache=False)
    out = tmp_path / "ball.npz"
    write_cache(out, built, file_sha256(glo))
    back, src = read_cache(out, "ball")
    assert src == file_sha256(glo)
    assert same_polyhedron(built, back)
    assert same_polyhedron(built, load_model(out))  # a cache file is a model too


def test_load_model_writes_the_cache_keyed_by_content_and_never_uses_a_stale_one(tmp_path):
    glo = tmp_path / "ball.glo"
    write_sphere(glo)
    digest = file_sha256(glo)
    first = load_model(glo)
    entry = os.path.join(cache_dir(), digest + ".npz")
    assert os.path.isfile(entry)
    assert same_polyhedron(first, load_model(glo))  # served from the cache
    # change the source: a different key, so the old entry is not used
    mesh = trimesh.creation.icosphere(subdivisions=1)
    write_glo(glo, GloModel.from_polygons(mesh.vertices, mesh.faces))
    changed = load_model(glo)
    assert len(changed.vertices) == len(mesh.vertices) != len(first.vertices)
    # an entry whose stored hash does not match its key is ignored, not trusted
    write_cache(os.path.join(cache_dir(), file_sha256(glo) + ".npz"), first, "0" * 64)
    assert len(load_model(glo).vertices) == len(mesh.vertices)


def test_bad_cache_files(tmp_path):
    p = tmp_path / "x.npz"
    np.savez(p, a=np.zeros(3))
    with pytest.raises(FormatError, match="not a vgxsim adjacency cache"):
        read_cache(p, "x")
    p.write_bytes(b"garbage")
    with pytest.raises(FormatError, match="cannot read"):
        read_cache(p, "x")
