"""Write the models, textures and scenes shipped in vgxsim/data/ (run from the repo root).

    python scripts/make_shipped_data.py

Everything is made by the project: boxes and grids from vgxsim.shadow.scene, an
icosphere and a torus from trimesh, the Utah teapot from its Bezier patches
(vgxsim.shadow.teapot) and a checkerboard texture.  The scenes are written by hand
below; ``cubes.scn`` is the default scene of :func:`vgxsim.shadow.scene.default_scene`.
"""

from __future__ import annotations

import pathlib

import numpy as np
import trimesh

from vgxsim.formats.glo import GloModel, write_glo
from vgxsim.formats.sgi import write_rgb
from vgxsim.shadow.scene import make_box, make_grid_box
from vgxsim.shadow.teapot import tessellate

DATA = pathlib.Path(__file__).resolve().parents[1] / "vgxsim" / "data"


def _rounded(a: np.ndarray, digits: int = 7) -> np.ndarray:
    return np.round(np.asarray(a, np.float64), digits) + 0.0  # + 0.0: no "-0.0"


def models() -> None:
    out = DATA / "models"
    cube = make_box("cube", (1.0, 1.0, 1.0))
    write_glo(out / "cube.glo", GloModel.from_polygons(
        _rounded(cube.vertices), cube.polygons, face_normals=_rounded(cube.normals)),
        "unit cube centred on the origin, one normal per face")
    floor = make_grid_box("floor", (14.0, 0.25, 14.0), (8, 1, 8))
    write_glo(out / "floor.glo", GloModel.from_polygons(
        _rounded(floor.vertices), floor.polygons, face_normals=_rounded(floor.normals)),
        "14 x 0.25 x 14 slab, its faces cut into quads for per-vertex lighting")
    ball = trimesh.creation.icosphere(subdivisions=3, radius=1.0)
    write_glo(out / "ball.glo", GloModel.from_polygons(
        _rounded(ball.vertices), ball.faces, vertex_normals=_rounded(ball.vertex_normals)),
        "icosphere of radius 1 (1,280 triangles), a normal per vertex")
    v, p, n = tessellate(8)
    write_glo(out / "teapot.glo", GloModel.from_polygons(
        _rounded(v), p, vertex_normals=_rounded(n)),
        "Utah teapot: 32 bicubic Bezier patches, 8 x 8 quads each, y up (open, hollow)")
    torus = trimesh.creation.torus(major_radius=1.6, minor_radius=0.55,
                                   major_sections=160, minor_sections=160)
    write_glo(out / "dense_torus.glo.gz", GloModel.from_polygons(
        _rounded(torus.vertices, 6), torus.faces,
        vertex_normals=_rounded(torus.vertex_normals, 5)),
        f"torus of {len(torus.faces)} triangles, a normal per vertex")


def textures() -> None:
    k = np.indices((64, 64)).sum(0) // 8 % 2
    img = np.where(k[..., None] == 1, [200, 190, 160], [90, 70, 60]).astype(np.uint8)
    write_rgb(DATA / "textures" / "checker.rgb", img)


CUBES = """\
ShadowScene
# The default scene of `vgxsim shadows`: three cubes over a floor, a red and a blue
# jitterable point light (vgxsim.shadow.scene.default_scene).
WINDOW 1 40 0.8284271247461901
LOOKAT 2.5 4.8 7.5  0 0.9 0
XMODEL ../models/floor.glo
  POSITION 0 -0.125 0
  MATERIAL AMBIENT 0.6 0.6 0.6 DIFFUSE 0.6 0.6 0.6 END
MODEL ../models/cube.glo
  SCALE 1.4 1.4 1.4  ROTATE 0 25 0  POSITION -1.3 0.7 0.2
  MATERIAL AMBIENT 0.9 0.9 0.9 DIFFUSE 0.9 0.9 0.9 SPECULAR 0.5 0.5 0.5 SHININESS 30 END
MODEL ../models/cube.glo
  SCALE 1 1 1  ROTATE 0 -30 0  POSITION 1.3 0.5 -0.6
  MATERIAL AMBIENT 0.9 0.85 0.45 DIFFUSE 0.9 0.85 0.45 SPECULAR 0.4 0.4 0.4 SHININESS 20 END
MODEL ../models/cube.glo
  SCALE 0.8 0.8 0.8  ROTATE 35 40 0  POSITION 0 2.4 0.45
  MATERIAL AMBIENT 0.5 0.9 0.55 DIFFUSE 0.5 0.9 0.55 SPECULAR 0.4 0.4 0.4 SHININESS 20 END
LIGHT POSITION -3.5 7.5 1.5 LCOLOR 1 0.25 0.2 AMBIENT 0.1 0.025 0.02 JITTER 0.6 END
LIGHT POSITION 4 6.5 3 LCOLOR 0.25 0.35 1 AMBIENT 0.025 0.035 0.1 JITTER 0.6 END
END
"""

