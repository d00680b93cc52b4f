"""rectzoom, rectwrite/rectread, writepixels/readpixels, writeRGB, by hand."""

import numpy as np
import pytest

from vgxsim import gl
from vgxsim.gl._core import GLUsageError, GLValueError


@pytest.fixture
def rgbwin(gl_window):
    return gl_window(8, 6)


@pytest.fixture
def cmwin(gl_window):
    return gl_window(8, 6, rgb=False)


def words(ctx):
    ctx.flush()
    return ctx.fb.front.astype(np.int64)


def test_rectzoom_replicates_pixels(rgbwin):
    gl.rectzoom(2.0, 3.0)
    gl.lrectwrite(1, 0, 2, 0, [0xFF000011, 0xFF000022])  # 2x1 pixels
    got = words(rgbwin)
    # Columns 1-2 take pixel 0, 3-4 pixel 1; rows 0-2.
    want = np.zeros((6, 8), np.int64)
    want[0:3, 1:3] = 0xFF000011
    want[0:3, 3:5] = 0xFF000022
    assert np.array_equal(got, want)
    gl.rectzoom(1.5, 1.0)  # nearest source pixel: X = 0, 1 -> 0; X = 2 -> 1 (2/1.5 = 1.33)
    gl.lrectwrite(0, 5, 1, 5, [0xFF0000AA, 0xFF0000BB])
    assert words(rgbwin)[5, :4].tolist() == [0xFF0000AA, 0xFF0000AA, 0xFF0000BB, 0]
    with pytest.raises(GLValueError, match="> 0"):
        gl.rectzoom(0.0, 1.0)


def test_rectwrite_and_rectread_in_colour_map_mode(cmwin):
    gl.rectwrite(2, 1, 4, 2, [1, 2, 3, 4, 5, 6])
    got = words(cmwin)
    assert got[1, 2:5].tolist() == [1, 2, 3] and got[2, 2:5].tolist() == [4, 5, 6]
    raw = gl.rectread(2, 1, 4, 2)
    assert np.frombuffer(raw, "<u2").tolist() == [1, 2, 3, 4, 5, 6]
    gl.rectwrite(0, 4, 1, 4, raw[:4])  # bytes round-trip: 16-bit words
    assert words(cmwin)[4, :2].tolist() == [1, 2]


def test_pixel_rows_move_the_character_position(cmwin):
    gl.cmov2i(5, 3)
    gl.writepixels(5, [7, 8, 9, 10, 11])  # only 3 fit before the right edge (x 5..7)
    assert words(cmwin)[3, 5:].tolist() == [7, 8, 9]
    gl.cmov2i(4, 3)
    assert gl.readpixels(3) == [0, 7, 8]
    assert gl.readpixels(1) == [9]  # the position moved past the three read


def test_writeRGB_and_readRGB_round_trip(rgbwin):
    gl.cmov2i(1, 2)
    gl.writeRGB(3, [10, 20, 30], [1, 2, 3], [100, 110, 120])
    assert words(rgbwin)[2, 1] == 10 | (1 << 8) | (100 << 16)
    gl.cmov2i(1, 2)
    assert gl.readRGB(3) == (3, [10, 20, 30], [1, 2, 3], [100, 110, 120])


def test_mode_errors(rgbwin):
    with pytest.raises(GLUsageError, match="colour-map mode"):
        gl.rectwrite(0, 0, 0, 0, [1])
    with pytest.raises(GLUsageError, match="colour-map mode"):
        gl.readpixels(1)
    with pytest.raises(GLValueError, match="0..255"):
        gl.writeRGB(1, [256], [0], [0])
