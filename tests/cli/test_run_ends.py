"""`vgxsim run`: runs that end (--timeout, --max-frames, SIGTERM, SIGINT, SIGKILL) and
keep their frames, targets checked before the run, outputs never replaced silently.

The signal tests run real subprocesses on a 16x12 window, the three sinks of one test
side by side; every wait is bounded by a subprocess timeout.
"""

import os
import signal
import subprocess
import sys
from pathlib import Path

import imageio.v3 as iio
import numpy as np
import pytest

from vgxsim.cli import main
from vgxsim.gl._core import session

PROGRAMS = Path(__file__).parent / "programs"
FOREVER = str(PROGRAMS / "forever.py")
ENV = dict(os.environ, NUMBA_CACHE_DIR=os.environ.get("NUMBA_CACHE_DIR", "/tmp/nbcache"))
TARGETS = ("movie.gif", "movie.mp4", "frames")


@pytest.fixture(autouse=True)
def fresh_session():
    session.reset()
    yield
    session.reset()


def colour_of(i: int) -> list[int]:
    """The RGB that forever.py's frame i shows: cpack(i * 0x010203), 0xAABBGGRR."""
    w = i * 0x010203 & 0xFFFFFF
    return [w & 0xFF, (w >> 8) & 0xFF, (w >> 16) & 0xFF]


def frames_in(target: Path) -> list[np.ndarray]:
    if target.suffix == ".gif":
        return list(iio.imread(target, index=None))
    if target.suffix == ".mp4":
        return list(iio.imread(target, index=None, plugin="FFMPEG"))
    # a run killed while writing a frame may leave its temporary (dot) file
    return [iio.imread(p) for p in sorted(target.glob("frame_*.png"))]


def vgxsim_run(*args: str, **kw) -> subprocess.Popen:
    return subprocess.Popen([sys.executable, "-m", "vgxsim.cli", "run", *args],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=ENV, **kw)


# -- limits ---------------------------------------------------------------------------
@pytest.mark.parametrize("mode", ["noswap", "busy"])
def test_timeout_ends_a_program_that_never_swaps(tmp_path, capsys, mode):
    out = tmp_path / "f"
    assert main(["run", FOREVER, "--timeout", "0.3", "--frames", str(out), "--", mode]) == 0
    err = capsys.readouterr()
    assert "the timeout of 0.3 s passed; the run ends here after 1 frame," in err.err
    assert "caught" not in err.out  # the program's `except Exception` cannot stop it
    # the single-buffered screen at the limit is written as the run's frame
    (png,) = frames_in(out)
    assert png.shape == (12, 16, 3)
    if mode == "noswap":  # colour-map index 1..7 of the default map: never black
        assert png.any(axis=2).all()


def test_timeout_and_max_frames_of_a_swapping_program(tmp_path, capsys):
    out = tmp_path / "f"
    assert main(["run", FOREVER, "--max-frames", "4", "--timeout", "600",
                 "--frames", str(out), "--", "swap"]) == 0
    assert [f[0, 0].tolist() for f in frames_in(out)] == [colour_of(i) for i in range(4)]
    assert "max_frames=4 reached" in capsys.readouterr().err


def test_bad_limits_and_sizes_are_usage_errors(capsys):
    for args in (["--timeout", "0"], ["--timeout", "soon"], ["--size", "100000x100000"],
                 ["--size", "16385x1"]):
        with pytest.raises(SystemExit) as exc:
            main(["run", FOREVER, *args])
        assert exc.value.code == 2
    assert "larger than the largest window, 16384x16384" in capsys.readouterr().err


# -- signals ----------------------------------------------------------------------------
def _record_and_signal(tmp_path: Path, sig: int, shown: int = 5):
    """Start forever.py recording to each target, wait until each has shown ``shown``
    frames, send ``sig``; return (target, returncode, frames printed before the signal,
    stderr) per target."""
    procs = []
    for name in TARGETS:
        target = tmp_path / name
        procs.append((target, vgxsim_run(FOREVER, "--frames", str(target), "--", "swap")))
    results = []
    for target, proc in procs:
        printed = 0
        while printed < shown:
            line = proc.stdout.readline()
            assert line, proc.stderr.read().decode()
            printed += line.startswith(b"frame")
        proc.send_signal(sig)
        results.append([target, proc, printed])
    out = []
    for target, proc, printed in results:
        _, err = proc.communicate(timeout=120)
        out.append((target, proc.returncode, printed, err.decode()))
    return out


@pytest.mark.parametrize("sig", [signal.SIGTERM, signal.SIGINT])
def test_terminate_and_interrupt_keep_every_frame(tmp_path, sig):
    for target, rc, printed, err in _record_and_signal(tmp_path, sig):
        assert rc == 128 + sig, err
        name = signal.Signals(sig).name
        assert f"vgxsim run: {name}" in err and "every sink complete" in err, err
        n = int(err.split("the run ends here after ")[1].split()[0])
        frames = frames_in(target)
        assert len(frames) == n >= printed  # every frame shown is in the file
        if target.suffix != ".mp4":  # lossless: frame k is frame k
            assert [f[0, 0, :3].tolist() for f in frames] == [colour_of(i) for i in range(n)]


