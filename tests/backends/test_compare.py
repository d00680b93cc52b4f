"""`vgxsim compare` and `vgxsim run --backend` on small programs."""

from __future__ import annotations

import os

import numpy as np
import pytest

from vgxsim.backends.compare import Frame, compare_frames, difference_image, psnr
from vgxsim.backends.opengl.surface import available
from vgxsim.cli import main

HERE = os.path.dirname(os.path.abspath(__file__))
BLEND = os.path.join(HERE, "programs", "blend_once.py")
HIST = os.path.join(HERE, "..", "cli", "programs", "histstyle.py")

needs_gl = pytest.mark.skipif(not available(), reason="needs PyOpenGL and libOSMesa")


def test_psnr_and_counts_by_hand():
    a = np.zeros((2, 2, 4), np.uint8)
    b = a.copy()
    b[0, 0, 0] = 10  # one channel of one pixel: MSE over RGB = 100 / 12
    assert psnr(a, b) == pytest.approx(10 * np.log10(255**2 * 12 / 100))
    assert psnr(a, a) == float("inf")
    z = np.zeros((2, 2), np.int32)
    zb = z.copy()
    zb[1, 1] = 3
    d = compare_frames(Frame(1, a, z, None), Frame(1, b, zb, None), 0, z_units=2)
    assert (d.colour_pixels, d.colour_max, d.z_pixels, d.z_max) == (1, 10, 1, 3)
    assert d.stencil_pixels is None and d.over == ["colour", "z"]
    assert compare_frames(Frame(1, a, z, None), Frame(1, b, zb, None), 0, levels=10,
                          z_units=3).over == []
    img = difference_image(a, b)
    assert img[0, 0].tolist() == [160, 0, 0, 255] and img[1, 1].tolist() == [0, 0, 0, 255]


@needs_gl
def test_compare_reports_the_blend_rounding_and_honours_levels(capsys, tmp_path):
    assert main(["compare", BLEND, "--diff", str(tmp_path)]) == 1
    out = capsys.readouterr().out
    row = [line for line in out.splitlines() if line.strip().startswith("0 ")][0]
    # 10 x 10 pixels blended, blue one level apart; z and stencil untouched.
    assert row.split()[2:4] == ["100", "1"] and "past tolerance: colour" in row
    assert (tmp_path / "diff_0000.png").exists()
    assert main(["compare", BLEND, "--levels", "1"]) == 0
    # 100 of 256 pixels differ: within a tolerance of 40 %, past one of 30 %.
    assert main(["compare", BLEND, "--tolerance", "0.4"]) == 0
    assert main(["compare", BLEND, "--tolerance", "0.3"]) == 1


@needs_gl
def test_compare_scripted_program_identical(capsys):
    events = os.path.join(HERE, "..", "cli", "programs", "histstyle.events")
    assert main(["compare", HIST, "--events", events]) == 0
    rows = [line.split() for line in capsys.readouterr().out.splitlines()
            if line[:5].strip().isdigit()]
    assert len(rows) >= 2 and all(r[2] == "0" for r in rows)


@needs_gl
def test_run_with_opengl_backend(capsys):
    assert main(["run", HIST, "--backend", "opengl", "--events",
                 os.path.join(HERE, "..", "cli", "programs", "histstyle.events")]) == 0


def test_opengl_missing_is_a_clear_error(capsys, monkeypatch):
    from vgxsim.backends.opengl import surface

    monkeypatch.setattr(surface, "available", lambda: False)
    assert main(["run", HIST, "--backend", "opengl"]) == 2
    assert "needs PyOpenGL and libOSMesa" in capsys.readouterr().err
    assert main(["compare", HIST]) == 2
    assert "needs PyOpenGL and libOSMesa" in capsys.readouterr().err


def test_compare_missing_program(capsys):
    assert main(["compare", "no_such_program.py"]) == 2
    assert "no such program file" in capsys.readouterr().err
