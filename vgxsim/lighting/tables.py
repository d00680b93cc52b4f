"""IRIS GL lighting definitions: the ``lmdef`` tables of materials, lights and models.

IRIS GL keeps three independent tables, one per definition type (``DEFMATERIAL``,
``DEFLIGHT``, ``DEFLMODEL``), each mapping a positive index to a definition.  Index 0
is the null definition: it cannot be defined, and ``lmbind(target, 0)`` unbinds.
``lmdef`` on an index that is already defined changes only the properties it lists;
on a new index it starts from the defaults below.

Defaults are those IGL installs (``src/light.c`` ``_igl_setLmDefaults``); Alice 4's
libgl uses the same numbers.  See shared/reference/irisgl_reference.md section 1.6.

The definitions are frozen dataclasses, so a stored definition never changes behind
a caller's back: ``lmdef`` replaces the table entry with a new object, and ``lmcolor``
overrides (see :func:`vgxsim.lighting.equation.apply_lmcolor`) build a new one too.
"""

from __future__ import annotations

import math
import operator
from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace
from typing import Any

# --- Token values, private to this package -------------------------------------------
# From <gl/gl.h> (Python 2's Lib/plat-irix5/GL.py transcription; identical in IGL's
# include/igl.h).  Defined here so vgxsim.lighting depends on nothing else in vgxsim.
_DEFMATERIAL, _DEFLIGHT, _DEFLMODEL = 0, 100, 200
_LMNULL = 0
_EMISSION, _AMBIENT, _DIFFUSE, _SPECULAR, _SHININESS, _COLORINDEXES, _ALPHA = 1, 2, 3, 4, 5, 6, 7
_LCOLOR, _POSITION, _SPOTDIRECTION, _SPOTLIGHT = 101, 102, 103, 104
_LOCALVIEWER, _ATTENUATION, _ATTENUATION2, _TWOSIDE = 201, 202, 203, 204
_LMC_COLOR, _LMC_EMISSION, _LMC_AMBIENT, _LMC_DIFFUSE = 0, 1, 2, 3
_LMC_SPECULAR, _LMC_AD, _LMC_NULL = 4, 5, 6
_MAXLIGHTS = 8
# --------------------------------------------------------------------------------------

_SHORT_MAX = 32767  # lmdef's index argument is a C short

Vec3 = tuple[float, float, float]
Vec4 = tuple[float, float, float, float]


class LightingError(ValueError):
    """An invalid lighting definition or lighting call (bad token, count or index)."""


@dataclass(frozen=True)
class Material:
    """A ``DEFMATERIAL`` definition (RGB values in [0, 1] by convention, not enforced).

    Attributes
    ----------
    emission, ambient, diffuse, specular : tuple of 3 float
        EMISSION, AMBIENT, DIFFUSE and SPECULAR reflectances (r, g, b).
    shininess : float
        SHININESS, the specular exponent (IRIS range 0..128).  Below 1 the specular
        term is off (see :func:`vgxsim.lighting.equation.shade`).
    colorindexes : tuple of 3 float
        COLORINDEXES (ambient, diffuse, specular colour-map indices); colour-map mode
        only, stored but unused by the RGB equation.  Default from IGL.
    alpha : float
        ALPHA, the alpha of every lit vertex (the diffuse alpha).
    """

    emission: Vec3 = (0.0, 0.0, 0.0)
    ambient: Vec3 = (0.2, 0.2, 0.2)
    diffuse: Vec3 = (0.8, 0.8, 0.8)
    specular: Vec3 = (0.0, 0.0, 0.0)
    shininess: float = 0.0
    colorindexes: Vec3 = (0.0, 127.5, 255.0)
    alpha: float = 1.0


@dataclass(frozen=True)
class Light:
    """A ``DEFLIGHT`` definition, in the coordinates given to ``lmdef``.

    Attributes
    ----------
    ambient : tuple of 3 float
        AMBIENT, the light's own ambient colour (default black).
    lcolor : tuple of 3 float
        LCOLOR, the one colour used for both the diffuse and the specular term.
    position : tuple of 4 float
        POSITION (x, y, z, w); w == 0 is a directional light shining from (x, y, z)
        towards the origin, w != 0 a local light at (x/w, y/w, z/w).  Object
        coordinates: the modelview current at ``lmbind`` takes it to eye space.
    spot_direction : tuple of 3 float
        SPOTDIRECTION, the cone axis (need not be unit length).
    spot_exponent, spot_spread : float
        SPOTLIGHT (exponent, spread half-angle in degrees); spread >= 180 means no cone.
    """

    ambient: Vec3 = (0.0, 0.0, 0.0)
    lcolor: Vec3 = (1.0, 1.0, 1.0)
    position: Vec4 = (0.0, 0.0, 1.0, 0.0)
    spot_direction: Vec3 = (0.0, 0.0, -1.0)
    spot_exponent: float = 0.0
    spot_spread: float = 180.0

    @property
    def is_local(self) -> bool:
        """True for a local (positional) light, ``position[3] != 0``."""
        return self.position[3] != 0.0


