"""Every technique on the hard cases (shadow_literature.md section 2), against the
exact ray cast: exact techniques have no misclassified pixel farther than one pixel
from a shadow boundary; the known failures are counted and must show up."""

from __future__ import annotations

import functools
import warnings

import numpy as np
import pytest

from vgxsim.shadow import api
from vgxsim.shadow.error import mask_error, near_boundary, shadow_error
from vgxsim.shadow.raycast import raycast
from vgxsim.shadow.techniques import TECHNIQUES, TechniqueError
from vgxsim.shadow.techniques.hard_cases import EXPECTED_FAILURES, HARD_CASES

W, H = 96, 80


def edge_on(sc, ref, light: int = 0) -> np.ndarray:
    """(H, W) bool: the visible polygon's plane holds the light exactly (N . L = 0).
    Such a face is in its own shadow by the facing rule and lit by the reference's
    segment, which runs inside its plane; either answer is right (shadow_literature.md
    H4: errors allowed on the grazing face's own footprint), so it is not compared."""
    from vgxsim.shadow.raycast import light_position

    tris, _ = sc.triangles()
    n = np.cross(tris[:, 1] - tris[:, 0], tris[:, 2] - tris[:, 0])
    lp = light_position(sc.lights[light])
    side = np.einsum("ij,ij->i", n, lp[:3][None, :] - lp[3] * tris[:, 0])
    flag = np.append(side == 0.0, False)
    return flag[ref.triangle]


@functools.cache
def case(name: str):
    sc = HARD_CASES[name]()
    return sc, raycast(sc, W, H, subpixel=True)


def render(sc, technique: str, **kw):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", api.ViewpointInShadowWarning)
        return api.render(sc, size=(W, H), technique=technique, subpixel=True, **kw)


@pytest.mark.parametrize("technique", list(TECHNIQUES))
@pytest.mark.parametrize("name", [n for n in HARD_CASES if n != "grazing_light"])
def test_against_reference(name, technique):
    sc, ref = case(name)
    why = EXPECTED_FAILURES.get((name, technique))
    if why is not None and why.startswith("refused"):
        with pytest.raises(TechniqueError):
            render(sc, technique)
        return
    frame = render(sc, technique)
    err = mask_error(frame.lit[0][::-1], ref.lit[..., 0], ref.hit & ~edge_on(sc, ref))
    if why is not None:
        # the failure is real and counted, not hidden (reported in the message)
        assert err.interior > 0, f"{name}/{technique}: expected to fail ({why})"
    else:
        assert err.interior == 0, (f"{name}/{technique}: {err.interior} interior pixels "
                                   f"wrong ({err.false_lit_interior} false lit)")


@pytest.mark.parametrize("angle", [1e-2, 1e-4, 1e-7, 0.0])
@pytest.mark.parametrize("technique", ["heidmann", "zfail", "counting"])
def test_grazing_light_errors_stay_on_the_grazing_face(angle, technique):
    """H4: the light in (or 1e-7 rad above) the plane of the cube's top: any wrong
    pixel away from a boundary lies on the grazing face's footprint (the cube's top),
    never on the floor, and the result is deterministic."""
    from vgxsim.shadow.techniques.hard_cases import grazing_light

    sc = grazing_light(angle)
    ref = raycast(sc, W, H, subpixel=True)
    a = render(sc, technique)
    b = render(sc, technique)
    assert np.array_equal(a.stencil, b.stencil)
    lit = a.lit[0][::-1]
    edge = near_boundary(np.where(ref.hit, ref.lit[..., 0].astype(np.int8), -1))
    wrong = ref.hit & (lit != ref.lit[..., 0]) & ~edge
    tris, _ = sc.triangles()
    normal = np.cross(tris[:, 1] - tris[:, 0], tris[:, 2] - tris[:, 0])
    up = normal[:, 1] > 0.0 * np.linalg.norm(normal, axis=1)
    top = np.zeros(len(tris) + 1, bool)
    top[:-1] = up & (np.abs(tris[:, :, 1] - 2.0).max(axis=1) == 0.0)
    cube_top = (ref.object_id == 1) & top[ref.triangle]
    assert not np.any(wrong & ~cube_top)


