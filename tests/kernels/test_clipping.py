"""Homogeneous clipping through vgxsim.geometry.pipeline.draw_triangles, against an
exact float64 reference written here: Sutherland-Hodgman of the triangle in clip
space against -w <= z <= w and a guard band, divide, viewport map (model section 1),
and pixel-centre tests against the projected (convex) polygon.

Kernel coverage is counted with stencil INCR.  Pixels farther than ``tol`` from the
reference polygon's edges must match exactly; ``tol`` covers the vertex snapping of
model section 2 (1/512 pixel per coordinate with subpixel, half a pixel without).
Everywhere, no pixel may be covered twice by the fan of one clipped polygon (with
subpixel; without it, snapping may flip slivers near the boundary only).
"""

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from kernel_helpers import clip_reference, full_state, kernel_batch, kernel_framebuffer

from vgxsim.geometry.pipeline import Viewing, draw_triangles
from vgxsim.geometry.transform import frustum, perspective, translation
from vgxsim.reference.naive import GD_ZMAX, GD_ZMIN
from vgxsim.state.raster import CMP_ALWAYS, OP_INCR

W, H = 48, 40
VIEWPORT = (0, W - 1, 0, H - 1)
DEPTH = (float(GD_ZMIN), float(GD_ZMAX))
TOL = {True: 0.01, False: 1.0}  # pixels, by subpixel


def infinite_perspective(fovy_deg, aspect, near):
    """perspective() with the far plane at infinity (row-vector convention): points
    at infinity (w = 0) land exactly on the far plane, as in shadow volumes."""
    f = 1.0 / math.tan(math.radians(fovy_deg) / 2.0)
    m = np.zeros((4, 4))
    m[0, 0] = f / aspect
    m[1, 1] = f
    m[2, 2] = -1.0
    m[2, 3] = -1.0
    m[3, 2] = -2.0 * near
    return m


MATRICES = {
    "perspective": perspective(600, W / H, 1.0, 100.0),
    "frustum": frustum(-0.7, 0.4, -0.5, 0.35, 1.5, 60.0),
    "infinite": infinite_perspective(50.0, W / H, 0.5),
    "moved": translation(0.3, -0.2, -2.0) @ perspective(900, W / H, 0.25, 40.0),
}


# ------------------------------------------------------------------- reference


def reference(clip_tri, viewport=VIEWPORT):
    """(inside, dist, polygon) of the projected clipped polygon over the window."""
    return clip_reference(clip_tri, viewport, W, H)


# ------------------------------------------------------------------ kernel side


def kernel_count(obj, tris, mvp, subpixel, mode="span"):
    fb = kernel_framebuffer(W, H, double=False, zbits=24, stencil=8)
    batch = kernel_batch(fb, mode)
    rs = full_state(W, H, stencil=True, sfunc=CMP_ALWAYS, spass=OP_INCR, wmpack=0,
                    subpixel=subpixel)
    view = Viewing(mvp, VIEWPORT, DEPTH)
    draw_triangles(batch, rs, view, np.asarray(obj, np.float64), None,
                   np.asarray(tris, np.int64))
    batch.flush()
    return fb.stencil.astype(np.int64)


def check_triangle(obj3, mvp, subpixel, mode="span"):
    obj = np.asarray(obj3, np.float64)
    count = kernel_count(obj, [[0, 1, 2]], mvp, subpixel, mode)
    inside, dist, poly = reference(obj @ mvp)
    robust = dist > TOL[subpixel]
    bad = robust & (count != inside)
    assert not bad.any(), (
        f"{int(bad.sum())} pixels differ away from edges, e.g. "
        f"{list(zip(*np.nonzero(bad), strict=True))[:5]}; polygon {poly}")
    if subpixel:
        assert count.max() <= 1
    else:
        assert count[robust].max(initial=0) <= 1
    return count, inside


# --------------------------------------------------------------------- tests

unit = st.floats(-1.6, 1.6)


@st.composite
def eye_vertex(draw):
    """A homogeneous object-space vertex: a point (mostly near the view frustum), a
    point behind the eye, a point in the eye plane (clip w = 0) or a point at
    infinity (w = 0)."""
    kind = draw(st.sampled_from(["point"] * 4 + ["behind", "eyeplane", "infinity"]))
    u, v = draw(unit), draw(unit)
    if kind == "point":
        z = draw(st.floats(-90, -0.2))
        return (u * 0.9 * -z, v * 0.7 * -z, z, 1.0)
    if kind == "behind":
        return (40 * u, 40 * v, draw(st.floats(0.01, 30)), 1.0)
    if kind == "eyeplane":
        return (40 * u, 40 * v, 0.0, 1.0)
    scale = draw(st.floats(0.1, 10))
    zdir = draw(st.sampled_from([-1.0, -1.0, 1.0, 0.0]))
    return (u * 0.9 * scale, v * 0.7 * scale, zdir * scale, 0.0)


