"""The IRIS GL per-vertex lighting equation (RGB mode), vectorised with numpy.

For each vertex, with N the unit normal, P the eye-space position and V the viewer
direction (``-P`` normalised for LOCALVIEWER, else (0, 0, 1))::

    rgb = emission_m + ambient_m * ambient_lmodel
        + sum_i atten_i * spot_i * ( ambient_m * ambient_i
                                   + max(N.L_i, 0) * diffuse_m * lcolor_i
                                   + max(N.H_i, 0)**shininess * specular_m * lcolor_i )
    alpha = ALPHA_m

where L_i is the unit vector to light i, H_i = normalize(L_i + V), and the specular
term is zero where N.L_i <= 0 or shininess < 1.  A light has one colour, LCOLOR, for
both diffuse and specular.  atten_i = 1 / (k0 + k1*d + k2*d*d) with d the distance to
a local light (w != 0) and (k0, k1, k2) from the *lighting model* (ATTENUATION,
ATTENUATION2); directional lights (w == 0) are not attenuated.  spot_i is
``max(-L_i.S_i, 0)**exponent`` inside the cone of half-angle ``spread`` degrees around
the unit spot direction S_i, 0 outside it, and 1 when spread >= 180 (no cone).  The
result is clamped to [0, 1].  See shared/reference/irisgl_reference.md section 1.6
(the exact IRIS form is reconstructed from IGL's OpenGL mapping).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import replace
from typing import NamedTuple

import numpy as np

from vgxsim.kernels.lighting import LIGHT_COLUMNS, LMODEL_COLUMNS
from vgxsim.kernels.lighting import light_object_runs as light_object_runs_kernel
from vgxsim.kernels.lighting import light_vertices as light_vertices_kernel
from vgxsim.kernels.transform import transform_points

from .tables import (
    _LMC_AD,
    _LMC_AMBIENT,
    _LMC_COLOR,
    _LMC_DIFFUSE,
    _LMC_EMISSION,
    _LMC_NULL,
    _LMC_SPECULAR,
    Light,
    LightingError,
    LightModel,
    Material,
)

# lmcolor mode -> (material colour fields the current colour replaces, alpha too?)
_LMC_FIELDS: dict[int, tuple[tuple[str, ...], bool]] = {
    _LMC_COLOR: ((), False),
    _LMC_EMISSION: (("emission",), False),
    _LMC_AMBIENT: (("ambient",), False),
    _LMC_DIFFUSE: (("diffuse",), True),
    _LMC_SPECULAR: (("specular",), False),
    _LMC_AD: (("ambient", "diffuse"), True),
    _LMC_NULL: ((), False),
}

# IGL (src/light.c, _igl_setLmMaterial) loads a zero specular colour unless
# SHININESS >= 1.  Without that, shininess 0 would make max(N.H, 0)**0 == 1, a full
# specular highlight over the whole lit side; IRIS treats 0 as "no specular".  We
# follow IGL's threshold exactly (so 0 < shininess < 1 is also off).
_MIN_SHININESS = 1.0

#: Fast-path switch: the lighting equation as one kernel pass over the vertices
#: (kernels/lighting.py) instead of whole-array numpy operations per light.  False:
#: the numpy form (tests/pipeline/test_batched_lighting.py: identical planes).
JIT_LIGHTING = True

_Vec = np.ndarray | Sequence[float] | None
#: One entry of shade()'s ``lights``: (Light, position_eye (4,), spot_direction_eye (3,)).
LightEntry = tuple[Light, _Vec, _Vec]


def _lmc_spec(mode: int) -> tuple[tuple[str, ...], bool]:
    try:
        return _LMC_FIELDS[int(mode)]
    except (KeyError, TypeError, ValueError):
        raise LightingError(f"lmcolor({mode!r}): unknown mode (expected LMC_COLOR 0 .. "
                            "LMC_NULL 6)") from None


def apply_lmcolor(material: Material, mode: int, rgba: Sequence[float]) -> Material:
    """Return ``material`` with the property ``lmcolor(mode)`` ties to the colour replaced.

    Models the IRIS rule that, with ``lmcolor`` other than LMC_COLOR / LMC_NULL,
    colour commands overwrite a property of the bound (front) material in the
    hardware; the stored definition is not changed (a new Material is returned).

    Parameters
    ----------
    material : Material
        The bound material.
    mode : int
        LMC_COLOR 0 and LMC_NULL 6: unchanged.  LMC_EMISSION 1, LMC_AMBIENT 2,
        LMC_SPECULAR 4: that colour.  LMC_DIFFUSE 3: diffuse and ALPHA.
        LMC_AD 5: ambient, diffuse and ALPHA.
    rgba : sequence of 3 or 4 float
        The current colour in [0, 1].  With 3 components ALPHA is left unchanged.

    Returns
    -------
    Material
        The effective material.

    Raises
    ------
    LightingError
        Unknown mode, or ``rgba`` not of length 3 or 4.
    """
    names, takes_alpha = _lmc_spec(mode)
    c = np.asarray(rgba, dtype=np.float64)
    if c.shape not in ((3,), (4,)):
        raise LightingError(f"apply_lmcolor: rgba must have 3 or 4 components, got shape "
                            f"{c.shape}")
    if not names:
        return material
    rgb = (float(c[0]), float(c[1]), float(c[2]))
    updates: dict[str, object] = {name: rgb for name in names}
    if takes_alpha and c.shape[0] == 4:
        updates["alpha"] = float(c[3])
    return replace(material, **updates)


class _MatArrays(NamedTuple):
    """Material terms: colours (3,) or per vertex (N, 3), shininess and alpha
    scalars or (N,), float64."""

    emission: np.ndarray
    ambient: np.ndarray
    diffuse: np.ndarray
    specular: np.ndarray
    shininess: np.ndarray
    alpha: np.ndarray


def _material_arrays(
    material: Material, n: int, override: tuple[int, np.ndarray] | None
) -> _MatArrays:
    """The material's terms for n vertices, with a per-vertex lmcolor override.

    Terms the override leaves alone stay (3,) colours and scalars: numpy broadcasts
    them in the arithmetic, element by element, to the values an (N, 3) copy gives,
    without building the copies (a polygon of four vertices is lit per call).
    """
    cols = {name: np.asarray(getattr(material, name), np.float64)
            for name in ("emission", "ambient", "diffuse", "specular")}
    alpha = np.float64(material.alpha)
    if override is not None:
        mode, c = override
        names, takes_alpha = _lmc_spec(mode)
        for name in names:
            cols[name] = c[:, :3]
        if takes_alpha and c.shape[1] == 4:
            alpha = c[:, 3]
    return _MatArrays(shininess=np.float64(material.shininess), alpha=alpha, **cols)


def _select(back: np.ndarray, a: _MatArrays, b: _MatArrays) -> _MatArrays:
    """Per vertex, b where ``back`` else a (terms broadcast to (N, 3) and (N,))."""
    colour = back[:, None]
    return _MatArrays(*(np.where(colour if name not in ("shininess", "alpha") else back,
                                 fb, fa)
                        for name, fa, fb in zip(_MatArrays._fields, a, b, strict=True)))


def _normalize(v: np.ndarray) -> np.ndarray:
    """Unit vectors along the last axis; zero vectors stay zero."""
    # np.linalg.norm's own arithmetic for real input, without its dispatch.
    length = np.sqrt(np.add.reduce(v * v, axis=-1, keepdims=True))
    return np.divide(v, length, out=np.zeros(v.shape), where=length > 0.0)


def _as_points(a: np.ndarray | Sequence, name: str) -> np.ndarray:
    arr = np.asarray(a, dtype=np.float64)
    if arr.ndim != 2 or arr.shape[1] != 3:
        raise LightingError(f"shade: {name} must have shape (N, 3), got {arr.shape}")
    return arr


def light_to_eye(light: Light, modelview: np.ndarray | Sequence[float]) -> LightEntry:
    """Transform a light's POSITION and SPOTDIRECTION to eye space (at ``lmbind``).

    IRIS GL uses row vectors: ``p_eye = p @ M``.  The position (x, y, z, w) is
    transformed as a homogeneous point; the spot direction as a direction by the
    upper-left 3x3 block (as OpenGL does).

    Parameters
    ----------
    light : Light
        The light definition (positions in the coordinates given to lmdef).
    modelview : array_like, shape (4, 4) or (16,)
        The ModelView matrix, row-major, IRIS row-vector convention (translation in
        row 3).

    Returns
    -------
    tuple
        ``(light, position_eye (4,) float64, spot_direction_eye (3,) float64)``, the
        entry :func:`shade` expects in its ``lights`` list.
    """
    m = np.asarray(modelview, dtype=np.float64).reshape(4, 4)
    pos = np.asarray(light.position, dtype=np.float64) @ m
    spot = np.asarray(light.spot_direction, dtype=np.float64) @ m[:3, :3]
    return light, pos, spot


def shade(
    positions_eye: np.ndarray,
    normals_eye: np.ndarray,
    material: Material,
    lights: Sequence[LightEntry],
    lmodel: LightModel,
    back_material: Material | None = None,
    facing: np.ndarray | None = None,
    color_override: tuple[int, np.ndarray | Sequence[float]] | None = None,
) -> np.ndarray:
    """Light N vertices with the IRIS GL equation (see the module docstring).

    Parameters
    ----------
    positions_eye : ndarray, shape (N, 3), float64
        Eye-space vertex positions (used for local lights and the local viewer).
    normals_eye : ndarray, shape (N, 3), float64
        Eye-space normals; normalised here.  A zero normal gets only the emission
        and ambient terms.
    material : Material
        The bound front MATERIAL.
    lights : sequence of (Light, position_eye, spot_direction_eye)
        Bound lights with POSITION as (4,) and SPOTDIRECTION as (3,) already in eye
        space (see :func:`light_to_eye`).  ``None`` in either slot uses the Light's
        own (untransformed) value.
    lmodel : LightModel
        The bound LMODEL (scene ambient, attenuation, viewer, two-sidedness).
    back_material : Material, optional
        The bound BACKMATERIAL; without it back faces use ``material``.
    facing : ndarray, shape (N,), bool, optional
        **True where the vertex is back-facing.**  Used only when
        ``lmodel.twoside``: those vertices are lit with the negated normal and
        ``back_material`` (if given).  Ignored otherwise (one-sided lighting lights
        back faces with the front normal, as IRIS GL and OpenGL do).  Pass all True
        to get the back colours of every vertex.
    color_override : (int, array_like), optional
        ``(lmcolor mode, rgba)`` with rgba of shape (3,), (4,), (N, 3) or (N, 4)
        in [0, 1]: per-vertex current colours replacing the property the mode
        names (see :func:`apply_lmcolor`; with 3 columns ALPHA is kept).  Applied
        to the front material only (IGL: "lmcolor() doesn't change properties to
        BACKMATERIAL"); it reaches back faces only when no ``back_material`` is
        given.

    Returns
    -------
    ndarray, shape (N, 4), float64
        RGBA, clamped to [0, 1].

    Raises
    ------
    LightingError
        Bad array shapes or an unknown lmcolor mode.
    """
    p = _as_points(positions_eye, "positions_eye")
    n_vert = p.shape[0]
    nrm = _normalize(_as_points(normals_eye, "normals_eye"))
    if nrm.shape[0] != n_vert:
        raise LightingError(f"shade: {n_vert} positions but {nrm.shape[0]} normals")

    override = None
    if color_override is not None:
        mode, rgba = color_override
        c = np.asarray(rgba, dtype=np.float64)
        if c.ndim == 1:
            c = np.broadcast_to(c, (n_vert, c.shape[0]))
        if c.ndim != 2 or c.shape[0] != n_vert or c.shape[1] not in (3, 4):
            raise LightingError(f"shade: color_override colours must have shape (3,), (4,), "
                                f"({n_vert}, 3) or ({n_vert}, 4), got {np.shape(rgba)}")
        override = (mode, c)
    mat = _material_arrays(material, n_vert, override)

    if lmodel.twoside and facing is not None:
        back = np.asarray(facing, dtype=bool)
        if back.shape != (n_vert,):
            raise LightingError(f"shade: facing must have shape ({n_vert},), got {back.shape}")
        nrm = np.where(back[:, None], -nrm, nrm)
        if back_material is not None and back.any():
            mat = _select(back, mat, _material_arrays(back_material, n_vert, None))

    return _light_vertices(p, nrm, mat, lights, lmodel)


def shade_runs(
    positions_eye: np.ndarray,
    normals_eye: np.ndarray,
    materials: Sequence[Material],
    counts: Sequence[int],
    lights: Sequence[LightEntry],
    lmodel: LightModel,
) -> np.ndarray:
    """:func:`shade` for consecutive runs of vertices, each with its own front
    material, under the same lights and one-sided lighting model, in one pass.

    The colours are those :func:`shade` gives each run on its own (the equation is
    evaluated vertex by vertex; only the material terms become per-vertex arrays).

    Parameters
    ----------
    positions_eye, normals_eye : ndarray, shape (N, 3), float64
    materials : sequence of Material
        One per run.
    counts : sequence of int
        Vertices in each run (summing to N).
    lights, lmodel
        As for :func:`shade`; ``lmodel.twoside`` must be off.

    Returns
    -------
    ndarray, shape (N, 4), float64
    """
    p = _as_points(positions_eye, "positions_eye")
    nrm = _normalize(_as_points(normals_eye, "normals_eye"))
    if lmodel.twoside:
        raise LightingError("shade_runs: two-sided lighting is lit per run (shade)")
    reps = np.asarray(counts, dtype=np.int64)
    if reps.shape != (len(materials),) or (int(reps.sum()) != p.shape[0]
                                                  or nrm.shape[0] != p.shape[0]):
        raise LightingError(f"shade_runs: {len(materials)} materials, counts {reps.tolist()} "
                            f"for {p.shape[0]} positions and {nrm.shape[0]} normals")
    terms = {name: np.repeat(np.array([getattr(m, name) for m in materials], np.float64),
                             reps, axis=0)
             for name in _MatArrays._fields}
    return _light_vertices(p, nrm, _MatArrays(**terms), lights, lmodel)


def shade_object_runs(
    obj: np.ndarray,
    normals: np.ndarray,
    colours: np.ndarray,
    lit: np.ndarray,
    counts: Sequence[int],
    modelviews: Sequence[np.ndarray],
    normal_matrices: Sequence[np.ndarray],
    materials: Sequence[Material],
    lights: Sequence[LightEntry],
    lmodel: LightModel,
) -> np.ndarray:
    """Vertex colours of runs of object-space vertices, each run with its own
    modelview, normal matrix and material, under the same lights: the lit vertices
    taken to eye space (``p @ M`` in transform.apply's order, divided by w unless it
    is 0) and lit by :func:`shade_runs`, the others keeping their colour.

    Parameters
    ----------
    obj : ndarray, shape (N, 4), float64
    normals : ndarray, shape (N, 3), float64
        Object-space normals.
    colours : ndarray, shape (N, 4), float64
    lit : ndarray, shape (N,), bool
    counts : sequence of int
        Vertices in each run (summing to N).
    modelviews : sequence of ndarray, shape (4, 4); normal_matrices : of shape (3, 3)
    materials : sequence of Material
    lights, lmodel
        As for :func:`shade_runs` (one-sided lighting).

    Returns
    -------
    ndarray, shape (N, 4), float64
    """
    if lmodel.twoside:
        raise LightingError("shade_object_runs: two-sided lighting is lit per run (shade)")
    reps = np.asarray(counts, dtype=np.int64)
    terms = {name: np.array([getattr(m, name) for m in materials], np.float64)
             for name in _MatArrays._fields}  # one row per run
    if JIT_LIGHTING:
        return light_object_runs_kernel(
            np.ascontiguousarray(obj, np.float64), np.ascontiguousarray(normals, np.float64),
            np.ascontiguousarray(colours, np.float64), np.ascontiguousarray(lit, np.bool_),
            np.repeat(np.arange(reps.shape[0], dtype=np.int64), reps),
            np.ascontiguousarray(modelviews, np.float64),
            np.ascontiguousarray(normal_matrices, np.float64), terms["emission"],
            terms["ambient"], terms["diffuse"], terms["specular"], terms["shininess"],
            terms["alpha"], _light_table(lights), _lmodel_row(lmodel), _MIN_SHININESS)
    out = np.array(colours, dtype=np.float64)
    lit = np.asarray(lit, bool)
    if not lit.any():
        return out
    eye_p, eye_n, lit_mats = [], [], {name: [] for name in _MatArrays._fields}
    at = 0
    for k, c in enumerate(reps.tolist()):
        sel = lit[at:at + c]
        eye = transform_points(np.ascontiguousarray(obj[at:at + c][sel], np.float64),
                               np.ascontiguousarray(modelviews[k], np.float64))
        eye_p.append(eye[:, :3] / np.where(eye[:, 3:4] == 0, 1.0, eye[:, 3:4]))
        eye_n.append(transform_points(np.ascontiguousarray(normals[at:at + c][sel],
                                                           np.float64),
                                      np.ascontiguousarray(normal_matrices[k], np.float64)))
        for name in _MatArrays._fields:
            lit_mats[name].append(np.repeat(terms[name][k:k + 1], int(sel.sum()), axis=0))
        at += c
    mat = _MatArrays(**{name: np.concatenate(v) for name, v in lit_mats.items()})
    out[lit] = _light_vertices_numpy(np.concatenate(eye_p), _normalize(np.concatenate(eye_n)),
                                     mat, lights, lmodel)
    return out


def _lmodel_row(lmodel: LightModel) -> np.ndarray:
    """The kernel's light-model row (kernels/lighting.py LMODEL_COLUMNS)."""
    lm = np.zeros(LMODEL_COLUMNS)
    lm[0:3] = np.asarray(lmodel.ambient, dtype=np.float64)
    lm[3] = 1.0 if lmodel.local_viewer else 0.0
    lm[4], lm[5] = lmodel.attenuation
    lm[6] = lmodel.attenuation2
    return lm


def _light_vertices(p: np.ndarray, nrm: np.ndarray, mat: _MatArrays,
                    lights: Sequence[LightEntry], lmodel: LightModel) -> np.ndarray:
    """The lighting equation for (N, 3) eye positions and unit normals."""
    if JIT_LIGHTING:
        return _light_vertices_jit(p, nrm, mat, lights, lmodel)
    return _light_vertices_numpy(p, nrm, mat, lights, lmodel)


def _per_vertex(term, n: int, width: int) -> np.ndarray:
    """A material term, (3,) or scalar for all vertices or one per vertex, as a
    C-contiguous (n, 3) or (n,) float64 array."""
    shape = (n, width) if width else (n,)
    return np.ascontiguousarray(np.broadcast_to(np.asarray(term, np.float64), shape))


def _light_table(lights: Sequence[LightEntry]) -> np.ndarray:
    """The kernel's light rows (kernels/lighting.py), derived as the numpy form
    derives them: the same position, direction and spot-axis arithmetic."""
    table = np.zeros((len(lights), LIGHT_COLUMNS))
    for k, (light, pos_eye, spot_eye) in enumerate(lights):
        pos = np.asarray(light.position if pos_eye is None else pos_eye, dtype=np.float64)
        if pos.shape != (4,):
            raise LightingError(f"shade: light position must have shape (4,), got {pos.shape}")
        row = table[k]
        if pos[3] != 0.0:
            row[0] = 1.0
            row[1:4] = pos[:3] / pos[3]
        else:
            row[1:4] = _normalize(pos[:3])
        row[4:7] = np.asarray(light.lcolor, dtype=np.float64)
        row[7:10] = np.asarray(light.ambient, dtype=np.float64)
        if light.spot_spread < 180.0:
            sdir = np.asarray(light.spot_direction if spot_eye is None else spot_eye,
                              dtype=np.float64)
            row[10] = 1.0
            row[11:14] = _normalize(sdir.reshape(3))
            row[14] = np.cos(np.radians(light.spot_spread))
            row[15] = light.spot_exponent
    return table


def _light_vertices_jit(p: np.ndarray, nrm: np.ndarray, mat: _MatArrays,
                        lights: Sequence[LightEntry], lmodel: LightModel) -> np.ndarray:
    """:func:`_light_vertices_numpy` as one kernel pass (kernels/lighting.py)."""
    n = p.shape[0]
    return light_vertices_kernel(
        np.ascontiguousarray(p, np.float64), np.ascontiguousarray(nrm, np.float64),
        _per_vertex(mat.emission, n, 3), _per_vertex(mat.ambient, n, 3),
        _per_vertex(mat.diffuse, n, 3), _per_vertex(mat.specular, n, 3),
        _per_vertex(mat.shininess, n, 0), _per_vertex(mat.alpha, n, 0),
        _light_table(lights), _lmodel_row(lmodel), _MIN_SHININESS)


def _light_vertices_numpy(p: np.ndarray, nrm: np.ndarray, mat: _MatArrays,
                          lights: Sequence[LightEntry], lmodel: LightModel) -> np.ndarray:
    """The lighting equation as whole-array numpy operations (the reference form of
    the kernel, and what :data:`JIT_LIGHTING` off runs)."""
    n_vert = p.shape[0]
    rgb = mat.emission + mat.ambient * np.asarray(lmodel.ambient, dtype=np.float64)

    if lmodel.local_viewer:
        view = _normalize(-p)
    else:
        view = np.broadcast_to(np.array([0.0, 0.0, 1.0]), (n_vert, 3))
    k0, k1 = lmodel.attenuation
    k2 = lmodel.attenuation2
    spec_on = mat.shininess >= _MIN_SHININESS

    for light, pos_eye, spot_eye in lights:
        pos = np.asarray(light.position if pos_eye is None else pos_eye, dtype=np.float64)
        if pos.shape != (4,):
            raise LightingError(f"shade: light position must have shape (4,), got {pos.shape}")
        lcolor = np.asarray(light.lcolor, dtype=np.float64)

        if pos[3] != 0.0:  # local light: direction and attenuation per vertex
            to_light = pos[:3] / pos[3] - p
            dist = np.linalg.norm(to_light, axis=1)
            ldir = _normalize(to_light)
            denom = k0 + k1 * dist + k2 * dist * dist
            # A non-positive denominator (all k zero, or a vertex on the light with
            # k0 == 0) contributes nothing rather than inf/NaN.
            factor = np.divide(1.0, denom, out=np.zeros(n_vert), where=denom > 0.0)
        else:  # directional light: from (x, y, z) towards the origin, no attenuation
            ldir = np.broadcast_to(_normalize(pos[:3]), (n_vert, 3))
            factor = np.ones(n_vert)

        if light.spot_spread < 180.0:
            sdir = np.asarray(light.spot_direction if spot_eye is None else spot_eye,
                              dtype=np.float64)
            axis = _normalize(sdir.reshape(3))
            cos_a = -(ldir @ axis)  # cosine of the angle between light->vertex and axis
            inside = cos_a >= np.cos(np.radians(light.spot_spread))
            spot = np.where(inside, np.maximum(cos_a, 0.0) ** light.spot_exponent, 0.0)
            factor = factor * spot

        n_dot_l = np.einsum("ij,ij->i", nrm, ldir)
        diffuse = np.maximum(n_dot_l, 0.0)
        half = _normalize(ldir + view)
        n_dot_h = np.maximum(np.einsum("ij,ij->i", nrm, half), 0.0)
        use_spec = spec_on & (n_dot_l > 0.0)
        specular = np.where(use_spec, n_dot_h ** np.where(use_spec, mat.shininess, 1.0), 0.0)

        term = (mat.ambient * np.asarray(light.ambient, dtype=np.float64)
                + diffuse[:, None] * mat.diffuse * lcolor
                + specular[:, None] * mat.specular * lcolor)
        rgb = rgb + factor[:, None] * term

    out = np.empty((n_vert, 4), dtype=np.float64)
    out[:, :3] = rgb
    out[:, 3] = mat.alpha
    return np.clip(out, 0.0, 1.0, out=out)
