"""Tests of vgxsim.lighting: lmdef tables and the IRIS GL lighting equation.

Expected values are computed by hand; the arithmetic is in the comments.  Defaults
used throughout: material ambient 0.2, diffuse 0.8, specular 0, emission 0, alpha 1;
lmodel ambient 0.2, attenuation (1, 0, 0); light LCOLOR 1, ambient 0, directional
from +z.  So the scene-ambient term is 0.2 * 0.2 = 0.04 for a default material.
"""

import math

import numpy as np
import pytest

from vgxsim.lighting import (
    Light,
    LightingError,
    LightingTables,
    LightModel,
    Material,
    apply_lmcolor,
    light_to_eye,
    shade,
)

# Token values from <gl/gl.h> (Lib/plat-irix5/GL.py), independent of the package's own.
DEFMATERIAL, DEFLIGHT, DEFLMODEL = 0, 100, 200
LMNULL = 0
EMISSION, AMBIENT, DIFFUSE, SPECULAR, SHININESS, COLORINDEXES, ALPHA = 1, 2, 3, 4, 5, 6, 7
LCOLOR, POSITION, SPOTDIRECTION, SPOTLIGHT = 101, 102, 103, 104
LOCALVIEWER, ATTENUATION, ATTENUATION2, TWOSIDE = 201, 202, 203, 204
LMC_COLOR, LMC_EMISSION, LMC_AMBIENT, LMC_DIFFUSE, LMC_SPECULAR, LMC_AD, LMC_NULL = range(7)

ORIGIN = np.zeros((1, 3))
UP_Z = np.array([[0.0, 0.0, 1.0]])
SUN = (Light(), None, None)  # default light: directional from +z, LCOLOR white


def one(rgba):
    """The single row of a (1, 4) result."""
    assert rgba.shape == (1, 4) and rgba.dtype == np.float64
    return rgba[0]


def point_light(x, y, z, **kw):
    light = Light(position=(x, y, z, 1.0), **kw)
    return (light, np.array(light.position), np.array(light.spot_direction))


# --------------------------------------------------------------------------- equation


def test_directional_light_on_facing_normal():
    # 0.2*0.2 (scene ambient) + max(N.L,0)=1 * 0.8 * 1 = 0.04 + 0.8 = 0.84; alpha 1.
    rgba = one(shade(ORIGIN, UP_Z, Material(), [SUN], LightModel()))
    np.testing.assert_allclose(rgba, [0.84, 0.84, 0.84, 1.0], atol=1e-12)


def test_directional_light_at_60_degrees():
    # N = (0, sin 60, cos 60): N.L = cos 60 = 0.5 with L = (0, 0, 1).
    n = np.array([[0.0, math.sqrt(3) / 2, 0.5]])
    mat = Material(diffuse=(1.0, 0.5, 0.25))
    light = Light(lcolor=(1.0, 1.0, 0.5))
    rgba = one(shade(ORIGIN, n, mat, [(light, None, None)], LightModel()))
    # r: 0.04 + 0.5*1.00*1.0 = 0.54
    # g: 0.04 + 0.5*0.50*1.0 = 0.29
    # b: 0.04 + 0.5*0.25*0.5 = 0.1025
    np.testing.assert_allclose(rgba, [0.54, 0.29, 0.1025, 1.0], atol=1e-12)


def test_normals_are_normalized_and_zero_normal_gets_ambient_only():
    n = np.array([[0.0, 0.0, 7.0], [0.0, 0.0, 0.0]])
    mat = Material(emission=(0.1, 0.0, 0.0))
    light = Light(ambient=(0.5, 0.5, 0.5))
    rgba = shade(np.zeros((2, 3)), n, mat, [(light, None, None)], LightModel())
    # length-7 normal: 0.1 + 0.04 + (0.2*0.5 + 1*0.8) = 1.04 -> r clamps to 1; g,b = 0.94
    np.testing.assert_allclose(rgba[0], [1.0, 0.94, 0.94, 1.0], atol=1e-12)
    # zero normal: emission + scene ambient + light ambient: 0.1 + 0.04 + 0.1 = 0.24 (r)
    np.testing.assert_allclose(rgba[1], [0.24, 0.14, 0.14, 1.0], atol=1e-12)


