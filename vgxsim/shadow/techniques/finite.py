"""finite: z-pass with finite volumes clipped between occluder and receiver
(Kolivand and Sunar 2011, shared/seeds/003: "clip each infinite quadrilateral to be
finite quadrilateral between occluder and shadow receiver").

Silhouettes come from the paper's edge set (:func:`.volumes.silhouettes_by_toggle`).
Each silhouette vertex is extruded away from the light only as far as the far side of
the receivers' bounding box along its ray (the slab exit), so the faces end where no
receiver can lie beyond them: shorter faces, less fill, and the same count as
infinite z-pass for every receiver.  (The paper's per-pixel formula for the length is
garbled in the stored text; the box exit is this module's reading of its intent.)
Like every z-pass, wrong with the eye in shadow or volumes cut by the near plane.
"""

from __future__ import annotations

import numpy as np

from .base import ZPASS_OPS, Technique
from .volumes import scene_box, side_quads
from .zpass import SILHOUETTE_METHODS, edge_pairs


def exit_lengths(vertices: np.ndarray, light: np.ndarray, lo: np.ndarray, hi: np.ndarray
                 ) -> np.ndarray:
    """(V,) distance from each vertex, away from the light, to where its ray leaves the
    box [lo, hi] (0 when it is already outside and leaving), plus a margin of 1 % of
    the box diagonal so that faces pass the far receivers."""
    d = light[3] * vertices - light[:3][None, :]
    n = np.linalg.norm(d, axis=1, keepdims=True)
    u = np.divide(d, n, out=np.zeros_like(d), where=n > 0)
    with np.errstate(divide="ignore", invalid="ignore"):
        t1 = (lo[None, :] - vertices) / u
        t2 = (hi[None, :] - vertices) / u
    tmax = np.where(u != 0, np.maximum(t1, t2), np.inf)
    t = np.min(tmax, axis=1)
    margin = 0.01 * float(np.linalg.norm(hi - lo)) + 1e-9
    return np.maximum(t, 0.0) + margin


class Finite(Technique):
    """Kolivand-Sunar finite volumes, z-pass."""

    name = "finite"

    def __init__(self, silhouettes: str = "toggle", cull: bool = False):
        if silhouettes not in SILHOUETTE_METHODS:
            raise ValueError(f"finite: silhouettes must be one of {SILHOUETTE_METHODS}")
        self.silhouettes = silhouettes
        self.cull = cull

    def mark(self, prog, i: int) -> None:
        self.start_stencil(prog)
        lt = self.light(prog, i)
        lo, hi = scene_box(prog.scene)
        for mesh in self.casters(prog, lt, None):
            length = exit_lengths(mesh.vertices, lt, lo, hi)
            quads = side_quads(mesh, edge_pairs(mesh, lt, "silhouette", self.silhouettes),
                               lt, length)
            self.draw_by_facing(quads, *ZPASS_OPS)
