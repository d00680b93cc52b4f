"""Matrix calls (gl/_matrix.py) against hand-computed matrices and pixels."""

from __future__ import annotations

import math

import numpy as np
import pytest

from vgxsim import GL, gl
from vgxsim.gl import _core

W, H = 16, 12


@pytest.fixture
def ctx(gl_window):
    return gl_window(W, H, projection=False)


def mat() -> np.ndarray:
    m = gl.getmatrix()
    assert isinstance(m, list) and len(m) == 16 and all(type(v) is float for v in m)
    return np.array(m).reshape(4, 4)


def xf(p, m=None) -> np.ndarray:
    """Row vector times the current matrix, p' = p M (IRIS convention)."""
    m = mat() if m is None else m
    v = np.array(list(p) + [1.0] * (4 - len(p)))
    out = v @ m
    return out[:3] / out[3]


def test_rotate_900_z_maps_x_to_y(ctx):
    gl.rotate(900, "z")
    np.testing.assert_allclose(xf((1, 0, 0)), (0, 1, 0), atol=1e-12)
    gl.loadmatrix(list(np.eye(4).reshape(-1)))
    gl.rotate(900, "X")  # upper-case axes are accepted (rotate(3G))
    np.testing.assert_allclose(xf((0, 1, 0)), (0, 0, 1), atol=1e-12)
    gl.loadmatrix(list(np.eye(4).reshape(-1)))
    gl.rotate(900, "y")
    np.testing.assert_allclose(xf((0, 0, 1)), (1, 0, 0), atol=1e-12)


def test_rot_takes_float_degrees(ctx):
    gl.rot(90.0, "x")
    np.testing.assert_allclose(xf((0, 1, 0)), (0, 0, 1), atol=1e-12)
    gl.rot(-90, "x")  # ints are fine for a float argument
    np.testing.assert_allclose(mat(), np.eye(4), atol=1e-12)


def test_rotate_rejects_float_angle_and_bad_axis(ctx):
    with pytest.raises(gl.GLTypeError, match=r"rotate\(45.0, 'z'\)"):
        gl.rotate(45.0, "z")
    with pytest.raises(gl.GLValueError, match="rotate"):
        gl.rotate(900, "w")
    with pytest.raises(gl.GLValueError, match="rot"):
        gl.rot(9.0, "xy")


def test_translate_then_getmatrix(ctx):
    gl.translate(1.5, -2, 3)
    m = gl.getmatrix()
    assert m[12:15] == [1.5, -2.0, 3.0]
    assert m[:12] == [1.0, 0, 0, 0, 0, 1.0, 0, 0, 0, 0, 1.0, 0]


def test_calls_premultiply(ctx):
    # translate then scale: current = S @ T, so a point is scaled, then translated.
    gl.translate(1, 0, 0)
    gl.scale(2, 2, 2)
    np.testing.assert_allclose(xf((1, 0, 0)), (3, 0, 0))
    np.testing.assert_allclose(xf((0, 1, 0)), (1, 2, 0))


def test_perspective_entries(ctx):
    gl.perspective(900, 2.0, 1.0, 10.0)
    m = mat()
    f = 1.0 / math.tan(math.radians(45.0))
    expected = np.zeros((4, 4))
    expected[0, 0] = f / 2.0
    expected[1, 1] = f
    expected[2, 2] = -11.0 / 9.0
    expected[2, 3] = -1.0
    expected[3, 2] = -20.0 / 9.0
    np.testing.assert_allclose(m, expected, atol=1e-12)


def test_projection_calls_load_not_multiply(ctx):
    gl.translate(5, 0, 0)
    gl.ortho2(0, 10, 0, 20)
    m = mat()
    # ortho2(0,10,0,20): x' = x/5 - 1, y' = y/10 - 1, z' = -z; no trace of translate.
    np.testing.assert_allclose(xf((10, 20, 0), m), (1, 1, 0))
    np.testing.assert_allclose(xf((0, 0, 0.5), m), (-1, -1, -0.5))


def test_window_and_ortho_entries(ctx):
    gl.window(-1, 1, -1, 1, 1, 3)
    m = mat()
    assert m[0, 0] == 1.0 and m[1, 1] == 1.0
    assert m[2, 2] == -2.0 and m[3, 2] == -3.0 and m[2, 3] == -1.0
    gl.ortho(0, 10, 0, 20, -1, 3)
    np.testing.assert_allclose(xf((10, 20, -3)), (1, 1, 1))
    np.testing.assert_allclose(xf((0, 0, 1)), (-1, -1, -1))


