"""``--window`` on the command line: the shadows program runs until the timeout and
leaves an events script; the recording options are refused without a window."""

from __future__ import annotations

from vgxsim.cli import main


def test_shadows_window_runs_until_the_timeout(tmp_path):
    events = tmp_path / "s.events"
    frames = tmp_path / "frames"
    status = main(["shadows", "--window", "--size", "64x48", "--timeout", "3",
                   "--record", str(frames), "--record-events", str(events)])
    assert status == 0
    assert events.read_text().startswith("# vgxsim window session")
    assert len(list(frames.glob("frame_*.png"))) >= 1  # the first frame, objects only


def test_recording_options_need_a_window(tmp_path, capsys):
    prog = tmp_path / "p.py"
    prog.write_text("from gl import *\n")
    assert main(["run", str(prog), "--record-events", str(tmp_path / "e")]) == 2
    assert "--record-events records a --window session" in capsys.readouterr().err
    script = tmp_path / "in.events"
    script.write_text("stop\n")
    assert main(["run", str(prog), "--window", "--events", str(script)]) == 2
    assert main(["shadows", "--window", "--record", "x", "-o", "y.png",
                 "--events", str(script)]) == 2