@settings(max_examples=150, deadline=None)
@given(tri=st.tuples(eye_vertex(), eye_vertex(), eye_vertex()),
       matrix=st.sampled_from(sorted(MATRICES)), subpixel=st.booleans())
def test_random_clipped_triangles(tri, matrix, subpixel):
    check_triangle(tri, MATRICES[matrix], subpixel)


def _rng_vertex(rng):
    kind = rng.choice(["point"] * 4 + ["behind", "eyeplane", "infinity"])
    u, v = rng.uniform(-1.6, 1.6, 2)
    if kind == "point":
        z = rng.uniform(-90, -0.2)
        return (u * 0.9 * -z, v * 0.7 * -z, z, 1.0)
    if kind == "behind":
        return (40 * u, 40 * v, rng.uniform(0.01, 30), 1.0)
    if kind == "eyeplane":
        return (40 * u, 40 * v, 0.0, 1.0)
    scale = rng.uniform(0.1, 10)
    return (u * 0.9 * scale, v * 0.7 * scale, rng.choice([-1.0, 1.0]) * scale, 0.0)


def test_seeded_clipped_triangles():
    rng = np.random.default_rng(2024)
    visible = crossing = 0
    for i in range(400):
        tri = [_rng_vertex(rng) for _ in range(3)]
        matrix = MATRICES[sorted(MATRICES)[i % len(MATRICES)]]
        count, inside = check_triangle(tri, matrix, bool(i % 2),
                                       ("span", "general", "edge")[i % 3])
        visible += bool(inside.any())
        w = (np.asarray(tri) @ matrix)[:, 3]
        crossing += bool(inside.any() and (w.min() <= 0 < w.max()))
    assert visible > 150 and crossing > 30


def test_one_and_two_vertices_behind_the_eye():
    mvp = MATRICES["perspective"]
    drawn = 0
    for subpixel in (False, True):
        for mode in ("span", "general", "edge"):
            # One vertex behind the eye: the triangle is cut by the near plane into
            # a quadrilateral that reaches the window edge.
            c, inside = check_triangle([(-3, -2, -10, 1), (4, -1, -12, 1), (0.5, 3, 2, 1)],
                                       mvp, subpixel, mode)
            drawn += c.sum()
            # Two vertices behind: a small triangle remains.
            check_triangle([(-3, -2, -10, 1), (40, -1, 5, 1), (0.5, 30, 2, 1)],
                           mvp, subpixel, mode)
            # All three behind: nothing.
            c, _ = check_triangle([(-3, -2, 1, 1), (4, -1, 5, 1), (0.5, 3, 2, 1)],
                                  mvp, subpixel, mode)
            assert c.sum() == 0
    assert drawn > 0


def test_shadow_volume_sides_to_infinity():
    """Quads (v0, v1, v1 - L at infinity, v0 - L at infinity) of a silhouette edge,
    with the far plane at infinity: the extruded points are visible."""
    mvp = MATRICES["infinite"]
    light = np.array([2.0, 8.0, -3.0])
    rng = np.random.default_rng(4)
    for _ in range(20):
        v0 = np.append(rng.uniform([-3, -3, -12], [3, 3, -5]), 1.0)
        v1 = np.append(rng.uniform([-3, -3, -12], [3, 3, -5]), 1.0)
        e0 = np.append(v0[:3] - light, 0.0)
        e1 = np.append(v1[:3] - light, 0.0)
        for subpixel in (False, True):
            for tri in ((v0, v1, e1), (v0, e1, e0)):
                check_triangle(tri, mvp, subpixel)
            # The two halves of the quad do not overlap.
            count = kernel_count(np.array([v0, v1, e1, e0]), [[0, 1, 2], [0, 2, 3]],
                                 mvp, subpixel)
            if subpixel:
                assert count.max() <= 1


def test_points_at_infinity_beyond_finite_far_plane_are_clipped():
    mvp = MATRICES["perspective"]
    # A triangle with one vertex at infinity straight ahead: cut at the far plane.
    for subpixel in (False, True):
        c, inside = check_triangle([(-2, -2, -10, 1), (2, -2, -10, 1), (0, 0.5, -1, 0)],
                                   mvp, subpixel)
        assert inside.any() and c.sum() > 0
        # Entirely at infinity: beyond the far plane, nothing.
        c, _ = check_triangle([(-2, -2, -1, 0), (2, -2, -1, 0), (0, 1, -1, 0)], mvp, subpixel)
        assert c.sum() == 0


def test_vertex_exactly_in_the_eye_plane():
    mvp = MATRICES["perspective"]
    for subpixel in (False, True):
        check_triangle([(-1, -1, -5, 1), (1, -1, -5, 1), (0, 3, 0, 1)], mvp, subpixel)
        check_triangle([(-1, -1, 0, 1), (1, -1, 0, 1), (0, 3, -4, 1)], mvp, subpixel)


