"""The Utah teapot from its Bezier patches: the slides' formulas, and the mesh they make."""

from __future__ import annotations

import numpy as np

from vgxsim.shadow.scene import polyhedron_from_polygons
from vgxsim.shadow.teapot import patch_points, read_patches, tessellate


def test_the_data_is_newells_32_patches_of_306_points():
    points, patches = read_patches()
    assert points.shape == (306, 3) and patches.shape == (32, 4, 4)
    assert patches.min() == 0 and patches.max() == 305
    # the rim's first control point and the teapot's height (Newell's data: z up to 3.15)
    assert np.array_equal(points[0], [1.4, 0.0, 2.4])
    assert points[:, 2].max() == 3.15 and points[:, 2].min() == 0.0


def test_patch_formulas_interpolate_corners_and_differentiate():
    points, patches = read_patches()
    ctrl = points[patches[5]]
    t = np.array([0.0, 1.0])
    p, _, _ = patch_points(ctrl, t, t)
    # a bicubic Bezier patch passes through its four corner control points
    assert np.allclose(p[0, 0], ctrl[0, 0]) and np.allclose(p[0, 1], ctrl[0, 3])
    assert np.allclose(p[1, 0], ctrl[3, 0]) and np.allclose(p[1, 1], ctrl[3, 3])
    # the slides' dP/du and dP/dv against central differences
    u, v, h = np.array([0.3]), np.array([0.7]), 1e-6
    _, pu, pv = patch_points(ctrl, u, v)
    fu = (patch_points(ctrl, u + h, v)[0] - patch_points(ctrl, u - h, v)[0]) / (2 * h)
    fv = (patch_points(ctrl, u, v + h)[0] - patch_points(ctrl, u, v - h)[0]) / (2 * h)
    assert np.allclose(pu, fu, atol=1e-6) and np.allclose(pv, fv, atol=1e-6)
    # at the corner u = v = 0 the tangents are 3 (P01 - P00) and 3 (P10 - P00)
    _, pu0, pv0 = patch_points(ctrl, np.array([0.0]), np.array([0.0]))
    assert np.allclose(pu0[0, 0], 3 * (ctrl[0, 1] - ctrl[0, 0]))
    assert np.allclose(pv0[0, 0], 3 * (ctrl[1, 0] - ctrl[0, 0]))


def test_tessellation_is_an_open_consistently_wound_mesh_with_outward_normals():
    verts, polys, vn = tessellate(6)
    poly = polyhedron_from_polygons(verts, polys, "teapot", vertex_normals=vn)
    # open and hollow: edges with one polygon (lid gap, spout end, handle ends)
    assert (poly.edge_faces[:, 1] < 0).sum() > 0 and not poly.is_closed
    # polygon winding agrees with the slides' normal N = dP/du x dP/dv
    agree = np.einsum("ij,ij->i", poly.normals, poly.vertex_normals[poly.polygons[:, 0]])
    assert np.mean(agree > 0) > 0.99
    # and N points outward on the body: away from the vertical axis at mid height (y up)
    rad = np.hypot(verts[:, 0], verts[:, 2])
    body = (np.abs(verts[:, 1] - 1.2) < 0.3) & (rad > 1.9) & (rad < 2.01)  # not spout, handle
    radial = np.stack([verts[body, 0], np.zeros(body.sum()), verts[body, 2]], axis=1)
    assert body.sum() > 20
    assert np.all(np.einsum("ij,ij->i", vn[body], radial) > 0)
    assert np.allclose(np.linalg.norm(vn, axis=1), 1.0)
