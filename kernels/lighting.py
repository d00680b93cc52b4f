"""The IRIS GL per-vertex lighting equation, one pass over the vertices.

The equation and its conventions are those of :mod:`vgxsim.lighting.equation`
(module docstring there: emission + ambient * scene ambient + per light
attenuation * spot * (ambient + diffuse + specular), LCOLOR for diffuse and specular,
no specular where N.L <= 0 or SHININESS < 1, clamped to [0, 1]).  That module's numpy
form evaluates it as about forty whole-array operations per light, each a dispatch
and a temporary; the 1991 frame lights its 640-vertex floor and three cubes once per
pass, and those dispatches were most of the front end's time.  Here every vertex is
lit in registers, in the numpy form's order of operations (sums of three products
left to right, ``(k0 + k1 d) + k2 d d``, ``(A La + d D Lc) + s S Lc``), so the
results are those of the numpy form to the last bit or so: numpy's SIMD ``power``
and ``einsum`` may round their last bit differently from libm's ``pow`` and a
sequential dot product (tests/lighting/test_lighting_kernel.py bounds the difference;
tests/pipeline/test_batched_lighting.py checks identical planes with the kernel off).

Light table rows (:data:`LIGHT_COLUMNS` float64 each), built by
``vgxsim.lighting.equation._light_table``:

====  ============================================================================
0     1.0 for a local light (POSITION w != 0), 0.0 for a directional one
1-3   local: the eye-space position (x, y, z) / w; directional: the unit direction
      towards the light
4-6   LCOLOR
7-9   the light's AMBIENT
10    1.0 when the light is a spot (SPOTLIGHT spread < 180 degrees)
11-13 the unit spot axis in eye space
14    cos(spread)
15    the spot exponent
====  ============================================================================
"""

from __future__ import annotations

import math

import numpy as np

from .options import jit

LIGHT_COLUMNS = 16
#: Light-model row: scene ambient (3), local viewer flag, k0, k1, k2.
LMODEL_COLUMNS = 7


@jit
def light_vertices(p, nrm, emission, ambient, diffuse, specular, shininess, alpha,
                   lights, lmodel, min_shininess):
    """Light N vertices.

    Parameters
    ----------
    p : ndarray, shape (N, 3), float64
        Eye-space positions.
    nrm : ndarray, shape (N, 3), float64
        Eye-space unit normals (zero vectors allowed: emission and ambient only).
    emission, ambient, diffuse, specular : ndarray, shape (N, 3), float64
        The material's colour terms per vertex.
    shininess, alpha : ndarray, shape (N,), float64
    lights : ndarray, shape (L, LIGHT_COLUMNS), float64
        The bound lights in slot order (module docstring).
    lmodel : ndarray, shape (LMODEL_COLUMNS,), float64
    min_shininess : float
        SHININESS below this turns the specular term off (IGL's threshold).

    Returns
    -------
    ndarray, shape (N, 4), float64
        RGBA clamped to [0, 1].
    """
    n = p.shape[0]
    out = np.empty((n, 4))
    rgb = np.empty(3)
    for i in range(n):
        _shade_vertex(out, i, p[i, 0], p[i, 1], p[i, 2], nrm[i, 0], nrm[i, 1], nrm[i, 2],
                      emission, ambient, diffuse, specular, shininess, alpha, i, lights,
                      lmodel, min_shininess, rgb)
    return out


