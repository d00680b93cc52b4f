"""Vertex order does not matter (docs/numeric_model.md section 4): the canonical
(y, x) order makes every interpolant bit-identical under permutation, which is what
lets a shadow-volume cap redraw a scene face with ZF_EQUAL."""

import itertools

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from kernel_helpers import full_state, kernel_batch, kernel_framebuffer

from vgxsim.reference.naive import GD_ZMAX, GD_ZMIN
from vgxsim.state.raster import CMP_ALWAYS, CMP_EQUAL, CMP_LEQUAL, OP_INCR

W, H = 40, 32
PERMS = list(itertools.permutations(range(3)))

coord = st.one_of(st.floats(-6, 46), st.integers(-6, 46).map(float),
                  st.integers(-12, 92).map(lambda v: v / 2))
zval = st.one_of(st.floats(GD_ZMIN, GD_ZMAX), st.floats(-100, 100),
                 st.integers(GD_ZMIN, GD_ZMAX).map(float))
chan = st.floats(0, 1)
vertex = st.tuples(coord, coord, zval, st.tuples(chan, chan, chan, chan))


def draw(tris, rs, mode="span", fb=None):
    """Draw triangles given as lists of (x, y, z, rgba) vertices; returns the fb."""
    if fb is None:
        fb = kernel_framebuffer(W, H, double=False, zbits=24, stencil=8)
    batch = kernel_batch(fb, mode)
    for tri in tris:
        v = np.array([[p[0], p[1], p[2]] for p in tri], np.float64)
        col = np.array([p[3] for p in tri], np.float64)
        batch.add_window_triangles(v[:, 0], v[:, 1], v[:, 2], col,
                                   np.array([[0, 1, 2]]), rs, flat_col=col[2:3])
    batch.flush()
    return fb


def overwrite_state(subpixel):
    """Every covered pixel gets the triangle's z, colour and a stencil increment."""
    return full_state(W, H, zbuffer=True, zfunc=CMP_ALWAYS, stencil=True, sfunc=CMP_ALWAYS,
                      szpass=OP_INCR, subpixel=subpixel)


@settings(max_examples=120, deadline=None)
@given(tri=st.tuples(vertex, vertex, vertex), subpixel=st.booleans())
def test_permutations_give_identical_z_colour_and_coverage(tri, subpixel):
    rs = overwrite_state(subpixel)
    ref = None
    for perm in PERMS:
        fb = draw([[tri[i] for i in perm]], rs)
        planes = (fb.front.copy(), fb.z.copy(), fb.stencil.copy())
        if ref is None:
            ref = planes
            assert ref[2].max() <= 1
            continue
        np.testing.assert_array_equal(planes[1], ref[1], err_msg=f"z, order {perm}")
        np.testing.assert_array_equal(planes[2], ref[2], err_msg=f"coverage, order {perm}")
        np.testing.assert_array_equal(planes[0], ref[0], err_msg=f"colour, order {perm}")


@settings(max_examples=100, deadline=None)
@given(tri=st.tuples(vertex, vertex, vertex), subpixel=st.booleans(),
       perm=st.sampled_from(PERMS), mode=st.sampled_from(["span", "general", "edge"]))
def test_redraw_with_zf_equal_passes_everywhere(tri, subpixel, perm, mode):
    """Scene pass (ZF_LEQUAL, z written), then the same face, vertices permuted,
    with ZF_EQUAL and stencil INCR on zpass (no colour, no z write: the cap pass of
    the 1991 algorithm): every pixel the first pass covered must pass again."""
    scene = full_state(W, H, zbuffer=True, zfunc=CMP_LEQUAL, subpixel=subpixel)
    fb = draw([list(tri)], scene)
    probe = draw([list(tri)], overwrite_state(subpixel))
    covered = probe.stencil == 1
    cap = full_state(W, H, zbuffer=True, zfunc=CMP_EQUAL, zwritemask=0, stencil=True,
                     sfunc=CMP_ALWAYS, spass=0, szpass=OP_INCR, wmpack=0, subpixel=subpixel)
    draw([[tri[i] for i in perm]], cap, mode=mode, fb=fb)
    np.testing.assert_array_equal(fb.stencil == 1, covered)
    assert fb.stencil.max() <= 1


def test_shadow_cap_scene_with_many_faces():
    """A mesh drawn with ZF_LEQUAL, then every face re-drawn as a cap, rotated."""
    rng = np.random.default_rng(8)
    for subpixel in (False, True):
        pts = rng.uniform([-4, -4], [W + 4, H + 4], (30, 2))
        z = rng.uniform(-5e6, 5e6, 30)
        col = rng.uniform(0, 1, (30, 4))
        faces = [rng.choice(30, 3, replace=False) for _ in range(60)]
        tris = [[(pts[i, 0], pts[i, 1], z[i], tuple(col[i])) for i in f] for f in faces]
        scene = full_state(W, H, zbuffer=True, zfunc=CMP_LEQUAL, subpixel=subpixel)
        fb = draw(tris, scene)
        # Which face is visible where: redraw each face alone against the final z
        # buffer with ZF_EQUAL; the union of passes must be every covered pixel.
        cover = np.zeros((H, W), bool)
        for t in tris:
            probe = draw([t], overwrite_state(subpixel))
            cover |= probe.stencil > 0
        cap = full_state(W, H, zbuffer=True, zfunc=CMP_EQUAL, zwritemask=0, stencil=True,
                         sfunc=CMP_ALWAYS, szpass=OP_INCR, wmpack=0, subpixel=subpixel)
        rotated = [[t[1], t[2], t[0]] for t in tris]
        draw(rotated, cap, fb=fb)
        # Every pixel some face covers is passed by at least one redraw.
        np.testing.assert_array_equal(fb.stencil > 0, cover)
        assert cover.sum() > W * H // 2


@settings(max_examples=80, deadline=None)
@given(quad=st.tuples(vertex, vertex, vertex, vertex), subpixel=st.booleans(),
       rot=st.integers(0, 2))
def test_quad_as_two_triangles_in_both_orders(quad, subpixel, rot):
    a, b, c, d = quad
    t1, t2 = [a, b, c], [a, c, d]
    rs = overwrite_state(subpixel)
    alone = [draw([t1], rs), draw([t2], rs)]
    own = [alone[0].stencil == 1, alone[1].stencil == 1]
    rotated = [t1[rot:] + t1[:rot], t2[rot:] + t2[:rot]]
    for first, second in ((0, 1), (1, 0)):
        for tris in ([t1, t2], rotated):
            fb = draw([tris[first], tris[second]], rs)
            # The triangle drawn second keeps its own z everywhere it covers; the
            # first keeps its z except where the second overlaps it (a non-convex
            # or self-intersecting quad; a convex one shares only the diagonal).
            m2 = own[second]
            m1 = own[first] & ~own[second]
            np.testing.assert_array_equal(fb.z[m2], alone[second].z[m2])
            np.testing.assert_array_equal(fb.z[m1], alone[first].z[m1])
            np.testing.assert_array_equal(fb.stencil, alone[0].stencil + alone[1].stencil)
