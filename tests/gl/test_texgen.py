"""texgen(3G) TG_CONTOUR and TG_SPHEREMAP against hand-computed coordinates.

As tests/gl/test_texture.py: a 2 x 2 texture, pixel centres on integer object
coordinates, the projection ortho2(-0.5, W - 0.5, ...), here in MVIEWING so that a
modelview exists.  The plane s = (x + 0.5) / 4 puts texel column 0 on pixels 0..1
and column 1 on pixels 2..3 (repeating every 4 pixels).
"""

import functools
import math

import numpy as np
import pytest

from vgxsim import GL
from vgxsim.geometry.texgen import sphere_map
from vgxsim.gl import bgnpolygon, endpolygon, loadmatrix, mmode, n3f, ortho2, t2f, v3f
from vgxsim.gl._core import GLValueError
from vgxsim.gl._texture import tevbind, tevdef, texbind, texdef2d, texgen

W = H = 8
RED, GREEN, BLUE, WHITE = (255, 0, 0, 255), (0, 255, 0, 255), (0, 0, 255, 255), (255,) * 4
IMAGE = np.array([[RED, GREEN], [BLUE, WHITE]], np.uint8)  # texel (i, j) = IMAGE[j, i]
S_PLANE = (0.25, 0.0, 0.0, 0.125)
T_PLANE = (0.0, 0.25, 0.0, 0.125)


@pytest.fixture
def win(gl_window):
    return functools.partial(gl_window, W, H, projection=False)


def translation(x, y):
    m = np.eye(4)
    m[3, :2] = (x, y)
    return m.reshape(-1).tolist()


def setup(mode_s, mode_t, modelview, s_plane=S_PLANE, t_plane=T_PLANE):
    mmode(GL.MVIEWING)
    ortho2(-0.5, W - 0.5, -0.5, H - 0.5)
    loadmatrix(modelview)
    texdef2d(1, 4, 2, 2, IMAGE, 1, (GL.TX_NULL,))
    tevdef(1, 1, (GL.TV_NULL,))
    texbind(GL.TX_TEXTURE_0, 1)
    tevbind(GL.TV_ENV0, 1)
    texgen(GL.TX_S, mode_s, s_plane if mode_s != GL.TG_SPHEREMAP else None)
    texgen(GL.TX_T, mode_t, t_plane if mode_t != GL.TG_SPHEREMAP else None)
    texgen(GL.TX_S, GL.TG_ON, None)
    texgen(GL.TX_T, GL.TG_ON, None)


def square(ctx, x0, y0, size=4, normal=None, coords=None):
    ctx.colour = (1.0, 1.0, 1.0, 1.0)
    bgnpolygon()
    for k, (x, y) in enumerate(((x0, y0), (x0 + size, y0), (x0 + size, y0 + size),
                                (x0, y0 + size))):
        if normal is not None:
            n3f(normal[k])
        if coords is not None:
            t2f(coords[k])
        v3f((x, y, 0))
    endpolygon()
    ctx.flush()
    return ctx.read_rgba().astype(int)


