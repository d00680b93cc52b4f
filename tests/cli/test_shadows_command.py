"""`vgxsim shadows` and `vgxsim convert` as a user runs them (subprocesses)."""

from __future__ import annotations

import os
import subprocess
import sys

import imageio.v3 as iio
import numpy as np
import pytest
import trimesh


def vgxsim(*args, cwd, timeout=600):
    env = dict(os.environ, VGXSIM_CACHE_DIR=str(cwd / "cache"))
    return subprocess.run([sys.executable, "-m", "vgxsim", *args], cwd=cwd, env=env,
                          capture_output=True, text=True, timeout=timeout)


def test_no_arguments_writes_a_non_blank_png(tmp_path):
    proc = vgxsim("shadows", "--size", "96x80", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    img = iio.imread(tmp_path / "shadows.png")
    assert img.shape == (80, 96, 3)
    assert len(np.unique(img.reshape(-1, 3), axis=0)) > 20  # a picture, not a fill
    assert "wrote shadows.png" in proc.stdout


def in_process(*args, cwd, monkeypatch, capsys):
    """Run the command in this interpreter (no start-up cost): (status, stdout, stderr)."""
    from vgxsim.cli import main

    monkeypatch.chdir(cwd)
    monkeypatch.setenv("VGXSIM_CACHE_DIR", str(cwd / "cache"))
    try:
        rc = main(list(args))
    except SystemExit as exc:  # argparse: -h and usage errors
        rc = exc.code
    out = capsys.readouterr()
    return rc, out.out, out.err


def test_help_lists_the_options(tmp_path, monkeypatch, capsys):
    _, out, _ = in_process("shadows", "-h", cwd=tmp_path, monkeypatch=monkeypatch,
                           capsys=capsys)
    for opt in ("--size", "--mode", "--light", "--soft", "--soft-max", "--rotate",
                "--translate", "--dolly", "--spin", "--subpixel", "-o"):
        assert opt in out
    assert "objects,volumes,mask,shadows" in out


def test_shipped_scene_soft_and_spin(tmp_path):
    proc = vgxsim("shadows", "teapot", "--size", "64x48", "--soft", "4", "-o", "t.png",
                  "--mode", "shadows", "--rotate=-30,10", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert iio.imread(tmp_path / "t.png").shape == (48, 64, 3)
    proc = vgxsim("shadows", "--spin", "3", "--size", "48x40", "-o", "s.gif", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert iio.imread(tmp_path / "s.gif", index=None).shape[:3] == (3, 40, 48)


def test_bad_scene_exits_non_zero_names_file_and_line_and_writes_nothing(tmp_path):
    (tmp_path / "bad.scn").write_text("ShadowScene\n\nLIGHT POSITION 1 2 END\n")
    proc = vgxsim("shadows", "bad.scn", "-o", "out.png", cwd=tmp_path)
    assert proc.returncode == 1
    assert "bad.scn:3:" in proc.stderr and "Traceback" not in proc.stderr
    assert not (tmp_path / "out.png").exists()
    assert [p.name for p in tmp_path.iterdir() if p.name.startswith(".out")] == []


@pytest.mark.parametrize("args, words", [
    (["--spin", "2", "-o", "x.png"], ".gif or .mp4"),
    (["-o", "x.gif"], "--spin"),
    (["--light", "5"], "lights 0..1"),
    (["--subpixel", "maybe"], "on or off"),
    (["nosuchscene.scn"], "no such scene file"),
])
def test_usage_errors(tmp_path, monkeypatch, capsys, args, words):
    rc, _, err = in_process("shadows", *args, cwd=tmp_path, monkeypatch=monkeypatch,
                            capsys=capsys)
    assert rc != 0 and words in err
    assert not any(p.suffix in (".png", ".gif") for p in tmp_path.iterdir())


def test_convert(tmp_path, monkeypatch, capsys):
    trimesh.creation.icosphere(subdivisions=1).export(tmp_path / "ball.off")
    kw = dict(cwd=tmp_path, monkeypatch=monkeypatch, capsys=capsys)
    rc, out, err = in_process("convert", "ball.off", "ball.glo", "-f", **kw)
    assert rc == 0, err
    assert "reversed" in out
    assert (tmp_path / "ball.glo").read_text().startswith("glo 1\n")
    rc, _, err = in_process("convert", "missing.obj", "x.glo", **kw)
    assert rc == 1 and "no such mesh file" in err
