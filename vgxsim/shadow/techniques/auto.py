"""auto: per-object z-pass or z-fail by Lengyel's (2002) near-plane pyramid test.

A caster's volume can hold a point of the near-plane rectangle only if the caster
meets some segment from that point to the light, i.e. meets the convex hull of the
light and the rectangle (for a directional light: the rectangle swept toward the
light).  Where the caster's bounding sphere lies wholly outside one plane of that
hull, cheap z-pass (no caps) is exact for it; otherwise it gets z-fail.  Both give
the number of volumes containing the visible point, so their counts add in one
stencil.  Every volume is extruded to infinity (infinite far plane), so z-pass faces
are never too short.  The choice only saves work: tested to change no stencil value.
"""

from __future__ import annotations

import numpy as np

from vgxsim.gl import getsize

from .base import ZPASS_OPS
from .volumes import near_rectangle, side_quads
from .zfail import ZFail
from .zpass import edge_pairs


def pyramid_planes(scene, aspect: float, light: np.ndarray) -> np.ndarray | None:
    """(P, 4) planes ``(n, d)``, inside where ``n . x + d >= 0``, of the hull of the
    light and the near rectangle; None when the light lies on the near plane (no
    z-pass is safe then)."""
    rect = near_rectangle(scene, aspect)
    c = rect.corners
    side = float(rect.normal @ light[:3] - rect.offset * light[3])
    if side == 0.0:
        return None
    inner = (c.mean(axis=0) + (light[:3] if light[3] != 0.0 else c.mean(axis=0)
                                + light[:3])) / 2.0
    planes = []
    near_n = rect.normal if side > 0 else -rect.normal
    planes.append(np.append(near_n, -near_n @ c[0]))
    for k in range(4):
        p, q = c[k], c[(k + 1) % 4]
        to_l = light[:3] - light[3] * p
        n = np.cross(q - p, to_l)
        nn = np.linalg.norm(n)
        if nn == 0.0:
            continue
        n = n / nn
        if n @ (inner - p) < 0:
            n = -n
        planes.append(np.append(n, -n @ p))
    return np.array(planes)


def needs_zfail(mesh, planes: np.ndarray | None) -> bool:
    """Whether the caster's bounding sphere may meet the pyramid (z-pass unsafe)."""
    if planes is None:
        return True
    centre = 0.5 * (mesh.vertices.min(axis=0) + mesh.vertices.max(axis=0))
    radius = float(np.linalg.norm(mesh.vertices - centre, axis=1).max())
    dist = planes[:, :3] @ centre + planes[:, 3]
    return not bool(np.any(dist < -radius))


class Auto(ZFail):
    """Per-caster z-pass / z-fail (Lengyel 2002).

    Parameters
    ----------
    force : {None, 'zpass', 'zfail'}
        None: Lengyel's test; otherwise every caster the same way (the switch the
        optimisation test turns off: 'zfail' everywhere must give the same stencil).
    """

    name = "auto"
    infinite_far = True

    def __init__(self, force: str | None = None, silhouettes: str = "adjacency",
                 cull: bool = False):
        super().__init__(silhouettes=silhouettes, cull=cull, infinite_far=True)
        if force not in (None, "zpass", "zfail"):
            raise ValueError(f"auto: force must be None, 'zpass' or 'zfail', not {force!r}")
        self.force = force
        self.last_choice: dict[str, str] = {}

    def mark(self, prog, i: int) -> None:
        self.start_stencil(prog)
        lt = self.light(prog, i)
        w, h = getsize()
        planes = pyramid_planes(prog.scene, w / h, lt)
        for mesh in self.casters(prog, lt, None):
            zf = needs_zfail(mesh, planes) if self.force is None else self.force == "zfail"
            self.last_choice[mesh.name] = "zfail" if zf else "zpass"
            if zf:
                self.draw_volume(mesh, lt)
            else:
                quads = side_quads(mesh, edge_pairs(mesh, lt, "silhouette", self.silhouettes),
                                   lt, None)
                self.draw_by_facing(quads, *ZPASS_OPS)
