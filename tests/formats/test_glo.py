""".glo geometry: exact round trips, the three normal modes, lmbind records, and errors
that name the file and line."""

from __future__ import annotations

import numpy as np
import pytest

from vgxsim.formats import FormatError
from vgxsim.formats.glo import GloModel, read_glo, write_glo


def ragged_model(normals: str) -> GloModel:
    rng = np.random.default_rng(3)
    verts = rng.normal(size=(7, 3))
    polys = [[0, 1, 2], [2, 1, 3, 4], [4, 5, 6, 0, 2]]
    kw = {}
    if normals == "vertex":
        kw["vertex_normals"] = rng.normal(size=(7, 3))
    if normals == "face":
        kw["face_normals"] = rng.normal(size=(3, 3))
    m = GloModel.from_polygons(verts, polys, **kw)
    m.lmbind[:] = [0, 3, 3]
    return m


@pytest.mark.parametrize("normals", ["none", "face", "vertex"])
@pytest.mark.parametrize("suffix", [".glo", ".glo.gz"])
def test_write_then_read_is_exact(tmp_path, normals, suffix):
    m = ragged_model(normals)
    path = tmp_path / f"m{suffix}"
    write_glo(path, m, "a comment\non two lines")
    r = read_glo(path)
    assert r.normals == normals
    assert np.array_equal(r.vertices, m.vertices)  # repr round-trips float64 exactly
    assert np.array_equal(r.poly_start, m.poly_start)
    assert np.array_equal(r.poly_verts, m.poly_verts)
    assert np.array_equal(r.lmbind, [0, 3, 3])
    for a, b in ((r.face_normals, m.face_normals), (r.vertex_normals, m.vertex_normals)):
        assert (a is None and b is None) or np.array_equal(a, b)



def test_reads_the_documented_grammar(tmp_path):
    p = tmp_path / "tri.glo"
    p.write_text("# a triangle and a quad\n\nglo 1\nnormals face\nv 0 0 0\nv 1 0 0\n"
                 "v 1 1 0\nv 0 1 0\nlmbind 2\nf 1 2 3 / 0 0 1\nlmbind 0\nf 1 3 4 / 0 0 1\n")
    m = read_glo(p)
    assert m.vertices.shape == (4, 3)
    assert [list(x) for x in m.polygons] == [[0, 1, 2], [0, 2, 3]]
    assert m.lmbind.tolist() == [2, 0]
    assert np.array_equal(m.face_normals, [[0, 0, 1], [0, 0, 1]])


@pytest.mark.parametrize("text, line, words", [
    ("glo 2\n", 1, "header 'glo 1'"),
    ("# only a comment\n", None, "empty file"),
    ("glo 1\nv 0 0\n", 2, "v needs 3 numbers"),
    ("glo 1\nv 0 0 zero\n", 2, "expected numbers"),
    ("glo 1\nv 0 0 nan\n", 2, "finite"),
    ("glo 1\nv 0 0 0\nv 1 0 0\nf 1 2\n", 4, "at least 3"),
    ("glo 1\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", 5, "vertex number 4"),
    ("glo 1\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n", 5, "expected vertex numbers"),
    ("glo 1\nnormals face\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", 6, "'/ NX NY NZ'"),
    ("glo 1\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3 / 0 0 1\n", 5, "normals none"),
    ("glo 1\nv 0 0 0\nvn 0 0 1\n", 3, "expected 'normals vertex'"),
    ("glo 1\nv 0 0 0\nnormals vertex\n", 3, "before any v or f"),
    ("glo 1\nnormals sometimes\n", 2, "none, face or vertex"),
    ("glo 1\nlmbind -1\n", 2, "lmbind"),
    ("glo 1\nbgnpolygon\n", 2, "unknown record"),
    ("glo 1\nnormals vertex\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1 2 3\n", None,
     "3 vertices but 1 vn"),
    ("glo 1\nv 0 0 0\n", None, "no polygons"),
])
def test_errors_name_file_and_line(tmp_path, text, line, words):
    p = tmp_path / "bad.glo"
    p.write_text(text)
    with pytest.raises(FormatError) as info:
        read_glo(p)
    assert info.value.line == line and words in str(info.value)
    assert str(info.value).startswith(f"{p}:{line}:" if line else f"{p}:")


def test_binary_junk_and_missing_file(tmp_path):
    p = tmp_path / "junk.glo"
    p.write_bytes(b"\xff\xfe\x00\x01" * 10)
    with pytest.raises(FormatError, match="not a text .glo"):
        read_glo(p)
    with pytest.raises(FormatError, match="cannot open"):
        read_glo(tmp_path / "none.glo")


def test_failed_write_leaves_no_file(tmp_path):
    m = ragged_model("vertex")
    m.vertex_normals = None  # inconsistent: normals 'vertex' without any
    path = tmp_path / "out.glo"
    with pytest.raises(AttributeError):
        write_glo(path, m)
    assert list(tmp_path.iterdir()) == []