BALLS = """\
ShadowScene
# Three balls (a normal per vertex) over a floor; the lights of the default scene.
WINDOW 1 40 0.8284271247461901
LOOKAT 2.5 4.8 7.5  0 0.9 0
XMODEL ../models/floor.glo
  POSITION 0 -0.125 0
MODEL ../models/ball.glo
  SCALE 0.8 0.8 0.8  POSITION -1.2 0.8 0.3
  MATERIAL DIFFUSE 0.85 0.3 0.3 AMBIENT 0.85 0.3 0.3 SPECULAR 0.6 0.6 0.6 SHININESS 40 END
MODEL ../models/ball.glo
  SCALE 0.6 0.6 0.6  POSITION 1.3 0.6 -0.5
  MATERIAL DIFFUSE 0.3 0.8 0.35 AMBIENT 0.3 0.8 0.35 SPECULAR 0.6 0.6 0.6 SHININESS 40 END
MODEL ../models/ball.glo
  SCALE 0.45 0.45 0.45  POSITION 0.2 2.3 0.5
  MATERIAL DIFFUSE 0.9 0.85 0.4 AMBIENT 0.9 0.85 0.4 SPECULAR 0.6 0.6 0.6 SHININESS 40 END
END
"""

TEXTURED = """\
ShadowScene
# A textured floor (checker.rgb on the floor's x-z plane) under a cube and a ball.
# The texture is modulated onto every pass (texgen TG_LINEAR: tex_sparams/tparams).
WINDOW 1 40 0.8284271247461901
LOOKAT 3 5 7.5  0 0.6 0
XMODEL ../models/floor.glo
  POSITION 0 -0.125 0
  TEXTURE ../textures/checker.rgb
  MATERIAL AMBIENT 0.8 0.8 0.8 DIFFUSE 0.8 0.8 0.8 END
MODEL ../models/cube.glo
  SCALE 1.2 1.2 1.2  ROTATE 0 30 0  POSITION -1 0.6 0
MODEL ../models/ball.glo
  SCALE 0.6 0.6 0.6  POSITION 1.2 1.4 0.6
LIGHT POSITION -2 7 3 LCOLOR 1 0.9 0.8 AMBIENT 0.1 0.1 0.1 JITTER 0.8 END
END
"""

DENSE = """\
ShadowScene
# A dense caster: a torus of 51,200 triangles standing on the floor.
WINDOW 1 40 0.8284271247461901
LOOKAT 2.5 4.8 7.5  0 0.9 0
XMODEL ../models/floor.glo
  POSITION 0 -0.125 0
MODEL ../models/dense_torus.glo.gz
  ROTATE 60 0 20  POSITION 0 1.9 0
  MATERIAL DIFFUSE 0.8 0.7 0.4 AMBIENT 0.8 0.7 0.4 SPECULAR 0.5 0.5 0.5 SHININESS 30 END
END
"""

TEAPOT = """\
ShadowScene
# The Utah teapot from its 32 Bezier patches: open and hollow (lid gap, open spout).
WINDOW 1 40 0.8284271247461901
LOOKAT 2.5 5.5 7.5  0 1 0
XMODEL ../models/floor.glo
  POSITION 0 -0.125 0
MODEL ../models/teapot.glo
  SCALE 0.8 0.8 0.8  ROTATE 0 20 0  POSITION 0 0 0
  MATERIAL DIFFUSE 0.85 0.85 0.9 AMBIENT 0.85 0.85 0.9 SPECULAR 0.6 0.6 0.6 SHININESS 50 END
END
"""


def scenes() -> None:
    for name, text in (("cubes", CUBES), ("balls", BALLS), ("textured_floor", TEXTURED),
                       ("dense", DENSE), ("teapot", TEAPOT)):
        (DATA / "scenes" / f"{name}.scn").write_text(text)


if __name__ == "__main__":
    for sub in ("models", "textures", "scenes"):
        (DATA / sub).mkdir(parents=True, exist_ok=True)
    models()
    textures()
    scenes()