def test_specular_with_exact_half_vector():
    # Light from (1, 0, 1)/sqrt2, infinite viewer V = (0,0,1), N = (0,0,1).
    # H = normalize(L + V) is 22.5 degrees from z: N.H = cos 22.5.
    # shininess 2: cos^2 22.5 = (1 + cos 45)/2 = (2 + sqrt2)/4 = 0.8535533...
    # N.L = 1/sqrt2 = 0.7071068 -> diffuse red 0.5 * 0.7071068 = 0.3535534.
    light = Light(position=(1.0, 0.0, 1.0, 0.0))
    mat = Material(ambient=(0, 0, 0), diffuse=(0.5, 0.0, 0.0), specular=(0.0, 1.0, 0.0),
                   shininess=2.0)
    rgba = one(shade(ORIGIN, UP_Z, mat, [(light, None, None)], LightModel()))
    np.testing.assert_allclose(rgba, [0.5 / math.sqrt(2), (2 + math.sqrt(2)) / 4, 0.0, 1.0],
                               atol=1e-12)


def test_specular_with_normal_on_half_vector_uses_lcolor():
    # N along H exactly: N.H = 1 -> 1**30 = 1; specular (0.5, 0.5, 0.5) * LCOLOR (1, .4, 0).
    # N.L = cos 22.5 but diffuse is 0, ambient 0.
    h = np.array([[math.sin(math.pi / 8), 0.0, math.cos(math.pi / 8)]])
    light = Light(position=(1.0, 0.0, 1.0, 0.0), lcolor=(1.0, 0.4, 0.0))
    mat = Material(ambient=(0, 0, 0), diffuse=(0, 0, 0), specular=(0.5, 0.5, 0.5),
                   shininess=30.0)
    rgba = one(shade(ORIGIN, h, mat, [(light, None, None)], LightModel()))
    np.testing.assert_allclose(rgba, [0.5, 0.2, 0.0, 1.0], atol=1e-12)


@pytest.mark.parametrize("shininess", [0.0, 0.5])
def test_shininess_below_one_disables_specular(shininess):
    # IGL loads a zero specular colour unless SHININESS >= 1 (x**0 would be 1 everywhere).
    mat = Material(ambient=(0, 0, 0), diffuse=(0, 0, 0), specular=(1, 1, 1),
                   shininess=shininess)
    rgba = one(shade(ORIGIN, UP_Z, mat, [SUN], LightModel()))
    np.testing.assert_allclose(rgba, [0.0, 0.0, 0.0, 1.0])


def test_no_specular_when_light_behind_surface():
    # L = normalize(1, 0, -0.2): N.L < 0, yet H = normalize(L + (0,0,1)) has N.H > 0.
    light = Light(position=(1.0, 0.0, -0.2, 0.0))
    mat = Material(ambient=(0, 0, 0), diffuse=(0, 0, 0), specular=(1, 1, 1), shininess=1.0)
    rgba = one(shade(ORIGIN, UP_Z, mat, [(light, None, None)], LightModel()))
    np.testing.assert_allclose(rgba, [0.0, 0.0, 0.0, 1.0])


