"""``.glo`` polygon geometry: reader and writer.

README of ``shadows``: "a simple format for 3D geometry which represents objects as
a series of gl bgnpolygon/v3f/endpolygon calls.  In addition, lmbinds can be
interspersed arbitrarily and objects can be saved without normals, with normal per
face, or with normal per vertex."  The 1991 file layout is lost (glo_obj.c was not
found), so the text grammar below is this project's, with the same content: one
line per vertex and one per polygon, so a polygon reads like its
``bgnpolygon(); v3f(...) ...; endpolygon()`` sequence with the vertices shared.

Grammar (one record per line; ``#`` starts a comment; blank lines are ignored;
tokens are separated by blanks; ``.glo.gz`` files are read through gzip)::

    file     := header { record }
    header   := "glo" "1"                      first non-comment line
    record   := "normals" ("none" | "face" | "vertex")    before any v or f
              | "v" X Y Z                      a vertex, numbered 1, 2, ... in order
              | "vn" X Y Z                     normals vertex: the normal of the vertex
                                               with the same number (one per v)
              | "lmbind" N                     material index (N >= 0) of the polygons
                                               that follow; 0: the object's own
              | "f" I J K { L }                a polygon of >= 3 vertex numbers,
                                               counter-clockwise seen from outside
              | "f" I J K { L } "/" NX NY NZ   normals face: the polygon and its normal

A ``.glo`` file read here is exact: numbers are written with Python's shortest
round-trip ``repr``, so write then read gives the same float64 values.
"""

from __future__ import annotations

import gzip
import os
from dataclasses import dataclass

import numpy as np

from vgxsim.sinks.atomic import atomic_path

from .errors import FormatError

NORMAL_MODES = ("none", "face", "vertex")


@dataclass(eq=False)
class GloModel:
    """The content of one ``.glo`` file.

    Attributes
    ----------
    vertices : ndarray, shape (V, 3), float64
    poly_start : ndarray, shape (F + 1,), int64
        Polygon ``f`` is ``poly_verts[poly_start[f]:poly_start[f + 1]]``.
    poly_verts : ndarray, shape (N,), int64
        Zero-based vertex indices.
    normals : {'none', 'face', 'vertex'}
    face_normals : ndarray, shape (F, 3), float64, or None
    vertex_normals : ndarray, shape (V, 3), float64, or None
    lmbind : ndarray, shape (F,), int64
        The material index in force for each polygon (0: none given).
    """

    vertices: np.ndarray
    poly_start: np.ndarray
    poly_verts: np.ndarray
    normals: str = "none"
    face_normals: np.ndarray | None = None
    vertex_normals: np.ndarray | None = None
    lmbind: np.ndarray | None = None

    def __post_init__(self) -> None:
        if self.lmbind is None:
            self.lmbind = np.zeros(len(self.poly_start) - 1, np.int64)

    @property
    def polygons(self) -> list[np.ndarray]:
        """Each polygon's zero-based vertex indices (a list of F arrays)."""
        s = self.poly_start
        return [self.poly_verts[s[i]:s[i + 1]] for i in range(len(s) - 1)]

    @classmethod
    def from_polygons(cls, vertices, polygons, *, vertex_normals=None,
                      face_normals=None) -> GloModel:
        """A model from vertices and (possibly ragged) zero-based polygons.

        Parameters
        ----------
        vertices : array_like, shape (V, 3)
        polygons : array_like, shape (F, K), or a list of F index sequences
        vertex_normals : array_like, shape (V, 3), optional
        face_normals : array_like, shape (F, 3), optional
        """
        lens = [len(p) for p in polygons]
        start = np.zeros(len(lens) + 1, np.int64)
        np.cumsum(lens, out=start[1:])
        flat = (np.concatenate([np.asarray(p, np.int64) for p in polygons])
                if lens else np.zeros(0, np.int64))
        mode = "vertex" if vertex_normals is not None else (
            "face" if face_normals is not None else "none")
        return cls(np.asarray(vertices, np.float64).reshape(-1, 3), start, flat, mode,
                   None if face_normals is None else np.asarray(face_normals, np.float64),
                   None if vertex_normals is None else np.asarray(vertex_normals, np.float64))


def _open_text(path: str, mode: str):
    if str(path).endswith(".gz"):
        return gzip.open(path, mode + "t", encoding="utf-8")
    return open(path, mode, encoding="utf-8")


def _floats(path, lineno, toks, n, what):
    if len(toks) != n:
        raise FormatError(path, lineno, f"{what} needs {n} numbers, found {len(toks)}")
    try:
        vals = [float(t) for t in toks]
    except ValueError:
        raise FormatError(path, lineno, f"{what}: expected numbers, found "
                          f"{' '.join(toks)!r}") from None
    if not all(np.isfinite(vals)):
        raise FormatError(path, lineno, f"{what}: numbers must be finite")
    return vals