@dataclass(frozen=True)
class LightModel:
    """A ``DEFLMODEL`` definition.

    Attributes
    ----------
    ambient : tuple of 3 float
        AMBIENT, the scene ambient colour multiplied by every material's ambient.
    local_viewer : bool
        LOCALVIEWER; False puts the viewer at infinity along +z of eye space.
    attenuation : tuple of 2 float
        ATTENUATION (k0, k1), constant and linear factors for all local lights.
    attenuation2 : float
        ATTENUATION2 (k2), the quadratic factor for all local lights.
    twoside : bool
        TWOSIDE; back faces are lit with the flipped normal and BACKMATERIAL.
    """

    ambient: Vec3 = (0.2, 0.2, 0.2)
    local_viewer: bool = False
    attenuation: tuple[float, float] = (1.0, 0.0)
    attenuation2: float = 0.0
    twoside: bool = False


Definition = Material | Light | LightModel


# Each property: token -> (name, number of values, values -> dataclass field updates).
_Setter = Callable[[tuple[float, ...]], dict[str, Any]]


def _field(name: str) -> _Setter:
    return lambda v: {name: v}


def _scalar(name: str) -> _Setter:
    return lambda v: {name: v[0]}


def _flag(name: str) -> _Setter:
    return lambda v: {name: v[0] != 0.0}


_MATERIAL_PROPS: dict[int, tuple[str, int, _Setter]] = {
    _EMISSION: ("EMISSION", 3, _field("emission")),
    _AMBIENT: ("AMBIENT", 3, _field("ambient")),
    _DIFFUSE: ("DIFFUSE", 3, _field("diffuse")),
    _SPECULAR: ("SPECULAR", 3, _field("specular")),
    _SHININESS: ("SHININESS", 1, _scalar("shininess")),
    _COLORINDEXES: ("COLORINDEXES", 3, _field("colorindexes")),
    _ALPHA: ("ALPHA", 1, _scalar("alpha")),
}
_LIGHT_PROPS: dict[int, tuple[str, int, _Setter]] = {
    _AMBIENT: ("AMBIENT", 3, _field("ambient")),
    _LCOLOR: ("LCOLOR", 3, _field("lcolor")),
    _POSITION: ("POSITION", 4, _field("position")),
    _SPOTDIRECTION: ("SPOTDIRECTION", 3, _field("spot_direction")),
    _SPOTLIGHT: ("SPOTLIGHT", 2, lambda v: {"spot_exponent": v[0], "spot_spread": v[1]}),
}
_LMODEL_PROPS: dict[int, tuple[str, int, _Setter]] = {
    _AMBIENT: ("AMBIENT", 3, _field("ambient")),
    _LOCALVIEWER: ("LOCALVIEWER", 1, _flag("local_viewer")),
    _ATTENUATION: ("ATTENUATION", 2, _field("attenuation")),
    _ATTENUATION2: ("ATTENUATION2", 1, _scalar("attenuation2")),
    _TWOSIDE: ("TWOSIDE", 1, _flag("twoside")),
}

# deftype -> (name, property table, definition class)
_DEFTYPES: dict[int, tuple[str, dict[int, tuple[str, int, _Setter]], type]] = {
    _DEFMATERIAL: ("DEFMATERIAL", _MATERIAL_PROPS, Material),
    _DEFLIGHT: ("DEFLIGHT", _LIGHT_PROPS, Light),
    _DEFLMODEL: ("DEFLMODEL", _LMODEL_PROPS, LightModel),
}
_ALL_PROP_NAMES: dict[int, str] = {
    tok: spec[0] for table in (_MATERIAL_PROPS, _LIGHT_PROPS, _LMODEL_PROPS)
    for tok, spec in table.items()
}


def _fmt_num(x: float) -> str:
    """Format a token-like float: ``99`` for 99.0, ``0.5`` for 0.5."""
    return str(int(x)) if math.isfinite(x) and x == int(x) else repr(x)


def _check_index(call: str, index: Any) -> int:
    try:
        idx = operator.index(index)
    except TypeError:
        if isinstance(index, float) and index.is_integer():
            idx = int(index)
        else:
            raise LightingError(f"{call}: index must be an integer, got {index!r}") from None
    if idx == 0:
        raise LightingError(f"{call}: index 0 is reserved for the null definition")
    if not 1 <= idx <= _SHORT_MAX:
        raise LightingError(f"{call}: index {idx} outside 1..{_SHORT_MAX}")
    return idx


