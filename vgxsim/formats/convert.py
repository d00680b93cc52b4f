"""Conversion to ``.glo`` and to the cache: the roles of ``bintoglo`` and ``glotopdat``.

README of ``shadows``: models of the demo program "flip" "can be converted into
".glo" format by the program "bintoglo" ... A command-line option, "-f", is provided
to reverse the ordering of the vertices ... required in some cases to get
front-facing and normal direction to work out", and ""..glo" files can be converted
into ".pdat" files with the "glotopdat" utility".

Here the input is any mesh trimesh reads (OBJ, STL, PLY, OFF, GLB/GLTF, ...) or a
``.glo``; the output is ``.glo`` / ``.glo.gz`` or a standalone cache ``.npz``.
Vertices that coincide are merged (trimesh's ``process``), so that neighbouring
polygons share edges, as the adjacency needs.
"""

from __future__ import annotations

import os

import numpy as np

from .cache import file_sha256, polyhedron_from_glo, write_cache
from .errors import FormatError
from .glo import NORMAL_MODES, GloModel, read_glo, write_glo


def mesh_to_glo(mesh, *, flip: bool = False, normals: str = "none") -> GloModel:
    """A trimesh mesh as a :class:`GloModel`.

    Parameters
    ----------
    mesh : trimesh.Trimesh
    flip : bool
        Reverse every polygon's vertex order (the README's ``-f``); normals turn too.
    normals : {'none', 'face', 'vertex'}
        What normals to store (trimesh's face normals, or its vertex normals: those
        of the file where it has them, else area-weighted).

    Returns
    -------
    GloModel
    """
    if normals not in NORMAL_MODES:
        raise ValueError(f"normals must be one of {NORMAL_MODES}, not {normals!r}")
    faces = np.asarray(mesh.faces, np.int64)
    sign = 1.0
    if flip:
        faces = faces[:, ::-1]
        sign = -1.0
    fn = sign * np.asarray(mesh.face_normals) if normals == "face" else None
    vn = sign * np.asarray(mesh.vertex_normals) if normals == "vertex" else None
    return GloModel.from_polygons(np.asarray(mesh.vertices, np.float64), faces,
                                  face_normals=fn, vertex_normals=vn)


def flipped(model: GloModel) -> GloModel:
    """``model`` with every polygon's vertex order reversed and its normals negated."""
    s = model.poly_start
    flat = np.concatenate([model.poly_verts[s[i]:s[i + 1]][::-1] for i in range(len(s) - 1)])
    return GloModel(model.vertices, s, flat, model.normals,
                    None if model.face_normals is None else -model.face_normals,
                    None if model.vertex_normals is None else -model.vertex_normals,
                    model.lmbind)


def read_any(path: str | os.PathLike, *, flip: bool = False, normals: str = "none") -> GloModel:
    """A ``.glo`` or any mesh file trimesh reads, as a :class:`GloModel`.

    Raises
    ------
    FormatError
        If the file is missing, unreadable, or holds no triangles.
    """
    import trimesh

    path = os.fspath(path)
    if not os.path.isfile(path):
        raise FormatError(path, None, "no such mesh file")
    if path.endswith((".glo", ".glo.gz")):
        model = read_glo(path)
        return flipped(model) if flip else model
    try:
        mesh = trimesh.load(path, force="mesh", process=True)
    except Exception as exc:  # trimesh raises many types for unreadable files
        raise FormatError(path, None, f"trimesh cannot read this mesh ({exc})") from None
    if not isinstance(mesh, trimesh.Trimesh) or len(mesh.faces) == 0:
        raise FormatError(path, None, "the file holds no triangles")
    return mesh_to_glo(mesh, flip=flip, normals=normals)


def convert(src: str | os.PathLike, dst: str | os.PathLike, *, flip: bool = False,
            normals: str = "none") -> GloModel:
    """Convert ``src`` to ``dst`` (``.glo``, ``.glo.gz`` or a cache ``.npz``).

    For a cache the adjacency is built (failing on a mesh the shadow code cannot
    use) and keyed by the SHA-256 of ``src``'s bytes.

    Returns
    -------
    GloModel
        What was converted.

    Raises
    ------
    FormatError
    """
    src, dst = os.fspath(src), os.fspath(dst)
    model = read_any(src, flip=flip, normals=normals)
    if dst.endswith((".glo", ".glo.gz")):
        write_glo(dst, model, f"converted from {os.path.basename(src)}"
                  + (" with the vertex order reversed (-f)" if flip else ""))
    elif dst.endswith(".npz"):
        poly = polyhedron_from_glo(model, os.path.basename(src), path=src)
        write_cache(dst, poly, file_sha256(src))
    else:
        raise FormatError(dst, None, "the output must end in .glo, .glo.gz or .npz")
    return model