def test_attenuation_of_local_light():
    # Light at (0,0,5), vertex at origin: d = 5.  k0=1, k1=0.5, k2=0.1:
    # 1 + 0.5*5 + 0.1*25 = 1 + 2.5 + 2.5 = 6 -> atten 1/6.
    # rgb = 0.04 + (0.2*0.3 (light ambient) + 1*0.8) / 6 = 0.04 + 0.86/6 = 0.1833333
    lm = LightModel(attenuation=(1.0, 0.5), attenuation2=0.1)
    expect = 0.04 + 0.86 / 6
    for pos in ((0.0, 0.0, 5.0, 1.0), (0.0, 0.0, 10.0, 2.0)):  # w = 2 is the same point
        light = Light(position=pos, ambient=(0.3, 0.3, 0.3))
        rgba = one(shade(ORIGIN, UP_Z, Material(), [(light, np.array(pos), None)], lm))
        np.testing.assert_allclose(rgba, [expect, expect, expect, 1.0], atol=1e-12)
    # Directional lights are never attenuated: 0.04 + 0.8 = 0.84.
    rgba = one(shade(ORIGIN, UP_Z, Material(), [SUN], lm))
    np.testing.assert_allclose(rgba[:3], 0.84, atol=1e-12)


def test_zero_attenuation_denominator_contributes_nothing():
    # k0 = k1 = k2 = 0: 1/0 -> treated as no contribution, never NaN: 0.04 left.
    lm = LightModel(attenuation=(0.0, 0.0))
    rgba = one(shade(ORIGIN, UP_Z, Material(), [point_light(0, 0, 5)], lm))
    np.testing.assert_allclose(rgba, [0.04, 0.04, 0.04, 1.0], atol=1e-12)


def test_spotlight_cone_and_exponent():
    # Light at (0,0,5) aiming down -z.  Only ambient terms so the result is spot * 0.5:
    # material ambient 0.5, light ambient 1, scene ambient 0, diffuse 0.
    mat = Material(ambient=(0.5, 0.5, 0.5), diffuse=(0, 0, 0))
    lm = LightModel(ambient=(0, 0, 0))
    pts = np.array([[0.0, 0.0, 0.0],    # on the axis: cos 0 = 1
                    [5.0, 0.0, 0.0]])   # 45 degrees off axis: cos 45 = 1/sqrt2
    n = np.tile(UP_Z, (2, 1))

    def run(exponent, spread):
        entry = point_light(0, 0, 5, ambient=(1.0, 1.0, 1.0), spot_exponent=exponent,
                            spot_spread=spread)
        return shade(pts, n, mat, [entry], lm)[:, 0]

    # spread 60, exponent 2: axis 1**2 * 0.5 = 0.5; 45 deg: (1/sqrt2)**2 * 0.5 = 0.25
    np.testing.assert_allclose(run(2.0, 60.0), [0.5, 0.25], atol=1e-12)
    # spread 30: the 45-degree vertex is outside the cone -> 0
    np.testing.assert_allclose(run(2.0, 30.0), [0.5, 0.0], atol=1e-12)
    # exponent 0 inside the cone: factor 1 -> 0.5 both
    np.testing.assert_allclose(run(0.0, 60.0), [0.5, 0.5], atol=1e-12)
    # spread 180 is "no cone": the exponent is ignored as well
    np.testing.assert_allclose(run(2.0, 180.0), [0.5, 0.5], atol=1e-12)


def test_spot_direction_argument_overrides_definition():
    # The caller's eye-space spot direction (+x) is used, not the definition's (-z):
    # the axis vertex is now 90 degrees off axis -> outside a 30-degree cone.
    mat = Material(ambient=(0.5, 0.5, 0.5), diffuse=(0, 0, 0))
    light = Light(position=(0, 0, 5, 1), ambient=(1, 1, 1), spot_spread=30.0)
    entry = (light, np.array([0, 0, 5, 1.0]), np.array([1.0, 0.0, 0.0]))
    rgba = one(shade(ORIGIN, UP_Z, mat, [entry], LightModel(ambient=(0, 0, 0))))
    np.testing.assert_allclose(rgba[:3], 0.0)


