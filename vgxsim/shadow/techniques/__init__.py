"""Shadow techniques since 1991, each a strategy for the one drawing engine
(:class:`vgxsim.shadow.program.Shadows`), selectable by name::

    from vgxsim.shadow.api import render
    frame = render(scene, technique="zfail")
    frame = render(scene, technique="roettger", technique_options={"application": "quick"})

=========== ====================================================== ========================
name        technique                                              exact where
=========== ====================================================== ========================
heidmann    z-pass as in 1991 (Heidmann), all edges or silhouettes eye and near plane outside
                                                                   every volume, closed
zfail       depth-fail, light and dark caps, w = 0, infinite far   closed casters
auto        per caster z-pass / z-fail, Lengyel's pyramid test     closed casters
zpplus      ZP+, stencil preloaded from the light (Hornus et al.)  closed casters
counting    signed edge counting (Bergeron; Aldridge and Woods)    any caster (z-pass:
                                                                   eye outside)
finite      finite volumes to the receivers (Kolivand and Sunar)   as heidmann
roettger    no stencil: x2 and /2 blending (Roettger et al.)       as heidmann, nesting <= 8
shadowmap   shadow maps, resolution and bias (Williams)            not exact
=========== ====================================================== ========================

Point, spot (a point light whose cone limits only its light) and directional
(w = 0, :class:`DirectionalLight`) lights work with every technique (tested on the
hard cases 'directional' and 'spot'), except that ``shadowmap`` refuses a point light
inside the casters' bounding sphere (one perspective map cannot see all round it)
and ``zpplus`` a light exactly on the camera's near plane (no projection from it onto
that plane); both raise :class:`TechniqueError`.

Every technique takes ``cache=False`` (:class:`.base.VolumeCache`: volume geometry in
display objects from frame to frame; off, the same planes, slower).  Scenes for the
hard cases of shared/reference/shadow_literature.md section 2 are in
:mod:`.hard_cases`.
"""

from __future__ import annotations

from .auto import Auto
from .base import Technique, TechniqueError
from .counting import Counting
from .finite import Finite
from .lights import DirectionalLight
from .roettger import Roettger
from .shadowmap import ShadowMap
from .zfail import ZFail
from .zpass import ZPass
from .zpplus import ZPPlus

TECHNIQUES: dict[str, type[Technique]] = {
    cls.name: cls for cls in (ZPass, ZFail, Auto, ZPPlus, Counting, Finite, Roettger,
                              ShadowMap)
}


def make(name: str | Technique, **options) -> Technique:
    """The technique ``name`` (a key of :data:`TECHNIQUES`) with its options.

    Raises
    ------
    TechniqueError
        For an unknown name or option.
    """
    if isinstance(name, Technique):
        if options:
            raise TechniqueError("options are for a technique given by name")
        return name
    if name not in TECHNIQUES:
        raise TechniqueError(f"unknown shadow technique {name!r} (known: "
                             f"{', '.join(TECHNIQUES)})")
    cache = options.pop("cache", True)
    try:
        tech = TECHNIQUES[name](**options)
    except TypeError as exc:
        raise TechniqueError(f"technique {name!r}: {exc}") from None
    tech.cache = bool(cache)  # every technique: volume geometry in display objects
    return tech


__all__ = ["TECHNIQUES", "DirectionalLight", "Technique", "TechniqueError", "make"]