def _parse_props(
    call: str, deftype_name: str, table: dict[int, tuple[str, int, _Setter]], props: Any
) -> dict[str, Any]:
    """Parse a flat lmdef property list into dataclass field updates (validated)."""
    try:
        values = [float(x) for x in props]
    except (TypeError, ValueError):
        raise LightingError(f"{call}: props must be a flat sequence of numbers") from None
    updates: dict[str, Any] = {}
    i, n = 0, len(values)
    previous: tuple[str, int] | None = None
    while i < n:
        tok = values[i]
        if tok == _LMNULL:
            if i != n - 1:
                raise LightingError(
                    f"{call}: LMNULL inside props at position {i}, "
                    f"followed by {n - 1 - i} more value(s); LMNULL must be last"
                )
            break
        itok = int(tok) if math.isfinite(tok) and tok == int(tok) else None
        if itok is None or itok not in table:
            if itok is not None and itok in _ALL_PROP_NAMES:
                valid = ", ".join(spec[0] for spec in table.values())
                raise LightingError(
                    f"{call}: property {_ALL_PROP_NAMES[itok]} ({itok}) at position {i} "
                    f"is not valid for {deftype_name} (valid: {valid})"
                )
            hint = ""
            if itok is None and previous is not None:  # a value where a token belongs
                hint = (f" (the {previous[0]} before it takes {previous[1]} value(s): "
                        "wrong number of values?)")
            raise LightingError(
                f"{call}: unknown property token {_fmt_num(tok)} at position {i}{hint}"
            )
        name, count, setter = table[itok]
        vals = values[i + 1 : i + 1 + count]
        if len(vals) != count:
            raise LightingError(
                f"{call}: wrong number of values for {name} at position {i}: "
                f"needs {count}, props has {len(vals)} left"
            )
        for k, v in enumerate(vals):
            if not math.isfinite(v):
                raise LightingError(
                    f"{call}: non-finite value {v!r} for {name} at position {i + 1 + k}"
                )
        updates.update(setter(tuple(vals)))
        previous = (name, count)
        i += 1 + count
    return updates


class LightingTables:
    """The three IRIS GL lighting tables: index -> definition for each deftype.

    Examples
    --------
    >>> t = LightingTables()
    >>> m = t.lmdef(0, 1, [3, 0.8, 0.2, 0.2, 5, 30.0, 0])  # DIFFUSE, SHININESS, LMNULL
    >>> m.diffuse, m.shininess, m.ambient
    ((0.8, 0.2, 0.2), 30.0, (0.2, 0.2, 0.2))
    """

    def __init__(self) -> None:
        self._tables: dict[int, dict[int, Definition]] = {d: {} for d in _DEFTYPES}
        #: Incremented by every successful lmdef; callers may cache on it.
        self.generation = 0

    def lmdef(self, deftype: int, index: int, props: Sequence[float] = ()) -> Definition:
        """Define or modify ``index`` of the ``deftype`` table (IRIS ``lmdef``).

        Parameters
        ----------
        deftype : int
            DEFMATERIAL (0), DEFLIGHT (100) or DEFLMODEL (200).
        index : int
            1..32767; 0 is the reserved null definition.
        props : sequence of float
            Flat ``token, values..., token, values..., [LMNULL]``; the count (IRIS
            ``np``) is ``len(props)``.  Empty: define with defaults (or leave an
            existing definition as it is).

        Returns
        -------
        Material or Light or LightModel
            The new stored definition.

        Raises
        ------
        LightingError
            Unknown deftype, reserved or out-of-range index, unknown token, a token
            of another deftype, a wrong number of values, LMNULL before the end, or
            a non-finite value.  The table is unchanged on error.
        """
        try:
            dname, table, cls = _DEFTYPES[operator.index(deftype)]
        except (TypeError, KeyError):
            raise LightingError(
                f"lmdef({deftype!r}, {index!r}, ...): unknown deftype {deftype!r} "
                "(expected DEFMATERIAL 0, DEFLIGHT 100 or DEFLMODEL 200)"
            ) from None
        call = f"lmdef({dname}, {index!r}, ...)"
        idx = _check_index(call, index)
        updates = _parse_props(call, dname, table, props)
        entries = self._tables[operator.index(deftype)]
        new = replace(entries.get(idx, cls()), **updates)
        entries[idx] = new
        self.generation += 1
        return new

    def get(self, deftype: int, index: int) -> Definition | None:
        """Return the definition at ``index``, or None for 0 and undefined indices."""
        try:
            entries = self._tables[operator.index(deftype)]
        except (TypeError, KeyError):
            raise LightingError(f"unknown deftype {deftype!r}") from None
        try:
            return entries.get(operator.index(index))
        except TypeError:
            raise LightingError(f"index must be an integer, got {index!r}") from None

    def material(self, index: int) -> Material | None:
        """``get(DEFMATERIAL, index)``."""
        return self.get(_DEFMATERIAL, index)  # type: ignore[return-value]

    def light(self, index: int) -> Light | None:
        """``get(DEFLIGHT, index)``."""
        return self.get(_DEFLIGHT, index)  # type: ignore[return-value]

    def lmodel(self, index: int) -> LightModel | None:
        """``get(DEFLMODEL, index)``."""
        return self.get(_DEFLMODEL, index)  # type: ignore[return-value]

    def is_defined(self, deftype: int, index: int) -> bool:
        """True if ``index`` has been defined in the ``deftype`` table."""
        entries = self._tables.get(deftype)
        if entries is not None and type(index) is int:  # lmbind's common case, directly
            return entries.get(index) is not None
        return self.get(deftype, index) is not None

    def indices(self, deftype: int) -> list[int]:
        """Sorted defined indices of the ``deftype`` table."""
        self.get(deftype, 1)  # validates deftype
        return sorted(self._tables[operator.index(deftype)])