def test_mviewing_separates_projection(ctx):
    assert gl.getmmode() == GL.MSINGLE
    gl.mmode(GL.MVIEWING)
    assert gl.getmmode() == GL.MVIEWING
    gl.perspective(600, 1.0, 1.0, 5.0)
    np.testing.assert_allclose(mat(), np.eye(4))  # the modelview is untouched
    gl.translate(0, 0, -2)
    gl.mmode(GL.MPROJECTION)
    p = mat()
    assert p[2, 3] == -1.0 and p[3, 3] == 0.0
    gl.mmode(GL.MVIEWING)
    assert mat()[3, 2] == -2.0
    np.testing.assert_allclose(ctx.matrices.mvp(), mat() @ p)


def test_mmode_rejects_unknown_mode(ctx):
    with pytest.raises(gl.GLValueError, match=r"mmode\(7\)"):
        gl.mmode(7)


def test_perspective_errors(ctx):
    with pytest.raises(gl.GLValueError, match="fovy"):
        gl.perspective(1, 1.0, 1.0, 10.0)
    with pytest.raises(gl.GLValueError, match="near and far"):
        gl.perspective(450, 1.0, 2.0, 2.0)
    with pytest.raises(gl.GLTypeError, match="perspective"):
        gl.perspective(45.0, 1.0, 1.0, 10.0)
    with pytest.raises(gl.GLValueError, match="ortho2"):
        gl.ortho2(1, 1, 0, 1)


def test_lookat(ctx):
    gl.lookat(0, 0, 5, 0, 0, 0, 0)
    np.testing.assert_allclose(xf((0, 0, 0)), (0, 0, -5), atol=1e-12)
    np.testing.assert_allclose(xf((1, 0, 0)), (1, 0, -5), atol=1e-12)
    np.testing.assert_allclose(xf((0, 1, 0)), (0, 1, -5), atol=1e-12)
    with pytest.raises(gl.GLValueError, match="lookat"):
        gl.lookat(1, 1, 1, 1, 1, 1, 0)
    with pytest.raises(gl.GLTypeError, match="lookat"):
        gl.lookat(0, 0, 5, 0, 0, 0, 0.5)


def test_polarview(ctx):
    gl.polarview(5.0, 0, 0, 0)
    np.testing.assert_allclose(xf((0, 0, 0)), (0, 0, -5), atol=1e-12)
    gl.loadmatrix([1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1])
    # translate(0,0,-5) then rotate(-900,'z') (premultiplied last): (1,0,0) ->
    # rotated by -90 degrees about z to (0,-1,0), then translated.
    gl.polarview(5, 900, 0, 0)
    np.testing.assert_allclose(xf((1, 0, 0)), (0, -1, -5), atol=1e-12)


def test_push_pop_and_limits(ctx):
    gl.pushmatrix()
    gl.translate(1, 2, 3)
    gl.popmatrix()
    np.testing.assert_allclose(mat(), np.eye(4))
    with pytest.raises(gl.GLUsageError, match="popmatrix.*underflow"):
        gl.popmatrix()
    for _ in range(GL.MATRIXSTACKDEPTH - 1):
        gl.pushmatrix()
    with pytest.raises(gl.GLUsageError, match="pushmatrix.*overflow"):
        gl.pushmatrix()


def test_loadmatrix_forms_and_round_trip(ctx):
    m = [float(i) for i in range(1, 17)]
    gl.loadmatrix(m)
    assert gl.getmatrix() == m
    gl.loadmatrix(*m)  # 16 separate arguments (METH_OLDARGS)
    assert gl.getmatrix() == m
    gl.loadmatrix(np.arange(16.0).reshape(4, 4))  # numpy convenience
    assert gl.getmatrix() == list(np.arange(16.0))
    gl.loadmatrix(gl.getmatrix())
    assert gl.getmatrix() == list(np.arange(16.0))
    with pytest.raises(gl.GLTypeError, match="loadmatrix.*flat"):
        gl.loadmatrix([[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]])
    with pytest.raises(gl.GLTypeError, match="loadmatrix"):
        gl.loadmatrix([1.0] * 15)
    with pytest.raises(gl.GLValueError, match="multmatrix"):
        gl.multmatrix([float("nan")] + [0.0] * 15)


def test_multmatrix_premultiplies(ctx):
    t = np.eye(4)
    t[3, :3] = (1, 2, 3)
    s = np.diag([2.0, 3.0, 4.0, 1.0])
    gl.loadmatrix(list(t.reshape(-1)))
    gl.multmatrix(list(s.reshape(-1)))
    np.testing.assert_allclose(mat(), s @ t)


def test_matrix_calls_need_a_window():
    _core.session.reset()
    with pytest.raises(gl.GLUsageError, match=r"translate\(1, 2, 3\).*winopen"):
        gl.translate(1, 2, 3)
    with pytest.raises(gl.GLUsageError, match="getmatrix"):
        gl.getmatrix()


