"""lmdef / lmbind / lmcolor through vgxsim.gl against the lighting equation by hand.

Scene: an 8x8 window, ortho(-4, 4, -4, 4), mmode(MVIEWING), a square from (-2, -2)
to (2, 2) (pixels 2..5) with one normal for all vertices, so every pixel has the
vertex colour.  Material: AMBIENT 0.1, DIFFUSE (0.8, 0.6, 0.4), no specular;
lighting model AMBIENT 0.2 (default); one directional white light.  The equation
(irisgl_reference.md 1.6) gives

    rgb = ambient_m * ambient_lmodel + max(N.L, 0) * diffuse_m * lcolor
        = 0.02 + (N.L) * (0.8, 0.6, 0.4)

and a byte is floor(c * 255 + 0.5).
"""

import math

import numpy as np
import pytest

from vgxsim import GL
from vgxsim.geometry.transform import orthographic, rotation
from vgxsim.gl._color import c3f, c4f, color, cpack
from vgxsim.gl._core import GLTypeError, GLValueError
from vgxsim.gl._lighting import *
from vgxsim.state.matrices import MVIEWING

N = 8
SQUARE = np.array([[-2, -2, 0], [2, -2, 0], [2, 2, 0], [-2, 2, 0]], float)
MAT = [GL.AMBIENT, 0.1, 0.1, 0.1, GL.DIFFUSE, 0.8, 0.6, 0.4, GL.LMNULL]
R90 = rotation(90.0, "z")


@pytest.fixture
def win(gl_window):
    def make(rgb=True):
        ctx = gl_window(N, N, rgb=rgb, stencil=0, projection=False)
        ctx.matrices.set_mode(MVIEWING)
        ctx.matrices.load_projection(orthographic(-4, 4, -4, 4, -1, 1))
        return ctx

    return make


def setup_scene(light_pos=(0, 1, 1, 0)):
    lmdef(GL.DEFMATERIAL, 1, MAT)
    lmdef(GL.DEFLIGHT, 1, [GL.POSITION, *light_pos, GL.LMNULL])
    lmdef(GL.DEFLMODEL, 1, [GL.LMNULL])


def bind_all():
    lmbind(GL.MATERIAL, 1)
    lmbind(GL.LMODEL, 1)
    lmbind(GL.LIGHT0, 1)


def draw_lit(ctx, normal):
    n = np.tile(np.asarray(normal, float), (4, 1))
    ctx.draw_arrays("polygon", SQUARE, normals=n)
    ctx.flush()
    img = ctx.read_rgba()
    inside = img[2:6, 2:6].reshape(-1, 4)
    assert np.all(inside == inside[0])  # one colour over the whole square
    assert np.all(img[0, :] == 0)  # and nothing outside
    return tuple(int(c) for c in inside[0])


def byte(c):
    return math.floor(c * 255 + 0.5)


def expected(n_dot_l, diffuse=(0.8, 0.6, 0.4), ambient=0.1, alpha=1.0):
    return tuple(byte(ambient * 0.2 + n_dot_l * d) for d in diffuse) + (byte(alpha),)


def test_lit_square_matches_the_equation(win):
    ctx = win()
    setup_scene()
    bind_all()
    assert ctx.lighting_active()
    got = draw_lit(ctx, (0, 0, 1))
    assert got == expected(1 / math.sqrt(2)) == (149, 113, 77, 255)


def test_light_is_transformed_by_the_modelview_at_lmbind(win):
    ctx = win()
    setup_scene()
    tilted = (0, 1 / math.sqrt(2), 1 / math.sqrt(2))
    bind_all()
    # Control: light and normal both untransformed -> N.L = 1.
    assert draw_lit(ctx, tilted) == expected(1.0) == (209, 158, 107, 255)
    # Rotating the modelview *after* lmbind turns the normal (to (-1, 0, 1)/sqrt 2)
    # but not the light: N.L = 1/2.  The square maps onto itself.
    ctx.matrices.load(R90)
    assert draw_lit(ctx, tilted) == expected(0.5) == (107, 82, 56, 255)
    # Binding under the rotation turns the light; drawing unrotated: N.L = 1/2 again.
    lmbind(GL.LIGHT0, 1)
    ctx.matrices.load(np.eye(4))
    assert draw_lit(ctx, tilted) == expected(0.5)
    pos = ctx.bound["lights"][0][1][1]
    assert np.allclose(pos, [-1, 0, 1, 0])


