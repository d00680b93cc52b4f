"""Rigid placement of scene objects and the box mesh, in plain numpy.

The README of ``shadows`` places every object by "Scale, Rotate, Position, with
Rotation done in the order z, y, x"; :func:`object_transform` builds that matrix and
:func:`transform_points` applies it.  :func:`box_mesh` is the cuboid the default
scene's cubes are made of (six quads, counter-clockwise from outside).

Why not trimesh: importing it (with SciPy and networkx) costs more CPU than the rest
of a warm start to the first ``vgxsim shadows`` image (issue 7 item 4).  The
numbers are the same ones trimesh computes -- the same operations in the same
order on float64 (axis rotation by Rodrigues' formula, homogeneous points through
one ``np.dot``) -- so scenes keep their vertices bit for bit;
tests/shadow/test_rigid.py checks that against trimesh itself.
"""

from __future__ import annotations

import math

import numpy as np

#: Unit cube corners, vertex ``i`` at bits (x, y, z) = (i >> 2 & 1, i >> 1 & 1, i & 1):
#: the corner order of trimesh's ``creation.box``.
_CUBE = np.array([[(i >> 2) & 1, (i >> 1) & 1, i & 1] for i in range(8)], dtype=np.float64)

#: The six faces of ``_CUBE``, counter-clockwise seen from outside, each starting at its
#: lowest vertex and sorted by it (-x, -y, -z, +z, +y, +x): the polygons
#: ``polyhedron_from_trimesh`` made of trimesh's box, whatever its placement.
BOX_QUADS = np.array([[0, 1, 3, 2], [0, 4, 5, 1], [0, 2, 6, 4],
                      [1, 5, 7, 3], [2, 3, 7, 6], [4, 6, 7, 5]], dtype=np.int64)

_I4 = np.eye(4)


def translation(offset) -> np.ndarray:
    """(4, 4) float64: translate by ``offset`` (3 numbers)."""
    m = np.eye(4)
    m[:3, 3] = offset[:3]
    return m


def axis_rotation(angle: float, axis: int) -> np.ndarray:
    """(4, 4) float64: rotate ``angle`` radians about coordinate axis 0, 1 or 2.

    Rodrigues' formula ``R = c I + (1 - c) u u^T + s [u]x`` for the unit vector ``u``
    of the axis, summed in that order.
    """
    s = np.sin(angle)
    c = np.cos(angle)
    u = np.zeros(3)
    u[axis] = 1.0
    m = np.diag([c, c, c, 1.0])
    m[:3, :3] += np.outer(u, u) * (1.0 - c)
    u = u * s
    m[:3, :3] += np.array([[0.0, -u[2], u[1]], [u[2], 0.0, -u[0]], [-u[1], u[0], 0.0]])
    return m


def object_transform(position=(0.0, 0.0, 0.0), rotate=(0.0, 0.0, 0.0),
                     scale=(1.0, 1.0, 1.0)) -> np.ndarray:
    """README: "the transformations are always done in the order Scale, Rotate,
    Position, with Rotation done in the order z, y, x" -- the gl sequence
    translate; rotate x; rotate y; rotate z; scale.

    Parameters
    ----------
    position, rotate, scale : sequence of 3 float
        Offset, degrees about x, y and z, and scale factors.

    Returns
    -------
    ndarray, shape (4, 4), float64
        For column vectors (``p' = M @ [x, y, z, 1]``).
    """
    m = translation(np.asarray(position, dtype=np.float64))
    for axis, ang in enumerate(rotate):  # x, then y, then z
        m = m @ axis_rotation(math.radians(ang), axis)
    return m @ np.diag([*scale, 1.0])


def transform_points(points: np.ndarray, matrix: np.ndarray) -> np.ndarray:
    """Points through a homogeneous matrix.

    Parameters
    ----------
    points : ndarray, shape (N, 3), float64
    matrix : ndarray, shape (4, 4), float64

    Returns
    -------
    ndarray, shape (N, 3), float64
        A copy of ``points`` when ``matrix`` is within 1e-8 of the identity.
    """
    points = np.asarray(points, dtype=np.float64)
    if np.abs(matrix - _I4).max() < 1e-8:
        return points.copy()
    stack = np.column_stack((points, np.ones(len(points))))
    return np.dot(matrix, stack.T).T[:, :3]


def box_mesh(extents, matrix: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """A box of edge lengths ``extents`` centred at the origin, then ``matrix``.

    Parameters
    ----------
    extents : sequence of 3 float
    matrix : ndarray, shape (4, 4), float64
        A rigid motion (no reflection: the quads stay counter-clockwise).

    Returns
    -------
    vertices : ndarray, shape (8, 3), float64
    quads : ndarray, shape (6, 4), int64
        :data:`BOX_QUADS`.

    Raises
    ------
    ValueError
        If ``extents`` is not 3 numbers or ``matrix`` reflects.
    """
    ext = np.asarray(extents, dtype=np.float64)
    if ext.shape != (3,):
        raise ValueError(f"box extents must be 3 numbers, got {extents!r}")
    if np.linalg.det(matrix[:3, :3]) < 0:
        raise ValueError("box placement must not reflect (the quads would turn inward)")
    verts = (_CUBE - 0.5) * ext
    return transform_points(verts, matrix), BOX_QUADS.copy()