def test_standard_2d_projection_puts_integers_on_pixel_centres(ctx):
    gl.ortho2(-0.5, W - 0.5, -0.5, H - 0.5)
    gl.cpack(0xFF0000FF)
    for x, y in ((0, 0), (3, 4), (W - 1, H - 1)):
        gl.pnt2i(x, y)
    img = ctx.read_rgba()
    lit = {(int(x), int(y)) for y, x in zip(*np.nonzero(img[..., 0]), strict=True)}
    assert lit == {(0, 0), (3, 4), (W - 1, H - 1)}


def test_standard_2d_projection_with_a_viewport(ctx):
    # subpixel(3G): ortho2(l-0.5, r+0.5, b-0.5, t+0.5); viewport(l, r, b, t).
    gl.viewport(4, 11, 2, 9)
    gl.ortho2(3.5, 11.5, 1.5, 9.5)
    gl.cpack(0xFFFFFFFF)
    gl.rectf(4, 2, 8, 5)  # right/top edges exclusive: columns 4..7, rows 2..4
    gl.pnt2i(11, 9)
    gl.pnt2i(12, 9)  # outside the viewport: clipped
    img = ctx.read_rgba()
    lit = {(int(x), int(y)) for y, x in zip(*np.nonzero(img[..., 0]), strict=True)}
    assert lit == {(x, y) for x in range(4, 8) for y in range(2, 5)} | {(11, 9)}


# -- issue 10: the matrix rules of greset(3G) and mmode(3G) ---------------------------------
def test_new_window_starts_in_msingle_with_the_pixel_projection(fresh_session):
    # greset(3G) / IGL: ortho2(-0.5, W-0.5, -0.5, H-0.5).  For 200x100 by hand:
    # 2/200 = 0.01, 2/100 = 0.02, z negated; translation -(199/200), -(99/100).
    gl.prefsize(200, 100)
    gl.winopen("ortho")
    assert gl.getmmode() == GL.MSINGLE
    m = mat()
    np.testing.assert_allclose(np.diag(m), (0.01, 0.02, -1.0, 1.0), atol=1e-15)
    np.testing.assert_allclose(m[3, :3], (-0.995, -0.99, 0.0), atol=1e-15)
    assert np.count_nonzero(m) == 6  # nothing else


def test_new_window_integer_coordinates_land_on_pixel_centres(fresh_session):
    gl.prefsize(20, 10)
    gl.winopen("pixel")
    gl.RGBmode()
    gl.gconfig()
    gl.cpack(0xFF000000)
    gl.clear()
    gl.cpack(0xFF0000FF)
    gl.bgnpoint()
    gl.v2i(7, 3)
    gl.endpoint()
    img = np.frombuffer(gl.lrectread(0, 0, 19, 9), dtype=np.uint32).reshape(10, 20)
    assert [tuple(map(int, p)) for p in np.argwhere(img & 0xFF)] == [(3, 7)]


def test_entering_and_leaving_msingle_resets_every_matrix(ctx):
    gl.translate(1, 2, 3)
    gl.pushmatrix()
    gl.mmode(GL.MVIEWING)  # leaving MSINGLE
    np.testing.assert_allclose(mat(), np.eye(4))
    with pytest.raises(gl.GLUsageError, match="underflow"):
        gl.popmatrix()  # the stack was emptied
    gl.mmode(GL.MPROJECTION)
    np.testing.assert_allclose(mat(), np.eye(4))  # the old single matrix is not kept
    gl.ortho2(0, 4, 0, 2)
    gl.mmode(GL.MVIEWING)
    gl.translate(5, 0, 0)
    gl.pushmatrix()
    gl.mmode(GL.MSINGLE)  # entering MSINGLE
    np.testing.assert_allclose(mat(), np.eye(4))
    np.testing.assert_allclose(ctx.matrices.mvp(), np.eye(4))
    with pytest.raises(gl.GLUsageError, match="underflow"):
        gl.popmatrix()
    gl.mmode(GL.MVIEWING)  # and the projection did not survive the round trip
    gl.mmode(GL.MPROJECTION)
    np.testing.assert_allclose(mat(), np.eye(4))


def test_switching_among_the_other_modes_keeps_the_matrices(ctx):
    gl.mmode(GL.MVIEWING)
    gl.translate(0, 0, -2)
    gl.mmode(GL.MPROJECTION)
    gl.ortho2(0, 4, 0, 2)
    gl.mmode(GL.MTEXTURE)
    gl.scale(2, 2, 1)
    gl.mmode(GL.MVIEWING)
    assert mat()[3, 2] == -2.0
    gl.mmode(GL.MPROJECTION)
    assert mat()[0, 0] == 0.5
    gl.mmode(GL.MTEXTURE)
    assert mat()[0, 0] == 2.0


