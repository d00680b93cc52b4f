"""The default shadow scene and the article's shadow-face construction."""

from __future__ import annotations

import numpy as np
import pytest
import trimesh

from vgxsim import GL
from vgxsim.shadow import (
    MATL_DIFFSPEC,
    MATL_EMITAMBIENT,
    SurfaceMaterial,
    all_edges,
    all_edges_faces,
    default_scene,
    is_ingoing,
    make_box,
    shadow_faces,
    shadow_quad,
    silhouette_edges,
)
from vgxsim.shadow.scene import make_grid_box


def test_default_scene_is_three_cubes_a_floor_a_red_and_a_blue_light():
    s = default_scene()
    names = [o.name for o in s.objects]
    assert names == ["floor", "cube1", "cube2", "cube3"]
    assert [o.casts for o in s.objects] == [False, True, True, True]
    red, blue = s.lights
    assert red.colour[0] > max(red.colour[1:]) and blue.colour[2] > max(blue.colour[:2])
    # README: ambient (0.2, 0.2, 0.2), local viewer, attenuation, two-side off
    assert s.lmodel.props() == [GL.AMBIENT, 0.2, 0.2, 0.2, GL.LOCALVIEWER, 0.0,
                                GL.ATTENUATION, 1.0, 0.0, GL.TWOSIDE, 0.0, GL.LMNULL]
    # the camera sees every object and is above the floor, outside every volume
    assert s.camera.eye[1] > 0
    for o in s.casters:
        assert o.vertices[:, 1].min() >= -1e-12  # on or above the floor top (y = 0)


def test_material_parts_split_the_components():
    m = SurfaceMaterial(emission=(0.1, 0.0, 0.0), ambient=(0.2, 0.3, 0.4),
                        diffuse=(0.5, 0.6, 0.7), specular=(0.8, 0.9, 1.0), shininess=10)
    ea = m.props(MATL_EMITAMBIENT)
    ds = m.props(MATL_DIFFSPEC)

    def prop(lst, tok):
        i = lst.index(tok)
        return tuple(lst[i + 1:i + 4])

    assert prop(ea, GL.EMISSION) == (0.1, 0.0, 0.0) and prop(ea, GL.AMBIENT) == (0.2, 0.3, 0.4)
    assert prop(ea, GL.DIFFUSE) == (0, 0, 0) and prop(ea, GL.SPECULAR) == (0, 0, 0)
    assert prop(ds, GL.EMISSION) == (0, 0, 0) and prop(ds, GL.AMBIENT) == (0, 0, 0)
    assert prop(ds, GL.DIFFUSE) == (0.5, 0.6, 0.7) and prop(ds, GL.SPECULAR) == (0.8, 0.9, 1.0)
    assert ea[-1] == GL.LMNULL and ds[-1] == GL.LMNULL


@pytest.mark.parametrize("index", range(4))
def test_objects_are_closed_outward_ccw_with_two_faces_per_edge(index):
    obj = default_scene().objects[index]
    assert obj.is_closed
    centre = obj.vertices.mean(axis=0)
    p = obj.vertices[obj.polygons]
    # CCW seen from outside: the polygon's own cross products agree with the normal
    # and the normal points away from the (convex) object's centre
    n = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
    assert np.all(np.einsum("ij,ij->i", n, obj.normals) > 0)
    assert np.all(np.einsum("ij,ij->i", obj.normals, p.mean(axis=1) - centre) > 0)
    assert np.allclose(np.linalg.norm(obj.normals, axis=1), 1.0)
    # each edge a -> b is traversed a -> b by its first face and b -> a by its second
    for (a, b), (f, g) in zip(obj.edges, obj.edge_faces, strict=True):
        pf, pg = list(obj.polygons[f]), list(obj.polygons[g])
        assert pf[(pf.index(a) + 1) % len(pf)] == b
        assert pg[(pg.index(b) + 1) % len(pg)] == a
    # Euler: V - E + F = 2 for these genus-0 meshes
    assert len(obj.vertices) - len(obj.edges) + len(obj.polygons) == 2


def test_adjacency_agrees_with_trimesh():
    obj = make_box("b", (1.0, 2.0, 3.0), position=(1, 2, 3), rotate=(10, 20, 30))
    mesh = trimesh.Trimesh(obj.vertices, obj.triangles, process=False)
    assert mesh.is_watertight and mesh.is_winding_consistent and mesh.volume > 0
    pairs = {tuple(sorted((obj.triangle_face[a], obj.triangle_face[b])))
             for a, b in mesh.face_adjacency
             if obj.triangle_face[a] != obj.triangle_face[b]}
    assert pairs == {tuple(sorted(fg)) for fg in obj.edge_faces.tolist()}
    assert np.isclose(mesh.volume, 6.0)


