"""Curves and patches (vgxsim.gl._curves) against hand-computed points and pixels.

Control points are chosen so the curves are straight lines or rectangles whose pixels
are known by hand: Bezier control points spaced evenly on a line trace that line;
a uniform B-spline of evenly spaced collinear points runs from the second point to
the last but one.
"""

import numpy as np
import pytest

import vgxsim.gl as gl
from vgxsim.gl._core import GLTypeError, GLUsageError
from vgxsim.gl._curves import eval_segment

pytestmark = pytest.mark.usefixtures("fresh_session")  # tests/gl/conftest.py
W, H = 40, 20
BEZIER = [-1, 3, -3, 1, 3, -6, 3, 0, -3, 3, 0, 0, 1, 0, 0, 0]
BSPLINE = [x / 6 for x in (-1, 3, -3, 1, 3, -6, 3, 0, -3, 0, 3, 0, 1, 4, 1, 0)]


@pytest.fixture
def win():
    gl.prefsize(W, H)
    gl.winopen("curves")
    gl.RGBmode()
    gl.gconfig()
    gl.cpack(0xFF000000)
    gl.clear()
    gl.cpack(0xFFFFFFFF)
    gl.defbasis(1, BEZIER)
    gl.defbasis(2, BSPLINE)


def lit() -> set[tuple[int, int]]:
    img = np.frombuffer(gl.lrectread(0, 0, W - 1, H - 1), dtype=np.uint32).reshape(H, W)
    return {(int(x), int(y)) for y, x in np.argwhere((img & 0xFFFFFF) != 0)}


def hline(x0, x1, y):
    return {(x, y) for x in range(x0, x1 + 1)}


def test_bezier_midpoint_by_hand():
    b = np.array(BEZIER, float).reshape(4, 4)
    g = np.array([[0, 0, 0], [0, 1, 0], [1, 1, 0], [1, 0, 0]], float)
    pts = eval_segment(b, g, 2)
    # B(1/2) = (P0 + 3 P1 + 3 P2 + P3) / 8
    np.testing.assert_allclose(pts, [[0, 0, 0], [0.5, 0.75, 0], [1, 0, 0]], atol=1e-15)


def test_crv_draws_the_bezier_segment(win):
    gl.curvebasis(1)
    gl.curveprecision(6)
    gl.crv([2, 5, 0, 12, 5, 0, 22, 5, 0, 32, 5, 0])
    assert lit() == hline(2, 32, 5)


def test_crvn_bspline_runs_from_second_to_last_but_one_point(win):
    gl.curvebasis(2)
    gl.crvn([0, 5, 0, 10, 5, 0, 20, 5, 0, 30, 5, 0, 40, 5, 0])
    assert lit() == hline(10, 30, 5)


def test_rational_forms_divide_by_w(win):
    gl.curvebasis(1)
    pts = [(2, 7), (12, 7), (22, 7), (32, 7)]
    gl.rcrv([c for x, y in pts for c in (2 * x, 2 * y, 0, 2)])  # w = 2 everywhere
    gl.rcrvn([c for x, y in pts for c in (3 * x, 3 * (y + 5), 0, 3)])
    assert lit() == hline(2, 32, 7) | hline(2, 32, 12)


def test_patch_mesh_outline(win):
    gl.patchbasis(1, 1)
    gl.patchcurves(2, 2)  # the four edges only
    gl.patchprecision(3, 3)
    gx = [5 + 10 * i for i in range(4) for j in range(4)]  # i along u
    gy = [3 + 5 * j for i in range(4) for j in range(4)]  # j along v
    gz = [0] * 16
    gl.patch(gx, gy, gz)
    want = hline(5, 35, 3) | hline(5, 35, 18)
    want |= {(5, y) for y in range(3, 19)} | {(35, y) for y in range(3, 19)}
    assert lit() == want


def test_patch_inner_curves(win):
    gl.patchbasis(1, 1)
    gl.patchcurves(3, 2)  # one more curve along u at v = 1/2
    gx = [5 + 10 * i for i in range(4) for j in range(4)]
    gy = [2 + 4 * j for i in range(4) for j in range(4)]  # v = 1/2 at y = 8
    gl.rpatch(gx, gy, [0] * 16, [1] * 16)
    assert lit() == (hline(5, 35, 2) | hline(5, 35, 8) | hline(5, 35, 14)
                     | {(5, y) for y in range(2, 15)} | {(35, y) for y in range(2, 15)})


def test_curves_compile_into_display_objects_as_lines(win):
    gl.curvebasis(1)
    gl.makeobj(5)
    gl.crv([2, 5, 0, 12, 5, 0, 22, 5, 0, 32, 5, 0])
    gl.closeobj()
    assert lit() == set()  # compiled, not drawn
    gl.curvebasis(2)  # the object holds lines, not the call
    gl.callobj(5)
    assert lit() == hline(2, 32, 5)


def test_curveit_iterates_forward_differences(win):
    # Clip coordinates: pixel x = (ndc + 1) * 20 - 0.5, pixel y = (ndc + 1) * 10 - 0.5.
    gl.loadmatrix([-0.475, 0.05, 0, 1, 0.25, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0])
    gl.curveit(4)  # (10, 10) .. (30, 10) in 4 steps of 5 pixels
    assert lit() == hline(10, 30, 10)
    assert gl.getmatrix()[4] == 0.25  # the matrix is left as it was


def test_errors_name_the_call(win):
    with pytest.raises(GLUsageError, match="no curve basis"):
        gl.crv([0] * 12)
    with pytest.raises(GLUsageError, match="basis 9 is not defined"):
        gl.curvebasis(9)
    gl.curvebasis(1)
    with pytest.raises(GLTypeError, match=r"crv.*12 numbers"):
        gl.crv([0] * 9)
    with pytest.raises(GLTypeError, match="defbasis"):
        gl.defbasis(3, [0] * 15)
    with pytest.raises(GLUsageError, match="no patch basis"):
        gl.patch([0] * 16, [0] * 16, [0] * 16)
