"""Technique invariants: optimisations and equivalent constructions change no
stencil value; the silhouette methods agree; library and CLI select techniques."""

from __future__ import annotations

import subprocess
import sys
import warnings

import numpy as np
import pytest

from vgxsim.shadow import api
from vgxsim.shadow.techniques import TechniqueError, make
from vgxsim.shadow.techniques.hard_cases import baseline, eye_in_shadow
from vgxsim.shadow.techniques.volumes import (
    light4,
    silhouettes_by_adjacency,
    silhouettes_by_toggle,
)

W, H = 96, 80


def render(sc, technique, **opts):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", api.ViewpointInShadowWarning)
        return api.render(sc, size=(W, H), technique=technique, technique_options=opts)


def test_toggle_set_equals_adjacency_silhouettes():
    sc = api.load_scene(None)
    for li in range(len(sc.lights)):
        lt = light4(sc.lights[li])
        for obj in sc.casters:
            a = {tuple(p) for p in silhouettes_by_adjacency(obj, lt).tolist()}
            b = {tuple(p) for p in silhouettes_by_toggle(obj, lt).tolist()}
            assert a == b and a


@pytest.mark.parametrize("technique", ["heidmann", "zfail", "finite"])
def test_silhouette_methods_give_identical_stencils(technique):
    sc = api.load_scene(None)
    a = render(sc, technique, silhouettes="adjacency")
    b = render(sc, technique, silhouettes="toggle")
    assert np.array_equal(a.stencil, b.stencil)


@pytest.mark.parametrize("technique", ["heidmann", "zfail", "counting"])
def test_culling_changes_no_stencil_value(technique):
    sc = api.load_scene("balls")
    a = render(sc, technique, cull=False)
    b = render(sc, technique, cull=True)
    assert np.array_equal(a.stencil, b.stencil)


@pytest.mark.parametrize("build", [baseline, eye_in_shadow])
def test_automatic_choice_changes_no_stencil_value(build):
    sc = build()
    auto = render(sc, "auto")
    zfail = render(sc, "auto", force="zfail")
    assert np.array_equal(auto.stencil, zfail.stencil)


def test_automatic_choice_uses_zpass_when_safe_and_zfail_when_not():
    t = make("auto")
    render(baseline(), t)
    assert set(t.last_choice.values()) == {"zpass"}
    t = make("auto")
    render(eye_in_shadow(), t)
    assert set(t.last_choice.values()) == {"zfail"}


def test_counting_equals_all_edges_zpass_on_closed_casters():
    """Bergeron: the signed counts are the all-edge faces after opposite faces
    cancel, so the shadow is the one of z-pass from every edge.  (Not bit-identical
    stencils: a cancelled pair of opposite quads is split along different diagonals,
    so their pixels do not cancel one for one.)"""
    sc = api.load_scene(None)
    a = render(sc, "counting")
    b = render(sc, "heidmann", edges="all", length=None)
    assert np.array_equal(a.lit, b.lit)


def test_heidmann_technique_matches_the_1991_code():
    sc = api.load_scene(None)
    a = api.render(sc, size=(W, H))
    b = render(sc, "heidmann")
    assert np.array_equal(a.lit, b.lit)


def test_roettger_ambient_equals_heidmann_image_where_masks_agree():
    """With a 255/0 mask, BF_DA + BF_ONE adds exactly what BF_ONE + BF_ONE adds."""
    sc = baseline()
    r = render(sc, "roettger")
    z = render(sc, "zfail")
    seen = z.depth < z.depth.max()
    assert np.array_equal(r.lit[:, seen], z.lit[:, seen])
    assert np.array_equal(r.colour[..., :3], z.colour[..., :3])


def test_unknown_technique_and_option_are_clear_errors():
    with pytest.raises(TechniqueError, match="unknown shadow technique"):
        make("nope")
    with pytest.raises(TechniqueError, match="shadowmap"):
        make("shadowmap", sizee=3)


