"""clipplane(3G): user clip planes against hand-computed pixels and Mesa glClipPlane.

The window is 8x8 with the standard ortho2(-0.5, 7.5, -0.5, 7.5): integer object
coordinates are pixel centres.  With subpixel(FALSE) the vertices the clipper makes
snap to pixel centres like any other (docs/numeric_model.md s. 2), so the planes of
the hand-computed cases cut at a quarter pixel, where the snap is unambiguous.
"""

import functools

import numpy as np
import pytest

from vgxsim import GL, gl
from vgxsim.gl._core import GLTypeError, GLValueError

W = H = 8


@pytest.fixture
def win(gl_window):
    return functools.partial(gl_window, W, H)


def full_square():
    gl.bgnpolygon()
    for v in ((-0.5, -0.5), (7.5, -0.5), (7.5, 7.5), (-0.5, 7.5)):
        gl.v2f(v)
    gl.endpolygon()


def covered(ctx):
    ctx.flush()
    return ctx.read_rgba()[..., 0] > 0


def columns(ctx):
    cov = covered(ctx)
    assert (cov == cov[0]).all()  # the planes below are vertical: whole columns
    return [int(x) for x in np.nonzero(cov[0])[0]]


def test_plane_keeps_the_positive_side(win):
    ctx = win()
    ctx.colour = (1.0, 1.0, 1.0, 1.0)
    gl.clipplane(0, GL.CP_DEFINE, (1.0, 0.0, 0.0, -3.25))  # x >= 3.25
    gl.clipplane(0, GL.CP_ON, (0.0,) * 4)
    full_square()
    # The cut edge x = 3.25 snaps to the centre 3, a left edge: it owns column 3.
    assert columns(ctx) == [3, 4, 5, 6, 7]


def test_two_planes_intersect_and_cp_off_restores(win):
    ctx = win()
    ctx.colour = (1.0, 1.0, 1.0, 1.0)
    gl.clipplane(0, GL.CP_DEFINE, (1.0, 0.0, 0.0, -1.75))  # x >= 1.75 -> edge at 2
    gl.clipplane(5, GL.CP_DEFINE, (-1.0, 0.0, 0.0, 5.25))  # x <= 5.25 -> edge at 5
    gl.clipplane(0, GL.CP_ON, ())
    gl.clipplane(5, GL.CP_ON, ())
    full_square()
    assert columns(ctx) == [2, 3, 4]  # right edge at centre 5 owns nothing
    gl.clipplane(0, GL.CP_OFF, ())
    gl.clipplane(5, GL.CP_OFF, ())
    full_square()
    assert columns(ctx) == list(range(8))


def test_plane_is_transformed_by_the_modelview_at_definition(win):
    ctx = win()
    ctx.colour = (1.0, 1.0, 1.0, 1.0)
    gl.mmode(GL.MVIEWING)
    gl.ortho2(-0.5, 7.5, -0.5, 7.5)
    gl.translate(2.0, 0.0, 0.0)
    # x_obj >= 1.25 under translate(2): x_eye >= 3.25, whatever the modelview later is.
    gl.clipplane(2, GL.CP_DEFINE, (1.0, 0.0, 0.0, -1.25))
    gl.clipplane(2, GL.CP_ON, ())
    gl.loadmatrix([1.0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1])
    full_square()
    assert columns(ctx) == [3, 4, 5, 6, 7]


def test_undefined_plane_switched_on_keeps_everything(win):
    ctx = win()
    ctx.colour = (1.0, 1.0, 1.0, 1.0)
    gl.clipplane(1, GL.CP_ON, ())
    full_square()
    assert columns(ctx) == list(range(8))


def test_lines_and_points_are_clipped(win):
    ctx = win()
    ctx.colour = (1.0, 1.0, 1.0, 1.0)
    gl.clipplane(0, GL.CP_DEFINE, (-1.0, 0.0, 0.0, 4.25))  # x <= 4.25
    gl.clipplane(0, GL.CP_ON, ())
    gl.bgnline()
    gl.v2i(0, 2)
    gl.v2i(7, 2)
    gl.endline()
    gl.bgnpoint()
    for x in (1, 4, 5, 7):
        gl.v2i(x, 5)
    gl.endpoint()
    cov = covered(ctx)
    # The line's cut end 4.25 snaps to 4 (closed line: columns 0..4); points at
    # x = 5 and 7 are outside the plane.
    assert {(int(x), int(y)) for y, x in zip(*np.nonzero(cov), strict=True)} == (
        {(x, 2) for x in range(5)} | {(1, 5), (4, 5)})


def test_plane_is_recorded_in_display_objects(win):
    ctx = win()
    ctx.colour = (1.0, 1.0, 1.0, 1.0)
    gl.makeobj(7)
    gl.clipplane(3, GL.CP_DEFINE, (1.0, 0.0, 0.0, -3.25))
    gl.clipplane(3, GL.CP_ON, ())
    gl.closeobj()
    full_square()
    assert columns(ctx) == list(range(8))  # recorded, not executed
    gl.callobj(7)
    full_square()
    assert columns(ctx) == list(range(8))  # the first square is still there
    gl.cpack(0)
    gl.clear()
    gl.cpack(0xFFFFFFFF)
    full_square()
    assert columns(ctx) == [3, 4, 5, 6, 7]


