"""The .scn reader: the README's grammar, its defaults, and an error naming the file and
line for each kind of mistake."""

from __future__ import annotations

import math
import os
import textwrap

import numpy as np
import pytest

from vgxsim.data import SCENES, scene_path
from vgxsim.formats import FormatError
from vgxsim.formats.scn import parse_scn, read_scene
from vgxsim.shadow.scene import default_scene

CUBE = """glo 1
normals none
v -0.5 -0.5 -0.5
v -0.5 -0.5 0.5
v -0.5 0.5 -0.5
v -0.5 0.5 0.5
v 0.5 -0.5 -0.5
v 0.5 -0.5 0.5
v 0.5 0.5 -0.5
v 0.5 0.5 0.5
f 1 2 4 3
f 5 7 8 6
f 1 5 6 2
f 3 4 8 7
f 1 3 7 5
f 2 6 8 4
"""


@pytest.fixture
def folder(tmp_path, monkeypatch):
    monkeypatch.setenv("VGXSIM_CACHE_DIR", str(tmp_path / "cache"))
    (tmp_path / "models").mkdir()
    (tmp_path / "models" / "cube.glo").write_text(CUBE)
    from vgxsim.formats.sgi import write_rgb

    (tmp_path / "textures").mkdir()
    write_rgb(tmp_path / "textures" / "t.rgb", np.zeros((4, 4, 3), np.uint8))
    (tmp_path / "textures" / "not_an_image.rgb").write_text("hello")
    return tmp_path


def scene_file(folder, body: str, name: str = "s.scn"):
    p = folder / name
    p.write_text(textwrap.dedent(body))
    return p


def error_of(path) -> FormatError:
    with pytest.raises(FormatError) as info:
        read_scene(path)
    return info.value


# -- errors: file, line, what was expected ---------------------------------------------------
@pytest.mark.parametrize("body, line, words", [
    ("Scene\nMODEL models/cube.glo\n", 1, "ShadowScene"),
    ("ShadowScene\nMODEL models/cube.glo\nBOGUS 1 2 3\n", 3, "unknown command"),
    ("ShadowScene\nWINDOW 1 40\nMODEL models/cube.glo\n", 3, "WINDOW expects 3 numbers"),
    ("ShadowScene\nWINDOW 1 40 x\n", 2, "WINDOW expects 3 numbers"),
    ("ShadowScene\nWINDOW 5 1 1\n", 2, "near < far"),
    ("ShadowScene\nLOOKAT 0 0 1  0 0 1\n", 2, "coincide"),
    ("ShadowScene\nMODEL models/cube.glo\n\nPOSITION 1 2\nEND\n", 5, "POSITION expects 3"),
    ("ShadowScene\nTEXTURE textures/t.rgb\nMODEL models/cube.glo\n", 2, "TEXTURE before any MODEL"),
    ("ShadowScene\nMATERIAL DIFFUSE 1 1 1 END\n", 2, "MATERIAL before any MODEL"),
    ("ShadowScene\nMODEL models/cube.glo\nMATERIAL\n  DIFFUSE 1 1 1\n  GLOSS 3\nEND\n", 5,
     "unknown material property"),
    ("ShadowScene\nMODEL models/cube.glo\nMATERIAL SHININESS 300 END\n", 3, "0..128"),
    ("ShadowScene\nMODEL models/cube.glo\nMATERIAL DIFFUSE 1 1 1\n", 3, "expected a material"),
    ("ShadowScene\nMODEL models/cube.glo\nLIGHT LCOLOR 1 0 0 END\n", 3, "no POSITION"),
    ("ShadowScene\nMODEL models/cube.glo\nLIGHT POSITION 0 5 0 0 END\n", 3, "w must be 1"),
    ("ShadowScene\nMODEL models/cube.glo\nLIGHT POSITION 0 5 0\n  FLICKER 2 END\n", 4,
     "unknown light property"),
    ("ShadowScene\nMODEL models/cube.glo\nLIGHT POSITION 0 5 0 JITTER -1 END\n", 3, ">= 0"),
    ("ShadowScene\nMODEL\n", 2, "file name after MODEL"),
    ("ShadowScene\nMODEL models/missing.glo\n", 2, "no such model file"),
    ("ShadowScene\nMODEL models/cube.glo\nTEXTURE textures/none.rgb\n", 3, "no such file"),
    ("ShadowScene\nMODEL models/cube.glo\nTEXTURE textures/not_an_image.rgb\n", 3, "SGI"),
    ("ShadowScene\nMODEL models/cube.glo SCALE -1 1 1\n", 2, "mirrors"),
    ("ShadowScene\nWINDOW 1 40 1\n", None, "no MODEL"),
])
def test_errors_name_file_and_line(folder, body, line, words):
    path = scene_file(folder, body)
    err = error_of(path)
    assert err.path == str(path)
    assert err.line == line
    assert words in str(err)
    prefix = f"{path}:{line}:" if line is not None else f"{path}:"
    assert str(err).startswith(prefix)


