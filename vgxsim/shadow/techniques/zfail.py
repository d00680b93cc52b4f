"""zfail: depth-fail counting with caps and an infinite far plane (Carmack's reverse;
Bilodeau and Songy 1999; Everitt and Kilgard 2002).

Counts the shadow faces *behind* the visible surface: back faces ST_INCR and front
faces ST_DECR where the z test fails, so the count runs from the surface to infinity
and never involves the eye or the near plane (shadow_literature.md H1, H2).  The
volume must be closed: the light-facing polygons are its near cap, the polygons
facing away, pushed to infinity (``(v - L, 0)``), its dark cap; the sides are
silhouette faces extruded to infinity too.  Under the infinite far plane
(:func:`.volumes.infinite_projection`) every w = 0 vertex lands on z_ndc = 1 and the
clipper (``-w <= z <= w``, ends included) keeps it (H3).  For a directional light
the dark cap is a single point and is not drawn.
"""

from __future__ import annotations

import numpy as np

from .base import ZFAIL_OPS, Technique
from .volumes import caps, side_quads
from .zpass import SILHOUETTE_METHODS, edge_pairs


def closed_volume(mesh, light: np.ndarray, silhouettes: str = "adjacency"
                  ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(sides (S, 4, 4), near cap (C, K, 4), dark cap (D, K, 4)) of one closed mesh."""
    sides = side_quads(mesh, edge_pairs(mesh, light, "silhouette", silhouettes), light, None)
    return sides, caps(mesh, light, "light"), caps(mesh, light, "dark")


class ZFail(Technique):
    """Z-fail with light and dark caps, extruded to infinity.

    Parameters
    ----------
    silhouettes : {'adjacency', 'toggle'}
    cull : bool
        Frustum culling of whole volumes (changes no stencil value; tested).
    infinite_far : bool
        False keeps the camera's finite far plane: the w = 0 vertices then lie beyond
        it and are clipped, and the count is lost wherever a volume reaches past the
        far plane (shadow_literature.md H3; kept to show the failure).
    """

    name = "zfail"

    def __init__(self, silhouettes: str = "adjacency", cull: bool = False,
                 infinite_far: bool = True):
        self.infinite_far = bool(infinite_far)
        if silhouettes not in SILHOUETTE_METHODS:
            raise ValueError(f"zfail: silhouettes must be one of {SILHOUETTE_METHODS}")
        self.silhouettes = silhouettes
        self.cull = cull

    def draw_volume(self, mesh, light: np.ndarray) -> None:
        sides, near, dark = closed_volume(mesh, light, self.silhouettes)
        for polys in (sides, near, dark):
            if len(polys):
                self.draw_by_facing(polys, *ZFAIL_OPS, zfail=True)

    def mark(self, prog, i: int) -> None:
        self.start_stencil(prog)
        lt = self.light(prog, i)
        for mesh in self.casters(prog, lt, None):
            self.draw_volume(mesh, lt)
