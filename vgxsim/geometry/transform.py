"""4x4 transforms in IRIS GL's row-vector convention.

IRIS GL transforms a point as the row vector ``p' = p @ M``, and ``multmatrix(M)``
makes ``current = M @ current`` (it premultiplies; MS "Porting Matrix and
Transformation Functions").  Stored row-major, an IRIS ``Matrix`` holds the same 16
floats in the same order as OpenGL's column-major matrix, translation in
``m[3][0:3]``.  Angles given to ``rotate`` are in tenths of a degree; ``rot`` takes
degrees.
"""

from __future__ import annotations

import math

import numpy as np

from vgxsim.kernels.transform import transform_points

Matrix = np.ndarray  # shape (4, 4), float64, row-vector convention


def identity() -> Matrix:
    return np.eye(4)


def translation(x: float, y: float, z: float) -> Matrix:
    m = np.eye(4)
    m[3, :3] = (x, y, z)
    return m


def scaling(x: float, y: float, z: float) -> Matrix:
    return np.diag([float(x), float(y), float(z), 1.0])


def rotation(degrees: float, axis: str) -> Matrix:
    """Right-handed rotation about 'x', 'y' or 'z' (counter-clockwise looking down
    the axis toward the origin), as a row-vector matrix."""
    a = math.radians(degrees)
    c, s = math.cos(a), math.sin(a)
    m = np.eye(4)
    ax = axis.lower()
    if ax == "x":
        m[1, 1], m[1, 2], m[2, 1], m[2, 2] = c, s, -s, c
    elif ax == "y":
        m[0, 0], m[0, 2], m[2, 0], m[2, 2] = c, -s, s, c
    elif ax == "z":
        m[0, 0], m[0, 1], m[1, 0], m[1, 1] = c, s, -s, c
    else:
        raise ValueError(f"axis must be 'x', 'y' or 'z', not {axis!r}")
    return m


def frustum(left: float, right: float, bottom: float, top: float, near: float,
            far: float) -> Matrix:
    """window(3G): perspective frustum (the transpose of glFrustum's matrix)."""
    m = np.zeros((4, 4))
    m[0, 0] = 2.0 * near / (right - left)
    m[1, 1] = 2.0 * near / (top - bottom)
    m[2, 0] = (right + left) / (right - left)
    m[2, 1] = (top + bottom) / (top - bottom)
    m[2, 2] = -(far + near) / (far - near)
    m[2, 3] = -1.0
    m[3, 2] = -2.0 * far * near / (far - near)
    return m


def perspective(fovy_tenths: float, aspect: float, near: float, far: float) -> Matrix:
    """perspective(3G): fovy in tenths of a degree."""
    f = 1.0 / math.tan(math.radians(fovy_tenths / 10.0) / 2.0)
    m = np.zeros((4, 4))
    m[0, 0] = f / aspect
    m[1, 1] = f
    m[2, 2] = -(far + near) / (far - near)
    m[2, 3] = -1.0
    m[3, 2] = -2.0 * far * near / (far - near)
    return m


def orthographic(left: float, right: float, bottom: float, top: float, near: float,
                 far: float) -> Matrix:
    """ortho(3G) (and ortho2 with near = -1, far = 1)."""
    m = np.eye(4)
    m[0, 0] = 2.0 / (right - left)
    m[1, 1] = 2.0 / (top - bottom)
    m[2, 2] = -2.0 / (far - near)
    m[3, 0] = -(right + left) / (right - left)
    m[3, 1] = -(top + bottom) / (top - bottom)
    m[3, 2] = -(far + near) / (far - near)
    return m


def lookat(vx: float, vy: float, vz: float, px: float, py: float, pz: float,
           twist_tenths: float) -> Matrix:
    """lookat(3G): viewpoint (vx, vy, vz) looking at (px, py, pz), twist in tenths.

    Up is +y; when the line of sight is parallel to y, up is +z looking along +y and
    -z looking along -y (so CPython's kunst.py demo, ``lookat(0,-6,0, 0,0,0, 0)``,
    stays upright; see irisgl_reference 1.7).  The twist is a rotation about the
    line of sight applied in eye space, ``rotate(-twist, 'z')`` as IGL does.
    """
    eye = np.array([vx, vy, vz], dtype=float)
    d = np.array([px, py, pz], dtype=float) - eye
    n = np.linalg.norm(d)
    if n == 0.0:
        raise ValueError("lookat: viewpoint and reference point coincide")
    f = d / n
    if abs(d[0]) < 1e-12 * n and abs(d[2]) < 1e-12 * n:
        up = np.array([0.0, 0.0, 1.0 if d[1] > 0 else -1.0])
    else:
        up = np.array([0.0, 1.0, 0.0])
    s = np.cross(f, up)
    s /= np.linalg.norm(s)
    u = np.cross(s, f)
    m = np.eye(4)
    m[:3, 0] = s
    m[:3, 1] = u
    m[:3, 2] = -f
    m = translation(*(-eye)) @ m
    return m @ rotation(-twist_tenths / 10.0, "z")


def polarview(dist: float, azim: float, inc: float, twist: float) -> Matrix:
    """polarview(3G): translate(0,0,-dist); rotate(-twist,'z'); rotate(-inc,'x');
    rotate(-azim,'z') -- angles in tenths; calls compose by premultiplying."""
    m = identity()
    m = translation(0.0, 0.0, -dist) @ m
    m = rotation(-twist / 10.0, "z") @ m
    m = rotation(-inc / 10.0, "x") @ m
    m = rotation(-azim / 10.0, "z") @ m
    return m


def apply(points: np.ndarray, m: Matrix) -> np.ndarray:
    """Row vectors times a matrix, ``points @ m``, computed the same way for every row.

    BLAS ``matmul`` may round a row differently depending on how many rows are in
    the call (blocking and FMA paths differ), so the same vertex could land on a
    different fixed-point position, or get a different z, when it is drawn alone
    (immediate mode) or inside a large array (a display object, a mesh).  The
    numeric model needs "two passes over the same triangle give bit-identical z"
    (docs/numeric_model.md s. 4), so the product is spelled out as elementwise
    multiply-adds in a fixed order: ``((p0*m0 + p1*m1) + p2*m2) + p3*m3``.

    Parameters
    ----------
    points : ndarray, shape (N, K), float64
    m : ndarray, shape (K, J), float64

    Returns
    -------
    ndarray, shape (N, J), float64
    """
    p = np.ascontiguousarray(points, dtype=np.float64)
    m = np.ascontiguousarray(m, dtype=np.float64)
    if p.shape[0] == 0:
        return np.zeros((0, m.shape[1]))
    return transform_points(p, m)