def test_an_error_inside_a_model_names_the_scene_line_and_the_model_line(folder):
    (folder / "models" / "bad.glo").write_text("glo 1\nv 0 0 0\nv 1 0 0\nf 1 2 3\n")
    path = scene_file(folder, "ShadowScene\n\nXMODEL models/bad.glo\n")
    err = error_of(path)
    assert err.line == 3
    assert "bad.glo:4:" in str(err) and "vertex number 3" in str(err)


def test_missing_scene_file(tmp_path):
    with pytest.raises(FormatError, match="no such scene file"):
        read_scene(tmp_path / "nope.scn")


# -- semantics -------------------------------------------------------------------------------
def test_last_transform_of_each_kind_wins_and_the_order_is_scale_rotate_position(folder):
    path = scene_file(folder, """\
        ShadowScene
        MODEL models/cube.glo
          POSITION 9 9 9  SCALE 5 5 5
          ROTATE 0 0 90   POSITION 1 2 3   SCALE 2 1 1
        END
        """)
    obj = read_scene(path).objects[0]
    # Scale (2, 1, 1), then rotate 90 degrees about z, then translate (1, 2, 3):
    # the corner (0.5, 0.5, 0.5) -> (1, 0.5, 0.5) -> (-0.5, 1, 0.5) -> (0.5, 3, 3.5)
    assert np.any(np.all(np.isclose(obj.vertices, [0.5, 3.0, 3.5]), axis=1))
    assert np.allclose(obj.vertices.min(0), [0.5, 1.0, 2.5])
    assert np.allclose(obj.vertices.max(0), [1.5, 3.0, 3.5])


def test_rotation_order_is_z_then_y_then_x(folder):
    path = scene_file(folder, "ShadowScene\nMODEL models/cube.glo SCALE 1 2 3 "
                              "ROTATE 90 90 0\n")
    obj = read_scene(path).objects[0]
    # extents (1, 2, 3); rotate y by 90: x<->z -> (3, 2, 1); then x by 90: y<->z -> (3, 1, 2)
    assert np.allclose(obj.vertices.max(0) - obj.vertices.min(0), [3.0, 1.0, 2.0])


def test_global_transforms_apply_after_each_objects_own(folder):
    path = scene_file(folder, """\
        ShadowScene
        SCALE 2 2 2
        POSITION 10 0 0
        MODEL models/cube.glo POSITION 1 0 0
        XMODEL models/cube.glo
        """)
    s = read_scene(path)
    # own (translate 1) first, then the global scale 2 and translate 10: centre x = 12
    assert np.allclose(s.objects[0].vertices.mean(0), [12.0, 0.0, 0.0])
    assert np.allclose(s.objects[1].vertices.mean(0), [10.0, 0.0, 0.0])
    assert np.allclose(s.objects[1].vertices.max(0) - s.objects[1].vertices.min(0), 2.0)
    assert [o.casts for o in s.objects] == [True, False]


