"""depthcue / lRGBrange / RGBrange / getdcm against hand-computed colours.

ortho2's depth: the standard projection maps object z to z_ndc = -z, and window depth
zw = ZMIN + (z_ndc + 1) * (ZMAX - ZMIN) / 2 (docs/numeric_model.md s. 1).
"""

import functools

import pytest

from vgxsim import GL, gl
from vgxsim.gl._core import GLValueError

W = H = 8


@pytest.fixture
def win(gl_window):
    return functools.partial(gl_window, W, H)


def square_at(z, rgb=True):
    if rgb:
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
    # lRGBrange(3G): znear takes the max colour, zfar the min colour.
    # z = 0 -> zw = ZMIN + (ZMAX - ZMIN) / 2 = -0.5: t = (-0.5 + 1000) / 2000 = 0.49975;
    # colour = max + (min - max) t: r = 200 (1 - t) = 100.05 -> 100,
    # g = 100 (1 - t) = 50.025 -> 50, b = 100 t = 49.975 -> 50.
    square_at(0.0)
    assert pixel(ctx) == (100, 50, 50)
    square_at(0.5)  # zw = -0x400000 - 0.5, nearer than znear: the max colour
    assert pixel(ctx) == (200, 100, 0)
    gl.RGBrange(10, 20, 30, 40, 50, 60, -1000, 1000)  # the old name, same ramp
    square_at(-0.5)  # zw farther than zfar: the min colour
    assert pixel(ctx) == (10, 20, 30)
    gl.depthcue(GL.FALSE)
    square_at(0.0)
    assert pixel(ctx) == (77, 230, 26)  # the current colour again: floor(255 c + 0.5)


def index_at(ctx, x=4, y=4):
    ctx.flush()
    return int(ctx.fb.front[y, x])


def test_colour_index_ramp_lshaderange(win):
    ctx = win(rgb=False)
    gl.color(3)  # ignored while depth cueing
    gl.lshaderange(32, 55, -1000, 1000)
    gl.depthcue(GL.TRUE)
    # lshaderange(3G): znear -> highin 55, zfar -> lowin 32.  z = 0: t = 0.49975,
    # index = 55 + (32 - 55) t = 43.50575 -> 44.
    square_at(0.0, False)
    assert index_at(ctx) == 44
    square_at(0.5, False)  # nearer than znear: highin
    assert index_at(ctx) == 55
    gl.shaderange(100, 300, -1000, 1000)  # the old name; a ramp across index 256
    square_at(-0.5, False)  # farther than zfar: lowin
    assert index_at(ctx) == 100
    square_at(0.5, False)
    assert index_at(ctx) == 300  # a vertex index above 255 is exact
    gl.depthcue(GL.FALSE)
    square_at(0.0, False)
    assert index_at(ctx) == 3


def test_default_shaderange_is_0_to_7(win):
    ctx = win(rgb=False)
    gl.depthcue(GL.TRUE)
    # lshaderange(0, 7, ZMIN, ZMAX): z = 0 gives zw = -0.5, t = 0.5 - 0.5 / 16777215,
    # index = 7 - 7 t = 3.5000002 -> 4.
    square_at(0.0, False)
    assert index_at(ctx) == 4


def test_index_ramp_interpolates_between_vertices(win):
    # A band whose left edge (x = 0) is at z = 0.5 and right edge (x = 8) at z = -0.5;
    # the ramp's znear / zfar are those edges' window depths (rounded into the ramp),
    # so the left vertices get highin 160 and the right ones lowin 0, and pixel x
    # (centre x) gets 160 - 20 x: 160, 140, ..., 20.
    ctx = win(rgb=False)
    gl.lshaderange(0, 160, -4194304, 4194303)  # zw(0.5) = -4194304.25, zw(-0.5) = 4194303.25
    gl.depthcue(GL.TRUE)
    gl.bgnpolygon()
    for x, y, z in ((0, 0, 0.5), (8, 0, -0.5), (8, 2, -0.5), (0, 2, 0.5)):
        gl.v3f(x, y, z)
    gl.endpolygon()
    ctx.flush()
    assert ctx.fb.front[1, :8].tolist() == [160 - 20 * x for x in range(8)]


def test_overlay_drawing_is_not_depth_cued(win):
    ctx = win(rgb=False)
    gl.depthcue(GL.TRUE)
    ctx.plane_sets["overlay"].bits = 2
    gl.drawmode(GL.OVERDRAW)
    gl.color(2)
    square_at(0.0, False)
    gl.drawmode(GL.NORMALDRAW)
    assert int(ctx.plane_sets["overlay"].fb.front[4, 4]) == 2


def test_depthcue_errors(win):
    win()
    with pytest.raises(GLValueError, match="rmax must be 0..255"):
        gl.lRGBrange(0, 0, 0, 256, 0, 0, 0, 10)
    with pytest.raises(GLValueError, match="lshaderange.*highin 4096"):
        gl.lshaderange(0, 4096, 0, 10)
    with pytest.raises(GLValueError, match="shaderange.*lowin -1"):
        gl.shaderange(-1, 7, 0, 10)