def test_grid_box_is_a_closed_quad_mesh():
    obj = make_grid_box("g", (4.0, 1.0, 2.0), (4, 1, 2))
    assert obj.polygons.shape == (2 * (4 * 1 + 1 * 2 + 4 * 2), 4)
    assert obj.is_closed
    mesh = trimesh.Trimesh(obj.vertices, obj.triangles, process=False)
    assert mesh.is_watertight and np.isclose(mesh.volume, 8.0)


def test_shadow_quad_projects_away_from_the_light():
    light = np.array([0.0, 10.0, 0.0])
    v1, v2 = np.array([1.0, 1.0, 0.0]), np.array([0.0, 1.0, 1.0])
    q = shadow_quad(v1, v2, light, 5.0)
    assert np.array_equal(q[0], v1) and np.array_equal(q[1], v2)
    for end, start in ((q[2], v2), (q[3], v1)):
        assert np.isclose(np.linalg.norm(end - start), 5.0)
        # on the line from the light through the vertex, beyond it
        d = start - light
        assert np.allclose(np.cross(end - light, d), 0.0, atol=1e-12)
        assert np.dot(end - start, d) > 0
    # planar (the light, v1 and v2 span its plane)
    n = np.cross(v2 - v1, light - v1)
    assert np.allclose((q - v1) @ n, 0.0, atol=1e-12)


def test_silhouette_of_a_cube_lit_from_above():
    cube = make_box("c", (1.0, 1.0, 1.0))
    light = (0.0, 10.0, 0.0)
    sil = silhouette_edges(cube, light)
    assert len(sil) == 4
    assert np.allclose(sil[:, :, 1], 0.5)  # the top face's four edges
    # each vertex starts one edge and ends another: a closed loop
    starts = sorted(map(tuple, sil[:, 0].round(12)))
    ends = sorted(map(tuple, sil[:, 1].round(12)))
    assert starts == ends
    # article: Ns points out of the shadow volume (away from its axis, the y axis)
    q = shadow_quad(sil[:, 0], sil[:, 1], light, 3.0)
    ns = np.cross(q[:, 1] - q[:, 0], q[:, 2] - q[:, 1])
    mid = q.mean(axis=1)
    assert np.all(np.einsum("ij,ij->i", ns[:, [0, 2]], mid[:, [0, 2]]) > 0)


@pytest.mark.parametrize("light", [(0.3, 9.0, 0.2), (-4.0, 1.2, 3.0), (0.0, -6.0, 0.5)])
def test_every_polygon_volume_face_points_outward(light):
    # "When a polygon is facing the light source ... drawn in the direction opposite
    # that of the original edge, ... Ns will point outward ... When the original
    # polygon is facing away from the light source, these directions are reversed."
    cube = make_box("c", (1.0, 1.5, 0.7), rotate=(20, 30, 40))
    e = all_edges(cube, light)
    q = shadow_quad(e[:, 0], e[:, 1], light, 4.0)
    ns = np.cross(q[:, 1] - q[:, 0], q[:, 2] - q[:, 1])
    k = cube.polygons.shape[1]
    centroid = np.repeat(cube.vertices[cube.polygons].mean(axis=1), k, axis=0)
    # the polygon (the volume's cap) lies on the inner side of each of its faces
    assert np.all(np.einsum("ij,ij->i", ns, centroid - q[:, 0]) < 0)
    # and the silhouette faces are a subset of the all-edge faces, same orientation
    sil = {tuple(np.round(s, 9).ravel()) for s in silhouette_edges(cube, light)}
    alle = {tuple(np.round(s, 9).ravel()) for s in e}
    assert sil <= alle


def test_ingoing_is_front_facing_on_screen():
    # "front-facing polygons will be going into shadow, and back-facing polygons will
    # be going out of the shadow": compare with the signed area in window coordinates.
    s = default_scene()
    w, h = 320, 256
    mvp = s.camera.modelview() @ s.camera.projection(w / h)
    for light in range(2):
        quads, ingoing = shadow_faces(s, light, "all")
        clip = np.concatenate([quads, np.ones(quads.shape[:2] + (1,))], axis=2) @ mvp
        assert np.all(clip[..., 3] > 0)  # nothing behind the eye in this scene
        xy = clip[..., :2] / clip[..., 3:4] * np.array([w / 2, h / 2])
        x, y = xy[..., 0], xy[..., 1]
        area = (x * np.roll(y, -1, axis=1) - np.roll(x, -1, axis=1) * y).sum(axis=1)
        big = np.abs(area) > 1e-6
        assert np.array_equal(area[big] > 0, ingoing[big])
        assert ingoing.any() and (~ingoing).any()


def test_all_edges_faces_returns_flags():
    s = default_scene()
    obj = s.objects[1]
    edges, ingoing = all_edges_faces(obj, s.lights[0].position, s.camera.eye)
    assert edges.shape == (obj.polygons.size, 2, 3)
    assert np.array_equal(ingoing, is_ingoing(edges, s.lights[0].position, s.camera.eye))
