"""IRIS GL lighting: ``lmdef`` tables and the per-vertex lighting equation.

Self-contained (numpy and the lighting kernel, vgxsim.kernels.lighting).  :mod:`.tables`
holds the definitions and the three index tables (:class:`LightingTables`, whose
``lmdef`` parses IRIS property lists);
:mod:`.equation` evaluates the RGB lighting equation for arrays of eye-space
vertices (:func:`shade`; :func:`shade_runs` for runs of several materials;
:func:`shade_object_runs` for runs given in object space), with
``lmcolor`` overrides (:func:`apply_lmcolor`) and a helper that takes a light to eye
space at ``lmbind`` (:func:`light_to_eye`).
"""

from .equation import (
    LightEntry,
    apply_lmcolor,
    light_to_eye,
    shade,
    shade_object_runs,
    shade_runs,
)
from .tables import Light, LightingError, LightingTables, LightModel, Material

__all__ = [
    "Light",
    "LightEntry",
    "LightModel",
    "LightingError",
    "LightingTables",
    "Material",
    "apply_lmcolor",
    "light_to_eye",
    "shade",
    "shade_runs",
    "shade_object_runs",
]