@jit
def light_object_runs(obj, normals, colours, lit, run, modelview, normal_matrix, emission,
                      ambient, diffuse, specular, shininess, alpha, lights, lmodel,
                      min_shininess):
    """Colours of vertices given in object space, in runs that each have their own
    modelview and material, under the same lights: what
    ``vgxsim.lighting.shade_runs`` gives the lit vertices after
    ``vgxsim.geometry.transform.apply`` took them to eye space, and the colour as
    given for the others.

    Parameters
    ----------
    obj : ndarray, shape (N, 4), float64
        Object-space positions.
    normals : ndarray, shape (N, 3), float64
        Object-space normals (normalised here, after the normal matrix).
    colours : ndarray, shape (N, 4), float64
        The current colour per vertex (kept where ``lit`` is False).
    lit : ndarray, shape (N,), bool
    run : ndarray, shape (N,), int64
        Each vertex's run.
    modelview : ndarray, shape (R, 4, 4); normal_matrix : ndarray, shape (R, 3, 3)
        Per run, row vectors (``p @ M``).
    emission, ambient, diffuse, specular : ndarray, shape (R, 3), float64
    shininess, alpha : ndarray, shape (R,), float64
        Per run, its material.
    lights, lmodel, min_shininess
        As for :func:`light_vertices`.

    Returns
    -------
    ndarray, shape (N, 4), float64
    """
    n = obj.shape[0]
    out = np.empty((n, 4))
    rgb = np.empty(3)
    for i in range(n):
        if not lit[i]:
            for c in range(4):
                out[i, c] = colours[i, c]
            continue
        r = run[i]
        m = modelview[r]
        p0, p1, p2, p3 = obj[i, 0], obj[i, 1], obj[i, 2], obj[i, 3]
        # transform.apply's order: ((p0*m0j + p1*m1j) + p2*m2j) + p3*m3j.
        ex = ((p0 * m[0, 0] + p1 * m[1, 0]) + p2 * m[2, 0]) + p3 * m[3, 0]
        ey = ((p0 * m[0, 1] + p1 * m[1, 1]) + p2 * m[2, 1]) + p3 * m[3, 1]
        ez = ((p0 * m[0, 2] + p1 * m[1, 2]) + p2 * m[2, 2]) + p3 * m[3, 2]
        ew = ((p0 * m[0, 3] + p1 * m[1, 3]) + p2 * m[2, 3]) + p3 * m[3, 3]
        if ew == 0.0:
            ew = 1.0
        q = normal_matrix[r]
        n0, n1, n2 = normals[i, 0], normals[i, 1], normals[i, 2]
        nx = (n0 * q[0, 0] + n1 * q[1, 0]) + n2 * q[2, 0]
        ny = (n0 * q[0, 1] + n1 * q[1, 1]) + n2 * q[2, 1]
        nz = (n0 * q[0, 2] + n1 * q[1, 2]) + n2 * q[2, 2]
        length = math.sqrt(nx * nx + ny * ny + nz * nz)
        if length > 0.0:
            nx, ny, nz = nx / length, ny / length, nz / length
        else:
            nx, ny, nz = 0.0, 0.0, 0.0
        _shade_vertex(out, i, ex / ew, ey / ew, ez / ew, nx, ny, nz, emission, ambient,
                      diffuse, specular, shininess, alpha, r, lights, lmodel, min_shininess,
                      rgb)
    return out


@jit
def _shade_vertex(out, i, px, py, pz, nx, ny, nz, emission, ambient, diffuse, specular,
                  shininess, alpha, mi, lights, lmodel, min_shininess, rgb):
    """The equation for one vertex (eye position, unit normal, material row ``mi``)
    into ``out[i]``; ``rgb`` is scratch (3,)."""
    local_viewer = lmodel[3] != 0.0
    k0, k1, k2 = lmodel[4], lmodel[5], lmodel[6]
    for c in range(3):
        rgb[c] = emission[mi, c] + ambient[mi, c] * lmodel[c]
    if local_viewer:
        vx, vy, vz = -px, -py, -pz
        vlen = math.sqrt(vx * vx + vy * vy + vz * vz)
        if vlen > 0.0:
            vx, vy, vz = vx / vlen, vy / vlen, vz / vlen
        else:
            vx, vy, vz = 0.0, 0.0, 0.0
    else:
        vx, vy, vz = 0.0, 0.0, 1.0
    spec_on = shininess[mi] >= min_shininess
    for k in range(lights.shape[0]):
        if lights[k, 0] != 0.0:
            tx = lights[k, 1] - px
            ty = lights[k, 2] - py
            tz = lights[k, 3] - pz
            dist = math.sqrt(tx * tx + ty * ty + tz * tz)
            if dist > 0.0:
                lx, ly, lz = tx / dist, ty / dist, tz / dist
            else:
                lx, ly, lz = 0.0, 0.0, 0.0
            denom = k0 + k1 * dist + k2 * dist * dist
            factor = 1.0 / denom if denom > 0.0 else 0.0
        else:
            lx, ly, lz = lights[k, 1], lights[k, 2], lights[k, 3]
            factor = 1.0
        if lights[k, 10] != 0.0:
            cos_a = -(lx * lights[k, 11] + ly * lights[k, 12] + lz * lights[k, 13])
            if cos_a >= lights[k, 14]:
                factor = factor * max(cos_a, 0.0) ** lights[k, 15]
            else:
                factor = factor * 0.0
        n_dot_l = nx * lx + ny * ly + nz * lz
        diff = max(n_dot_l, 0.0)
        hx, hy, hz = lx + vx, ly + vy, lz + vz
        hlen = math.sqrt(hx * hx + hy * hy + hz * hz)
        if hlen > 0.0:
            hx, hy, hz = hx / hlen, hy / hlen, hz / hlen
        else:
            hx, hy, hz = 0.0, 0.0, 0.0
        n_dot_h = max(nx * hx + ny * hy + nz * hz, 0.0)
        spec = 0.0
        if spec_on and n_dot_l > 0.0:
            spec = n_dot_h ** shininess[mi]
        for c in range(3):
            lc = lights[k, 4 + c]
            term = (ambient[mi, c] * lights[k, 7 + c] + diff * diffuse[mi, c] * lc
                    + spec * specular[mi, c] * lc)
            rgb[c] = rgb[c] + factor * term
    for c in range(3):
        out[i, c] = min(max(rgb[c], 0.0), 1.0)
    out[i, 3] = min(max(alpha[mi], 0.0), 1.0)