def test_clipplane_errors_and_gdesc(win):
    win()
    assert gl.getgdesc(GL.GD_CLIPPLANES) == 6
    with pytest.raises(GLValueError, match=r"index must be 0\.\.5"):
        gl.clipplane(6, GL.CP_ON, ())
    with pytest.raises(GLValueError, match=r"CP_"):
        gl.clipplane(0, 9, ())
    with pytest.raises(GLTypeError, match="expected 4 numbers"):
        gl.clipplane(0, GL.CP_DEFINE, (1.0, 2.0))
    with pytest.raises(GLValueError, match="finite"):
        gl.clipplane(0, GL.CP_DEFINE, (1.0, 0.0, float("nan"), 0.0))


# -- Mesa glClipPlane as an independent peer ---------------------------------------------
def _mesa_coverage(polys, mv, proj, planes, width, height):
    """Coverage of ``polys`` (lists of (x, y, z)) in Mesa, with ``planes`` defined
    under the row-vector modelview ``mv`` and drawn under ``mv`` and ``proj``."""
    from vgxsim.reference.mesa import MesaPeer, _import_gl

    GLm, _ = _import_gl()
    peer = MesaPeer(width, height)
    try:
        GLm.glViewport(0, 0, width, height)
        GLm.glDisable(GLm.GL_SCISSOR_TEST)
        GLm.glDisable(GLm.GL_DEPTH_TEST)
        GLm.glDisable(GLm.GL_DEPTH_CLAMP)
        GLm.glClearColor(0, 0, 0, 0)
        GLm.glClear(GLm.GL_COLOR_BUFFER_BIT)
        GLm.glMatrixMode(GLm.GL_PROJECTION)
        GLm.glLoadMatrixd(np.ascontiguousarray(proj, np.float64).reshape(-1))
        GLm.glMatrixMode(GLm.GL_MODELVIEW)
        GLm.glLoadMatrixd(np.ascontiguousarray(mv, np.float64).reshape(-1))
        for i, q in enumerate(planes):
            GLm.glClipPlane(GLm.GL_CLIP_PLANE0 + i, np.asarray(q, np.float64))
            GLm.glEnable(GLm.GL_CLIP_PLANE0 + i)
        GLm.glColor4f(1, 1, 1, 1)
        for poly in polys:
            GLm.glBegin(GLm.GL_POLYGON)
            for v in poly:
                GLm.glVertex3d(*v)
            GLm.glEnd()
        GLm.glFinish()
        return (peer.color() & 0xFF) > 0
    finally:
        peer.close()


def test_clipped_coverage_matches_mesa(gl_window):
    from vgxsim.reference import mesa

    if not mesa.mesa_available():
        pytest.skip("OSMesa is not available")
    size = 32
    ctx = gl_window(size, size)
    ctx.colour = (1.0, 1.0, 1.0, 1.0)
    rng = np.random.default_rng(3)
    proj = np.eye(4)  # ortho2(-0.5, 31.5, ...) as a row-vector matrix, z = 0 kept
    proj[0, 0] = proj[1, 1] = 2.0 / size
    proj[3, 0] = proj[3, 1] = -1.0 + 1.0 / size
    ang = 0.4
    mv = np.eye(4)
    mv[:2, :2] = [[np.cos(ang), np.sin(ang)], [-np.sin(ang), np.cos(ang)]]
    mv[3, :2] = (9.0, -3.0)
    # Planes with c = 0 in the defining coordinates: each cuts the window along a line.
    planes = [(1.0, 0.3, 0.0, -9.3), (-0.2, -1.0, 0.0, 21.7), (0.7, -0.7, 0.0, 4.1)]
    polys = [[tuple(p) + (0.0,) for p in rng.uniform(-2, 30, size=(3, 2))]
             for _ in range(12)]
    gl.subpixel(GL.TRUE)  # clip vertices keep 8 fractional bits, as llvmpipe's do
    gl.mmode(GL.MVIEWING)
    gl.mmode(GL.MPROJECTION)
    gl.loadmatrix(list(proj.reshape(-1)))
    gl.mmode(GL.MVIEWING)
    gl.loadmatrix(list(mv.reshape(-1)))
    for i, q in enumerate(planes):
        gl.clipplane(i, GL.CP_DEFINE, q)
        gl.clipplane(i, GL.CP_ON, ())
    for poly in polys:
        gl.bgnpolygon()
        for v in poly:
            gl.v3f(v)
        gl.endpolygon()
    ours = covered(ctx)
    theirs = _mesa_coverage(polys, mv, proj, planes, size, size)
    # Compare away from ties: pixel centres within 0.05 px of a plane or an edge.
    ys, xs = np.mgrid[0:size, 0:size].astype(float)
    inv = np.linalg.inv(mv)
    obj = np.stack([xs.ravel(), ys.ravel(), np.zeros(xs.size), np.ones(xs.size)], 1) @ inv
    near = np.zeros(xs.size, bool)
    for q in planes:
        near |= np.abs(obj @ np.asarray(q)) / np.hypot(q[0], q[1]) < 0.05
    win_pts = np.stack([xs.ravel(), ys.ravel()], 1)
    for poly in polys:
        p = (np.array([[v[0], v[1], 0, 1] for v in poly]) @ mv)[:, :2]
        for a, b in zip(p, np.roll(p, -1, axis=0), strict=True):
            d = b - a
            rel = win_pts - a
            cross = d[0] * rel[:, 1] - d[1] * rel[:, 0]
            near |= np.abs(cross) / np.hypot(*d) < 0.05
    keep = ~near.reshape(size, size)
    assert 100 < ours[keep].sum() < 0.8 * keep.sum()  # planes cut real coverage
    assert (ours[keep] == theirs[keep]).all()
