"""heidmann: z-pass stencil shadow volumes as in 1991, for any light (Heidmann 1991).

"As you travel along the path from your viewpoint to the object visible at that
pixel, count the number of times you cross through one of these semi-transparent
surfaces going into shadow, and subtract the number of times you cross going out of
shadow."  Shadow faces from every edge (``edges='all'``, the article's loop "For each
edge in the scene") or from silhouettes only (``edges='silhouette'``, the article's
"only the silhouette edges need to be projected"), found by edge adjacency or by the
Kolivand-Sunar edge set (``silhouettes='toggle'``); faces extruded ``length`` units
(default the scene's volume length, the article's "some arbitrary distance") or to
infinity (``length=None``, under an infinite far plane).

Known failures, kept (tests count them): the eye inside a volume and volumes cut by
the near plane (shadow_literature.md H1, H2), open and non-manifold casters (H5),
faces too short to reach a receiver.
"""

from __future__ import annotations

import numpy as np

from .base import ZPASS_OPS, Technique, TechniqueError
from .volumes import (
    facing,
    polygon_edges,
    side_quads,
    silhouettes_by_adjacency,
    silhouettes_by_toggle,
)

EDGE_SETS = ("silhouette", "all")
SILHOUETTE_METHODS = ("adjacency", "toggle")


def edge_pairs(mesh, light: np.ndarray, edges: str, silhouettes: str) -> np.ndarray:
    """(S, 2) vertex pairs whose shadow faces bound the mesh's volume (see volumes)."""
    if edges == "all":
        a, b = polygon_edges(mesh)
        fac = np.repeat(facing(mesh, light), mesh.polygons.shape[1])
        return np.stack([np.where(fac, a, b), np.where(fac, b, a)], axis=1)
    if silhouettes == "toggle":
        return silhouettes_by_toggle(mesh, light)
    return silhouettes_by_adjacency(mesh, light)


class ZPass(Technique):
    """Heidmann's z-pass.

    Parameters
    ----------
    edges : {'silhouette', 'all'}
    silhouettes : {'adjacency', 'toggle'}
        How silhouettes are found (same faces on closed meshes).
    length : float or None, optional
        Extrusion length; default the scene's ``volume_length``; None: to infinity.
    cull : bool
        Skip casters whose whole shadow volume lies outside the view frustum
        (McGuire et al. 2003's shadow-volume culling; :func:`.volumes.volume_culled`):
        an optimisation, tested to change no stencil value.
    """

    name = "heidmann"

    def __init__(self, edges: str = "silhouette", silhouettes: str = "adjacency",
                 length: float | None | str = "scene", cull: bool = False):
        if edges not in EDGE_SETS:
            raise TechniqueError(f"heidmann: edges must be one of {EDGE_SETS}, not {edges!r}")
        if silhouettes not in SILHOUETTE_METHODS:
            raise TechniqueError(f"heidmann: silhouettes must be one of "
                                 f"{SILHOUETTE_METHODS}, not {silhouettes!r}")
        self.edges = edges
        self.silhouettes = silhouettes
        self.length = length
        self.infinite_far = length is None
        self.cull = cull
        self.exact = False

    def faces(self, prog, i: int) -> np.ndarray:
        """(N, 4, 4) homogeneous shadow faces of light ``i``."""
        lt = self.light(prog, i)
        length = prog.scene.volume_length if self.length == "scene" else self.length
        parts = [side_quads(m, edge_pairs(m, lt, self.edges, self.silhouettes), lt, length)
                 for m in self.casters(prog, lt, length)]
        return np.concatenate(parts) if parts else np.zeros((0, 4, 4))

    def mark(self, prog, i: int) -> None:
        self.start_stencil(prog)
        self.draw_by_facing(self.faces(prog, i), *ZPASS_OPS)