def test_clip_space_origin_vertex_covers_nothing():
    """A vertex at the homogeneous origin (0, 0, 0, 0) -- e.g. a vertex extruded from
    a light placed on it -- puts the triangle's plane through the eye: edge-on, it
    covers nothing (the clipper drops such polygons when it clips them)."""
    ident = np.eye(4)
    for subpixel in (False, True):
        tri = np.array([[0.0, 0.0, 0.0, 0.0], [0.5, -0.5, 0.0, 1.0], [0.5, 0.5, 0.0, 1.0]])
        count = kernel_count(tri, [[0, 1, 2]], ident, subpixel)
        assert count.sum() == 0, f"drew {int(count.sum())} pixels"


def test_clipped_mesh_is_watertight():
    """A planar mesh (a tilted ground plane) crossing the near plane and the eye
    plane: shared edges are clipped identically (intersection from the
    lexicographically smaller end), so no pixel is covered twice and none is lost
    along clipped edges.  The plane misses the eye, so its image does not fold."""
    mvp = MATRICES["perspective"]
    rng = np.random.default_rng(12)
    for _ in range(8):
        a, b, c = rng.uniform(-0.3, 0.3), rng.uniform(-0.2, 0.2), rng.uniform(-4, -1)
        nx, nz = 9, 7
        xs = np.linspace(-30, 30, nx)
        zs = np.linspace(-45, 8, nz)
        obj = []
        for j in range(nz):
            for i in range(nx):
                x = xs[i] + (rng.uniform(-2, 2) if 0 < i < nx - 1 else 0)
                z = zs[j] + (rng.uniform(-2, 2) if 0 < j < nz - 1 else 0)
                obj.append((x, a * x + b * z + c, z, 1.0))
        obj = np.array(obj)
        tris = []
        for j in range(nz - 1):
            for i in range(nx - 1):
                p, q = j * nx + i, j * nx + i + 1
                r, s_ = q + nx, p + nx
                tris += [[p, q, r], [p, r, s_]] if rng.random() < 0.5 else [[p, q, s_],
                                                                         [q, r, s_]]
        for subpixel in (False, True):
            count = kernel_count(obj, tris, mvp, subpixel)
            union = np.zeros((H, W), bool)
            near = np.zeros((H, W), bool)
            for t in tris:
                inside, dist, _ = reference(obj[t] @ mvp)
                union |= inside
                near |= dist <= TOL[subpixel]
            np.testing.assert_array_equal(count[~near], union[~near].astype(np.int64))
            if subpixel:
                assert count.max() <= 1
            assert union.sum() > 100


# -- user clip planes (clipplane(3G)) in the homogeneous clipper ---------------------------
def test_user_plane_cuts_a_triangle_exactly():
    from vgxsim.kernels.clip import clip_segments, clip_triangles

    # Triangle (0,0) (1,0) (0,1) at w = 2 (so the plane must be applied to x, not x/w),
    # plane x - 0.25 w >= 0, i.e. x/w >= 0.25: keeps the corner near (1, 0).
    v = np.array([[0.0, 0, 0, 2], [2.0, 0, 0, 2], [0.0, 2, 0, 2]])
    attr = np.array([[0.0], [1.0], [2.0]])
    user = np.array([[1.0, 0.0, 0.0, -0.25]])
    out_v, out_attr, out_tris, out_src = clip_triangles(
        v, attr, np.array([[0, 1, 2]]), 10.0, 10.0, user)
    poly = out_v[out_tris[0]].tolist() + out_v[out_tris[1:, 2]].tolist()
    # By hand: edge 0->1 enters at x = 0.5 (t = 1/4 from vertex 0: attr 0.25); edge
    # 1->2 leaves at x = 0.5 (t = 3/4 from vertex 1: y = 1.5, attr 1.75).
    assert sorted(map(tuple, poly)) == [(0.5, 0.0, 0.0, 2.0), (0.5, 1.5, 0.0, 2.0),
                                        (2.0, 0.0, 0.0, 2.0)]
    assert sorted(out_attr[len(v):, 0].tolist()) == [0.25, 1.0, 1.75]
    assert out_src.tolist() == [0]
    # The same plane on the segment 0 -> 1 keeps 0.5 .. 2.
    sv, sa, src, t0 = clip_segments(v, attr, np.array([[0, 1]]), 10.0, 10.0, user)
    assert sv[0].tolist() == [[0.5, 0.0, 0.0, 2.0], [2.0, 0.0, 0.0, 2.0]]
    assert t0.tolist() == [0.25] and sa[0, :, 0].tolist() == [0.25, 1.0]
    # Wholly outside a second plane (y/w <= -0.5): nothing is left.
    both = np.array([[1.0, 0.0, 0.0, -0.25], [0.0, -1.0, 0.0, -1.0]])
    assert clip_triangles(v, attr, np.array([[0, 1, 2]]), 10.0, 10.0, both)[2].shape[0] == 0
    assert clip_segments(v, attr, np.array([[0, 1]]), 10.0, 10.0, both)[0].shape[0] == 0