@pytest.mark.parametrize("mode", [GL.MPROJECTION, GL.MTEXTURE])
def test_push_and_pop_are_errors_where_there_is_no_stack(ctx, mode):
    # mmode(3G): "The Projection and Texture matrices are not stacked. Thus ...
    # pushmatrix and popmatrix should not be called" there.  vgxsim: GLUsageError.
    gl.mmode(mode)
    gl.loadmatrix([2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 1])
    with pytest.raises(gl.GLUsageError, match=r"pushmatrix\(\).*not stacked"):
        gl.pushmatrix()
    with pytest.raises(gl.GLUsageError, match=r"popmatrix\(\).*not stacked"):
        gl.popmatrix()
    assert mat()[0, 0] == 2.0  # untouched
    gl.mmode(GL.MVIEWING)
    gl.pushmatrix()  # the modelview stack still works
    gl.popmatrix()


# -- viewport stack, mapw/mapw2, libgl helpers ---------------------------------------------
def test_pushviewport_popviewport(ctx):
    gl.viewport(1, 10, 2, 8)
    gl.scrmask(3, 4, 5, 6)
    gl.pushviewport()
    gl.viewport(0, 3, 0, 3)
    assert gl.getviewport() == (0, 3, 0, 3)
    gl.popviewport()
    assert gl.getviewport() == (1, 10, 2, 8) and gl.getscrmask() == (3, 4, 5, 6)
    with pytest.raises(gl.GLUsageError, match="underflow"):
        gl.popviewport()
    for _ in range(GL.VPSTACKDEPTH):
        gl.pushviewport()
    with pytest.raises(gl.GLUsageError, match="overflow"):
        gl.pushviewport()


def test_mapw2_and_mapw_undo_the_objects_transform(ctx):
    # Window 16 x 12, viewport the whole window.  Object: ortho2(0, 8, 0, 6), so screen
    # pixel centre x maps to world (x + 0.5) / 2 and y to (y + 0.5) / 2.
    gl.makeobj(7)
    gl.ortho2(0, 8, 0, 6)
    gl.closeobj()
    before = gl.getmatrix()
    wx, wy = gl.mapw2(7, 3, 5)
    assert (wx, wy) == pytest.approx((1.75, 2.75))
    assert gl.getmatrix() == before  # the object's transform is not left behind
    # ortho(0, 8, 0, 6, 1, 3): z_ndc -1 is world z = -1 (near), +1 is z = -3 (far).
    gl.makeobj(8)
    gl.ortho(0, 8, 0, 6, 1, 3)
    gl.closeobj()
    assert gl.mapw(8, 3, 5) == pytest.approx((1.75, 2.75, -1.0, 1.75, 2.75, -3.0))


def test_mapw_draws_nothing(ctx):
    ctx.clear_planes(1, colour=0)  # CLEAR_COLOUR
    before = ctx.read_rgba().copy()
    gl.makeobj(9)
    gl.ortho2(0, 8, 0, 6)
    gl.cpack(0xFFFFFFFF)
    gl.clear()
    gl.rectf(0, 0, 8, 6)
    gl.closeobj()
    gl.mapw2(9, 1, 1)
    assert np.array_equal(ctx.read_rgba(), before)


def test_gl_invertmat_and_gl_sincos():
    m = [2, 0, 0, 0, 0, 4, 0, 0, 0, 0, 5, 0, 1, 2, 3, 1]
    inv = np.array(gl.gl_invertmat(m)).reshape(4, 4)
    np.testing.assert_allclose(np.array(m, float).reshape(4, 4) @ inv, np.eye(4), atol=1e-12)
    with pytest.raises(gl.GLValueError, match="singular"):
        gl.gl_invertmat([0] * 16)
    s, c = gl.gl_sincos(300)  # 30 degrees
    assert (s, c) == pytest.approx((0.5, math.sqrt(3) / 2))


def test_screenspace_maps_screen_pixels_to_the_window(fresh_session):
    gl.prefposition(100, 115, 50, 61)  # a 16 x 12 window at screen (100, 50)
    gl.winopen("screen")
    gl.RGBmode()
    gl.gconfig()
    gl.cpack(0xFF000000)
    gl.clear()
    gl.screenspace()
    gl.cpack(0xFF0000FF)
    gl.bgnpoint()
    gl.v2i(103, 54)  # screen coordinates
    gl.endpoint()
    img = np.frombuffer(gl.lrectread(0, 0, 15, 11), dtype=np.uint32).reshape(12, 16)
    assert [tuple(map(int, p)) for p in np.argwhere(img & 0xFF)] == [(4, 3)]
    assert gl.getscrmask() == (0, 15, 0, 11)