def read_glo(path: str | os.PathLike) -> GloModel:
    """Read a ``.glo`` (or ``.glo.gz``) file.

    Raises
    ------
    FormatError
        Naming the file and line of the first record that breaks the grammar, a
        vertex number out of range, or a missing normal.
    """
    path = os.fspath(path)
    verts: list[list[float]] = []
    vnorms: list[list[float]] = []
    fnorms: list[list[float]] = []
    starts = [0]
    flat: list[int] = []
    binds: list[int] = []
    mode = "none"
    bind = 0
    header = False
    try:
        fh = _open_text(path, "r")
    except OSError as exc:
        raise FormatError(path, None, f"cannot open model file: {exc.strerror}") from None
    with fh:
        try:
            for lineno, line in enumerate(fh, 1):
                toks = line.split("#", 1)[0].split()
                if not toks:
                    continue
                key, args = toks[0], toks[1:]
                if not header:
                    if key != "glo" or args != ["1"]:
                        raise FormatError(path, lineno,
                                          f"expected the header 'glo 1', found {line.strip()!r}")
                    header = True
                elif key == "v":
                    verts.append(_floats(path, lineno, args, 3, "v"))
                elif key == "f":
                    nrm = None
                    if "/" in args:
                        k = args.index("/")
                        args, nrm = args[:k], args[k + 1:]
                    if len(args) < 3:
                        raise FormatError(path, lineno,
                                          f"f needs at least 3 vertex numbers, found {len(args)}")
                    try:
                        idx = [int(a) for a in args]
                    except ValueError:
                        raise FormatError(path, lineno, "f: expected vertex numbers, found "
                                          f"{' '.join(args)!r}") from None
                    bad = [i for i in idx if not 1 <= i <= len(verts)]
                    if bad:
                        raise FormatError(path, lineno, f"f: vertex number {bad[0]} is not one "
                                          f"of the {len(verts)} vertices defined so far")
                    if mode == "face":
                        if nrm is None:
                            raise FormatError(path, lineno, "normals face: expected "
                                              "'/ NX NY NZ' after the vertex numbers")
                        fnorms.append(_floats(path, lineno, nrm, 3, "face normal"))
                    elif nrm is not None:
                        raise FormatError(path, lineno, f"a face normal given, but the file "
                                          f"declares 'normals {mode}'")
                    flat.extend(i - 1 for i in idx)
                    starts.append(len(flat))
                    binds.append(bind)
                elif key == "vn":
                    if mode != "vertex":
                        raise FormatError(path, lineno, f"vn given, but the file declares "
                                          f"'normals {mode}' (expected 'normals vertex' first)")
                    vnorms.append(_floats(path, lineno, args, 3, "vn"))
                elif key == "normals":
                    if len(args) != 1 or args[0] not in NORMAL_MODES:
                        raise FormatError(path, lineno, "normals: expected none, face or "
                                          f"vertex, found {' '.join(args)!r}")
                    if verts or len(starts) > 1:
                        raise FormatError(path, lineno, "normals must come before any v or f")
                    mode = args[0]
                elif key == "lmbind":
                    if len(args) != 1 or not args[0].isdigit():
                        raise FormatError(path, lineno, "lmbind: expected one material "
                                          f"index >= 0, found {' '.join(args)!r}")
                    bind = int(args[0])
                else:
                    raise FormatError(path, lineno, f"unknown record {key!r} (expected v, vn, "
                                      "f, lmbind or normals)")
        except (UnicodeDecodeError, EOFError, OSError) as exc:
            raise FormatError(path, None, f"not a text .glo file ({exc})") from None
    if not header:
        raise FormatError(path, None, "empty file: expected the header 'glo 1'")
    if mode == "vertex" and len(vnorms) != len(verts):
        raise FormatError(path, None, f"normals vertex: {len(verts)} vertices but "
                          f"{len(vnorms)} vn records")
    if len(starts) == 1:
        raise FormatError(path, None, "no polygons (expected at least one f record)")
    return GloModel(np.array(verts, np.float64).reshape(-1, 3), np.array(starts, np.int64),
                    np.array(flat, np.int64), mode,
                    np.array(fnorms, np.float64) if mode == "face" else None,
                    np.array(vnorms, np.float64) if mode == "vertex" else None,
                    np.array(binds, np.int64))


def write_glo(path: str | os.PathLike, model: GloModel, comment: str | None = None) -> None:
    """Write ``model`` as ``.glo`` (gzip for a ``.gz`` name), atomically.

    Parameters
    ----------
    path : str or PathLike
    model : GloModel
    comment : str, optional
        Written as ``#`` lines after the header.
    """
    path = os.fspath(path)
    with atomic_path(path) as tmp, _open_text(tmp, "w") as fh:
        fh.write("glo 1\n")
        for line in (comment or "").splitlines():
            fh.write(f"# {line}\n")
        fh.write(f"normals {model.normals}\n")
        fh.writelines(f"v {x!r} {y!r} {z!r}\n" for x, y, z in model.vertices.tolist())
        if model.normals == "vertex":
            fh.writelines(f"vn {x!r} {y!r} {z!r}\n"
                          for x, y, z in model.vertex_normals.tolist())
        s = model.poly_start
        flat = (model.poly_verts + 1).tolist()
        fn = model.face_normals.tolist() if model.normals == "face" else None
        bind = 0
        for f, b in enumerate(model.lmbind.tolist()):
            if b != bind:
                fh.write(f"lmbind {b}\n")
                bind = b
            rec = "f " + " ".join(map(str, flat[s[f]:s[f + 1]]))
            if fn is not None:
                x, y, z = fn[f]
                rec += f" / {x!r} {y!r} {z!r}"
            fh.write(rec + "\n")
