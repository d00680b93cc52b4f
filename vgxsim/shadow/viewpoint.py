"""Is the viewpoint inside a shadow volume?  (README of ``shadows``, Bugs: "The program
does not handle the special case of the viewpoint being in shadow.")

The z-pass count starts at zero at the eye; an eye inside k volumes starts every
pixel's count k too low, so lit and shadowed swap where the volume reaches.  Until
the robust techniques (z-fail, ZP+) land, the program detects the case and warns.

The eye is inside a caster's (finite) shadow volume for a light when the segment
from the eye to the light meets a caster triangle no farther from the eye than the
volume's length: the exact, float64 point-in-volume test for the article's volumes
of length ``scene.volume_length`` (up to the volume's far end, where the quads'
endpoints lie at that distance from the silhouette).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .scene import Scene


@dataclass(frozen=True)
class EyeInShadow:
    """One light whose shadow contains the eye."""

    light: int
    light_name: str
    caster: str


def _segment_hits(p: np.ndarray, q: np.ndarray, tris: np.ndarray) -> np.ndarray:
    """Moller-Trumbore: which triangles (T, 3, 3) the open segment p -> q crosses."""
    d = q - p
    e1 = tris[:, 1] - tris[:, 0]
    e2 = tris[:, 2] - tris[:, 0]
    h = np.cross(d, e2)
    a = np.einsum("ij,ij->i", e1, h)
    ok = np.abs(a) > 1e-300
    f = np.divide(1.0, a, out=np.zeros_like(a), where=ok)
    s = p - tris[:, 0]
    u = f * np.einsum("ij,ij->i", s, h)
    qv = np.cross(s, e1)
    v = f * (qv @ d)
    t = f * np.einsum("ij,ij->i", e2, qv)
    return ok & (u >= 0) & (v >= 0) & (u + v <= 1) & (t > 0) & (t < 1)


def eye_in_shadow(scene: Scene) -> list[EyeInShadow]:
    """Every (light, caster) pair whose shadow volume contains the camera's eye.

    Parameters
    ----------
    scene : Scene

    Returns
    -------
    list of EyeInShadow
        Empty when the eye is lit by every light (z-pass counts are then exact).
    """
    eye = np.asarray(scene.camera.eye, np.float64)
    found = []
    for i, lt in enumerate(scene.lights):
        lp = np.asarray(lt.position, np.float64)
        for obj in scene.casters:
            tris = obj.vertices[obj.triangles]
            hit = _segment_hits(eye, lp, tris)
            if not hit.any():
                continue
            # within the finite volume: the caster is at most volume_length from the eye
            near = np.linalg.norm(tris[hit].mean(axis=1) - eye, axis=1).min()
            if near <= scene.volume_length:
                found.append(EyeInShadow(i, lt.name, obj.name))
    return found
