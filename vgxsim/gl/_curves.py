"""IRIS GL's older curve and patch calls: defbasis, curvebasis, curveprecision, crv,
crvn, rcrv, rcrvn, curveit, patchbasis, patchprecision, patchcurves, patch, rpatch.

A cubic segment with basis matrix ``B`` (4x4, defbasis(3G)) and geometry ``G`` (four
control points, one per row) is ``P(t) = [t^3, t^2, t, 1] B G`` for ``0 <= t <= 1``
(crv(3G); with the Bezier basis ``P(0)`` is the first control point and ``P(1)`` the
fourth).  A patch (patch(3G)) with geometry ``Gx, Gy, Gz`` (4x4 each, index [i][j]
with i along u and j along v) and bases ``Bu, Bv`` is
``x(u, v) = U Bu Gx Bv^T V^T``, ``U = [u^3, u^2, u, 1]``, ``V`` likewise.  Rational
forms (rcrv, rcrvn, rpatch) add a w coordinate and are drawn as homogeneous
vertices (v4f), so the divide is the pipeline's own.

Evaluation is vgxsim's: each segment is sampled at ``curveprecision`` equal steps of
``t`` (forward differencing on the VGX; the sampled points are the same) and drawn as
one ``bgnline``/``v3f``.../``endline`` strip through the public gl calls, so display
objects and the command stream record the line strips themselves (the calls here
are ``record=False``: inside ``makeobj`` they evaluate at once with the current basis
and precision, and the object holds the lines they drew).  ``crvn`` and ``rcrvn``
draw one segment for each four consecutive control points ``i .. i+3`` (B-spline and
Cardinal bases join there; with the Bezier basis use 3k+1 points and step 3 --
vgxsim steps by one as crvn(3G) describes).

``patch`` draws the patch's curve mesh (patch(3G): the patch "is drawn as a grid of
curves"): ``patchcurves(ucurves, vcurves)`` curves of constant v running along u and
of constant u running along v (evenly spaced, including both edges), each curve drawn
with ``patchprecision(usegments, vsegments)`` segments.

``curveit(n)`` iterates the current matrix as a forward-difference matrix: its rows
are a point and its first, second and third differences, already in clip
coordinates (crv(3G) builds that matrix on the stack); the point is drawn to, then
each iteration adds row 2 to row 1, row 3 to row 2, row 4 to row 3 and draws to the
new point.  The line is drawn with the transform set aside (the points are clip
coordinates), so curveit records as a call, not as lines.

Choices where the manuals are silent: no basis is defined at first (crv before
``defbasis``/``curvebasis`` is a GLUsageError naming the missing call); the default
precisions are 10 segments and the default patchcurves 5 x 5 (*assumed*).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from vgxsim.state.matrices import MSINGLE

from . import _draw
from ._core import (
    GLTypeError,
    GLUsageError,
    GLValueError,
    as_array,
    as_int,
    current,
    describe,
    flat_numbers,
    gl_function,
    topic_state,
)

#: Largest short, the type of curveit's iteration count (curveit(3G)).
_SHORT_MAX = 0x7FFF

__all__ = [
    "defbasis", "curvebasis", "curveprecision", "crv", "crvn", "rcrv", "rcrvn", "curveit",
    "patchbasis", "patchprecision", "patchcurves", "patch", "rpatch",
]

DEFAULT_PRECISION = 10  # assumed: segments per curve until curveprecision
DEFAULT_PATCHCURVES = (5, 5)  # assumed


@dataclass
class CurveState:
    """Bases by id and the evaluator's settings."""

    bases: dict[int, np.ndarray] = field(default_factory=dict)
    curvebasis: int | None = None
    precision: int = DEFAULT_PRECISION
    patchbasis: tuple[int, int] | None = None
    patchprecision: tuple[int, int] = (DEFAULT_PRECISION, DEFAULT_PRECISION)
    patchcurves: tuple[int, int] = DEFAULT_PATCHCURVES