def test_defaults_newlines_as_blanks_and_comments(folder):
    path = scene_file(folder, "ShadowScene MODEL\n\n   models/cube.glo  # a cube\n")
    s = read_scene(path)
    d = default_scene()
    assert s.lights == d.lights  # "a red one and a blue one are created"
    assert s.camera == d.camera
    m = s.objects[0].material
    assert m.diffuse == (0.8, 0.8, 0.8) and m.specular == (0.0, 0.0, 0.0)  # diffuse grey
    assert s.lmodel.ambient == (0.2, 0.2, 0.2) and not s.lmodel.local_viewer


def test_material_light_window_lookat_texture_are_read(folder):
    path = scene_file(folder, """\
        shadowscene
        window 0.5 30 0.4
        LOOKAT 1 2 3  0 0 0
        MODEL models/cube.glo
          TEXTURE textures/t.rgb
          MATERIAL SPECULAR 0.1 0.2 0.3 SHININESS 12 DIFFUSE 0.4 0.5 0.6
                   EMISSION 0.7 0.8 0.9 AMBIENT 0.3 0.2 0.1 END
        LIGHT AMBIENT 0.1 0.1 0.1 LCOLOR 1 0.5 0 POSITION 1 6 2 1
              SPOTDIRECTION 0 -1 0 SPOTLIGHT 10 45 JITTER 0.5 END
        LIGHT POSITION -1 5 0 JITTER 1 2 3 END
        END
        MODEL models/never_read.glo
        """)
    s = read_scene(path)
    assert len(s.objects) == 1  # END finishes the scene
    m = s.objects[0].material
    assert (m.specular, m.shininess, m.diffuse, m.emission, m.ambient) == (
        (0.1, 0.2, 0.3), 12.0, (0.4, 0.5, 0.6), (0.7, 0.8, 0.9), (0.3, 0.2, 0.1))
    assert s.objects[0].texture == str(folder / "textures" / "t.rgb")
    a, b = s.lights
    assert a.position == (1.0, 6.0, 2.0) and a.colour == (1.0, 0.5, 0.0)
    assert a.spot_direction == (0.0, -1.0, 0.0) and a.spot == (10.0, 45.0)
    assert a.jitter == (0.5, 0.5, 0.5) and b.jitter == (1.0, 2.0, 3.0)
    cam = s.camera
    assert (cam.near, cam.far, cam.near_height) == (0.5, 30.0, 0.4)
    assert cam.eye == (1.0, 2.0, 3.0) and cam.target == (0.0, 0.0, 0.0)
    # WINDOW: frustum height 0.4 at the near plane 0.5
    p = cam.projection(1.0)
    assert math.isclose(p[1, 1], 2 * 0.5 / 0.4)


def test_paths_resolve_relative_to_the_scene_file(folder, monkeypatch):
    sub = folder / "scenes"
    sub.mkdir()
    path = scene_file(sub, "ShadowScene\nMODEL ../models/cube.glo\n")
    monkeypatch.chdir(folder.parent)
    assert len(read_scene(path).objects) == 1
    assert parse_scn(path).models[0].path == os.path.join(str(sub), "../models/cube.glo")


# -- shipped scenes ----------------------------------------------------------------------------
def test_shipped_cubes_scene_is_the_default_scene():
    s = read_scene(scene_path("cubes"))
    d = default_scene()
    assert len(s.objects) == len(d.objects)
    for a, b in zip(s.objects, d.objects, strict=True):
        assert a.casts == b.casts and a.material == b.material
        assert np.allclose(np.sort(a.vertices, axis=0), np.sort(b.vertices, axis=0), atol=1e-6)
    assert [lt.position for lt in s.lights] == [lt.position for lt in d.lights]
    assert np.allclose(s.camera.projection(1.25), d.camera.projection(1.25), atol=1e-6)


@pytest.mark.parametrize("name", SCENES)
def test_every_shipped_scene_loads(name):
    s = read_scene(scene_path(name))
    assert s.casters
    tris = sum(len(o.triangles) for o in s.objects)
    if name == "dense":
        assert tris >= 50_000
    if name == "textured_floor":
        assert any(o.texture for o in s.objects)