def test_kill_leaves_a_playable_file_of_the_frames_so_far(tmp_path):
    import time

    for target, rc, printed, _err in _record_and_signal(tmp_path, signal.SIGKILL):
        assert rc == -signal.SIGKILL
        # ffmpeg, in its own session, completes the MP4 after vgxsim is gone
        for _ in range(200):
            try:
                frames = frames_in(target)
            except Exception:  # noqa: BLE001 - not complete yet
                frames = []
            if len(frames) >= printed:
                break
            time.sleep(0.1)
        assert len(frames) >= printed, (target, len(frames), printed)
        if target.suffix != ".mp4":
            k = len(frames)
            assert [f[0, 0, :3].tolist() for f in frames] == [colour_of(i) for i in range(k)]


# -- targets ------------------------------------------------------------------------------
@pytest.mark.parametrize("target", ["full.gif", "full.mp4", "file/frames", "/proc/frames"])
def test_unwritable_target_fails_before_the_program_starts(tmp_path, capsys, target):
    if target.endswith(".mp4"):
        pytest.importorskip("imageio_ffmpeg")
    (tmp_path / "file").write_text("not a folder")
    if target.startswith("full"):
        (tmp_path / target).symlink_to("/dev/full")
    path = target if target.startswith("/") else str(tmp_path / target)
    assert main(["run", FOREVER, "--overwrite", "--frames", path, "--", "swap"]) == 2
    got = capsys.readouterr()
    assert "cannot record frames" in got.err and path in got.err
    assert got.out == ""  # the program never ran


def test_a_target_filling_up_mid_run_exits_non_zero_naming_it(tmp_path):
    """RLIMIT_FSIZE stands in for a full disk: writes past 40 kB fail (EFBIG)."""
    import resource

    def limit():
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)  # an error, not a kill
        resource.setrlimit(resource.RLIMIT_FSIZE, (40_000, 40_000))

    procs = [(tmp_path / name, vgxsim_run(FOREVER, "--max-frames", "1000", "--frames",
                                          str(tmp_path / name), "--", "swap", "128x96",
                                          preexec_fn=limit))
             for name in ("movie.gif", "movie.mp4")]
    for target, proc in procs:
        _, err = proc.communicate(timeout=300)
        assert proc.returncode == 1, err.decode()
        # the GIF fails at the frame that crosses the limit; ffmpeg may only fail
        # when it writes out its last frames, at the end
        assert (f"vgxsim run: cannot write video {target}" in err.decode()
                or f"vgxsim run: cannot finish video {target}" in err.decode()), err
    frames = frames_in(tmp_path / "movie.gif")  # the frames before the failure, intact
    assert 0 < len(frames) < 1000


def test_earlier_frames_are_refused_then_replaced_never_mixed(tmp_path, capsys):
    out = tmp_path / "f"
    assert main(["run", FOREVER, "--max-frames", "3", "--frames", str(out), "--",
                 "swap"]) == 0
    assert main(["run", FOREVER, "--max-frames", "2", "--frames", str(out), "--",
                 "swap"]) == 2
    assert "already holds 3 frame files" in capsys.readouterr().err
    assert len(os.listdir(out)) == 3
    assert main(["run", FOREVER, "--max-frames", "2", "--overwrite", "--frames", str(out),
                 "--", "swap"]) == 0
    assert sorted(os.listdir(out)) == ["frame_0000.png", "frame_0001.png"]


def test_existing_video_is_refused_without_overwrite(tmp_path, capsys):
    gif = tmp_path / "m.gif"
    gif.write_bytes(b"earlier")
    assert main(["run", FOREVER, "--max-frames", "2", "--frames", str(gif), "--",
                 "swap"]) == 2
    assert f"{gif} exists" in capsys.readouterr().err
    assert gif.read_bytes() == b"earlier"
    assert main(["run", FOREVER, "--max-frames", "2", "--frames", str(gif), "--overwrite",
                 "--", "swap"]) == 0
    assert len(frames_in(gif)) == 2


def test_non_utf8_events_name_the_file_and_line(tmp_path, capsys):
    events = tmp_path / "in.events"
    events.write_bytes(b"wait 1\nkey \xff\n")
    assert main(["run", FOREVER, "--events", str(events), "--", "swap"]) == 2
    assert f"{events}:2: not UTF-8 text" in capsys.readouterr().err


# -- render --out -------------------------------------------------------------------------
def test_render_out_format_and_overwrite(tmp_path, monkeypatch, capsys):
    import types

    import vgxsim.examples

    fake = types.ModuleType("vgxsim.examples.heidmann1991")
    fake.render = lambda w, h, mode, edges: np.full((h, w, 4), 200, np.uint8)
    monkeypatch.setitem(sys.modules, "vgxsim.examples.heidmann1991", fake)
    monkeypatch.setattr(vgxsim.examples, "heidmann1991", fake, raising=False)
    jpg = tmp_path / "x.jpg"
    assert main(["render", "--out", str(jpg), "--size", "8x4"]) == 0
    assert jpg.read_bytes()[:3] == b"\xff\xd8\xff"  # JPEG, not PNG bytes
    before = jpg.read_bytes()
    assert main(["render", "--out", str(jpg), "--size", "8x4"]) == 2
    assert f"{jpg} exists; give --overwrite" in capsys.readouterr().err
    assert jpg.read_bytes() == before
    assert main(["render", "--out", str(jpg), "--size", "16x4", "--overwrite"]) == 0
    assert iio.imread(jpg).shape == (4, 16, 3)
    assert main(["render", "--out", str(tmp_path / "x.bmp")]) == 2
    assert "cannot tell the image format" in capsys.readouterr().err