def test_contour_plane_is_fixed_in_the_eye_space_of_the_texgen_call(win):
    """The plane was given under translate(2, 0): in eye space it is s = (xe - 2 + 0.5)
    / 4.  A square drawn later at object x = 2..6 under the identity shows texel column
    0 from eye x = 2 (pixels 2, 3), where TG_LINEAR with the same plane would show
    column 1 (s = (2 + 0.5) / 4 -> u = 1.25)."""
    ctx = win()
    setup(GL.TG_CONTOUR, GL.TG_CONTOUR, translation(2, 0))
    loadmatrix(translation(0, 0))
    img = square(ctx, 2, 0)
    for x in range(2, 6):
        for y in range(4):
            assert tuple(img[y, x]) == tuple(IMAGE[y // 2, (x - 2) // 2]), (x, y)


def test_contour_equals_linear_when_the_modelview_is_unchanged(win):
    """Eye point o M on the eye plane M^-1 p: (o M) . (M^-1 p) = o . p."""
    got = []
    for mode in (GL.TG_CONTOUR, GL.TG_LINEAR):
        ctx = win()
        setup(mode, mode, translation(2, 1))
        got.append(square(ctx, 0, 0))
    assert np.array_equal(got[0], got[1])
    assert tuple(got[0][1, 2]) == RED  # object (0, 0) at eye (2, 1): texel (0, 0)


def test_linear_follows_the_object_and_contour_stays_in_the_eye(win):
    """Moving the modelview after texgen moves a TG_LINEAR pattern with the object but
    leaves a TG_CONTOUR pattern where it was in the window."""
    shots = {}
    for mode in (GL.TG_LINEAR, GL.TG_CONTOUR):
        ctx = win()
        setup(mode, mode, translation(0, 0))
        loadmatrix(translation(2, 0))
        shots[mode] = square(ctx, 0, 0)  # drawn over window x = 2..5
    # linear: object x 0 (window 2) shows column 0; contour: window x 2 shows column 1
    assert tuple(shots[GL.TG_LINEAR][0, 2]) == RED
    assert tuple(shots[GL.TG_CONTOUR][0, 2]) == GREEN


def _sphere_by_hand(pos, n):
    """The sphere map formula, written out for one vertex."""
    length = math.sqrt(sum(c * c for c in pos))
    u = [c / length for c in pos]
    nu = sum(a * b for a, b in zip(n, u, strict=True))
    r = [u[k] - 2 * n[k] * nu for k in range(3)]
    m = 2 * math.sqrt(r[0] ** 2 + r[1] ** 2 + (r[2] + 1) ** 2)
    return r[0] / m + 0.5, r[1] / m + 0.5


def test_sphere_map_of_known_vectors():
    # looking straight at a mirror facing the eye: r = (0, 0, 1), m = 4: the centre
    eye = np.array([[0.0, 0.0, -5.0, 1.0], [0.0, 0.0, -1.0, 1.0], [3.0, -4.0, 0.0, 1.0]])
    normals = np.array([[0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])
    got = sphere_map(eye, normals)
    assert got[0].tolist() == [0.5, 0.5]
    # normal perpendicular to u: r = u = (0, 0, -1), m = 0: the chosen centre
    assert got[1].tolist() == [0.5, 0.5]
    # u = (0.6, -0.8, 0), n . u = 0: r = u, m = 2 sqrt(2)
    assert got[2] == pytest.approx([0.6 / (2 * 2 ** 0.5) + 0.5, -0.8 / (2 * 2 ** 0.5) + 0.5],
                                   abs=1e-15)
    rng = np.random.default_rng(3)
    for _ in range(20):
        pos = rng.uniform(-3, 3, 3)
        n = rng.normal(size=3)
        n /= np.linalg.norm(n)
        want = _sphere_by_hand(pos.tolist(), n.tolist())
        assert sphere_map(np.array([[*pos, 1.0]]), n[None])[0] == pytest.approx(want,
                                                                                 abs=1e-14)


def test_sphere_map_draws_as_t2f_of_the_hand_computed_coordinates(win):
    """A square at z = 0 under translate(-3.5, -3.5) (eye positions around the axis)
    with per-vertex normals: the image equals the same square drawn with t2f of the
    coordinates computed by hand from the eye-space vertices and normals."""
    normals = [(0.0, 0.0, 1.0), (0.6, 0.0, 0.8), (0.0, -0.6, 0.8), (0.48, 0.6, 0.64)]
    corners = [(0, 0), (8, 0), (8, 8), (0, 8)]
    ctx = win()
    setup(GL.TG_SPHEREMAP, GL.TG_SPHEREMAP, translation(-3.5, -3.5))
    got = square(ctx, 0, 0, 8, normal=normals)
    by_hand = [_sphere_by_hand((x - 3.5, y - 3.5, 0.0), n)
               for (x, y), n in zip(corners, normals, strict=True)]
    ctx2 = win()
    setup(GL.TG_LINEAR, GL.TG_LINEAR, translation(-3.5, -3.5))
    texgen(GL.TX_S, GL.TG_OFF, None)
    texgen(GL.TX_T, GL.TG_OFF, None)
    want = square(ctx2, 0, 0, 8, coords=by_hand)
    assert np.array_equal(got, want)
    assert len({tuple(c) for c in got.reshape(-1, 4).tolist()}) >= 3  # several texels


def test_sphere_map_without_normals_uses_the_current_normal(win):
    ctx = win()
    setup(GL.TG_SPHEREMAP, GL.TG_SPHEREMAP, translation(-3.5, -3.5))
    n3f((0.0, 0.6, 0.8))
    got = square(ctx, 0, 0, 8)
    ctx2 = win()
    setup(GL.TG_SPHEREMAP, GL.TG_SPHEREMAP, translation(-3.5, -3.5))
    want = square(ctx2, 0, 0, 8, normal=[(0.0, 0.6, 0.8)] * 4)
    assert np.array_equal(got, want)


def test_texgen_errors_name_the_call(win):
    win()
    with pytest.raises(GLValueError, match="texgen.*TG_CONTOUR needs a plane"):
        texgen(GL.TX_S, GL.TG_CONTOUR, (1.0, 0.0))
    with pytest.raises(GLValueError, match="texgen.*TG_REFRACTMAP is not modelled"):
        texgen(GL.TX_S, GL.TG_REFRACTMAP, None)
    with pytest.raises(GLValueError, match="texgen.*TG_ON before"):
        texgen(GL.TX_T, GL.TG_ON, None)