def test_redefining_a_bound_light_resends_it(win):
    ctx = win()
    setup_scene()
    bind_all()
    ctx.matrices.load(R90)
    lmdef(GL.DEFLIGHT, 1, [GL.LCOLOR, 1, 1, 1, GL.LMNULL])  # re-sent through R90
    ctx.matrices.load(np.eye(4))
    assert np.allclose(ctx.bound["lights"][0][1][1], [-1, 0, 1, 0])
    assert draw_lit(ctx, (0, 1 / math.sqrt(2), 1 / math.sqrt(2))) == expected(0.5)


def test_lighting_needs_material_and_lmodel(win):
    ctx = win()
    setup_scene()
    cpack(0xFF00FF00)
    lmbind(GL.MATERIAL, 1)
    lmbind(GL.LIGHT0, 1)
    assert not ctx.lighting_active()
    assert draw_lit(ctx, (0, 0, 1)) == (0, 255, 0, 255)  # the current colour
    lmbind(GL.LMODEL, 1)
    assert ctx.lighting_active()
    lmbind(GL.MATERIAL, 0)  # index 0 unbinds
    assert not ctx.lighting_active()


def test_lmbind_undefined_and_bad_target(win):
    win()
    setup_scene()
    with pytest.raises(GLValueError) as e:
        lmbind(GL.MATERIAL, 5)
    assert str(e.value) == ("lmbind(MATERIAL, 5): material 5 is not defined "
                            "(define it with lmdef(DEFMATERIAL, 5, ...))")
    with pytest.raises(GLValueError, match=r"lmbind\(LIGHT3, 2\): light 2 is not defined"):
        lmbind(GL.LIGHT3, 2)
    with pytest.raises(GLValueError, match="lighting model 9 is not defined"):
        lmbind(GL.LMODEL, 9)
    with pytest.raises(GLValueError, match="target 1108 is not a valid token"):
        lmbind(1108, 1)
    with pytest.raises(GLTypeError):
        lmbind(GL.MATERIAL, 1.0)


def test_lmcolor_diffuse_and_ad_then_lost_on_rebind(win):
    ctx = win()
    setup_scene()
    bind_all()
    lmcolor(GL.LMC_DIFFUSE)
    ctx.last_sent = "normal"
    assert draw_lit(ctx, (0, 0, 1)) == expected(1 / math.sqrt(2))  # no colour sent yet
    c3f(1.0, 0.0, 0.0)
    assert ctx.last_sent == "normal"
    assert draw_lit(ctx, (0, 0, 1)) == expected(1 / math.sqrt(2), (1, 0, 0)) == (
        185, 5, 5, 255)
    lmbind(GL.MATERIAL, 1)  # "lmcolor changes are lost whenever a new material is bound"
    assert draw_lit(ctx, (0, 0, 1)) == (149, 113, 77, 255)
    lmcolor(GL.LMC_AD)
    c4f(0.5, 0.5, 0.5, 0.5)
    got = draw_lit(ctx, (0, 0, 1))
    assert got == expected(1 / math.sqrt(2), (0.5,) * 3, ambient=0.5, alpha=0.5)
    assert got == (116, 116, 116, 128)
    with pytest.raises(GLValueError, match=r"mode 7 is not a valid token \(LMC_\*\)"):
        lmcolor(7)


def test_lmdef_c_form_with_np(win):
    ctx = win()
    lmdef(GL.DEFMATERIAL, 2, 4, [GL.DIFFUSE, 0.1, 0.2, 0.3, GL.SHININESS, 5.0])
    m = ctx.lighting.material(2)
    assert m.diffuse == (0.1, 0.2, 0.3) and m.shininess == 0.0
    lmdef(GL.DEFMATERIAL, 2, 0, [GL.SHININESS, 5.0, GL.LMNULL])
    m = ctx.lighting.material(2)
    assert m.diffuse == (0.1, 0.2, 0.3) and m.shininess == 5.0
    lmdef(GL.DEFMATERIAL, 3, np.array([GL.ALPHA, 0.25, GL.LMNULL]))
    assert ctx.lighting.material(3).alpha == 0.25
    with pytest.raises(GLValueError, match="np 9 is outside 0..2"):
        lmdef(GL.DEFMATERIAL, 2, 9, [GL.ALPHA, 1.0])