def test_local_viewer_changes_specular():
    # Light from +z, N = (0,0,1), vertex at (10, 0, -10), shininess 2, specular white.
    # Infinite viewer: V = (0,0,1) = L -> H = (0,0,1), N.H = 1 -> 1.
    # Local viewer: V = normalize(-P) = (-1, 0, 1)/sqrt2, 45 degrees from L,
    #   H is 22.5 degrees from z -> N.H**2 = cos^2 22.5 = (2 + sqrt2)/4 = 0.8535534.
    p = np.array([[10.0, 0.0, -10.0]])
    mat = Material(ambient=(0, 0, 0), diffuse=(0, 0, 0), specular=(1, 1, 1), shininess=2.0)
    inf = one(shade(p, UP_Z, mat, [SUN], LightModel()))
    loc = one(shade(p, UP_Z, mat, [SUN], LightModel(local_viewer=True)))
    np.testing.assert_allclose(inf[:3], 1.0, atol=1e-12)
    np.testing.assert_allclose(loc[:3], (2 + math.sqrt(2)) / 4, atol=1e-12)


def test_two_sided_lighting_flips_normal_and_uses_back_material():
    # Both vertices have N = (0,0,-1), facing away from the light at +z.
    pts = np.zeros((2, 3))
    n = np.array([[0.0, 0.0, -1.0], [0.0, 0.0, -1.0]])
    back = np.array([False, True])
    front_mat = Material()
    back_mat = Material(ambient=(0, 0, 0), diffuse=(0.0, 0.5, 0.0), alpha=0.5)

    # One-sided: N.L = -1 -> only 0.04 for both; `facing` is ignored.
    one_sided = shade(pts, n, front_mat, [SUN], LightModel(), back_mat, back)
    np.testing.assert_allclose(one_sided[:, :3], 0.04, atol=1e-12)
    np.testing.assert_allclose(one_sided[:, 3], 1.0)

    lm = LightModel(twoside=True)
    # Two-sided, no back material: vertex 1 flips to N.L = 1 -> 0.84 with the front one.
    rgba = shade(pts, n, front_mat, [SUN], lm, None, back)
    np.testing.assert_allclose(rgba[0], [0.04, 0.04, 0.04, 1.0], atol=1e-12)
    np.testing.assert_allclose(rgba[1], [0.84, 0.84, 0.84, 1.0], atol=1e-12)
    # With BACKMATERIAL: vertex 1 = 0 (ambient 0) + 1 * (0, 0.5, 0), alpha 0.5.
    rgba = shade(pts, n, front_mat, [SUN], lm, back_mat, back)
    np.testing.assert_allclose(rgba[0], [0.04, 0.04, 0.04, 1.0], atol=1e-12)
    np.testing.assert_allclose(rgba[1], [0.0, 0.5, 0.0, 0.5], atol=1e-12)


def test_clamping_above_one_and_below_zero():
    # emission 0.9 + 0.04 + 0.8 = 1.74 -> 1; emission -2 + 0.84 = -1.16 -> 0; alpha 3 -> 1.
    mat = Material(emission=(0.9, -2.0, 0.1), alpha=3.0)
    rgba = one(shade(ORIGIN, UP_Z, mat, [SUN], LightModel()))
    np.testing.assert_allclose(rgba, [1.0, 0.0, 0.94, 1.0], atol=1e-12)


def test_two_lights_add():
    # Sun (0.84) plus a second directional light from +x with N.L = 0: adds 0 diffuse
    # but its ambient 0.1 * material ambient 0.2 = 0.02 -> 0.86.
    second = (Light(position=(1.0, 0.0, 0.0, 0.0), ambient=(0.1, 0.1, 0.1)), None, None)
    rgba = one(shade(ORIGIN, UP_Z, Material(), [SUN, second], LightModel()))
    np.testing.assert_allclose(rgba[:3], 0.86, atol=1e-12)


def test_no_lights_and_no_vertices():
    # No lights: emission + 0.2*0.2.
    rgba = one(shade(ORIGIN, UP_Z, Material(), [], LightModel()))
    np.testing.assert_allclose(rgba, [0.04, 0.04, 0.04, 1.0], atol=1e-12)
    assert shade(np.zeros((0, 3)), np.zeros((0, 3)), Material(), [SUN],
                 LightModel()).shape == (0, 4)


