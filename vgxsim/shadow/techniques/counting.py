"""counting: signed edge counting for casters that are not closed or not manifold
(Bergeron 1986; Aldridge and Woods 2004).

Every polygon of a caster contributes its own shadow volume: a light-facing polygon
with +1, one facing away with -1 (its volume is entered through the other side).
Per edge (vertices welded by position) the contributions of the polygons that run it
add up, +1 or -1 for the direction; opposite runs cancel, and an edge whose sum is
k != 0 gets its shadow face drawn |k| times, oriented by the sign.  The product of a
polygon's facing and its direction along the edge does not depend on which way the
polygon is wound, so open meshes (an edge of one polygon: |k| = 1), "book" edges of
three polygons, duplicated and inconsistently wound triangles all work: the count at
a point is the number of caster surfaces between it and the light (Kim, Kim and Turk
2008's formulation), twice the silhouette count on a closed mesh ("shadow polygons
cast from silhouette edges of closed objects count 2", Bergeron).  A pixel is lit
iff the count is 0.

Counting is z-pass (``zfail=False``, the eye must be outside every volume) or z-fail
(``zfail=True``): then every polygon is also a near cap (light-facing as drawn,
facing away reversed) and, pushed to infinity, a dark cap, each once.  Stencil
range: counts up to 127 either way from MYZERO.
"""

from __future__ import annotations

import numpy as np

from .base import ZFAIL_OPS, ZPASS_OPS, Technique
from .volumes import extrude, facing, side_quads, signed_edge_counts


def every_polygon_caps(mesh, light: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(near caps (F, K, 4), dark caps (F, K, 4)): every polygon wound toward the light
    (reversed if it faces away) and its image at infinity, wound away from it."""
    fac = facing(mesh, light)
    polys = np.where(fac[:, None], mesh.polygons, mesh.polygons[:, ::-1])
    v = np.concatenate([mesh.vertices, np.ones((len(mesh.vertices), 1))], axis=1)
    near = v[polys]
    far = extrude(mesh.vertices, light, None)[polys[:, ::-1]]
    if light[3] == 0.0:
        far = far[:0]
    return near, far


class Counting(Technique):
    """Signed edge counting (Bergeron; Aldridge and Woods).

    Parameters
    ----------
    zfail : bool
        Count behind the surface with caps (robust to the eye in shadow).
    """

    name = "counting"

    def __init__(self, zfail: bool = False, cull: bool = False):
        self.zfail = zfail
        self.infinite_far = True
        self.cull = cull

    def mark(self, prog, i: int) -> None:
        self.start_stencil(prog)
        lt = self.light(prog, i)
        ops = ZFAIL_OPS if self.zfail else ZPASS_OPS
        for mesh in self.casters(prog, lt, None):
            pairs, weight = signed_edge_counts(mesh, lt)
            self.draw_by_facing(side_quads(mesh, pairs, lt, None), *ops, zfail=self.zfail,
                           times=weight)
            if self.zfail:
                near, far = every_polygon_caps(mesh, lt)
                for polys in (near, far):
                    if len(polys):
                        self.draw_by_facing(polys, *ops, zfail=True)
