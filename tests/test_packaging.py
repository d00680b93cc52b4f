"""kernels/ ships as vgxsim.kernels, never as a top-level ``kernels`` module.

A different PyPI package owns the name ``kernels``; a wheel that installed our
folder under that name would clash with it.  These tests build a real,
non-editable wheel, look inside it, install it into a scratch folder and import
it from there in a fresh interpreter.
"""

from __future__ import annotations

import os
import pathlib
import re
import subprocess
import sys
import zipfile

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[1]


def test_no_source_imports_top_level_kernels():
    pattern = re.compile(r"^\s*(import kernels\b|from kernels\b)", re.MULTILINE)
    offenders = [str(p.relative_to(ROOT)) for d in ("vgxsim", "kernels", "bench", "tests")
                 for p in (ROOT / d).rglob("*.py") if pattern.search(p.read_text())]
    assert offenders == []


def test_installed_package_maps_kernels_folder():
    import vgxsim.kernels

    assert pathlib.Path(vgxsim.kernels.__file__).parent.name == "kernels"


@pytest.fixture(scope="module")
def wheel(tmp_path_factory):
    out = tmp_path_factory.mktemp("wheel")
    proc = subprocess.run(
        [sys.executable, "-m", "pip", "wheel", str(ROOT), "--no-deps",
         "-q", "-w", str(out)], capture_output=True, text=True)
    if proc.returncode != 0:
        pytest.fail(f"building the wheel failed:\n{proc.stderr[-2000:]}")
    wheels = list(out.glob("vgxsim-*.whl"))
    assert len(wheels) == 1
    return wheels[0]


def test_wheel_layout(wheel):
    names = zipfile.ZipFile(wheel).namelist()
    assert "vgxsim/kernels/__init__.py" in names
    assert "vgxsim/kernels/render.py" in names
    assert not any(n.startswith("kernels/") for n in names)
    top = {n.split("/")[0] for n in names if not n.split("/")[0].endswith(".dist-info")}
    assert top == {"vgxsim"}


def test_wheel_ships_the_scenes_models_and_textures(wheel):
    # an installed user has the shadows program's scenes (and what they name)
    names = set(zipfile.ZipFile(wheel).namelist())
    from vgxsim.data import SCENES

    for scene in SCENES:
        assert f"vgxsim/data/scenes/{scene}.scn" in names
    for model in ("cube.glo", "floor.glo", "ball.glo", "teapot.glo", "dense_torus.glo.gz",
                  "teapot_patches.txt"):
        assert f"vgxsim/data/models/{model}" in names
    assert "vgxsim/data/textures/checker.rgb" in names
    assert "vgxsim/formats/scn.py" in names and "vgxsim/kernels/adjacency.py" in names


def test_wheel_imports_when_installed(wheel, tmp_path):
    target = tmp_path / "site"
    subprocess.run([sys.executable, "-m", "pip", "install", "--no-deps", "-q", "--target",
                    str(target), str(wheel)], check=True)
    code = ("import vgxsim.kernels, vgxsim.gl, importlib.util, sys\n"
            "from vgxsim.data import scene_path\n"
            "from vgxsim.formats.scn import parse_scn\n"
            "assert len(parse_scn(scene_path('teapot')).models) == 2\n"
            "print(vgxsim.kernels.__file__)\n"
            "spec = importlib.util.find_spec('kernels')\n"
            "print('kernels-origin', spec.origin if spec else None)\n")
    env = dict(os.environ, PYTHONPATH=str(target))
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          env=env, cwd=tmp_path, check=True)
    lines = proc.stdout.strip().splitlines()
    assert lines[0].startswith(str(target))
    origin = lines[1].split(" ", 1)[1]
    assert origin == "None" or not origin.startswith(str(target))
