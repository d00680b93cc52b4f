"""NURBS (vgxsim.gl._nurbs, vgxsim.geometry.nurbs).

Independent expectations: scipy's B-spline evaluation for the basis functions, the
unit circle for a rational quadratic arc, hand-placed flat patches whose covered
pixels are known, and the binding's control-point transposition worked out by hand
(cpython_gl_module.md 1.6: GL sees point (s, t) at ctlpoints[t][s]).
"""

import numpy as np
import pytest

import vgxsim.gl as gl
from vgxsim import GL
from vgxsim.geometry import nurbs as N
from vgxsim.gl import _draw
from vgxsim.gl._core import GLTypeError, GLUsageError, GLValueError

pytestmark = pytest.mark.usefixtures("fresh_session")  # tests/gl/conftest.py
W = H = 64
BEZ = [0.0, 0, 0, 0, 1, 1, 1, 1]  # cubic Bezier as a NURBS knot vector


@pytest.fixture
def win():
    gl.prefsize(W, H)
    gl.winopen("nurbs")
    gl.RGBmode()
    gl.gconfig()
    gl.cpack(0xFF000000)
    gl.clear()
    gl.cpack(0xFFFFFFFF)


def lit() -> np.ndarray:
    img = np.frombuffer(gl.lrectread(0, 0, W - 1, H - 1), dtype=np.uint32).reshape(H, W)
    return (img & 0xFFFFFF) != 0


def flat_grid(x0=10.0, x1=50.0, y0=10.0, y1=50.0):
    """ctlpoints[i][j] = (x_j, y_i, 0): x follows the inner index."""
    xs, ys = np.linspace(x0, x1, 4), np.linspace(y0, y1, 4)
    return [[[float(xs[j]), float(ys[i]), 0.0] for j in range(4)] for i in range(4)]


def surface(ctl, trims=(), typ=GL.N_XYZ):
    gl.bgnsurface()
    gl.nurbssurface(BEZ, BEZ, ctl, 4, 4, typ)
    for loop in trims:
        gl.bgntrim()
        gl.pwlcurve(loop, GL.N_ST)
        gl.endtrim()
    gl.endsurface()


def test_basis_matches_scipy():
    from scipy.interpolate import BSpline

    knots = np.array([0, 0, 0, 1, 2, 2.5, 4, 4, 4], float)
    order = 3
    ts = np.linspace(0, 4, 41)
    ours = N.basis_matrix(knots, order, ts)
    n = len(knots) - order
    for i in range(n):
        c = np.zeros(n)
        c[i] = 1.0
        ref = BSpline(knots, c, order - 1, extrapolate=False)(ts)
        ref[-1] = BSpline(knots, c, order - 1)(4.0)  # the closed right end
        np.testing.assert_allclose(ours[:, i], ref, atol=1e-12)
        dref = BSpline(knots, c, order - 1).derivative()(ts[:-1])
        np.testing.assert_allclose(N.basis_derivative_matrix(knots, order, ts)[:-1, i],
                                   dref, atol=1e-12)
    np.testing.assert_allclose(ours.sum(axis=1), 1.0)


def test_rational_quadratic_is_a_circle():
    r = np.sqrt(0.5)
    ctrl = np.array([[1, 0, 1], [r, r, r], [0, 1, 1]], float)  # (w x, w y, w)
    h = N.curve_points(ctrl, np.array([0, 0, 0, 1, 1, 1.0]), 3, np.linspace(0, 1, 50))
    np.testing.assert_allclose(np.hypot(h[:, 0] / h[:, 2], h[:, 1] / h[:, 2]), 1.0,
                               atol=1e-12)


def test_flat_patch_normals_and_points():
    ctl = np.array(flat_grid(), float)  # [i][j]
    control = np.concatenate([ctl.transpose(1, 0, 2), np.ones((4, 4, 1))], axis=2)
    p, n = N.surface_points(control, np.array(BEZ), np.array(BEZ), 4, 4,
                            np.array([0.0, 0.5, 1.0]), np.array([0.0, 0.25]))
    np.testing.assert_allclose(p[1, 1, :3], (30.0, 20.0, 0.0))  # s -> x, t -> y
    np.testing.assert_allclose(n, np.broadcast_to([0.0, 0.0, 1.0], n.shape))


def test_filled_patch_covers_its_square(win):
    surface(flat_grid())
    img = lit()
    assert img[12:48, 12:48].all()
    assert not img[:8].any() and not img[53:].any()
    assert not img[:, :8].any() and not img[:, 53:].any()


def test_trim_hole_and_the_binding_transposition(win):
    outer = [[0, 0], [1, 0], [1, 1], [0, 1], [0, 0]]  # counter-clockwise: keep inside
    hole = [[0.3, 0.3], [0.3, 0.7], [0.7, 0.7], [0.7, 0.3], [0.3, 0.3]]  # clockwise
    surface(flat_grid(), trims=[outer, hole])
    img = lit()
    assert not img[26:35, 26:35].any()  # the hole: x, y in 22..38 (0.3..0.7 of 10..50)
    assert img[12:18, 12:48].all() and img[43:48, 12:48].all()  # the ring
    gl.cpack(0xFF000000)
    gl.clear()
    gl.cpack(0xFFFFFFFF)
    # Keep s < 0.5 only.  s follows the *inner* index of ctlpoints (GL reads point
    # (s, t) at ctlpoints[t][s]), which flat_grid made x: the left half stays.
    surface(flat_grid(), trims=[[[0, 0], [0.5, 0], [0.5, 1], [0, 1], [0, 0]]])
    img = lit()
    assert img[12:48, 12:28].all()
    assert not img[:, 32:].any()