def test_eye_in_shadow_zpass_failure_is_counted():
    """H1, as numbers: z-pass inverts the shadow around the eye; z-fail does not."""
    sc, ref = case("eye_in_shadow")
    zp = shadow_error(render(sc, "heidmann").lit[0][::-1], ref, 0)
    zf = shadow_error(render(sc, "zfail").lit[0][::-1], ref, 0)
    assert zf.interior == 0
    assert zp.interior > zp.compared // 10  # a large part of the image, not a few pixels
    assert api.render.__module__  # (the warning path is tested in test_techniques)


def test_nested_volumes_beyond_255():
    """H8: 300 plates nested over the floor with 8 stencil planes.  z-fail counts up
    from MYZERO = 128 and ST_INCR clamps at 255 (stencil(3G)), so no count wraps
    back to 128: the floor under the stack still reads as shadow."""
    from vgxsim.shadow.techniques.hard_cases import nested_volumes

    sc = nested_volumes(300)
    ref = raycast(sc, 48, 40, subpixel=True, counts=False)
    frame = api.render(sc, size=(48, 40), technique="zfail", subpixel=True)
    err = shadow_error(frame.lit[0][::-1], ref, 0)
    assert err.false_lit_interior == 0
    assert frame.stencil[0].max() == 255  # saturated, as documented


SNAPPED = ("baseline", "thin_geometry", "directional", "translated", "spot")


@pytest.mark.parametrize("technique", ["heidmann", "zfail", "zpplus", "counting", "auto"])
@pytest.mark.parametrize("name", SNAPPED)
def test_snapped_vertices_against_the_snapped_reference(name, technique):
    """subpixel(FALSE), the IRIS default: vertices snap to pixel centres, and the
    reference snaps the same vertices (raycast(subpixel=False)); thin geometry (a rod
    about a pixel thick) included."""
    sc = HARD_CASES[name]()
    ref = raycast(sc, W, H, subpixel=False)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", api.ViewpointInShadowWarning)
        frame = api.render(sc, size=(W, H), technique=technique, subpixel=False)
    assert shadow_error(frame.lit[0][::-1], ref, 0).interior == 0


def test_snapped_default_scene_zfail_within_two_pixels_zpass_stray_pixels_counted():
    """The default scene under subpixel(FALSE): z-fail has no wrong pixel farther than
    two pixels from a boundary (a snapped silhouette vertex turns its whole shadow
    face, whose far end at w = 0 is not snapped, so far from the caster the shadow
    edge moves by a little more than the one pixel the metric allows); z-pass (the
    1991 code's counting, also ZP+ and counting, which count in front of the
    surface) leaves a few stray pixels 3 to 5 pixels from any
    boundary (5 at 96x80 when measured) -- the README's "stray pixels" bug, counted
    here: present, and stray (well under 1 % of the image), not an area."""
    from vgxsim.shadow.error import mask_error

    sc = api.load_scene(None)
    ref = raycast(sc, W, H, subpixel=False)
    zf = api.render(sc, size=(W, H), technique="zfail", subpixel=False)
    zp = api.render(sc, size=(W, H), technique="heidmann", subpixel=False)
    stray = 0
    for li in range(len(sc.lights)):
        cls = np.where(ref.hit, ref.lit[..., li].astype(np.int8), np.int8(-1))
        near1 = near_boundary(cls)
        near2 = near1 | near_boundary(np.where(near1, np.int8(2), cls))
        assert not np.any(ref.hit & (zf.lit[li][::-1] != ref.lit[..., li]) & ~near2)
        err = mask_error(zp.lit[li][::-1], ref.lit[..., li], ref.hit)
        stray += err.interior
        assert err.interior < err.compared // 100
    assert stray > 0  # the failure is there and counted, not hidden


def sheet_seen_from_behind(eye=(3.0, 2.5, -6.0)):
    """An open caster, one square sheet in z = 0 (x in [-1, 1], y in [0.5, 2.5]), the
    light in front of it (z = 3) and the eye behind it (z = -6), outside its volume:
    the line from the light through the eye crosses z = 0 at y = 3.5, above the
    sheet.  Every point of the sheet the eye sees is on its dark side."""
    from vgxsim.shadow.scene import Camera, PointLight
    from vgxsim.shadow.techniques.hard_cases import floor, scene, soup

    v = [[-1.0, 0.5, 0.0], [1.0, 0.5, 0.0], [1.0, 2.5, 0.0], [-1.0, 2.5, 0.0]]
    cam = Camera(fovy=450, near=1.0, far=40.0, eye=eye, target=(0.0, 1.5, 0.0))
    return scene([floor(), soup("sheet", v, [[0, 1, 2, 3]])],
                 lights=(PointLight("front", (-2.0, 4.0, 3.0), (1.0, 1.0, 1.0)),), camera=cam)