def test_cli_technique(tmp_path):
    out = tmp_path / "s.png"
    r = subprocess.run([sys.executable, "-m", "vgxsim", "shadows", "--technique", "zfail",
                        "--size", "48x40", "-o", str(out)], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    assert out.exists()
    r = subprocess.run([sys.executable, "-m", "vgxsim", "shadows", "--technique",
                        "shadowmap", "--option", "bogus=1", "-o", str(tmp_path / "t.png")],
                       capture_output=True, text=True)
    assert r.returncode == 2 and "bogus" in r.stderr


def test_roettger_colour_channel_equals_alpha_channel():
    sc = baseline()
    a = render(sc, "roettger", channel="alpha")
    c = render(sc, "roettger", channel="colour")
    assert np.array_equal(a.lit, c.lit)


def test_roettger_quick_halves_shadowed_pixels_of_the_full_scene():
    """QuickNDirty: the scene once with every component, then x255/255 where lit and
    x127/255 in shadow, with the VGX blend's rounding (docs/numeric_model.md)."""
    sc = baseline()
    q = render(sc, "roettger", application="quick")
    full = api.render(sc, size=(W, H), mode="objects").colour[..., :3].astype(int)
    lit = q.lit[0][..., None]
    expect = np.where(lit, full, (full * 127 + 127) // 255)
    assert np.array_equal(q.colour[..., :3], expect.astype(np.uint8))


def test_roettger_has_no_stencil_planes_and_low_resolution_mask_is_blocky():
    from vgxsim.gl import getgdesc  # noqa: F401  (the engine reads GD_BITS_STENCIL)
    from vgxsim.shadow.program import Shadows

    t = make("roettger", mask_scale=2)
    frame = render(baseline(), t)
    mask = frame.stencil[0][::-1]            # bottom row first, as counted
    blocks = mask[: H // 2 * 2, : W // 2 * 2].reshape(H // 2, 2, W // 2, 2)
    assert np.all(blocks == blocks[:, :1, :, :1])
    prog = Shadows(baseline(), technique=make("roettger"))
    assert prog.technique.name == "roettger"
    with pytest.raises(TechniqueError, match="accumulation"):
        api.render(baseline(), size=(W, H), soft=2, technique="roettger",
                   technique_options={"channel": "colour"})


def test_zfail_far_plane_needs_the_infinite_projection():
    """H3: with the camera's finite far plane the extruded (w = 0) geometry is
    clipped and the count is lost; with the far plane at infinity it is exact."""
    from vgxsim.shadow.error import shadow_error
    from vgxsim.shadow.raycast import raycast
    from vgxsim.shadow.techniques.hard_cases import far_plane

    sc = far_plane()
    ref = raycast(sc, W, H, subpixel=True)
    kw = dict(size=(W, H), technique="zfail", subpixel=True)
    inf = api.render(sc, **kw)
    fin = api.render(sc, technique_options={"infinite_far": False}, **kw)
    assert shadow_error(inf.lit[0][::-1], ref, 0).interior == 0
    assert shadow_error(fin.lit[0][::-1], ref, 0).interior > 0


@pytest.mark.parametrize("technique", ["zfail", "zpplus", "auto"])
def test_near_plane_sweep(technique):
    """H2: sweep the near plane through the volume: z-fail, ZP+ and auto match the
    reference at every distance, z-pass only while the plane misses the volume."""
    from dataclasses import replace

    from vgxsim.shadow.error import shadow_error
    from vgxsim.shadow.raycast import nearest_hit, pixel_rays, raycast
    from vgxsim.shadow.techniques.hard_cases import near_plane_cut

    base = near_plane_cut()
    for near in (0.3, 1.2, 2.2):
        sc = replace(base, camera=replace(base.camera, near=near))
        ref = raycast(sc, W, H, subpixel=True)
        kw = dict(size=(W, H), subpixel=True)
        robust = api.render(sc, technique=technique, **kw)
        assert shadow_error(robust.lit[0][::-1], ref, 0).interior == 0, near
        zpass = shadow_error(api.render(sc, technique="heidmann", **kw).lit[0][::-1], ref, 0)
        # does the near rectangle reach into the volume?  segments from the near-plane
        # point of every pixel to the light, against the casters
        q, _ = pixel_rays(sc, W, H)
        q = q.reshape(-1, 3)
        tris = np.concatenate([o.vertices[o.triangles] for o in sc.casters])
        idx, _ = nearest_hit(q, np.asarray(sc.lights[0].position) - q, tris)
        assert (zpass.interior > 0) == bool(np.any(idx >= 0)), (near, zpass.interior)


def test_soft_shadows_work_with_a_technique():
    f = api.render(baseline(), size=(W, H), soft=2, technique="zfail")
    assert f.colour.shape == (H, W, 4) and f.stencil.shape[0] == 0


def reader(prog, planes):
    """A stencil hook appending the technique's mask plane to ``planes``."""
    return lambda i: planes.append(np.array(prog.technique.read_mask(prog, i)))


@pytest.mark.parametrize("technique", ["heidmann", "zfail", "zpplus", "counting",
                                       "roettger"])
def test_volume_cache_changes_no_plane(technique):
    """Display objects for the volume geometry (VolumeCache): the same planes as
    immediate mode, on the first frame and on a replayed second frame."""
    from vgxsim.gl import finish, prefsize, read_pixels, swapbuffers, winclose, winopen
    from vgxsim.shadow.program import Shadows

    sc = api.load_scene(None)
    got = []
    for cache in (False, True):
        planes = []
        t = make(technique, cache=cache)
        prog = Shadows(sc, signs="screen", technique=t)
        prog.stencil_hook = reader(prog, planes)
        prefsize(W, H)
        gid = winopen("cache")
        try:
            prog.setup()
            for _ in range(2):
                prog.DrawFrame()
                swapbuffers()
                finish()
            planes.append(read_pixels("front"))
        finally:
            prog.teardown()
            winclose(gid)
        got.append(planes)
    assert len(got[0]) == len(got[1])
    for a, b in zip(*got, strict=True):
        assert np.array_equal(a, b)


@pytest.mark.parametrize("start", [1, 8, 64])
def test_roettger_start_value_gives_the_same_mask_on_shallow_nesting(start):
    """Any start value is exact while no more than 8 - log2(start) volumes nest
    (one cube here: 1)."""
    sc = baseline()
    z = render(sc, "zfail")
    r = render(sc, "roettger", start=start)
    seen = z.depth < z.depth.max()
    assert np.array_equal(r.lit[:, seen], z.lit[:, seen])


def test_points_at_infinity_land_on_the_infinite_far_plane():
    """H3 (a) and H10: under the infinite projection a vertex (x, y, z, 0) in front
    of the eye has z_clip == w_clip exactly, and a triangle of such vertices is
    rasterized at depth GD_ZMAX (kept by the clipper's closed far plane); one whose
    vertices point behind the eye is clipped away without error."""
    from vgxsim.gl import (  # noqa: I001
        GD_ZMAX,
        MPROJECTION,
        MVIEWING,
        TRUE,
        ZF_ALWAYS,
        RGBmode,
        bgnpolygon,
        czclear,
        endpolygon,
        gconfig,
        getgdesc,
        loadmatrix,
        mmode,
        prefsize,
        read_pixels,
        swapbuffers,
        v4f,
        winclose,
        winopen,
        zbuffer,
        zfunction,
    )
    from vgxsim.shadow.techniques.volumes import infinite_projection

    sc = baseline()
    p = infinite_projection(sc.camera, W / H)
    mv = sc.camera.modelview()
    rng = np.random.default_rng(7)
    d = rng.normal(size=(200, 3))
    clip = np.concatenate([d, np.zeros((200, 1))], axis=1) @ mv @ p
    front = clip[:, 3] > 0
    assert np.all(clip[front, 2] == clip[front, 3])
    prefsize(W, H)
    gid = winopen("inf")
    try:
        RGBmode()
        gconfig()
        zbuffer(TRUE)
        zfunction(ZF_ALWAYS)
        mmode(MPROJECTION)
        loadmatrix(p.reshape(-1).tolist())
        mmode(MVIEWING)
        loadmatrix(mv.reshape(-1).tolist())
        czclear(0, 0)
        ahead = np.asarray(sc.camera.target) - np.asarray(sc.camera.eye)
        side = np.cross(ahead, [0.0, 1.0, 0.0])
        for tri in ([ahead - side, ahead + side, ahead + [0, 1.0, 0]],
                    [-ahead - side, -ahead + side, -ahead + [0, 1.0, 0]]):
            bgnpolygon()
            for v in tri:
                v4f((*v, 0.0))
            endpolygon()
        swapbuffers()
        z = read_pixels("front", "z")
    finally:
        winclose(gid)
    drawn = z != 0
    assert drawn.any()
    assert np.all(z[drawn] == getgdesc(GD_ZMAX))


def test_roettger_black_leaves_shadows_black():
    sc = baseline()
    f = render(sc, "roettger", application="black")
    seen = f.depth < f.depth.max()
    shadow = seen & ~f.lit[0]
    assert shadow.any()
    assert np.all(f.colour[shadow][:, :3] == 0)
    assert f.colour[seen & f.lit[0]][:, :3].max() > 0


def test_shadowmap_resolution_and_bias_parameters():
    from vgxsim.shadow.error import shadow_error
    from vgxsim.shadow.raycast import raycast

    sc = baseline()
    ref = raycast(sc, W, H, subpixel=True)

    def wrong(**opts):
        f = api.render(sc, size=(W, H), technique="shadowmap", technique_options=opts,
                       subpixel=True)
        return shadow_error(f.lit[0][::-1], ref, 0).misclassified

    assert wrong(size=2048) < wrong(size=32)
    # no bias: the casters' lit faces shadow themselves (acne)
    assert wrong(size=512, bias=0.0) > wrong(size=512, bias=0.05)
