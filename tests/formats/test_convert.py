"""Conversion (bintoglo / glotopdat): every format trimesh reads, -f, and .glo -> cache."""

from __future__ import annotations

import numpy as np
import pytest
import trimesh

from vgxsim.formats import FormatError
from vgxsim.formats.cache import file_sha256, load_model, read_cache
from vgxsim.formats.convert import convert
from vgxsim.formats.glo import read_glo


def triangles_as_points(vertices, faces) -> set:
    """Each triangle as the rounded coordinates of its vertices, rotated to start at
    its smallest point (keeps the winding, forgets the numbering)."""
    out = set()
    for f in faces:
        pts = [tuple(np.round(vertices[i], 5)) for i in f]
        k = pts.index(min(pts))
        out.add(tuple(pts[k:] + pts[:k]))
    return out


@pytest.mark.parametrize("ext", ["obj", "stl", "ply", "off", "glb"])
def test_every_trimesh_format_converts_to_the_same_triangles(tmp_path, ext):
    mesh = trimesh.creation.icosphere(subdivisions=2)
    src = tmp_path / f"ball.{ext}"
    mesh.export(src)
    out = tmp_path / "ball.glo"
    convert(src, out)
    m = read_glo(out)
    faces = np.array([list(p) for p in m.polygons])
    assert triangles_as_points(m.vertices, faces) == triangles_as_points(mesh.vertices,
                                                                         mesh.faces)
    # welded: a closed mesh whose edges all have two polygons
    assert load_model(out, use_cache=False).is_closed


def test_flip_reverses_the_vertex_order(tmp_path):
    mesh = trimesh.creation.box()
    src = tmp_path / "box.obj"
    mesh.export(src)
    convert(src, tmp_path / "a.glo", normals="face")
    convert(src, tmp_path / "b.glo", flip=True, normals="face")
    a, b = read_glo(tmp_path / "a.glo"), read_glo(tmp_path / "b.glo")
    for pa, pb in zip(a.polygons, b.polygons, strict=True):
        assert list(pb) == list(pa)[::-1]
    assert np.array_equal(b.face_normals, -a.face_normals)
    # the Newell normals of the flipped box point inwards
    pa, pb = load_model(tmp_path / "a.glo"), load_model(tmp_path / "b.glo")
    centre = pa.vertices.mean(0)
    out_a = np.einsum("ij,ij->i", pa.normals, pa.face_points - centre)
    out_b = np.einsum("ij,ij->i", pb.normals, pb.face_points - centre)
    assert np.all(out_a > 0) and np.all(out_b < 0)


def test_glo_to_cache_is_keyed_by_the_source(tmp_path):
    mesh = trimesh.creation.icosphere(subdivisions=1)
    src = tmp_path / "ball.stl"
    mesh.export(src)
    convert(src, tmp_path / "ball.glo")
    convert(tmp_path / "ball.glo", tmp_path / "ball.npz")
    poly, digest = read_cache(tmp_path / "ball.npz", "ball")
    assert digest == file_sha256(tmp_path / "ball.glo")
    assert np.array_equal(poly.vertices, load_model(tmp_path / "ball.glo").vertices)


def test_bad_inputs(tmp_path):
    with pytest.raises(FormatError, match="no such mesh"):
        convert(tmp_path / "none.obj", tmp_path / "x.glo")
    bad = tmp_path / "bad.stl"
    bad.write_text("solid nothing\nendsolid\n")
    with pytest.raises(FormatError):
        convert(bad, tmp_path / "x.glo")
    mesh = trimesh.creation.box()
    mesh.export(tmp_path / "box.obj")
    with pytest.raises(FormatError, match="must end in"):
        convert(tmp_path / "box.obj", tmp_path / "box.txt")
    assert not (tmp_path / "x.glo").exists()
