"""depthcue / lRGBrange / RGBrange / getdcm against hand-computed colours.

ortho2's depth: the standard projection maps object z to z_ndc = -z, and window depth
zw = ZMIN + (z_ndc + 1) * (ZMAX - ZMIN) / 2 (docs/numeric_model.md s. 1).
"""

import functools

import pytest

from vgxsim import GL, gl
from vgxsim.gl._core import GLUsageError, GLValueError

W = H = 8


@pytest.fixture
def win(gl_window):
    return functools.partial(gl_window, W, H)


def square_at(z):
    gl.c3f(0.3, 0.9, 0.1)  # ignored while depth cueing
    gl.bgnpolygon()
    for x, y in ((-0.5, -0.5), (7.5, -0.5), (7.5, 7.5), (-0.5, 7.5)):
        gl.v3f(x, y, z)
    gl.endpolygon()


def pixel(ctx):
    ctx.flush()
    return tuple(int(c) for c in ctx.read_rgba()[4, 4, :3])


def test_ramp_from_znear_to_zfar(win):
    ctx = win()
    assert gl.getdcm() == 0
    gl.lRGBrange(0, 0, 100, 200, 100, 0, -1000, 1000)
    gl.depthcue(GL.TRUE)
    assert gl.getdcm() == 1
    # z = 0 -> zw = ZMIN + (ZMAX - ZMIN) / 2 = -0.5: t = (-0.5 + 1000) / 2000 = 0.49975
    # r = 200 t = 99.95 -> 100, g = 100 t = 49.975 -> 50, b = 100 (1 - t) = 50.025 -> 50.
    square_at(0.0)
    assert pixel(ctx) == (100, 50, 50)
    square_at(0.5)  # zw = -0x400000 - 0.5, far below znear: t = 0, the min colour
    assert pixel(ctx) == (0, 0, 100)
    gl.RGBrange(10, 20, 30, 40, 50, 60, -1000, 1000)  # the old name, same ramp
    square_at(-0.5)  # zw far above zfar: the max colour
    assert pixel(ctx) == (40, 50, 60)
    gl.depthcue(GL.FALSE)
    square_at(0.0)
    assert pixel(ctx) == (77, 230, 26)  # the current colour again: floor(255 c + 0.5)


def test_depthcue_errors(win):
    win()
    with pytest.raises(GLValueError, match="rmax must be 0..255"):
        gl.lRGBrange(0, 0, 0, 256, 0, 0, 0, 10)
    win(rgb=False)
    with pytest.raises(GLUsageError, match="colour-map mode"):
        gl.depthcue(GL.TRUE)
