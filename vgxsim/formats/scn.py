"""``.scn`` scene descriptions of the ``shadows`` program (README, "File Formats").

The grammar, as the README gives it (keywords in any letter case; blank lines are
ignored and newlines are blank space; ``#`` to the end of a line is a comment, an
addition of this reader)::

    scene    := "ShadowScene" { command } [ "END" ]      END or end of file finishes
    command  := "WINDOW" near far height      clipping planes, frustum height at near
              | "LOOKAT" ex ey ez tx ty tz    look-from and look-to points
              | ("MODEL" | "XMODEL") file     a new object (.glo, .glo.gz or cache .npz);
                                              XMODEL casts no shadow
              | "POSITION" x y z | "ROTATE" x y z | "SCALE" x y z
              | "TEXTURE" file                SGI image; only after MODEL/XMODEL
              | "MATERIAL" { mprop } "END"    only after MODEL/XMODEL
              | "LIGHT" { lprop } "END"       a new light
    mprop    := ("SPECULAR" | "DIFFUSE" | "EMISSION" | "AMBIENT") r g b
              | "SHININESS" s
    lprop    := ("AMBIENT" | "LCOLOR") r g b | "POSITION" x y z [w]
              | "SPOTDIRECTION" x y z | "SPOTLIGHT" exponent spread
              | "JITTER" size | "JITTER" sx sy sz

README semantics kept: POSITION, ROTATE and SCALE "may appear in any order, but only
the last one of each takes effect, and the transformations are always done in the
order Scale, Rotate, Position, with Rotation done in the order z, y, x";
"Transformation commands which appear before any MODEL command are global scene
transformations, done after individual object transformations".  Without MATERIAL
an object gets "a default diffuse gray"; without LIGHT "a red one and a blue one
are created" (those of :func:`vgxsim.shadow.scene.default_scene`); the light model
is the README's ``theLModel``.  Without WINDOW or LOOKAT the default scene's camera
is used.  File names are relative to the scene file.

Choices where the README is silent: a light's POSITION w must be 1 (shadow volumes
are projected from a point); a SCALE that mirrors (negative determinant) is refused,
since it would turn the model's polygons inside out.  Every error is a
:class:`~vgxsim.formats.errors.FormatError` naming the scene file, the line and what
was expected; nothing is drawn or written before the whole scene has loaded.
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass, field, replace

import numpy as np

from vgxsim.shadow.scene import (
    LightModel,
    PointLight,
    Polyhedron,
    Scene,
    SurfaceMaterial,
    default_scene,
    newell_normals,
    object_transform,
)

from .errors import FormatError

HEADER = "shadowscene"
_TRANSFORMS = ("position", "rotate", "scale")
_MPROPS = {"specular": 3, "diffuse": 3, "emission": 3, "ambient": 3, "shininess": 1}
_LPROPS = {"ambient": (3,), "lcolor": (3,), "position": (3, 4), "spotdirection": (3,),
           "spotlight": (2,), "jitter": (1, 3)}


@dataclass
class ModelSpec:
    """One MODEL/XMODEL entry as read (before its geometry is loaded)."""

    path: str
    line: int
    casts: bool
    transform: dict[str, tuple[float, ...]] = field(default_factory=dict)
    texture: str | None = None
    material: SurfaceMaterial | None = None


@dataclass
class SceneSpec:
    """A parsed ``.scn`` file: what it says, before models are loaded."""

    path: str
    window: tuple[float, float, float] | None = None
    lookat: tuple[float, ...] | None = None
    global_transform: dict[str, tuple[float, ...]] = field(default_factory=dict)
    models: list[ModelSpec] = field(default_factory=list)
    lights: list[PointLight] = field(default_factory=list)


def _tokens(path: str, text: str) -> list[tuple[str, int]]:
    out = []
    for lineno, line in enumerate(text.splitlines(), 1):
        out.extend((tok, lineno) for tok in line.split("#", 1)[0].split())
    return out


class _Reader:
    def __init__(self, path: str, toks: list[tuple[str, int]]):
        self.path, self.toks, self.i = path, toks, 0

    def error(self, line: int | None, reason: str) -> FormatError:
        return FormatError(self.path, line, reason)

    @property
    def line(self) -> int | None:
        if self.i < len(self.toks):
            return self.toks[self.i][1]
        return self.toks[-1][1] if self.toks else None

    def next(self, what: str) -> tuple[str, int]:
        if self.i >= len(self.toks):
            raise self.error(self.line, f"unexpected end of file, expected {what}")
        tok = self.toks[self.i]
        self.i += 1
        return tok

    def is_number(self) -> bool:
        if self.i >= len(self.toks):
            return False
        try:
            float(self.toks[self.i][0])
        except ValueError:
            return False
        return True

    def numbers(self, keyword: str, counts: tuple[int, ...], line: int) -> tuple[float, ...]:
        vals = []
        while self.is_number() and len(vals) < max(counts):
            vals.append(float(self.toks[self.i][0]))
            self.i += 1
        if len(vals) not in counts:
            found = self.toks[self.i][0] if self.i < len(self.toks) else "end of file"
            want = " or ".join(str(c) for c in counts)
            raise self.error(self.line if self.i < len(self.toks) else line,
                             f"{keyword.upper()} expects {want} numbers, found {len(vals)} "
                             f"then {found!r}")
        if not all(math.isfinite(v) for v in vals):
            raise self.error(line, f"{keyword.upper()}: numbers must be finite")
        return tuple(vals)

    def filename(self, keyword: str) -> tuple[str, int]:
        tok, line = self.next(f"a file name after {keyword.upper()}")
        return os.path.join(os.path.dirname(os.path.abspath(self.path)), tok), line


def parse_scn(path: str | os.PathLike, text: str | None = None) -> SceneSpec:
    """Parse a ``.scn`` file (the grammar in the module docstring).

    Parameters
    ----------
    path : str or PathLike
        The scene file; relative file names in it resolve against its folder.
    text : str, optional
        The file's content (default: read ``path``).

    Returns
    -------
    SceneSpec

    Raises
    ------
    FormatError
    """
    path = os.fspath(path)
    if text is None:
        try:
            with open(path, encoding="utf-8") as fh:
                text = fh.read()
        except FileNotFoundError:
            raise FormatError(path, None, "no such scene file") from None
        except (OSError, UnicodeDecodeError) as exc:
            raise FormatError(path, None, f"cannot read the scene file ({exc})") from None
    r = _Reader(path, _tokens(path, text))
    spec = SceneSpec(path)
    tok, line = r.next("the header 'ShadowScene'")
    if tok.lower() != HEADER:
        raise r.error(line, f"the first word must be 'ShadowScene', found {tok!r}")
    current: ModelSpec | None = None
    while r.i < len(r.toks):
        tok, line = r.next("a command")
        key = tok.lower()
        if key == "end":
            break
        if key == "window":
            near, far, height = r.numbers(key, (3,), line)
            if not 0 < near < far or height <= 0:
                raise r.error(line, f"WINDOW expects 0 < near < far and height > 0, found "
                              f"{near:g} {far:g} {height:g}")
            spec.window = (near, far, height)
        elif key == "lookat":
            spec.lookat = r.numbers(key, (6,), line)
            if np.allclose(spec.lookat[:3], spec.lookat[3:]):
                raise r.error(line, "LOOKAT: the look-from and look-to points coincide")
        elif key in ("model", "xmodel"):
            fname, fline = r.filename(key)
            current = ModelSpec(fname, fline, casts=(key == "model"))
            spec.models.append(current)
        elif key in _TRANSFORMS:
            vals = r.numbers(key, (3,), line)
            target = current.transform if current is not None else spec.global_transform
            target[key] = vals
        elif key == "texture":
            if current is None:
                raise r.error(line, "TEXTURE before any MODEL or XMODEL (expected a MODEL "
                              "or XMODEL command first)")
            fname, fline = r.filename(key)
            if not os.path.isfile(fname):
                raise r.error(fline, f"TEXTURE: no such file {fname!r}")
            from .sgi import read_rgb

            try:
                read_rgb(fname)
            except FormatError as exc:
                raise r.error(fline, f"TEXTURE: {exc}") from None
            current.texture = fname
        elif key == "material":
            if current is None:
                raise r.error(line, "MATERIAL before any MODEL or XMODEL (expected a MODEL "
                              "or XMODEL command first)")
            current.material = _material(r, line)
        elif key == "light":
            spec.lights.append(_light(r, line, len(spec.lights)))
        else:
            raise r.error(line, f"unknown command {tok!r} (expected WINDOW, LOOKAT, MODEL, "
                          "XMODEL, POSITION, ROTATE, SCALE, TEXTURE, MATERIAL, LIGHT or END)")
    return spec


def _material(r: _Reader, start: int) -> SurfaceMaterial:
    props: dict[str, tuple[float, ...]] = {}
    while True:
        tok, line = r.next(f"a material property or END (MATERIAL of line {start})")
        key = tok.lower()
        if key == "end":
            break
        if key not in _MPROPS:
            raise r.error(line, f"unknown material property {tok!r} (expected SPECULAR, "
                          "SHININESS, DIFFUSE, EMISSION, AMBIENT or END)")
        props[key] = r.numbers(key, (_MPROPS[key],), line)
        if key == "shininess" and not 0 <= props[key][0] <= 128:
            raise r.error(line, f"SHININESS must be in 0..128, found {props[key][0]:g}")
    base = SurfaceMaterial()
    return SurfaceMaterial(
        emission=props.get("emission", base.emission), ambient=props.get("ambient", base.ambient),
        diffuse=props.get("diffuse", base.diffuse), specular=props.get("specular", base.specular),
        shininess=props.get("shininess", (base.shininess,))[0])


def _light(r: _Reader, start: int, index: int) -> PointLight:
    props: dict[str, tuple[float, ...]] = {}
    while True:
        tok, line = r.next(f"a light property or END (LIGHT of line {start})")
        key = tok.lower()
        if key == "end":
            break
        if key not in _LPROPS:
            raise r.error(line, f"unknown light property {tok!r} (expected AMBIENT, LCOLOR, "
                          "POSITION, SPOTDIRECTION, SPOTLIGHT, JITTER or END)")
        props[key] = r.numbers(key, _LPROPS[key], line)
        if key == "position" and len(props[key]) == 4 and props[key][3] != 1.0:
            raise r.error(line, "POSITION w must be 1: shadow volumes are cast from a local "
                          "(point) light")
        if key == "jitter" and min(props[key]) < 0:
            raise r.error(line, "JITTER sizes must be >= 0")
    if "position" not in props:
        raise r.error(start, "LIGHT has no POSITION (expected POSITION x y z before END)")
    jit = props.get("jitter", (0.0,))
    return PointLight(f"light{index}", tuple(props["position"][:3]),
                      tuple(props.get("lcolor", (1.0, 1.0, 1.0))),
                      ambient=tuple(props.get("ambient", (0.0, 0.0, 0.0))),
                      spot_direction=props.get("spotdirection"), spot=props.get("spotlight"),
                      jitter=tuple(jit * 3 if len(jit) == 1 else jit))


def _matrix(t: dict[str, tuple[float, ...]]) -> np.ndarray:
    return object_transform(t.get("position", (0.0, 0.0, 0.0)), t.get("rotate", (0.0, 0.0, 0.0)),
                            t.get("scale", (1.0, 1.0, 1.0)))


def place(poly: Polyhedron, m: np.ndarray) -> Polyhedron:
    """``poly`` transformed by the column-vector 4x4 ``m`` (adjacency is unchanged;
    normals are recomputed, vertex normals by the inverse transpose)."""
    verts = poly.vertices @ m[:3, :3].T + m[:3, 3]
    kk = poly.polygons.shape[1]
    start = np.arange(len(poly.polygons) + 1, dtype=np.int64) * kk
    normals = newell_normals(verts, start, poly.polygons.reshape(-1))
    vn = poly.vertex_normals
    if vn is not None:
        vn = vn @ np.linalg.inv(m[:3, :3])
        length = np.linalg.norm(vn, axis=1, keepdims=True)
        vn = np.divide(vn, length, out=np.zeros_like(vn), where=length > 0)
    return replace(poly, vertices=verts, normals=normals, vertex_normals=vn)


def build_scene(spec: SceneSpec, *, use_cache: bool = True) -> Scene:
    """Load every model of ``spec`` and assemble the :class:`Scene`.

    Raises
    ------
    FormatError
        Naming the scene file and the MODEL line when a model cannot be loaded.
    """
    from .cache import load_model

    default = default_scene()
    g = _matrix(spec.global_transform)
    objects = []
    for k, ms in enumerate(spec.models):
        m = g @ _matrix(ms.transform)
        if np.linalg.det(m[:3, :3]) <= 0:
            raise FormatError(spec.path, ms.line, "SCALE mirrors or flattens the model "
                              "(expected factors whose product is positive)")
        name = f"{os.path.basename(ms.path)}#{k}"
        try:
            poly = load_model(ms.path, name, ms.material, ms.casts, use_cache=use_cache)
        except FormatError as exc:
            raise FormatError(spec.path, ms.line, f"model {exc}") from None
        objects.append(replace(place(poly, m), texture=ms.texture))
    if not objects:
        raise FormatError(spec.path, None, "the scene has no MODEL or XMODEL")
    cam = default.camera
    if spec.window is not None:
        near, far, height = spec.window
        cam = replace(cam, near=near, far=far, near_height=height)
    if spec.lookat is not None:
        cam = replace(cam, eye=spec.lookat[:3], target=spec.lookat[3:])
    lights = tuple(spec.lights) if spec.lights else default.lights
    allv = np.concatenate([o.vertices for o in objects])
    diag = float(np.linalg.norm(allv.max(0) - allv.min(0)))
    return Scene(objects=tuple(objects), lights=lights, lmodel=LightModel(), camera=cam,
                 volume_length=max(2.0 * diag, 1e-3))


def read_scene(path: str | os.PathLike, *, use_cache: bool = True) -> Scene:
    """Parse and load a ``.scn`` file.

    Parameters
    ----------
    path : str or PathLike
    use_cache : bool
        Use the adjacency cache for ``.glo`` models (see :mod:`vgxsim.formats.cache`).

    Returns
    -------
    Scene

    Raises
    ------
    FormatError
        Naming the file, the line and what was expected.
    """
    return build_scene(parse_scn(path), use_cache=use_cache)
