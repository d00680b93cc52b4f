"""Shadow scenes and shadow-volume geometry (Heidmann, IRIS Universe 1991).

:mod:`.scene` holds the default ``shadows`` scene (three cubes, a floor, a red and a
blue light) as numpy data, with edge adjacency and the shadow-face construction of
the article; :mod:`.raycast` is the exact float64 ray-cast reference for it.
"""

from .scene import (
    MATL_DIFFSPEC,
    MATL_EMITAMBIENT,
    MATL_FULL,
    Camera,
    LightModel,
    PointLight,
    Polyhedron,
    Scene,
    SurfaceMaterial,
    all_edges,
    all_edges_faces,
    default_scene,
    is_ingoing,
    make_box,
    make_grid_box,
    polyhedron_from_polygons,
    polyhedron_from_trimesh,
    shadow_faces,
    shadow_quad,
    silhouette_edges,
)

__all__ = [
    "MATL_DIFFSPEC",
    "MATL_EMITAMBIENT",
    "MATL_FULL",
    "Camera",
    "LightModel",
    "PointLight",
    "Polyhedron",
    "Scene",
    "SurfaceMaterial",
    "all_edges",
    "all_edges_faces",
    "default_scene",
    "is_ingoing",
    "make_box",
    "make_grid_box",
    "polyhedron_from_polygons",
    "polyhedron_from_trimesh",
    "shadow_faces",
    "shadow_quad",
    "silhouette_edges",
]
