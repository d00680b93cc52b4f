"""A directional light (IRIS GL POSITION with w = 0) for the shadow scenes."""

from __future__ import annotations

from dataclasses import dataclass

from vgxsim import GL
from vgxsim.shadow.scene import PointLight


@dataclass(frozen=True)
class DirectionalLight(PointLight):
    """A light at infinity: ``position`` is the direction *toward* the light.

    lmdef(3G): POSITION with w = 0 "is an infinite light ... located at infinity in
    the direction (x, y, z)".  The reference (:func:`vgxsim.shadow.raycast.
    light_position`) reads the class attribute ``w``.
    """

    w = 0.0  # class attribute, not a field

    def props(self) -> list[float]:
        out = [GL.LCOLOR, *self.colour, GL.AMBIENT, *self.ambient,
               GL.POSITION, *self.position, 0.0]
        return out + [GL.LMNULL]
