"""Memory of every file sink stays flat over 1,000 frames (issue 11: a GIF sink held
the whole movie, about 1.25 MiB a frame at 640x512).

Each sink runs in its own subprocess -- side by side -- that writes 1,000 different
128x96 frames and reads its resident set size from /proc/self/statm after frame 100
and frame 1,000.  A sink keeping its frames would grow by 900 x 36 KiB = 32 MiB, far
past the 5 % allowed.
"""

import subprocess
import sys

import imageio.v3 as iio
import pytest

SCRIPT = r"""
import os, sys
import numpy as np
from vgxsim.sinks import open_sink

page = os.sysconf("SC_PAGE_SIZE")
def rss():
    with open("/proc/self/statm") as fh:
        return int(fh.read().split()[1]) * page

sink = open_sink(sys.argv[1], fps=30)
img = np.zeros((96, 128, 4), np.uint8)
for i in range(1, 1001):
    img[:] = (i * 3 % 256, i * 5 % 256, i * 7 % 256, 255)
    img[:, i % 120:i % 120 + 8] = 255  # a bar that moves: no two frames alike
    sink.write(img)
    if i in (100, 1000):
        print("rss", i, rss(), flush=True)
sink.close()
"""


def test_rss_is_flat_from_frame_100_to_frame_1000(tmp_path):
    pytest.importorskip("imageio_ffmpeg")
    targets = [tmp_path / "m.gif", tmp_path / "m.mp4", tmp_path / "frames"]
    procs = [(t, subprocess.Popen([sys.executable, "-c", SCRIPT, str(t)],
                                  stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True))
             for t in targets]
    for target, proc in procs:
        out, err = proc.communicate(timeout=300)
        assert proc.returncode == 0, err
        rss = {int(w[1]): int(w[2]) for w in (ln.split() for ln in out.splitlines())}
        assert rss[1000] < 1.05 * rss[100], (target.name, rss)
    assert len(iio.imread(targets[0], index=None)) == 1000
    assert len(iio.imread(targets[1], index=None, plugin="FFMPEG")) == 1000
    assert len(list(targets[2].iterdir())) == 1000