def test_light_to_eye_row_vector_convention():
    # Translation by (1, 2, 3) in row 3 (IRIS row vectors); rotation 90 deg about z
    # (x -> y): rows are the images of the basis vectors.
    m = np.array([[0.0, 1.0, 0.0, 0.0],
                  [-1.0, 0.0, 0.0, 0.0],
                  [0.0, 0.0, 1.0, 0.0],
                  [1.0, 2.0, 3.0, 1.0]])
    light = Light(position=(1.0, 0.0, 0.0, 1.0), spot_direction=(1.0, 0.0, 0.0))
    same, pos, spot = light_to_eye(light, m.ravel())
    assert same is light
    # (1,0,0,1) @ m = row0 + row3 = (0+1, 1+2, 0+3, 1) = (1, 3, 3, 1)
    np.testing.assert_allclose(pos, [1.0, 3.0, 3.0, 1.0])
    # (1,0,0) @ m[:3,:3] = (0, 1, 0): directions ignore the translation
    np.testing.assert_allclose(spot, [0.0, 1.0, 0.0])
    _, pos, _ = light_to_eye(Light(), m)  # (0,0,1,0): w = 0 keeps (0, 0, 1, 0)
    np.testing.assert_allclose(pos, [0.0, 0.0, 1.0, 0.0])


def test_shape_errors():
    with pytest.raises(LightingError, match="positions_eye"):
        shade(np.zeros(3), UP_Z, Material(), [SUN], LightModel())
    with pytest.raises(LightingError, match="normals"):
        shade(np.zeros((2, 3)), UP_Z, Material(), [SUN], LightModel())
    with pytest.raises(LightingError, match="facing"):
        shade(ORIGIN, UP_Z, Material(), [SUN], LightModel(twoside=True), None,
              np.array([True, False]))


# ---------------------------------------------------------------------------- lmcolor


def test_apply_lmcolor_modes():
    m = Material()
    c = (0.1, 0.2, 0.3, 0.4)
    assert apply_lmcolor(m, LMC_COLOR, c) is m
    assert apply_lmcolor(m, LMC_NULL, c) is m
    assert apply_lmcolor(m, LMC_EMISSION, c) == Material(emission=(0.1, 0.2, 0.3))
    assert apply_lmcolor(m, LMC_AMBIENT, c) == Material(ambient=(0.1, 0.2, 0.3))
    assert apply_lmcolor(m, LMC_SPECULAR, c) == Material(specular=(0.1, 0.2, 0.3))
    assert apply_lmcolor(m, LMC_DIFFUSE, c) == Material(diffuse=(0.1, 0.2, 0.3), alpha=0.4)
    assert apply_lmcolor(m, LMC_AD, c) == Material(ambient=(0.1, 0.2, 0.3),
                                                   diffuse=(0.1, 0.2, 0.3), alpha=0.4)
    # three components: alpha untouched
    assert apply_lmcolor(m, LMC_DIFFUSE, c[:3]) == Material(diffuse=(0.1, 0.2, 0.3))
    assert m == Material()  # the input is never modified
    with pytest.raises(LightingError, match="unknown mode"):
        apply_lmcolor(m, 9, c)
    with pytest.raises(LightingError, match="3 or 4"):
        apply_lmcolor(m, LMC_AD, (1.0, 1.0))


