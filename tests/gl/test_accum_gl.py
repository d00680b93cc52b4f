"""acbuf through vgxsim.gl against hand-computed accumulation arithmetic.

docs/numeric_model.md section 9: components are 0..255 integers in 16-bit signed
accumulators, round(x) = floor(x + 0.5), AC_RETURN clamps to 0..255.
"""

import functools

import numpy as np
import pytest

from vgxsim import GL
from vgxsim.gl._accum import acbuf
from vgxsim.gl._core import GLTypeError, GLUsageError, GLValueError
from vgxsim.gl._raster import czclear, wmpack
from vgxsim.state.planes import ZMAX

W = H = 4


@pytest.fixture
def win(gl_window):
    return functools.partial(gl_window, W, H, stencil=0, acbits=16)


def pixel(ctx, x, y):
    ctx.flush()
    return tuple(int(c) for c in ctx.read_rgba()[y, x])


def test_accumulate_and_return_average_two_images(win):
    ctx = win()
    acbuf(GL.AC_CLEAR, 0.0)
    czclear(0xFFFF0064, ZMAX)  # image 1: (100, 0, 255, 255) everywhere
    acbuf(GL.AC_ACCUMULATE, 1.0)
    czclear(0xFF00C833, ZMAX)  # image 2: (51, 200, 0, 255) ...
    ctx.colour = (1.0, 1.0, 1.0, 1.0)  # ... with a white square on pixels 0..1
    ctx.draw_arrays("polygon", np.array([[0, 0, 0], [2, 0, 0], [2, 2, 0], [0, 2, 0]], float))
    acbuf(GL.AC_ACCUMULATE, 1.0)
    assert tuple(ctx.fb.accum[3, 3]) == (151, 200, 255, 510)
    acbuf(GL.AC_RETURN, 0.5)
    # round(151/2) = floor(76.0) = 76, 200/2 = 100, round(127.5) = 128, 255.
    assert pixel(ctx, 3, 3) == (76, 100, 128, 255)
    # (100+255)/2 = 177.5 -> 178, 255/2 -> 128, (255+255)/2 = 255.
    assert pixel(ctx, 0, 0) == (178, 128, 255, 255)


def test_clear_accumulate_mult_add_and_saturation(win):
    ctx = win()
    czclear(0x0A0A0A0A, ZMAX)
    acbuf(GL.AC_CLEAR_ACCUMULATE, 2.0)  # 20
    acbuf(GL.AC_ADD, 5.0)  # 25
    acbuf(GL.AC_MULT, 1.5)  # round(37.5) = 38
    assert np.all(ctx.fb.accum == 38)
    acbuf(GL.AC_RETURN, 1.0)
    assert pixel(ctx, 1, 2) == (38, 38, 38, 38)
    acbuf(GL.AC_CLEAR, 30000.0)
    acbuf(GL.AC_ADD, 5000.0)  # saturates at 32767
    assert np.all(ctx.fb.accum == 32767)
    acbuf(GL.AC_RETURN, -1.0)  # negative results clamp to 0
    assert pixel(ctx, 0, 0) == (0, 0, 0, 0)


def test_return_through_wmpack_and_raster_rectangle(win):
    ctx = win()
    czclear(0x01020304, ZMAX)
    acbuf(GL.AC_CLEAR, 200.0)
    ctx.raster.set(viewport=(2, 3, 0, 3), scrmask=(2, 3, 0, 3))
    wmpack(0x000000FF)
    acbuf(GL.AC_RETURN, 1.0)
    assert pixel(ctx, 3, 0) == (200, 3, 2, 1)
    assert pixel(ctx, 1, 0) == (4, 3, 2, 1)
    acbuf(GL.AC_CLEAR, 7.0)
    assert np.all(ctx.fb.accum[:, 2:] == 7) and np.all(ctx.fb.accum[:, :2] == 200)


def test_acbuf_errors(win):
    win(acbits=0)
    with pytest.raises(GLUsageError, match="no accumulation buffer"):
        acbuf(GL.AC_CLEAR, 0.0)
    win()
    with pytest.raises(GLValueError) as e:
        acbuf(9, 1.0)
    assert str(e.value) == "acbuf(9, 1.0): op 9 is not a valid token (AC_*)"
    with pytest.raises(GLValueError, match="finite"):
        acbuf(GL.AC_MULT, float("nan"))
    with pytest.raises(GLTypeError):
        acbuf(1.0, 1.0)
    win(rgb=False)
    with pytest.raises(GLUsageError, match="RGBmode"):
        acbuf(GL.AC_ACCUMULATE, 1.0)
