"""The ``vgxsim`` command: ``run`` (vgxsim.runner) and ``render``.

One test runs a historical-style program through a real subprocess
(``python -m vgxsim.cli run ...``); the others call :func:`vgxsim.cli.main` in-process,
which runs the same code without paying for a second Numba start-up.
"""

import io
import os
import subprocess
import sys
import types
from pathlib import Path

import imageio.v3 as iio
import numpy as np
import pytest

import vgxsim
import vgxsim.examples
from vgxsim.cli import main
from vgxsim.gl._core import session

PROGRAMS = Path(__file__).parent / "programs"
EXITS = str(PROGRAMS / "exits.py")


@pytest.fixture(autouse=True)
def fresh_session():
    session.reset()
    yield
    session.reset()


def test_version(capsys):
    with pytest.raises(SystemExit) as exc:
        main(["--version"])
    assert exc.value.code == 0
    assert capsys.readouterr().out.strip() == f"vgxsim {vgxsim.__version__}"


def test_histstyle_program_through_a_subprocess(tmp_path):
    frames = tmp_path / "frames"
    env = dict(os.environ, NUMBA_CACHE_DIR=os.environ.get("NUMBA_CACHE_DIR", "/tmp/nbcache"))
    proc = subprocess.run(
        [sys.executable, "-m", "vgxsim.cli", "run", str(PROGRAMS / "histstyle.py"),
         "--events", str(PROGRAMS / "histstyle.events"), "--frames", str(frames)],
        capture_output=True, text=True, env=env, timeout=600)
    assert proc.returncode == 0, proc.stderr
    assert "histstyle done 1280" in proc.stdout
    files = sorted(p.name for p in frames.iterdir())
    # single-buffered: a frame each time the program waits with a changed screen
    assert files == ["frame_0000.png", "frame_0001.png", "frame_0002.png"]
    red, green, split = (iio.imread(frames / f) for f in files)
    assert red.shape == (48, 64, 3)  # prefsize(64, 48)
    assert (red == [255, 0, 0]).all()  # color(RED); clear() in cmode, default map
    assert (green == [0, 255, 0]).all()
    # bottom half (window rows 0..23) blue: the last 24 rows of the top-down file
    assert (split[:24] == [0, 255, 0]).all() and (split[24:] == [0, 0, 255]).all()
    assert "gl" not in sys.modules or sys.modules["gl"] is not vgxsim.gl


def test_exit_status_of_sys_exit():
    assert main(["run", EXITS, "--", "exit3"]) == 3


def test_uncaught_exception_gives_traceback_and_1(capsys):
    assert main(["run", EXITS, "--", "raise"]) == 1
    err = capsys.readouterr().err
    assert "Traceback" in err and "RuntimeError: deliberate failure" in err


def test_gl_error_names_the_call(capsys):
    assert main(["run", EXITS, "--", "glerror"]) == 1
    assert "stensize(9)" in capsys.readouterr().err


def test_script_exhausted_is_a_clean_end(capsys):
    assert main(["run", EXITS, "--", "wait"]) == 0
    assert "input script exhausted" in capsys.readouterr().err


def test_argv_stdin_size_and_main(capsys, monkeypatch):
    monkeypatch.setattr(sys, "stdin", io.StringIO("hello from stdin\n"))
    argv_before = list(sys.argv)
    assert main(["run", EXITS, "--size", "32x16", "--", "echo", "x y"]) == 0
    out = capsys.readouterr().out
    assert "argv ['echo', 'x y']" in out
    assert "stdin hello from stdin" in out
    assert "size (32, 16)" in out
    assert "name __main__" in out
    assert sys.argv == argv_before


def test_module_aliases_are_restored(monkeypatch):
    sentinel = types.ModuleType("GL")
    monkeypatch.setitem(sys.modules, "GL", sentinel)
    monkeypatch.delitem(sys.modules, "gl", raising=False)
    assert main(["run", EXITS, "--", "exit3"]) == 3
    assert sys.modules["GL"] is sentinel
    assert "gl" not in sys.modules


def test_max_frames_and_double_buffered_frames(tmp_path, capsys):
    frames = tmp_path / "f"
    assert main(["run", EXITS, "--frames", str(frames), "--max-frames", "3", "--",
                 "spin"]) == 0
    names = sorted(p.name for p in frames.iterdir())
    assert names == ["frame_0000.png", "frame_0001.png", "frame_0002.png"]
    colours = [iio.imread(frames / n)[0, 0].tolist() for n in names]
    assert colours == [[0, 255, 0], [255, 0, 0], [0, 255, 0]]
    assert "max_frames=3" in capsys.readouterr().err