def test_color_override_per_vertex_values():
    # N at 60 degrees from the light: N.L = 0.5.  Three vertices, three colours.
    n = np.tile([[0.0, math.sqrt(3) / 2, 0.5]], (3, 1))
    pts = np.zeros((3, 3))
    cols = np.array([[0.6, 0.4, 0.2, 0.3],
                     [1.0, 0.0, 0.0, 0.5],
                     [0.0, 0.0, 0.0, 1.0]])
    rgba = shade(pts, n, Material(), [SUN], LightModel(), color_override=(LMC_AD, cols))
    # LMC_AD: rgb = 0.2 * c (scene ambient) + 0.5 * c (diffuse) = 0.7 * c; alpha = c.a
    #   (0.42, 0.28, 0.14, 0.3), (0.7, 0, 0, 0.5), (0, 0, 0, 1)
    np.testing.assert_allclose(rgba, [[0.42, 0.28, 0.14, 0.3],
                                      [0.7, 0.0, 0.0, 0.5],
                                      [0.0, 0.0, 0.0, 1.0]], atol=1e-12)
    rgba = shade(pts, n, Material(), [SUN], LightModel(), color_override=(LMC_DIFFUSE, cols))
    # LMC_DIFFUSE: 0.04 + 0.5 * c: (0.34, 0.24, 0.14, 0.3)
    np.testing.assert_allclose(rgba[0], [0.34, 0.24, 0.14, 0.3], atol=1e-12)
    rgba = shade(pts, n, Material(), [SUN], LightModel(),
                 color_override=(LMC_EMISSION, cols[:, :3]))
    # LMC_EMISSION: c + 0.04 + 0.5*0.8 = c + 0.44; alpha stays 1: (1.04->1, 0.84, 0.64)
    np.testing.assert_allclose(rgba[0], [1.0, 0.84, 0.64, 1.0], atol=1e-12)


@pytest.mark.parametrize("mode", range(7))
def test_color_override_matches_apply_lmcolor(mode):
    # The vectorised override must equal shading each vertex with apply_lmcolor.
    rng = np.random.default_rng(mode)
    pts = rng.normal(size=(5, 3)) - [0.0, 0.0, 5.0]
    n = rng.normal(size=(5, 3))
    cols = rng.uniform(size=(5, 4))
    mat = Material(specular=(0.5, 0.5, 0.5), shininess=8.0)
    lights = [SUN, point_light(1.0, 2.0, 3.0, spot_spread=70.0, spot_exponent=1.5)]
    lm = LightModel(local_viewer=True, attenuation=(0.5, 0.1))
    got = shade(pts, n, mat, lights, lm, color_override=(mode, cols))
    for i in range(5):
        want = shade(pts[i:i + 1], n[i:i + 1], apply_lmcolor(mat, mode, cols[i]), lights, lm)
        np.testing.assert_allclose(got[i], want[0], atol=1e-12)


def test_color_override_skips_back_material():
    # IGL: lmcolor() does not change BACKMATERIAL.  Back vertex with BACKMATERIAL
    # diffuse (0, 0.5, 0), ambient 0, flipped normal N.L = 1 -> (0, 0.5, 0) whatever the colour.
    n = np.array([[0.0, 0.0, -1.0]])
    back_mat = Material(ambient=(0, 0, 0), diffuse=(0.0, 0.5, 0.0))
    rgba = shade(ORIGIN, n, Material(), [SUN], LightModel(twoside=True), back_mat,
                 np.array([True]), color_override=(LMC_DIFFUSE, (1.0, 0.0, 0.0, 0.2)))
    np.testing.assert_allclose(one(rgba), [0.0, 0.5, 0.0, 1.0], atol=1e-12)


# ------------------------------------------------------------------------------ lmdef


