"""Vertex fog (fogvertex(3G)): each vertex colour blended toward the fog colour by
its eye-space distance, after lighting and before clipping.

``f = exp(-ln(255) * density * Z)`` (FG_VTX_EXP), ``exp(-ln(255) * (density * Z)**2)``
(FG_VTX_EXP2), ``(end - Z) / (end - start)`` (FG_VTX_LIN), clamped to [0, 1], with
``Z = |z_eye|``; the colour becomes ``f * c + (1 - f) * fog`` in r, g, b (alpha
kept).  The ln(255) scale makes an IRIS density the inverse of the distance at which
fog is complete to 8 bits (1/255 of the colour left), the reading IGL gives the
density when it hands it to OpenGL (``GL_FOG_DENSITY = 5.54 * density``); |z_eye| is
OpenGL's fog distance for a vertex.  The FG_PIX_* modes are evaluated per vertex
too: per-pixel fog needs the fragment stage (getgdesc(GD_FOGPIXEL) answers 0).
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from vgxsim.geometry.transform import apply

LN255 = math.log(255.0)


class FogState(NamedTuple):
    """What vertex fog reads.

    Attributes
    ----------
    mode : str
        'exp', 'exp2' or 'lin'.
    density, start, end : float
    colour : tuple of 3 float
        Fog RGB in [0, 1].
    modelview : ndarray, shape (4, 4)
        Object -> eye (the identity in MSINGLE, where eye space is object space).
    """

    mode: str
    density: float
    start: float
    end: float
    colour: tuple
    modelview: np.ndarray


def fog_factor(fog: FogState, dist: np.ndarray) -> np.ndarray:
    """Fraction of the vertex colour kept at eye distances ``dist`` (N,) float64."""
    if fog.mode == "lin":
        span = fog.end - fog.start
        f = (np.ones_like(dist) if span == 0.0 else (fog.end - dist) / span)
    elif fog.mode == "exp":
        f = np.exp(-LN255 * fog.density * dist)
    else:
        f = np.exp(-LN255 * (fog.density * dist) ** 2)
    return np.clip(f, 0.0, 1.0)


def fog_vertices(fog: FogState, obj: np.ndarray, rgba: np.ndarray) -> np.ndarray:
    """Fogged copy of vertex colours.

    Parameters
    ----------
    fog : FogState
    obj : ndarray, shape (N, 4), float64
        Object-space vertices.
    rgba : ndarray, shape (N, 4), float64

    Returns
    -------
    ndarray, shape (N, 4), float64
    """
    eye = apply(obj, fog.modelview)
    w = np.where(eye[:, 3] == 0.0, 1.0, eye[:, 3])
    f = fog_factor(fog, np.abs(eye[:, 2] / w))[:, None]
    out = np.array(rgba, dtype=np.float64)
    out[:, :3] = f * out[:, :3] + (1.0 - f) * np.asarray(fog.colour, np.float64)
    return out