def curve_state() -> CurveState:
    """The session's :class:`CurveState` (dropped by ``session.reset()``)."""
    return topic_state("curves", CurveState)


# -- evaluation (pure) ----------------------------------------------------------------------
def power_basis(t: np.ndarray) -> np.ndarray:
    """Rows ``[t^3, t^2, t, 1]`` for each ``t``: shape (len(t), 4)."""
    t = np.asarray(t, dtype=np.float64)
    return np.stack([t ** 3, t ** 2, t, np.ones_like(t)], axis=1)


def eval_segment(basis: np.ndarray, geom: np.ndarray, steps: int) -> np.ndarray:
    """Points of one cubic segment at ``t = 0, 1/steps, ..., 1``.

    Parameters
    ----------
    basis : ndarray, shape (4, 4)
    geom : ndarray, shape (4, D)
        Control points (D = 3, or 4 for rational segments).
    steps : int

    Returns
    -------
    ndarray, shape (steps + 1, D), float64
    """
    return power_basis(np.linspace(0.0, 1.0, steps + 1)) @ basis @ geom


def eval_patch(bu: np.ndarray, bv: np.ndarray, geoms: list[np.ndarray], u: np.ndarray,
               v: np.ndarray) -> np.ndarray:
    """Patch points at the grid ``u`` x ``v``: shape (len(u), len(v), len(geoms))."""
    U, V = power_basis(u), power_basis(v)
    return np.stack([U @ bu @ g @ bv.T @ V.T for g in geoms], axis=-1)


# -- argument handling -------------------------------------------------------------------------
def _array(name: str, args: tuple, values, n: int | None, what: str, width: int) -> np.ndarray:
    """Flat numbers (the binding's form) or nested rows/numpy arrays, as (k, width)."""
    if isinstance(values, np.ndarray) or (isinstance(values, (list, tuple)) and values and
                                          isinstance(values[0], (list, tuple, np.ndarray))):
        a = as_array(name, args, what, values, np.float64).reshape(-1)
        flat = a.tolist()
    else:
        flat = flat_numbers(name, (values,), None)
    if n is not None and len(flat) != n:
        raise GLTypeError(f"{describe(name, args)}: {what} must be {n} numbers, got "
                          f"{len(flat)}")
    if len(flat) % width:
        raise GLTypeError(f"{describe(name, args)}: {what} must be a multiple of {width} "
                          f"numbers, got {len(flat)}")
    a = np.array(flat, dtype=np.float64).reshape(-1, width)
    if not np.all(np.isfinite(a)):
        raise GLValueError(f"{describe(name, args)}: {what} must be finite")
    return a


def _last_geom(name: str, args: tuple):
    """The geometry of ``crvn(geom)`` or ``crvn(n, geom)``."""
    if len(args) not in (1, 2):
        raise GLTypeError(f"{describe(name, args)}: expected 1 or 2 arguments (geom, or "
                          f"n and geom), got {len(args)}")
    return args[-1]


def _basis(name: str, args: tuple, bid: int) -> np.ndarray:
    st = curve_state()
    b = st.bases.get(bid)
    if b is None:
        raise GLUsageError(f"{describe(name, args)}: basis {bid} is not defined (defbasis)")
    return b


def _current_curve_basis(name: str, args: tuple) -> np.ndarray:
    st = curve_state()
    if st.curvebasis is None:
        raise GLUsageError(f"{describe(name, args)}: no curve basis selected (call defbasis "
                           f"and curvebasis first)")
    return _basis(name, args, st.curvebasis)


def _positive(name: str, args: tuple, what: str, v) -> int:
    n = as_int(name, args, what, v)
    if n < 1:
        raise GLValueError(f"{describe(name, args)}: {what} must be at least 1")
    return n


def _strip(points: np.ndarray) -> None:
    """Draw points (k, 3) or (k, 4) as one line strip through the public calls."""
    vert = _draw.v4f if points.shape[1] == 4 else _draw.v3f
    _draw.bgnline()
    for p in points.tolist():
        vert(p)
    _draw.endline()