def test_each_window_gets_its_own_frames(tmp_path):
    frames = tmp_path / "f"
    assert main(["run", EXITS, "--frames", str(frames), "--", "two"]) == 0
    # neither window drew or swapped: each leaves its final picture at the end
    assert sorted(p.name for p in frames.iterdir()) == ["frame_0000.png",
                                                        "win2_frame_0000.png"]
    assert iio.imread(frames / "win2_frame_0000.png").shape == (2, 2, 3)


def test_gif_frames(tmp_path):
    pytest.importorskip("PIL")
    out = tmp_path / "spin.gif"
    assert main(["run", EXITS, "--frames", str(out), "--max-frames", "2", "--", "spin"]) == 0
    gif = iio.imread(out, index=None)
    assert gif.shape[:3] == (2, 6, 8)
    assert gif[0, 0, 0, :3].tolist() == [0, 255, 0] and gif[1, 0, 0, :3].tolist() == [255, 0, 0]


def test_command_line_errors(tmp_path, capsys):
    assert main(["run", str(tmp_path / "missing.py")]) == 2
    assert "no such program file" in capsys.readouterr().err
    assert main(["run", EXITS, "--frames", str(tmp_path / "out.png")]) == 2
    assert "cannot record frames" in capsys.readouterr().err
    bad = tmp_path / "bad.events"
    bad.write_text("press NOSUCHDEVICE\n")
    assert main(["run", EXITS, "--events", str(bad)]) == 2
    assert "bad event script" in capsys.readouterr().err
    with pytest.raises(SystemExit) as exc:
        main(["run", EXITS, "--size", "64by48"])
    assert exc.value.code == 2
    assert main([]) == 2


def test_render_writes_the_example_image(tmp_path, monkeypatch, capsys):
    calls = []

    def render(width, height, mode, edges):
        calls.append((width, height, mode, edges))
        img = np.zeros((height, width, 4), np.uint8)
        img[0] = [255, 0, 0, 255]  # row 0 is the bottom row
        return img

    fake = types.ModuleType("vgxsim.examples.heidmann1991")
    fake.render = render
    monkeypatch.setitem(sys.modules, "vgxsim.examples.heidmann1991", fake)
    monkeypatch.setattr(vgxsim.examples, "heidmann1991", fake, raising=False)
    out = tmp_path / "h.png"
    assert main(["render", "--out", str(out), "--size", "8x4", "--mode", "volumes",
                 "--edges", "all"]) == 0
    assert calls == [(8, 4, "volumes", "all")]
    png = iio.imread(out)
    assert png.shape == (4, 8, 3)
    assert (png[3] == [255, 0, 0]).all() and (png[:3] == 0).all()  # flipped to top-down
    assert str(out) in capsys.readouterr().out


def test_render_without_the_example_module(monkeypatch, capsys):
    monkeypatch.setitem(sys.modules, "vgxsim.examples.heidmann1991", None)
    monkeypatch.delattr(vgxsim.examples, "heidmann1991", raising=False)
    assert main(["render", "--out", "never.png"]) == 1
    assert "vgxsim.examples.heidmann1991" in capsys.readouterr().err
    assert not Path("never.png").exists()


def test_render_with_the_real_example(tmp_path):
    pytest.importorskip("vgxsim.examples.heidmann1991")
    out = tmp_path / "real.png"
    assert main(["render", "--out", str(out), "--size", "40x32", "--mode", "objects"]) == 0
    png = iio.imread(out)
    assert png.shape == (32, 40, 3) and png.any()


def test_gl_misuse_reports_program_line_and_call(tmp_path):
    """A GLError ends the run with status 1 and a report naming the program's file
    and line and the IRIS GL call, without vgxsim's internal frames."""
    prog = tmp_path / "misuse.py"
    prog.write_text("from gl import *\nwinopen('x')\nstensize(9)\n")
    proc = subprocess.run([sys.executable, "-m", "vgxsim.cli", "run", str(prog)],
                          capture_output=True, text=True, cwd=tmp_path)
    assert proc.returncode == 1
    assert f'File "{prog}", line 3' in proc.stderr
    assert "GLValueError: stensize(9): planes must be 0..8" in proc.stderr
    assert "vgxsim/gl/" not in proc.stderr
