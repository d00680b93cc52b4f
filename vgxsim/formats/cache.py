"""The precomputed adjacency cache: the role of the 1991 ``.pdat`` files.

README of ``shadows``: "When ``.glo`` files are read into the "shadows" program, all
this processing must happen before any display can occur ... for some models this
time was getting up around 30 seconds or so.  To eliminate this problem, a binary
format for the geometry files was created, including all the neat info the
"shadows" program wants."

Here the cache is a numpy ``.npz`` holding everything :class:`Polyhedron` needs for
silhouette extraction and drawing (vertices, polygons, Newell normals, edges with
their two polygons, fan triangles, optional vertex normals) and the SHA-256 of the
bytes of the ``.glo`` it was built from.  A cache is used only when that hash
matches the source file as it is now, so a stale cache is never used:

* ``load_model(path)`` of a ``.glo`` looks for ``<cache dir>/<sha256>.npz``
  (``$VGXSIM_CACHE_DIR``, default ``~/.cache/vgxsim/models``), builds and writes it
  when absent (best effort: a read-only cache folder only costs the rebuild);
* ``write_cache(out.npz, ...)`` makes a standalone cache file (``vgxsim convert
  model.glo model.npz``, the role of ``glotopdat``); a scene's MODEL may name it.
"""

from __future__ import annotations

import hashlib
import os
import zipfile

import numpy as np

from vgxsim.shadow.scene import MeshError, Polyhedron, SurfaceMaterial, polyhedron_from_polygons
from vgxsim.sinks.atomic import atomic_path

from .errors import FormatError
from .glo import GloModel, read_glo

CACHE_FORMAT = "vgxsim-adjacency-1"
_ARRAYS = ("vertices", "polygons", "normals", "edges", "edge_faces", "triangles",
           "triangle_face")


def file_sha256(path: str | os.PathLike) -> str:
    """Hex SHA-256 of a file's bytes (the cache key)."""
    h = hashlib.sha256()
    with open(path, "rb") as fh:
        for block in iter(lambda: fh.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def cache_dir() -> str:
    """``$VGXSIM_CACHE_DIR`` or ``~/.cache/vgxsim/models``."""
    return os.environ.get("VGXSIM_CACHE_DIR") or os.path.join(
        os.path.expanduser("~"), ".cache", "vgxsim", "models")


def polyhedron_from_glo(model: GloModel, name: str, material: SurfaceMaterial | None = None,
                        casts: bool = True, *, path: str = "<model>") -> Polyhedron:
    """Edge adjacency and normals of a ``.glo`` model (the expensive step).

    Raises
    ------
    FormatError
        If the mesh has an edge traversed twice in one direction or by more than two
        polygons (naming the file).
    """
    try:
        return polyhedron_from_polygons(model.vertices, model.polygons, name, material, casts,
                                        vertex_normals=model.vertex_normals)
    except MeshError as exc:
        raise FormatError(path, None, str(exc)) from None


def write_cache(path: str | os.PathLike, poly: Polyhedron, source_sha256: str) -> None:
    """Write ``poly``'s arrays and the source hash to ``path`` (.npz), atomically."""
    arrays = {k: getattr(poly, k) for k in _ARRAYS}
    if poly.vertex_normals is not None:
        arrays["vertex_normals"] = poly.vertex_normals
    with atomic_path(path) as tmp, open(tmp, "wb") as fh:
        np.savez_compressed(fh, format=np.array(CACHE_FORMAT),
                            source_sha256=np.array(source_sha256), **arrays)


def read_cache(path: str | os.PathLike, name: str, material: SurfaceMaterial | None = None,
               casts: bool = True) -> tuple[Polyhedron, str]:
    """Read a cache file.

    Returns
    -------
    poly : Polyhedron
    source_sha256 : str
        The hash of the ``.glo`` it was built from.

    Raises
    ------
    FormatError
        If the file is not a vgxsim adjacency cache or its arrays are inconsistent.
    """
    path = os.fspath(path)
    try:
        with np.load(path, allow_pickle=False) as z:
            if "format" not in z or str(z["format"]) != CACHE_FORMAT:
                raise FormatError(path, None, f"not a vgxsim adjacency cache (expected "
                                  f"format {CACHE_FORMAT!r})")
            data = {k: z[k] for k in _ARRAYS}
            vn = z["vertex_normals"] if "vertex_normals" in z else None
            src = str(z["source_sha256"])
    except (OSError, ValueError, KeyError, zipfile.BadZipFile) as exc:
        if isinstance(exc, FormatError):
            raise
        raise FormatError(path, None, f"cannot read the adjacency cache: {exc}") from None
    nv = len(data["vertices"])
    if (data["polygons"].size and (data["polygons"].max() >= nv or data["polygons"].min() < 0)):
        raise FormatError(path, None, "cache polygons name vertices that do not exist")
    poly = Polyhedron(name=name, material=material or SurfaceMaterial(), casts=casts,
                      vertex_normals=vn, **data)
    return poly, src


def load_model(path: str | os.PathLike, name: str | None = None,
               material: SurfaceMaterial | None = None, casts: bool = True, *,
               use_cache: bool = True) -> Polyhedron:
    """Load a model file (``.glo``, ``.glo.gz`` or a cache ``.npz``) as a Polyhedron.

    Parameters
    ----------
    path : str or PathLike
    name : str, optional
        Default: the file name.
    material, casts
        As for :class:`Polyhedron`.
    use_cache : bool
        Look up and write the adjacency cache of a ``.glo`` (False: always rebuild).

    Raises
    ------
    FormatError
    """
    path = os.fspath(path)
    name = name or os.path.basename(path)
    if not os.path.isfile(path):
        raise FormatError(path, None, "no such model file")
    if path.endswith(".npz"):
        return read_cache(path, name, material, casts)[0]
    digest = file_sha256(path)
    cached = os.path.join(cache_dir(), digest + ".npz")
    if use_cache and os.path.isfile(cached):
        try:
            poly, src = read_cache(cached, name, material, casts)
            if src == digest:
                return poly
        except FormatError:
            pass  # a damaged cache entry is rebuilt below
    poly = polyhedron_from_glo(read_glo(path), name, material, casts, path=path)
    if use_cache:
        try:
            os.makedirs(cache_dir(), exist_ok=True)
            write_cache(cached, poly, digest)
        except OSError:
            pass  # no writable cache folder: the model still loads
    return poly