# -- the calls ------------------------------------------------------------------------------------
@gl_function(record=False)
def defbasis(*args) -> None:
    """defbasis(id, mat): define basis ``id`` as the 4x4 matrix ``mat`` (16 numbers,
    row-major, the binding's form) (defbasis(3G))."""
    if len(args) != 2:
        raise GLTypeError(f"{describe('defbasis', args)}: expected (id, mat), got "
                          f"{len(args)} arguments")
    bid = as_int("defbasis", args, "id", args[0])
    curve_state().bases[bid] = _array("defbasis", args, args[1], 16, "mat", 4)


@gl_function(record=False)
def curvebasis(basid: int) -> None:
    """curvebasis(id): the basis crv, crvn, rcrv and rcrvn use (curvebasis(3G))."""
    args = (basid,)
    bid = as_int("curvebasis", args, "basid", basid)
    _basis("curvebasis", args, bid)
    curve_state().curvebasis = bid


@gl_function(record=False)
def curveprecision(nsegments: int) -> None:
    """curveprecision(n): line segments drawn per curve segment (curveprecision(3G))."""
    args = (nsegments,)
    curve_state().precision = _positive("curveprecision", args, "nsegments", nsegments)


def _draw_curves(name: str, args: tuple, geom: np.ndarray) -> None:
    basis = _current_curve_basis(name, args)
    current(name, args)
    if geom.shape[0] < 4:
        raise GLValueError(f"{describe(name, args)}: a curve needs at least 4 control "
                           f"points, got {geom.shape[0]}")
    steps = curve_state().precision
    for i in range(geom.shape[0] - 3):
        _strip(eval_segment(basis, geom[i:i + 4], steps))


@gl_function(record=False)
def crv(*args) -> None:
    """crv(geom): one cubic segment from 4 points (12 numbers) (crv(3G))."""
    g = args[0] if len(args) == 1 else args
    _draw_curves("crv", args, _array("crv", args, g, 12, "geom", 3))


@gl_function(record=False)
def crvn(*args) -> None:
    """crvn(geom): segments through n points (3n numbers; n implied, as the binding
    did) (crvn(3G)); ``crvn(n, geom)`` is accepted too."""
    g = _last_geom("crvn", args)
    arr = _array("crvn", args, g, None, "geom", 3)
    if len(args) == 2 and as_int("crvn", args, "n", args[0]) != arr.shape[0]:
        raise GLTypeError(f"{describe('crvn', args)}: n does not match the points given")
    _draw_curves("crvn", args, arr)


@gl_function(record=False)
def rcrv(*args) -> None:
    """rcrv(geom): one rational cubic segment from 4 homogeneous points (16 numbers)."""
    g = args[0] if len(args) == 1 else args
    _draw_curves("rcrv", args, _array("rcrv", args, g, 16, "geom", 4))


@gl_function(record=False)
def rcrvn(*args) -> None:
    """rcrvn(geom): rational segments through n homogeneous points (4n numbers)."""
    g = _last_geom("rcrvn", args)
    arr = _array("rcrvn", args, g, None, "geom", 4)
    if len(args) == 2 and as_int("rcrvn", args, "n", args[0]) != arr.shape[0]:
        raise GLTypeError(f"{describe('rcrvn', args)}: n does not match the points given")
    _draw_curves("rcrvn", args, arr)


@gl_function(record=True)
def curveit(iterations: int) -> None:
    """curveit(n): iterate the current matrix as a forward-difference matrix ``n``
    times, drawing a line through the points (module docstring)."""
    args = (iterations,)
    n = as_int("curveit", args, "iterations", iterations)
    if not 0 <= n <= _SHORT_MAX:  # curveit(3G) takes a short iteration count
        raise GLValueError(f"{describe('curveit', args)}: iterations must be 0..{_SHORT_MAX} "
                           "(a short)")
    ctx = current("curveit", args)
    rows = np.array(ctx.matrices.current(), dtype=np.float64)
    pts = [rows[0].copy()]
    for _ in range(n):
        rows[0] += rows[1]
        rows[1] += rows[2]
        rows[2] += rows[3]
        pts.append(rows[0].copy())
    m = ctx.matrices
    saved = (m.mode, m.modelview, m.projection, m.pick)
    m.mode, m.modelview, m.pick = MSINGLE, [np.eye(4)], None  # points are clip coords
    m._touch()
    try:
        _strip(np.array(pts))
    finally:
        m.mode, m.modelview, m.projection, m.pick = saved
        m._touch()


