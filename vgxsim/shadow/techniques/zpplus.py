"""zpplus: ZP+, z-pass made correct by a stencil preloaded from the light (Hornus,
Hoberock, Lefebvre and Hart 2005).

Before z-pass counting, the stencil of each pixel is set to the number of volumes
that hold the pixel's point Q on the near plane: the light-facing polygons of every
caster (the near caps) are drawn, without z test, through a projection from the
light onto the camera's near-plane rectangle, so a cap covers the pixel exactly when
it crosses the segment from Q to the light.  z-pass counting (infinite faces) then
adds the crossings from Q to the visible point: the count is right with the eye in
shadow and with volumes cut by the near plane (shadow_literature.md H1, H2).

The projection (row-vector, 4 x 4): with the near plane ``n . x = d``, the light
``L = (l, lw)``, ``a = n . l - d lw`` and ``b(X) = n . X - d``, the point of the
near plane on the line through X and L is ``Q = a X - b(X) L`` (homogeneous); the
camera's model-view-projection then gives its pixel.  Depth is replaced so that
``z/w = (c b - a) / (a - b)`` (c = 1 + 2^-10): -1 on the near plane, > -1 between it
and the light -- caps beyond the near plane and behind the light are clipped.  For
a directional light ``z/w = 2 b / (a S) - 1`` with S = 4 x the scene's radius.
A light on the near plane (a = 0) has no such projection: TechniqueError.
"""

from __future__ import annotations

import numpy as np

from vgxsim.gl import (
    FALSE,
    MPROJECTION,
    MVIEWING,
    SF_ALWAYS,
    ST_INCR,
    ST_KEEP,
    TRUE,
    getmatrix,
    getsize,
    loadmatrix,
    mmode,
    popmatrix,
    pushmatrix,
    stencil,
    zbuffer,
)

from .base import ZPASS_OPS, Technique, TechniqueError
from .volumes import caps, infinite_projection, near_rectangle, scene_box, side_quads
from .zpass import SILHOUETTE_METHODS, edge_pairs

DEPTH_MARGIN = 2.0 ** -10


def light_to_near_plane(scene, aspect: float, light: np.ndarray) -> np.ndarray:
    """The (4, 4) row-vector matrix taking world points to the clip coordinates of
    their image on the near plane, seen from the light (see the module docstring)."""
    rect = near_rectangle(scene, aspect)
    n, d = rect.normal, rect.offset
    plane = np.append(n, -d)                         # b(X) = plane . X
    a = float(n @ light[:3] - d * light[3])
    if a == 0.0:
        raise TechniqueError("zpplus: the light lies on the camera's near plane; ZP+ "
                             "has no projection from it (use zfail)")
    project = a * np.eye(4) - np.outer(plane, light)  # X_h @ project = a X - b(X) L
    cam = scene.camera
    m = project @ cam.modelview() @ infinite_projection(cam, aspect)
    near = cam.near
    if light[3] != 0.0:
        zcol = near * ((1.0 + DEPTH_MARGIN) * plane - a * np.array([0, 0, 0, 1.0]))
    else:
        lo, hi = scene_box(scene)
        s = 4.0 * max(1.0, float(np.abs(np.concatenate([lo, hi])).max()),
                      float(np.abs(np.asarray(cam.eye)).max())) * np.sqrt(3.0)
        zcol = near * (2.0 / s * plane - a * np.array([0, 0, 0, 1.0]))
    m[:, 2] = zcol
    if a < 0.0:
        m = -m                                       # same points, w > 0
    return m


class ZPPlus(Technique):
    """ZP+ (Hornus et al. 2005).

    Parameters
    ----------
    silhouettes : {'adjacency', 'toggle'}
    """

    name = "zpplus"
    infinite_far = True

    def __init__(self, silhouettes: str = "adjacency"):
        if silhouettes not in SILHOUETTE_METHODS:
            raise ValueError(f"zpplus: silhouettes must be one of {SILHOUETTE_METHODS}")
        self.silhouettes = silhouettes

    def preload(self, prog, light: np.ndarray) -> None:
        """Add, per pixel, the number of near caps between its near-plane point and
        the light."""
        w, h = getsize()
        m = light_to_near_plane(prog.scene, w / h, light)
        mmode(MPROJECTION)
        saved = getmatrix()                          # (not stacked: mmode(3G))
        loadmatrix(m.reshape(-1).tolist())
        mmode(MVIEWING)
        pushmatrix()
        loadmatrix(np.eye(4).reshape(-1).tolist())
        zbuffer(FALSE)
        stencil(TRUE, 0, SF_ALWAYS, 0xff, ST_INCR, ST_INCR, ST_INCR)
        for mesh in prog.scene.casters:
            self.draw_polygons(caps(mesh, light, "light"))
        zbuffer(TRUE)
        popmatrix()
        mmode(MPROJECTION)
        loadmatrix(saved)
        mmode(MVIEWING)
        stencil(TRUE, 0, SF_ALWAYS, 0xff, ST_KEEP, ST_KEEP, ST_KEEP)

    def mark(self, prog, i: int) -> None:
        self.start_stencil(prog)
        lt = self.light(prog, i)
        self.preload(prog, lt)
        for mesh in prog.scene.casters:
            quads = side_quads(mesh, edge_pairs(mesh, lt, "silhouette", self.silhouettes),
                               lt, None)
            self.draw_by_facing(quads, *ZPASS_OPS)