def test_lmdef_defaults_and_partial_redefinition():
    t = LightingTables()
    assert t.lmdef(DEFMATERIAL, 1, []) == Material()
    assert t.lmdef(DEFLIGHT, 1, []) == Light()
    assert t.lmdef(DEFLMODEL, 1, []) == LightModel()
    assert t.material(2) is None and t.material(0) is None

    m = t.lmdef(DEFMATERIAL, 3, [DIFFUSE, 0.8, 0.2, 0.2, SHININESS, 30.0, LMNULL])
    assert m.diffuse == (0.8, 0.2, 0.2) and m.shininess == 30.0 and m.ambient == (0.2,) * 3
    # Redefinition changes only SPECULAR; DIFFUSE and SHININESS keep their values.
    m2 = t.lmdef(DEFMATERIAL, 3, [SPECULAR, 1.0, 1.0, 1.0])  # LMNULL is optional
    assert m2 == Material(diffuse=(0.8, 0.2, 0.2), shininess=30.0, specular=(1.0, 1.0, 1.0))
    assert t.material(3) is m2 and t.get(DEFMATERIAL, 3) is m2
    assert t.lmdef(DEFMATERIAL, 3, []) == m2  # empty list: no change
    m3 = t.lmdef(DEFMATERIAL, 3, np.array([ALPHA, 0.5, EMISSION, 0.1, 0.2, 0.3,
                                           COLORINDEXES, 1, 2, 3, AMBIENT, 0, 0, 0, 0]))
    assert (m3.alpha, m3.emission, m3.colorindexes, m3.ambient) == (
        0.5, (0.1, 0.2, 0.3), (1.0, 2.0, 3.0), (0.0, 0.0, 0.0))
    assert m3.diffuse == (0.8, 0.2, 0.2)
    assert t.indices(DEFMATERIAL) == [1, 3]


def test_lmdef_light_and_lmodel_properties():
    t = LightingTables()
    light = t.lmdef(DEFLIGHT, 5, [LCOLOR, 1, 0.5, 0, POSITION, 1, 2, 3, 1,
                                  SPOTDIRECTION, 0, -1, 0, SPOTLIGHT, 10, 45, AMBIENT,
                                  0.1, 0.1, 0.1, LMNULL])
    assert light == Light(ambient=(0.1, 0.1, 0.1), lcolor=(1.0, 0.5, 0.0),
                          position=(1.0, 2.0, 3.0, 1.0), spot_direction=(0.0, -1.0, 0.0),
                          spot_exponent=10.0, spot_spread=45.0)
    assert light.is_local and not Light().is_local
    assert t.lmdef(DEFLIGHT, 5, [POSITION, 0, 0, 1, 0]).lcolor == (1.0, 0.5, 0.0)
    lm = t.lmdef(DEFLMODEL, 1, [LOCALVIEWER, 1, TWOSIDE, 2.0, ATTENUATION, 1, 0.5,
                                ATTENUATION2, 0.1, AMBIENT, 0, 0, 0, LMNULL])
    assert lm == LightModel(ambient=(0.0, 0.0, 0.0), local_viewer=True,
                            attenuation=(1.0, 0.5), attenuation2=0.1, twoside=True)
    assert t.lmdef(DEFLMODEL, 1, [LOCALVIEWER, 0]).local_viewer is False
    assert t.lmodel(1).twoside is True and t.light(5).spot_spread == 45.0


def test_lmdef_generation_counts_successful_calls():
    t = LightingTables()
    assert t.generation == 0
    t.lmdef(DEFMATERIAL, 1, [])
    t.lmdef(DEFMATERIAL, 1, [SHININESS, 5])
    with pytest.raises(LightingError):
        t.lmdef(DEFMATERIAL, 1, [99])
    assert t.generation == 2


