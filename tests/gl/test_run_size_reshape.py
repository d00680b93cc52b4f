"""``vgxsim run --size WxH`` reshapes windows like a user (docs in gl/_window.py):
a program that called prefsize gets REDRAW and sees the new size."""

import json

from vgxsim.runner import run_program

PROGRAM = """
import json, sys
from gl import *
from DEVICE import *
prefsize(40, 30)
winopen("reshaped")
seen = [["open", list(getsize()), list(getviewport())]]
RGBmode()
gconfig()
while qtest():
    dev, val = qread()
    if dev == REDRAW:
        reshapeviewport()
        cpack(0xFF0000FF)
        clear()
        seen.append(["redraw", val, list(getsize()), list(getviewport())])
with open(sys.argv[1], "w") as f:
    json.dump(seen, f)
"""


def run(tmp_path, size):
    prog = tmp_path / "prog.py"
    prog.write_text(PROGRAM)
    out = tmp_path / "seen.json"
    assert run_program(prog, [str(out)], size=size) == 0
    return json.loads(out.read_text())


def test_prefsize_window_is_reshaped_to_the_run_size(tmp_path):
    seen = run(tmp_path, (64, 48))
    # Opened at 40x30 (its viewport), reshaped at once to 64x48: the viewport stays
    # until reshapeviewport; two REDRAWs (winopen's and the reshape's).
    assert seen[0] == ["open", [64, 48], [0, 39, 0, 29]]
    assert seen[1:] == [["redraw", 1, [64, 48], [0, 63, 0, 47]]] * 2


def test_without_size_the_prefsize_stands(tmp_path):
    seen = run(tmp_path, None)
    assert seen == [["open", [40, 30], [0, 39, 0, 29]], ["redraw", 1, [40, 30],
                                                          [0, 39, 0, 29]]]