def test_an_open_sheet_seen_from_its_dark_side_is_in_its_own_shadow():
    """The teapot's false shadow in small (item 2 of issue 9): the segment from a
    point of the sheet to the light meets nothing but the sheet's own triangle, so a
    reference that only asks "is the segment blocked" called the sheet lit; but the
    eye sees the side facing away from the light, inside the volume of the sheet's
    own polygon ("the volume of space behind the triangle ... is in shadow"), and
    signed edge counting's stencil holds 1 there.  Seen from the front, it is lit."""
    sc = sheet_seen_from_behind()
    ref = raycast(sc, W, H, subpixel=True)
    sheet = ref.object_id == 1
    assert sheet.sum() > 500  # the sheet fills a good part of the view
    assert not ref.lit[..., 0][sheet].any()
    assert ref.lit[..., 0][ref.object_id == 0].any()  # the floor around its shadow
    for technique in ("counting", "heidmann"):
        frame = render(sc, technique)
        assert shadow_error(frame.lit[0][::-1], ref, 0).interior == 0, technique
        cnt = frame.stencil[0][::-1].astype(int) - frame.stencil_zero
        inner = sheet & ~near_boundary(np.where(ref.hit, ref.object_id, -1).astype(np.int8))
        assert np.all(cnt[inner] == 1), technique  # one surface: its own
    front = raycast(sheet_seen_from_behind(eye=(-3.0, 2.5, 6.0)), W, H, subpixel=True)
    assert front.lit[..., 0][front.object_id == 1].all()


def test_own_side_rule_by_hand():
    """own_side_shadowed on one triangle with normal +z, seen along -z (from +z)."""
    from vgxsim.shadow.raycast import own_side_shadowed

    tri = np.array([[[0.0, 0.0, 0.0, 1.0], [1.0, 0.0, 0.0, 1.0], [0.0, 1.0, 0.0, 1.0]]])
    lights = np.array([[0.0, 0.0, 5.0, 1.0],    # on the seen side: lit
                       [0.0, 0.0, -5.0, 1.0],   # behind it: its own shadow
                       [7.0, 3.0, 0.0, 1.0],    # in its plane: not shadowed (H4)
                       [0.0, 0.2, -1.0, 0.0]])  # directional, from behind
    down = np.array([[0.0, 0.0, -1.0], [0.0, 0.0, 1.0]])
    out = own_side_shadowed(tri, np.array([0, 0]), down, lights)
    assert out[0].tolist() == [False, True, False, True]
    assert out[1].tolist() == [True, False, False, False]  # seen from below
    assert not own_side_shadowed(tri, np.array([-1]), down[:1], lights).any()


def test_teapot_open_mesh_counting_against_the_reference():
    """H5 on the shipped teapot (open: the lid gap and the spout): the 1991 silhouette
    z-pass and the closed-mesh z-fail misclassify whole regions; signed edge counting
    is exact.  It used to leave 183 pixels of false shadow with count 1 at 320x256
    (subpixel(TRUE), both lights): walls seen from their dark side, where light enters
    through the lid gap, which the reference called lit (see the sheet test above)."""
    sc = api.load_scene("teapot")
    ref = raycast(sc, W, H, subpixel=True)

    def interior(technique, ref=ref, size=(W, H)):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", api.ViewpointInShadowWarning)
            frame = api.render(sc, size=size, technique=technique, subpixel=True)
        return sum(shadow_error(frame.lit[i][::-1], ref, i).interior
                   for i in range(len(sc.lights)))

    counting, heidmann, zfail = interior("counting"), interior("heidmann"), interior("zfail")
    assert counting == 0
    assert heidmann > 20 and zfail > 200, (heidmann, zfail)
    big = raycast(sc, 320, 256, subpixel=True)
    assert interior("counting", big, (320, 256)) == 0
