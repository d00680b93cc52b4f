"""Programs in the historical binding's style that use popup menus, NURBS, picking,
the Font Manager and the overlay planes (tests/cli/programs), run under ``vgxsim run``
with scripted events.

Expected frames are worked out by hand from each program's geometry: pixel positions
of the clock hand after k quarter hours, the squares a pick at the cursor must hit,
the trim hole's interior, the font bitmaps doubled with numpy.
"""

from pathlib import Path

import imageio.v3 as iio
import numpy as np
import pytest

from vgxsim import font as builtin
from vgxsim.cli import main
from vgxsim.gl._core import session

PROGRAMS = Path(__file__).parent / "programs"


@pytest.fixture(autouse=True)
def fresh_session():
    session.reset()
    yield
    session.reset()


def run(name: str, tmp_path: Path) -> list[np.ndarray]:
    frames = tmp_path / "frames"
    code = main(["run", str(PROGRAMS / f"{name}.py"), "--events",
                 str(PROGRAMS / f"{name}.events"), "--frames", str(frames)])
    assert code == 0
    # PNG rows run top-down; flip so that row y is window row y (origin lower left).
    return [iio.imread(p)[::-1] for p in sorted(frames.iterdir())]


def test_clock_with_popup_menu(tmp_path, capsys):
    frames = run("clock", tmp_path)
    assert "clock done 15" in capsys.readouterr().out
    assert len(frames) == 3  # the first redraw, the timer, the menu's blue face
    red, blue, white = [255, 0, 0], [0, 0, 255], [255, 255, 255]
    f0, f1, f2 = frames
    # Minute hand: 35 long from the centre (50, 50); at 0 minutes it points up, after
    # 15 minutes (rotate(-900, 'z')) it points right.
    assert f0[70, 50].tolist() == white and f0[50, 70].tolist() == red
    assert f1[50, 70].tolist() == white and f1[70, 50].tolist() == red
    assert f2[50, 70].tolist() == white and f2[30, 50].tolist() == blue
    assert f2[2, 2].tolist() == [0, 0, 0]  # outside the face


def test_nurbs_patch_with_trim_hole(tmp_path):
    frames = run("nurbspatch", tmp_path)
    assert len(frames) == 2
    trimmed, whole = ((f[..., 0] > 0) for f in frames)
    # Patch: x, y in 10..70.  Hole: the triangle (0.25, 0.25) (0.5, 0.75) (0.75, 0.25)
    # of the parameter square: window (25, 25) (40, 55) (55, 25).  Its centroid is
    # (40, 35); the patch corners are far from it.
    assert not trimmed[33:38, 37:44].any()
    assert trimmed[12:20, 12:68].all() and trimmed[60:68, 12:68].all()
    assert whole[12:68, 12:68].all()
    assert not whole[:6].any() and not whole[75:].any()


def test_picking_program(tmp_path, capsys):
    frames = run("picking", tmp_path)
    out = capsys.readouterr().out
    assert out.splitlines() == ["hits [1, 1]", "hits [1, 2]", "hits []"]
    grey, yellow = [128, 128, 128], [255, 255, 0]
    assert len(frames) == 4
    assert frames[0][25, 25].tolist() == grey and frames[0][75, 75].tolist() == grey
    assert frames[1][25, 25].tolist() == yellow and frames[1][75, 75].tolist() == grey
    assert frames[2][25, 25].tolist() == grey and frames[2][75, 75].tolist() == yellow
    assert frames[3][75, 75].tolist() == grey and frames[3][25, 75].tolist() == grey


def test_font_manager_text(tmp_path, capsys):
    frames = run("fmtext", tmp_path)
    out = capsys.readouterr().out
    assert "faces Screen Courier Helvetica Times-Roman Iris" in out
    assert "width 32 info (0, 1, 0, 6, 16, 26, 26, 95)" in out
    (frame,) = frames
    want = np.zeros((40, 64), bool)
    # 26-point face: the 13-pixel design doubled; baseline at y = 10, descender 6.
    want[4:30, 4:36] = np.kron(builtin.string_bitmap("Ab"), np.ones((2, 2), bool))
    assert np.array_equal(frame[..., 0] > 0, want)


def test_overlay_planes_program(tmp_path, capsys):
    frames = run("overlay", tmp_path)
    out = capsys.readouterr().out.splitlines()
    assert out == ["overlay bits 4", "overlay planes 2", "overlay done True"]
    # The scene, drawn once: dark blue, and rectf(20, 20, 80, 80) red over pixels
    # 20..79 (the polygon fill covers the centres on its left and bottom edges only).
    scene = np.zeros((100, 100, 3), np.uint8)
    scene[:] = (0, 0, 64)
    scene[20:80, 20:80] = (255, 0, 0)

    def with_marker(x, y):
        # recti(x-5, y-5, x+5, y+5): the outline's pixels, ends included, in overlay
        # index 2 (cyan); rectfi(x-2, y-2, x+3, y+3): pixels x-2..x+2, y-2..y+2 in
        # index 1 (yellow).  Index 0 elsewhere: the scene shows through.
        img = scene.copy()
        img[y - 5, x - 5:x + 6] = img[y + 5, x - 5:x + 6] = (0, 255, 255)
        img[y - 5:y + 6, x - 5] = img[y - 5:y + 6, x + 5] = (0, 255, 255)
        img[y - 2:y + 3, x - 2:x + 3] = (255, 255, 0)
        return img

    assert len(frames) == 4  # the scene, two markers, the marker erased at ESC
    assert np.array_equal(frames[0], scene)
    assert np.array_equal(frames[1], with_marker(30, 30))
    assert np.array_equal(frames[2], with_marker(60, 70))
    assert np.array_equal(frames[3], scene)  # the normal planes were never touched
