"""Boxes and placements built in numpy (vgxsim/shadow/rigid.py) against trimesh.

The default scene's cubes were trimesh boxes; rigid.py computes them without
importing trimesh (warm start, issue 7 item 4).  trimesh is the independent
expectation here: the vertices must be the same floats and the polygons the same
loops, so every image of a scene made of boxes is unchanged.
"""

from __future__ import annotations

import numpy as np
import pytest

creation = pytest.importorskip("trimesh.creation")
from trimesh import transformations as tr  # noqa: E402

from vgxsim.shadow import rigid  # noqa: E402
from vgxsim.shadow.scene import (  # noqa: E402
    make_box,
    make_grid_box,
    polyhedron_from_trimesh,
)


def _trimesh_transform(position, rotate, scale=(1.0, 1.0, 1.0)):
    """translate; rotate x; rotate y; rotate z; scale -- with trimesh's matrices."""
    m = tr.translation_matrix(position)
    for ang, axis in zip(rotate, np.eye(3), strict=True):
        m = m @ tr.rotation_matrix(np.radians(ang), axis)
    return m @ np.diag([*scale, 1.0])


def _placements(n=40, seed=7):
    rng = np.random.default_rng(seed)
    fixed = [((1.0, 1.0, 1.0), (0.0, 0.0, 0.0), (0.0, 0.0, 0.0)),  # identity: no transform
             ((1.4, 1.4, 1.4), (-1.3, 0.7, 0.2), (0.0, 25.0, 0.0)),
             ((0.8, 0.8, 0.8), (0.0, 2.4, 0.45), (35.0, 40.0, 0.0)),
             ((2.0, 0.5, 1.0), (0.0, 0.0, 0.0), (90.0, 180.0, -270.0))]
    rand = [(tuple(rng.uniform(0.05, 6.0, 3)), tuple(rng.uniform(-9.0, 9.0, 3)),
             tuple(rng.uniform(-400.0, 400.0, 3))) for _ in range(n)]
    return fixed + rand


def test_object_transform_is_trimesh_matrix_bit_for_bit():
    rng = np.random.default_rng(3)
    for _, pos, rot in _placements():
        scale = tuple(rng.uniform(0.2, 3.0, 3))
        assert np.array_equal(rigid.object_transform(pos, rot, scale),
                              _trimesh_transform(pos, rot, scale))


@pytest.mark.parametrize("ext,pos,rot", _placements())
def test_make_box_is_trimesh_box_bit_for_bit(ext, pos, rot):
    mesh = creation.box(extents=ext)
    mesh.apply_transform(_trimesh_transform(pos, rot))
    want = polyhedron_from_trimesh(mesh, "b")
    got = make_box("b", ext, position=pos, rotate=rot)
    assert np.array_equal(got.vertices, want.vertices)
    assert np.array_equal(got.polygons, want.polygons)
    assert np.array_equal(got.normals, want.normals)
    assert np.array_equal(got.edges, want.edges)
    assert np.array_equal(got.edge_faces, want.edge_faces)
    assert np.array_equal(got.triangles, want.triangles)


def test_box_vertices_are_corners_of_the_extents():
    verts, quads = rigid.box_mesh((2.0, 4.0, 6.0), np.eye(4))
    assert sorted(map(tuple, verts)) == sorted(
        (x, y, z) for x in (-1.0, 1.0) for y in (-2.0, 2.0) for z in (-3.0, 3.0))
    # each quad's Newell normal points away from the centre
    for q in quads:
        p = verts[q]
        n = np.cross(p[1] - p[0], p[2] - p[0])
        assert np.dot(n, p.mean(axis=0)) > 0


def test_box_rejects_reflection_and_bad_extents():
    with pytest.raises(ValueError, match="reflect"):
        rigid.box_mesh((1.0, 1.0, 1.0), np.diag([-1.0, 1.0, 1.0, 1.0]))
    with pytest.raises(ValueError, match="3 numbers"):
        rigid.box_mesh((1.0, 1.0), np.eye(4))


def test_grid_box_volume_check_rejects_inward_mesh(monkeypatch):
    ok = make_grid_box("g", (2.0, 1.0, 3.0), (2, 1, 3))
    assert np.all(ok.edge_faces[:, 1] >= 0)
    # turn every quad inward: still closed and consistent, but of negative volume
    real = rigid.object_transform
    monkeypatch.setattr("vgxsim.shadow.scene.object_transform",
                        lambda p, r: real(p, r, (-1.0, 1.0, 1.0)))
    with pytest.raises(ValueError, match="closed outward"):
        make_grid_box("g", (2.0, 1.0, 3.0), (2, 1, 3))


def test_default_scene_imports_no_trimesh():
    import subprocess
    import sys

    code = ("import sys; from vgxsim.shadow.scene import default_scene; default_scene(); "
            "print('trimesh' in sys.modules, 'networkx' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True).stdout.split()
    assert out == ["False", "False"]