@gl_function(record=False)
def patchbasis(uid: int, vid: int) -> None:
    """patchbasis(uid, vid): the bases patch and rpatch use (patchbasis(3G))."""
    args = (uid, vid)
    u = as_int("patchbasis", args, "uid", uid)
    v = as_int("patchbasis", args, "vid", vid)
    _basis("patchbasis", args, u)
    _basis("patchbasis", args, v)
    curve_state().patchbasis = (u, v)


@gl_function(record=False)
def patchprecision(usegments: int, vsegments: int) -> None:
    """patchprecision(usegments, vsegments): segments per curve along u and v."""
    args = (usegments, vsegments)
    curve_state().patchprecision = (_positive("patchprecision", args, "usegments", usegments),
                                    _positive("patchprecision", args, "vsegments", vsegments))


@gl_function(record=False)
def patchcurves(ucurves: int, vcurves: int) -> None:
    """patchcurves(ucurves, vcurves): how many curves run along u (at evenly spaced
    v) and along v (at evenly spaced u); each count >= 2 includes both edges."""
    args = (ucurves, vcurves)
    curve_state().patchcurves = (_positive("patchcurves", args, "ucurves", ucurves),
                                 _positive("patchcurves", args, "vcurves", vcurves))


def _draw_patch(name: str, args: tuple, geoms: list[np.ndarray]) -> None:
    st = curve_state()
    if st.patchbasis is None:
        raise GLUsageError(f"{describe(name, args)}: no patch basis selected (call defbasis "
                           f"and patchbasis first)")
    current(name, args)
    bu = _basis(name, args, st.patchbasis[0])
    bv = _basis(name, args, st.patchbasis[1])
    nu, nv = st.patchcurves
    su, sv = st.patchprecision
    fixed_v = np.linspace(0.0, 1.0, nu) if nu > 1 else np.zeros(1)
    fixed_u = np.linspace(0.0, 1.0, nv) if nv > 1 else np.zeros(1)
    along_u = eval_patch(bu, bv, geoms, np.linspace(0.0, 1.0, su + 1), fixed_v)
    for j in range(along_u.shape[1]):  # curves running along u at fixed v
        _strip(along_u[:, j])
    along_v = eval_patch(bu, bv, geoms, fixed_u, np.linspace(0.0, 1.0, sv + 1))
    for i in range(along_v.shape[0]):  # curves running along v at fixed u
        _strip(along_v[i])


@gl_function(record=False)
def patch(*args) -> None:
    """patch(geomx, geomy, geomz): draw a bicubic patch's curve mesh; each geometry
    is 16 numbers, row i along u, column j along v (patch(3G))."""
    if len(args) != 3:
        raise GLTypeError(f"{describe('patch', args)}: expected geomx, geomy, geomz")
    geoms = [_array("patch", args, g, 16, what, 4) for g, what in
             zip(args, ("geomx", "geomy", "geomz"), strict=True)]
    _draw_patch("patch", args, geoms)


@gl_function(record=False)
def rpatch(*args) -> None:
    """rpatch(geomx, geomy, geomz, geomw): the rational form of patch."""
    if len(args) != 4:
        raise GLTypeError(f"{describe('rpatch', args)}: expected geomx, geomy, geomz, geomw")
    geoms = [_array("rpatch", args, g, 16, what, 4) for g, what in
             zip(args, ("geomx", "geomy", "geomz", "geomw"), strict=True)]
    _draw_patch("rpatch", args, geoms)
