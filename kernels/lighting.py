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
    local_viewer = lmodel[3] != 0.0
    k0, k1, k2 = lmodel[4], lmodel[5], lmodel[6]
    rgb = np.empty(3)
    ldir = np.empty(3)
    for i in range(n):
        for c in range(3):
            rgb[c] = emission[i, c] + ambient[i, c] * lmodel[c]
        if local_viewer:
            vx, vy, vz = -p[i, 0], -p[i, 1], -p[i, 2]
            vlen = math.sqrt(vx * vx + vy * vy + vz * vz)
            if vlen > 0.0:
                vx, vy, vz = vx / vlen, vy / vlen, vz / vlen
            else:
                vx, vy, vz = 0.0, 0.0, 0.0
        else:
            vx, vy, vz = 0.0, 0.0, 1.0
        nx, ny, nz = nrm[i, 0], nrm[i, 1], nrm[i, 2]
        spec_on = shininess[i] >= min_shininess
        for k in range(lights.shape[0]):
            if lights[k, 0] != 0.0:
                tx = lights[k, 1] - p[i, 0]
                ty = lights[k, 2] - p[i, 1]
                tz = lights[k, 3] - p[i, 2]
                dist = math.sqrt(tx * tx + ty * ty + tz * tz)
                if dist > 0.0:
                    ldir[0], ldir[1], ldir[2] = tx / dist, ty / dist, tz / dist
                else:
                    ldir[0], ldir[1], ldir[2] = 0.0, 0.0, 0.0
                denom = k0 + k1 * dist + k2 * dist * dist
                factor = 1.0 / denom if denom > 0.0 else 0.0
            else:
                ldir[0], ldir[1], ldir[2] = lights[k, 1], lights[k, 2], lights[k, 3]
                factor = 1.0
            if lights[k, 10] != 0.0:
                cos_a = -(ldir[0] * lights[k, 11] + ldir[1] * lights[k, 12]
                          + ldir[2] * lights[k, 13])
                if cos_a >= lights[k, 14]:
                    factor = factor * max(cos_a, 0.0) ** lights[k, 15]
                else:
                    factor = factor * 0.0
            n_dot_l = nx * ldir[0] + ny * ldir[1] + nz * ldir[2]
            diff = max(n_dot_l, 0.0)
            hx, hy, hz = ldir[0] + vx, ldir[1] + vy, ldir[2] + vz
            hlen = math.sqrt(hx * hx + hy * hy + hz * hz)
            if hlen > 0.0:
                hx, hy, hz = hx / hlen, hy / hlen, hz / hlen
            else:
                hx, hy, hz = 0.0, 0.0, 0.0
            n_dot_h = max(nx * hx + ny * hy + nz * hz, 0.0)
            spec = 0.0
            if spec_on and n_dot_l > 0.0:
                spec = n_dot_h ** shininess[i]
            for c in range(3):
                lc = lights[k, 4 + c]
                term = (ambient[i, c] * lights[k, 7 + c] + diff * diffuse[i, c] * lc
                        + spec * specular[i, c] * lc)
                rgb[c] = rgb[c] + factor * term
        for c in range(3):
            out[i, c] = min(max(rgb[c], 0.0), 1.0)
        out[i, 3] = min(max(alpha[i], 0.0), 1.0)
    return out