@pytest.mark.parametrize(
    ("deftype", "index", "props", "message"),
    [
        (DEFMATERIAL, 3, [DIFFUSE, 1, 1, 1, 99, 0],
         r"^lmdef\(DEFMATERIAL, 3, \.\.\.\): unknown property token 99 at position 4$"),
        (DEFMATERIAL, 3, [SHININESS],
         r"^lmdef\(DEFMATERIAL, 3, \.\.\.\): wrong number of values for SHININESS "
         r"at position 0"),
        (DEFLIGHT, 2, [POSITION, 1, 2, 3],
         r"wrong number of values for POSITION"),
        # a fourth DIFFUSE value 1 reads as the token EMISSION, which lacks its values
        (DEFMATERIAL, 3, [DIFFUSE, 1, 1, 1, 1, LMNULL],
         r"wrong number of values for EMISSION at position 4: needs 3, props has 1 left"),
        (DEFMATERIAL, 3, [DIFFUSE, 0.5, 0.5, 0.5, 0.5, LMNULL],
         r"unknown property token 0\.5 at position 4 \(the DIFFUSE before it takes 3"),
        (DEFMATERIAL, 3, [LMNULL, DIFFUSE, 1, 1, 1],
         r"^lmdef\(DEFMATERIAL, 3, \.\.\.\): LMNULL inside props at position 0"),
        (DEFMATERIAL, 3, [LCOLOR, 1, 1, 1],
         r"property LCOLOR \(101\) at position 0 is not valid for DEFMATERIAL"),
        (DEFLIGHT, 1, [SHININESS, 3],
         r"^lmdef\(DEFLIGHT, 1, \.\.\.\): property SHININESS \(5\) .* not valid for DEFLIGHT"),
        (DEFLMODEL, 1, [POSITION, 0, 0, 1, 0], r"POSITION .* not valid for DEFLMODEL"),
        (DEFLIGHT, 1, [TWOSIDE, 1], r"TWOSIDE .* not valid for DEFLIGHT"),
        (DEFMATERIAL, 0, [], r"^lmdef\(DEFMATERIAL, 0, \.\.\.\): index 0 is reserved"),
        (DEFLIGHT, 40000, [], r"index 40000 outside"),
        (DEFLIGHT, -1, [], r"index -1 outside"),
        (DEFLIGHT, 1.5, [], r"index must be an integer"),
        (57, 1, [], r"^lmdef\(57, 1, \.\.\.\): unknown deftype 57"),
        (DEFMATERIAL, 1, [SHININESS, float("nan")], r"non-finite value nan for SHININESS"),
        (DEFMATERIAL, 1, ["shiny"], r"flat sequence of numbers"),
        (DEFMATERIAL, 1, [[DIFFUSE, 1, 1, 1]], r"flat sequence of numbers"),
    ],
)
def test_lmdef_errors(deftype, index, props, message):
    t = LightingTables()
    t.lmdef(DEFMATERIAL, 3, [DIFFUSE, 0.1, 0.1, 0.1])
    before = t.material(3)
    with pytest.raises(LightingError, match=message) as info:
        t.lmdef(deftype, index, props)
    assert isinstance(info.value, ValueError)
    assert t.material(3) is before  # a failed lmdef changes nothing
    assert t.indices(DEFLIGHT) == [] and t.indices(DEFLMODEL) == []


def test_lmdef_accepts_integral_float_index_and_token_floats():
    t = LightingTables()
    m = t.lmdef(DEFMATERIAL, 4.0, [5.0, 12.0, 0.0])
    assert m.shininess == 12.0 and t.indices(DEFMATERIAL) == [4]


def test_lmdef_material_then_shade_end_to_end():
    # The Microsoft porting-guide material, lit head-on by the default light:
    # ambient .1 * .2 = 0.02; diffuse (0, .369, .165); specular .5 * 1**10 = .5
    # r = 0.02 + 0 + 0.5 = 0.52; g = 0.02 + 0.369 + 0.5 = 0.889; b = 0.02 + 0.165 + 0.5 = 0.685
    t = LightingTables()
    mat = t.lmdef(DEFMATERIAL, 1, [AMBIENT, .1, .1, .1, DIFFUSE, 0, .369, .165,
                                   SPECULAR, .5, .5, .5, SHININESS, 10, LMNULL])
    lm = t.lmdef(DEFLMODEL, 1, [])
    light = t.lmdef(DEFLIGHT, 1, [])
    rgba = one(shade(ORIGIN, UP_Z, mat, [light_to_eye(light, np.eye(4))], lm))
    np.testing.assert_allclose(rgba, [0.52, 0.889, 0.685, 1.0], atol=1e-12)