def test_rational_surface_homogeneous_points(win):
    ctl = [[[2 * x, 2 * y, 0.0, 2.0] for x, y, _ in row] for row in flat_grid()]
    surface(ctl, typ=GL.N_XYZW)
    img = lit()
    assert img[12:48, 12:48].all() and not img[:8].any()


def test_pixel_tolerance_bounds_edge_length(win, monkeypatch):
    seen = []
    real = _draw.v4f
    monkeypatch.setattr(_draw, "v4f", lambda p: (seen.append(p[:2]), real(p)))
    gl.setnurbsproperty(GL.N_PIXEL_TOLERANCE, 5.0)
    surface(flat_grid())  # 40 pixels wide: 8 pieces of 5
    xs = sorted({round(p[0], 9) for p in seen})
    assert len(xs) == 9 and max(np.diff(xs)) <= 5.0 + 1e-9
    seen.clear()
    gl.setnurbsproperty(GL.N_PIXEL_TOLERANCE, 50.0)
    surface(flat_grid())
    assert len({round(p[0], 9) for p in seen}) == 2  # one piece (>= 1 per knot span)


def test_outline_modes(win):
    gl.setnurbsproperty(GL.N_DISPLAY, GL.N_OUTLINE_PATCH)
    assert gl.getnurbsproperty(GL.N_DISPLAY) == 5.0
    surface(flat_grid())
    img = lit()
    assert img[10, 10:51].all() and img[50, 10:51].all() and img[10:51, 10].all()
    assert not img[20:40, 20:40].any()  # outline only
    gl.setnurbsproperty(GL.N_DISPLAY, GL.N_OUTLINE_POLY)
    gl.setnurbsproperty(GL.N_PIXEL_TOLERANCE, 20.0)
    gl.cpack(0xFF000000)
    gl.clear()
    gl.cpack(0xFFFFFFFF)
    surface(flat_grid())
    img = lit()
    assert img[30, 10:51].all()  # the middle grid line (40 / 20 = 2 pieces)
    assert not img[20, 15:25].all()


def test_bgncurve_draws_a_3d_curve(win):
    r = np.sqrt(0.5)
    gl.setnurbsproperty(GL.N_PIXEL_TOLERANCE, 3.0)  # chords short enough to hug the arc
    gl.bgncurve()
    gl.nurbscurve([0, 0, 0, 1, 1, 1], [[60, 32, 0, 1], [60 * r, 60 * r, 0, r],
                                       [32, 60, 0, 1]], 3, GL.N_XYZW)
    gl.endcurve()
    ys, xs = np.nonzero(lit())
    assert ys.size > 20
    # Control points (60, 32), (60, 60) w=r, (32, 60): a quarter circle of radius 28
    # around (32, 32); every drawn pixel within a pixel of it (vertex snapping plus the
    # line raster's half pixel).
    assert np.all(np.abs(np.hypot(xs - 32.0, ys - 32.0) - 28.0) < 1.0)


def test_sequence_and_argument_errors(win):
    with pytest.raises(GLUsageError, match="bgnsurface"):
        gl.nurbssurface(BEZ, BEZ, flat_grid(), 4, 4, GL.N_XYZ)
    gl.bgnsurface()
    with pytest.raises(GLTypeError, match="ctlpoints must be a list of 4 lists"):
        gl.nurbssurface(BEZ, BEZ, flat_grid()[:3], 4, 4, GL.N_XYZ)
    with pytest.raises(GLValueError, match="order"):
        gl.nurbssurface(BEZ, BEZ, flat_grid(), 9, 4, GL.N_XYZ)
    with pytest.raises(GLValueError, match="N_ST or N_STW"):
        gl.bgntrim()
        gl.nurbscurve([0, 0, 1, 1], [[0, 0, 0], [1, 1, 1]], 2, GL.N_XYZ)
    gl.endtrim()
    with pytest.raises(GLUsageError, match="no nurbssurface"):
        gl.endsurface()
    with pytest.raises(GLValueError, match="N_PIXEL_TOLERANCE"):
        gl.setnurbsproperty(99, 1.0)
    assert gl.getnurbsproperty(GL.N_PIXEL_TOLERANCE) == 50.0


def test_lit_surface_normals_face_the_light(win):
    # Diffuse 0.8, no ambient anywhere, a directional light from +z: a surface whose
    # normal is +z shades to 0.8 * 255 = 204; a normal of -z would give black.
    gl.lmdef(GL.DEFMATERIAL, 1, [GL.DIFFUSE, 0.8, 0.8, 0.8, GL.AMBIENT, 0, 0, 0, GL.LMNULL])
    gl.lmdef(GL.DEFLIGHT, 1, [GL.POSITION, 0, 0, 1, 0, GL.LMNULL])
    gl.lmdef(GL.DEFLMODEL, 1, [GL.AMBIENT, 0, 0, 0, GL.LMNULL])
    gl.lmbind(GL.MATERIAL, 1)
    gl.lmbind(GL.LIGHT0, 1)
    gl.lmbind(GL.LMODEL, 1)
    surface(flat_grid())
    img = np.frombuffer(gl.lrectread(0, 0, W - 1, H - 1), dtype=np.uint32).reshape(H, W)
    assert np.all((img[12:48, 12:48] & 0xFF) == 204)
