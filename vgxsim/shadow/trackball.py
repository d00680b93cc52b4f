"""A virtual trackball: mouse drags to rotation quaternions.

The 1991 ``shadows`` program let "the viewer rotate the scene trackball style" with the
middle mouse (README).  This follows the scheme SGI's demos used (Gavin Bell's
trackball.c, after Thant Tessman and the August 1988 SIGGRAPH "Virtual Trackball"
notes): the two mouse positions, in window coordinates scaled to [-1, 1], are lifted
onto a sphere of radius :data:`TRACKBALL_SIZE` that turns into a hyperbolic sheet away
from the centre (so drags near the edge still rotate smoothly); the rotation axis is
perpendicular to both lifted points and the angle grows with the distance between them.
Rotations compose as unit quaternions ``(x, y, z, w)``.

Coordinates are the eye's: x to the right, y up, z towards the viewer.  The rotation
turns the point on the sphere under the first mouse position to the point under the
second ("the scene follows the mouse").  The matrix is for IRIS GL's row vectors
(``v' = v @ M``, the ``multmatrix`` layout).
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["TRACKBALL_SIZE", "IDENTITY", "project_to_sphere", "trackball", "add_quats",
           "rotation_matrix"]

#: Radius of the virtual sphere in normalized window units (trackball.c's 0.8).
TRACKBALL_SIZE = 0.8

#: The quaternion of no rotation.
IDENTITY = (0.0, 0.0, 0.0, 1.0)


def project_to_sphere(r: float, x: float, y: float) -> float:
    """z of the point above ``(x, y)`` on a sphere of radius ``r``, or on the hyperbolic
    sheet ``z = r**2 / (2 d)`` that meets the sphere at ``d = r / sqrt(2)``."""
    d = math.hypot(x, y)
    if d < r * math.sqrt(0.5):
        return math.sqrt(r * r - d * d)
    return r * r / (2.0 * d)


def trackball(p1x: float, p1y: float, p2x: float, p2y: float,
              size: float = TRACKBALL_SIZE) -> tuple[float, float, float, float]:
    """The rotation of a drag from ``(p1x, p1y)`` to ``(p2x, p2y)``.

    Parameters
    ----------
    p1x, p1y, p2x, p2y : float
        Mouse positions in normalized window coordinates, -1..1, y up.
    size : float
        Trackball radius.

    Returns
    -------
    (x, y, z, w) : tuple of float
        A unit quaternion; :data:`IDENTITY` for no motion.
    """
    if p1x == p2x and p1y == p2y:
        return IDENTITY
    p1 = np.array([p1x, p1y, project_to_sphere(size, p1x, p1y)])
    p2 = np.array([p2x, p2y, project_to_sphere(size, p2x, p2y)])
    axis = np.cross(p1, p2)
    norm = float(np.linalg.norm(axis))
    if norm == 0.0:
        return IDENTITY
    t = min(1.0, float(np.linalg.norm(p2 - p1)) / (2.0 * size))
    phi = 2.0 * math.asin(t)  # the chord p1-p2 of a circle of radius `size`
    s = math.sin(phi / 2.0) / norm
    return (float(axis[0] * s), float(axis[1] * s), float(axis[2] * s), math.cos(phi / 2.0))


def add_quats(q1, q2) -> tuple[float, float, float, float]:
    """The rotation ``q1`` followed by ``q2`` (the product ``q2 * q1``), renormalized.

    trackball.c renormalized every 97 additions; renormalizing every time costs
    nothing here and keeps a long spin from drifting off the unit sphere.
    """
    x1, y1, z1, w1 = q1
    x2, y2, z2, w2 = q2
    x = w2 * x1 + x2 * w1 + (y2 * z1 - z2 * y1)
    y = w2 * y1 + y2 * w1 + (z2 * x1 - x2 * z1)
    z = w2 * z1 + z2 * w1 + (x2 * y1 - y2 * x1)
    w = w2 * w1 - (x2 * x1 + y2 * y1 + z2 * z1)
    n = math.sqrt(x * x + y * y + z * z + w * w)
    return (x / n, y / n, z / n, w / n)


def rotation_matrix(q) -> np.ndarray:
    """The 4x4 rotation of unit quaternion ``q`` for row vectors (``v @ M``).

    Returns
    -------
    ndarray, shape (4, 4), float64
    """
    x, y, z, w = q
    # column-vector rotation R; IRIS GL's row vectors use its transpose
    r = np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
        [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
        [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
    ])
    m = np.eye(4)
    m[:3, :3] = r.T
    return m
