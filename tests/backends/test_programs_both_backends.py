"""Every test program and every shipped scene runs on both backends (issue 12).

A smoke test with teeth: each program of vgxsim/examples, tests/cli/programs and
tests/backends/programs runs through ``vgxsim compare`` (the same events on the
software and the OpenGL backend); both runs must end with the same status and
show the same number of frames, at least one, and the frames must agree up to the
allowed differences of docs/opengl_backend.md: colour within one level and stencil
equal on all but 0.4 % of the pixels (the D1, D3 and D4 pixels of the subpixel(FALSE)
shadows programs; measured at 80 x 64, at most 8 of 5 120 pixels, heidmann1991
volumes, and 2 stencil pixels; every other program 0).  z is left to the compare
tool's own tests.
Each shipped scene is drawn in every display mode of the shadows program.
"""

from __future__ import annotations

import os

import numpy as np
import pytest

import vgxsim.backends as backends
from vgxsim.backends.compare import compare_program
from vgxsim.backends.opengl.surface import available
from vgxsim.gl._core import session

pytestmark = pytest.mark.skipif(not available(), reason="needs PyOpenGL and libOSMesa")

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
EXAMPLES = os.path.join(ROOT, "vgxsim", "examples")
CLI = os.path.join(ROOT, "tests", "cli", "programs")
SMALL = (80, 64)


def _events(tmp_path, name, text):
    path = tmp_path / name
    path.write_text(text)
    return str(path)


def _programs(tmp_path):
    """(program, args, events, max_frames, status) of every program to run."""
    out = {
        "heidmann1991": (os.path.join(EXAMPLES, "heidmann1991.py"), [], None, None, 0),
        "heidmann1991 volumes": (os.path.join(EXAMPLES, "heidmann1991.py"),
                                 ["--mode", "volumes"], None, None, 0),
        "shadows_interactive": (os.path.join(EXAMPLES, "shadows_interactive.py"),
                                ["--mode", "shadows"],
                                _events(tmp_path, "esc.events",
                                        "move 40 32\npress MIDDLEMOUSE\nafter 1 move 44 33\n"
                                        "after 1 release MIDDLEMOUSE\nafter 2 key ESC\n"),
                                None, 0),
        "soft_shadows": (os.path.join(EXAMPLES, "soft_shadows.py"),
                         ["--images", "2", "--size", "80x64", "--out",
                          str(tmp_path / "soft.png")], None, None, 0),
        "blend_once": (os.path.join(ROOT, "tests", "backends", "programs", "blend_once.py"),
                       [], None, None, 0),
        "forever": (os.path.join(CLI, "forever.py"), [], None, 3, 0),
        "exits glerror": (os.path.join(CLI, "exits.py"), ["glerror"], None, None, 1),
    }
    for name in ("clock", "fmtext", "histstyle", "nurbspatch", "overlay", "picking"):
        out[name] = (os.path.join(CLI, name + ".py"), [],
                     os.path.join(CLI, name + ".events"), None, 0)
    return out


PROGRAM_NAMES = ["heidmann1991", "heidmann1991 volumes", "shadows_interactive",
                 "soft_shadows", "blend_once", "forever", "exits glerror", "clock", "fmtext",
                 "histstyle", "nurbspatch", "overlay", "picking"]


def test_every_program_is_listed(tmp_path):
    # A program added to these folders must be added to the smoke test.
    listed = {os.path.basename(p[0]) for p in _programs(tmp_path).values()}
    shipped = {f for d in (EXAMPLES, CLI, os.path.join(ROOT, "tests", "backends", "programs"))
               for f in os.listdir(d) if f.endswith(".py") and f != "__init__.py"}
    assert shipped == listed


@pytest.mark.parametrize("name", PROGRAM_NAMES)
def test_program_runs_alike_on_both_backends(tmp_path, name, capsys):
    program, args, events, max_frames, status = _programs(tmp_path)[name]
    lines: list[str] = []
    got = compare_program(program, args, events=events, size=SMALL, max_frames=max_frames,
                          levels=1, z_units=1 << 24, tolerance=0.004, out=lines.append)
    report = "\n".join(lines)
    rows = [line.split() for line in lines if line[:5].strip().isdigit()]
    assert "differs" not in report, report  # exit status and frame count
    if status == 0:
        assert got == 0, report
        assert rows, report
    else:
        assert got == status, report


SCENES = ("cubes", "balls", "textured_floor", "dense", "teapot")


@pytest.mark.parametrize("mode", ["objects", "volumes", "mask"])  # shadows: test_shadows_backends
@pytest.mark.parametrize("scene", SCENES)
def test_shipped_scene_every_mode_on_both_backends(scene, mode):
    from vgxsim.shadow import api

    sc = api.load_scene(scene)
    frames = {}
    for backend in backends.BACKENDS:
        backends.set_backend(backend)
        try:
            frames[backend] = api.render(sc, mode=mode, size=SMALL, subpixel=True)
        finally:
            backends.set_backend(None)
            session.reset()
    a, b = frames["software"], frames["opengl"]
    assert a.colour.any()
    d = np.abs(a.colour.astype(int) - b.colour.astype(int)).max(axis=2)
    # At subpixel(TRUE) no z tie decides a pixel (D3, D4 do not arise): colour within
    # one level (D5; measured 0), and in 'volumes' within D1's two (translucent faces
    # blend with BF_SA/BF_MSA, each layer rounding; measured: up to 72 of 5 120
    # pixels two levels off, the teapot).
    assert d.max() <= (2 if mode == "volumes" else 1), np.bincount(d.ravel())
    if mode == "mask":
        assert np.array_equal(a.stencil, b.stencil)
        assert (a.stencil != a.stencil_zero).any()