def test_lmdef_errors_name_the_call(win):
    win()
    with pytest.raises(GLValueError) as e:
        lmdef(GL.DEFLIGHT, 1, [GL.DIFFUSE, 1, 1, 1])
    msg = str(e.value)
    assert msg.startswith("lmdef(DEFLIGHT, 1, [DIFFUSE, 1, 1, 1]): property DIFFUSE (3)")
    assert "not valid for DEFLIGHT" in msg
    with pytest.raises(GLValueError, match="index 0 is reserved"):
        lmdef(GL.DEFMATERIAL, 0, [])
    with pytest.raises(GLValueError, match="wrong number of values for DIFFUSE"):
        lmdef(GL.DEFMATERIAL, 1, [GL.DIFFUSE, 1, 1])
    with pytest.raises(GLValueError, match=r"deftype 5 is not a valid token"):
        lmdef(5, 1, [])
    with pytest.raises(GLTypeError, match="props must be a flat sequence"):
        lmdef(GL.DEFMATERIAL, 1, "abc")
    with pytest.raises(GLTypeError):
        lmdef(GL.DEFMATERIAL, 1)


def test_cmode_lighting_keeps_the_index(win):
    ctx = win(rgb=False)
    setup_scene()
    bind_all()
    color(5)
    ctx.draw_arrays("polygon", SQUARE, normals=np.tile([0.0, 0.0, 1.0], (4, 1)))
    ctx.flush()
    assert np.all(ctx.fb.front[2:6, 2:6] == 5)


def test_two_sided_lighting_lights_back_faces_with_backmaterial(gl_window):
    """TWOSIDE: a clockwise (back-facing) square facing away from the light is lit
    from the back with the BACKMATERIAL (lmdef(3G)); without TWOSIDE it gets only
    the ambient terms.  Hand computation: directional light from +z, LCOLOR 1, the
    square's normal is -z (facing away); flipped, N.L = 1, so the back colour is
    lmodel ambient 0.2 * back ambient 0.2 + diffuse (0, 0.5, 0) = (0.04, 0.54, 0.04).
    Without TWOSIDE the front material sees N.L < 0: 0.2 * 0.2 = 0.04 each."""
    import vgxsim.gl as gl

    ctx = gl_window(8, 8, stencil=0)
    gl.lmdef(gl.DEFMATERIAL, 1, [gl.DIFFUSE, 0.5, 0.0, 0.0, gl.AMBIENT, 0.2, 0.2, 0.2,
                                  gl.LMNULL])
    gl.lmdef(gl.DEFMATERIAL, 2, [gl.DIFFUSE, 0.0, 0.5, 0.0, gl.AMBIENT, 0.2, 0.2, 0.2,
                                  gl.LMNULL])
    gl.lmdef(gl.DEFLIGHT, 1, [gl.POSITION, 0.0, 0.0, 1.0, 0.0, gl.LMNULL])
    gl.lmdef(gl.DEFLMODEL, 1, [gl.TWOSIDE, 1.0, gl.LMNULL])
    gl.lmdef(gl.DEFLMODEL, 2, [gl.TWOSIDE, 0.0, gl.LMNULL])
    gl.lmbind(gl.MATERIAL, 1)
    gl.lmbind(gl.BACKMATERIAL, 2)
    gl.lmbind(gl.LIGHT0, 1)
    results = {}
    for model in (1, 2):
        gl.lmbind(gl.LMODEL, model)
        gl.bgnpolygon()
        gl.n3f(0.0, 0.0, -1.0)
        for v in ((0, 0, 0), (0, 7, 0), (7, 7, 0), (7, 0, 0)):  # clockwise on screen
            gl.v3f(v)
        gl.endpolygon()
        results[model] = ctx.read_rgba()[3, 3, :3].astype(int)
    expect = [round(0.04 * 255), round(0.54 * 255), round(0.04 * 255)]
    assert np.array_equal(results[1], expect)
    assert np.array_equal(results[2], [round(0.04 * 255)] * 3)
