"""IRIS GL NURBS: setnurbsproperty, getnurbsproperty, bgnsurface, nurbssurface,
endsurface, bgntrim, nurbscurve, pwlcurve, endtrim, bgncurve, endcurve.

Tessellated by vgxsim's own code (:mod:`vgxsim.geometry.nurbs`: Cox-de Boor basis
functions, exact derivatives for normals) and drawn through the public gl calls
(``bgntmesh``/``bgnpolygon``/``bgnline``, ``n3f``, ``v4f``), so display objects and the
command stream record the triangles and lines themselves; every call here is
``record=False`` and a surface is evaluated at ``endsurface`` with the matrices and
properties current then.

The binding's control-point layout is kept exactly (cpython_gl_module.md 1.6):
``nurbssurface(sknots, tknots, ctlpoints, sorder, torder, type)`` takes
``ctlpoints`` as a list of ``len(sknots) - sorder`` lists, each of
``len(tknots) - torder`` points (3 numbers for N_XYZ, 4 homogeneous ``(wx, wy, wz,
w)`` for N_XYZW); the stub filled a flat array in that order but passed GL an s
stride of one point and a t stride of one row of ``s_nctl`` points, so the surface
GL draws has control point (s index a, t index b) at flat position ``a + b * s_nctl``
-- for a square grid ``ctlpoints[b][a]``, the transpose of the nesting.  Trim curves
are given in that same (s, t) parameter space (so they look flipped against the
nesting, as on the real binding).

Tessellation to N_PIXEL_TOLERANCE (default 50.0, the maximum length in pixels of a
tessellation edge, as GLU's sampling tolerance): along each parameter direction the
longest control-polygon row, projected to the window, is divided into pieces no
longer than the tolerance (at least one per knot span, at most 256); the samples are
uniform in the parameter and include every knot.  Trimmed surfaces are sampled at
least 32 times per direction, and a tessellation triangle is kept when its centroid
lies inside the trim region (bgntrim(3G): the region on the *left* of each trim loop
is kept: counter-clockwise outer loops, clockwise holes; the loops' winding number
must be positive), so trimmed edges are accurate to one tessellation cell.  The
curves between one bgntrim and endtrim are joined into one closed loop.

N_DISPLAY: N_FILL (triangles with normals, lit when lighting is active),
N_OUTLINE_POLY (each tessellation triangle outlined) or N_OUTLINE_PATCH (the
patch's boundary: its four edges, or its trim loops).  N_CULLING 1 skips a surface
whose control hull lies entirely outside one clip plane.  N_ERRORCHECKING is
accepted; errors are always reported (GLError naming the call).  Not emulated:
N_C4D/N_T2D colour and texture surfaces (the binding's stub accepted only N_XYZ and
N_XYZW), N_ISOLINE_S.

Outside a trim, ``nurbscurve`` (in bgncurve/endcurve) also takes N_XYZ/N_XYZW
points and draws a 3-D curve to the pixel tolerance; the binding's stub only
accepted N_ST/N_STW, which vgxsim keeps for trims.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from vgxsim import GL
from vgxsim.geometry import assembly
from vgxsim.geometry import nurbs as N
from vgxsim.geometry.transform import apply

from . import _draw
from ._core import (
    GLTypeError,
    GLUsageError,
    GLValueError,
    as_array,
    as_float,
    as_int,
    current,
    describe,
    gl_function,
    topic_state,
)

__all__ = [
    "setnurbsproperty", "getnurbsproperty", "bgnsurface", "nurbssurface", "endsurface",
    "bgntrim", "nurbscurve", "pwlcurve", "endtrim", "bgncurve", "endcurve",
]

MAX_ORDER = 8  # getgdesc(GD_NURBS_ORDER / GD_TRIMCURVE_ORDER)
MAX_STEPS = 256
TRIM_MIN_STEPS = 32
TRIM_STEPS_PER_SPAN = 32

_DISPLAY = {float(GL.N_FILL), float(GL.N_OUTLINE_POLY), float(GL.N_OUTLINE_PATCH)}
_DEFAULTS = {int(GL.N_PIXEL_TOLERANCE): 50.0, int(GL.N_CULLING): 0.0,
             int(GL.N_DISPLAY): float(GL.N_FILL), int(GL.N_ERRORCHECKING): 0.0}
_NAMES = {int(GL.N_PIXEL_TOLERANCE): "N_PIXEL_TOLERANCE", int(GL.N_CULLING): "N_CULLING",
          int(GL.N_DISPLAY): "N_DISPLAY", int(GL.N_ERRORCHECKING): "N_ERRORCHECKING"}


@dataclass
class Surface:
    control: np.ndarray  # (ns, nt, 4) homogeneous, [s index, t index]
    sknots: np.ndarray
    tknots: np.ndarray
    sorder: int
    torder: int


@dataclass
class NurbsState:
    props: dict[int, float] = field(default_factory=lambda: dict(_DEFAULTS))
    open: str | None = None  # 'surface' or 'curve'
    surface: Surface | None = None
    loops: list[np.ndarray] = field(default_factory=list)
    trim: list[np.ndarray] | None = None  # pieces of the loop being defined
    curves: list[tuple[np.ndarray, np.ndarray, int]] = field(default_factory=list)


def nurbs_state() -> NurbsState:
    """The session's :class:`NurbsState` (dropped by ``session.reset()``)."""
    return topic_state("nurbs", NurbsState)


# -- properties --------------------------------------------------------------------------
@gl_function(record=False)
def setnurbsproperty(prop: int, value: float) -> None:
    """setnurbsproperty(property, value) (setnurbsproperty(3G); module docstring)."""
    args = (prop, value)
    p = as_int("setnurbsproperty", args, "property", prop)
    if p not in _DEFAULTS:
        raise GLValueError(f"{describe('setnurbsproperty', args)}: property {p} is not "
                           f"N_PIXEL_TOLERANCE, N_CULLING, N_DISPLAY or N_ERRORCHECKING")
    v = as_float("setnurbsproperty", args, "value", value)
    if p == GL.N_PIXEL_TOLERANCE and not v > 0:
        raise GLValueError(f"{describe('setnurbsproperty', args)}: N_PIXEL_TOLERANCE must "
                           f"be > 0")
    if p == GL.N_DISPLAY and v not in _DISPLAY:
        raise GLValueError(f"{describe('setnurbsproperty', args)}: N_DISPLAY must be "
                           f"N_FILL, N_OUTLINE_POLY or N_OUTLINE_PATCH")
    nurbs_state().props[p] = v


@gl_function(record=False)
def getnurbsproperty(prop: int) -> float:
    """getnurbsproperty(property) -> float (the binding returns the value)."""
    args = (prop,)
    p = as_int("getnurbsproperty", args, "property", prop)
    if p not in _DEFAULTS:
        raise GLValueError(f"{describe('getnurbsproperty', args)}: property {p} is not a "
                           f"NURBS property")
    return float(nurbs_state().props[p])


# -- argument checks ---------------------------------------------------------------------
def _knots(name: str, args: tuple, what: str, v) -> np.ndarray:
    if not isinstance(v, (list, tuple, np.ndarray)):
        raise GLTypeError(f"{describe(name, args)}: {what} must be a list of numbers")
    k = np.array([as_float(name, args, what, x) for x in
                  as_array(name, args, what, v).reshape(-1).tolist()])
    if k.size and (not np.all(np.isfinite(k)) or np.any(np.diff(k) < 0)):
        raise GLValueError(f"{describe(name, args)}: {what} must be finite and "
                           f"nondecreasing")
    return k


def _order(name: str, args: tuple, what: str, v, nknots: int) -> int:
    k = as_int(name, args, what, v)
    if not 2 <= k <= MAX_ORDER:
        raise GLValueError(f"{describe(name, args)}: {what} must be 2..{MAX_ORDER} "
                           f"(getgdesc(GD_NURBS_ORDER))")
    if nknots - k < k:
        raise GLValueError(f"{describe(name, args)}: {nknots} knots leave "
                           f"{nknots - k} control points for order {k}; at least {k} needed")
    return k


def _point(name: str, args: tuple, p, width: int, where: str) -> list[float]:
    if not isinstance(p, (list, tuple)) or len(p) != width:
        raise GLTypeError(f"{describe(name, args)}: {where} must be a point of {width} "
                          f"numbers")
    vals = [as_float(name, args, where, x) for x in p]
    if not all(math.isfinite(x) for x in vals):
        raise GLValueError(f"{describe(name, args)}: {where} must be finite")
    return vals


def _homogeneous(pts: np.ndarray, rational: bool) -> np.ndarray:
    if rational:
        return pts
    return np.concatenate([pts, np.ones(pts.shape[:-1] + (1,))], axis=-1)


def _need(name: str, args: tuple, state: str | None) -> NurbsState:
    st = nurbs_state()
    if st.open != state or (state == "surface" and st.trim is not None):
        opener = {"surface": "bgnsurface", "curve": "bgncurve", None: "endsurface/endcurve"}
        raise GLUsageError(f"{describe(name, args)}: not inside {opener[state]}()")
    return st


# -- surfaces ------------------------------------------------------------------------------
@gl_function(record=False)
def bgnsurface(*args) -> None:
    """bgnsurface(): start a NURBS surface (nurbssurface, trims, endsurface)."""
    st = nurbs_state()
    if st.open is not None:
        raise GLUsageError(f"{describe('bgnsurface', args)}: bgn{st.open}() is still open")
    current("bgnsurface", args)
    st.open, st.surface, st.loops, st.trim = "surface", None, [], None


@gl_function(record=False)
def nurbssurface(*args) -> None:
    """nurbssurface(sknots, tknots, ctlpoints, sorder, torder, type): the surface's
    definition in the binding's form (module docstring for the layout)."""
    name = "nurbssurface"
    if len(args) != 6:
        raise GLTypeError(f"{describe(name, args)}: expected (sknots, tknots, ctlpoints, "
                          f"sorder, torder, type)")
    st = _need(name, args, "surface")
    sk = _knots(name, args, "sknots", args[0])
    tk = _knots(name, args, "tknots", args[1])
    so = _order(name, args, "sorder", args[3], sk.size)
    to = _order(name, args, "torder", args[4], tk.size)
    typ = as_int(name, args, "type", args[5])
    if typ not in (GL.N_XYZ, GL.N_XYZW):
        raise GLValueError(f"{describe(name, args)}: type must be N_XYZ or N_XYZW")
    width = 3 if typ == GL.N_XYZ else 4
    ns_, nt_ = sk.size - so, tk.size - to
    rows = args[2]
    if not isinstance(rows, list) or len(rows) != ns_ or not all(
            isinstance(r, list) and len(r) == nt_ for r in rows):
        raise GLTypeError(f"{describe(name, args)}: ctlpoints must be a list of {ns_} lists "
                          f"(len(sknots) - sorder) of {nt_} points (len(tknots) - torder)")
    flat = np.array([_point(name, args, p, width, f"ctlpoints[{i}][{j}]")
                     for i, r in enumerate(rows) for j, p in enumerate(r)])
    # The stub's strides: s stride one point, t stride s_nctl points.
    a, b = np.meshgrid(np.arange(ns_), np.arange(nt_), indexing="ij")
    control = _homogeneous(flat[a + b * ns_], width == 4)
    st.surface = Surface(control, sk, tk, so, to)


@gl_function(record=False)
def bgntrim(*args) -> None:
    """bgntrim(): start a trim loop (nurbscurve/pwlcurve pieces, endtrim)."""
    st = _need("bgntrim", args, "surface")
    st.trim = []


def _trim_piece(name: str, args: tuple, pts: np.ndarray) -> None:
    st = nurbs_state()
    if st.trim is None:
        raise GLUsageError(f"{describe(name, args)}: not inside bgntrim() (or bgncurve())")
    st.trim.append(pts)


@gl_function(record=False)
def nurbscurve(*args) -> None:
    """nurbscurve(knots, ctlpoints, order, type): a trim curve piece (N_ST, N_STW) in
    bgntrim, or a 3-D curve (N_XYZ, N_XYZW) in bgncurve."""
    name = "nurbscurve"
    if len(args) != 4:
        raise GLTypeError(f"{describe(name, args)}: expected (knots, ctlpoints, order, type)")
    st = nurbs_state()
    k = _knots(name, args, "knots", args[0])
    order = _order(name, args, "order", args[2], k.size)
    typ = as_int(name, args, "type", args[3])
    in_trim = st.trim is not None
    allowed = (GL.N_ST, GL.N_STW) if in_trim else (GL.N_XYZ, GL.N_XYZW)
    if st.open is None or (st.open == "surface" and not in_trim):
        raise GLUsageError(f"{describe(name, args)}: only inside bgntrim() or bgncurve()")
    if typ not in allowed:
        want = "N_ST or N_STW in a trim" if in_trim else "N_XYZ or N_XYZW in bgncurve"
        raise GLValueError(f"{describe(name, args)}: type must be {want}")
    width = {GL.N_ST: 2, GL.N_STW: 3, GL.N_XYZ: 3, GL.N_XYZW: 4}[typ]
    pts = args[1]
    n = k.size - order
    if not isinstance(pts, list) or len(pts) != n:
        raise GLTypeError(f"{describe(name, args)}: ctlpoints must be a list of {n} points "
                          f"(len(knots) - order)")
    ctrl = np.array([_point(name, args, p, width, f"ctlpoints[{i}]")
                     for i, p in enumerate(pts)])
    rational = typ in (GL.N_STW, GL.N_XYZW)
    ctrl = _homogeneous(ctrl, rational)
    if in_trim:
        lo, hi = N.domain(k, order, n)
        spans = max(1, int(np.count_nonzero(np.diff(np.unique(k[order - 1:n + 1])))))
        ts = np.linspace(lo, hi, spans * TRIM_STEPS_PER_SPAN + 1)
        h = N.curve_points(ctrl, k, order, ts)
        _trim_piece(name, args, h[:, :2] / h[:, 2:3])
    else:
        st.curves.append((ctrl, k, order))


@gl_function(record=False)
def pwlcurve(*args) -> None:
    """pwlcurve(points, type): a piecewise-linear trim piece; ``type`` N_ST, points
    a list of (s, t) pairs (the binding's form)."""
    name = "pwlcurve"
    if len(args) != 2:
        raise GLTypeError(f"{describe(name, args)}: expected (points, type)")
    if as_int(name, args, "type", args[1]) != GL.N_ST:
        raise GLValueError(f"{describe(name, args)}: type must be N_ST")
    if not isinstance(args[0], list) or len(args[0]) < 2:
        raise GLTypeError(f"{describe(name, args)}: points must be a list of at least 2 "
                          f"(s, t) points")
    pts = np.array([_point(name, args, p, 2, f"points[{i}]") for i, p in enumerate(args[0])])
    _trim_piece(name, args, pts)


@gl_function(record=False)
def endtrim(*args) -> None:
    """endtrim(): close the trim loop: its pieces, joined end to end."""
    st = nurbs_state()
    if st.open != "surface" or st.trim is None:
        raise GLUsageError(f"{describe('endtrim', args)}: without bgntrim()")
    pieces, st.trim = st.trim, None
    if pieces:
        loop = np.concatenate(pieces, axis=0)
        if np.allclose(loop[0], loop[-1]):
            loop = loop[:-1]
        if loop.shape[0] >= 3:
            st.loops.append(loop)


@gl_function(record=False)
def endsurface(*args) -> None:
    """endsurface(): tessellate and draw the surface (module docstring)."""
    st = _need("endsurface", args, "surface")
    st.open = None
    surf, loops = st.surface, st.loops
    st.surface, st.loops = None, []
    if surf is None:
        raise GLUsageError(f"{describe('endsurface', args)}: no nurbssurface() was given")
    ctx = current("endsurface", args)
    if st.props[GL.N_CULLING] and _culled(ctx, surf.control.reshape(-1, 4)):
        return
    _draw_surface(ctx, surf, loops, st.props)


@gl_function(record=False)
def bgncurve(*args) -> None:
    """bgncurve(): start NURBS curves (nurbscurve with N_XYZ/N_XYZW, endcurve)."""
    st = nurbs_state()
    if st.open is not None:
        raise GLUsageError(f"{describe('bgncurve', args)}: bgn{st.open}() is still open")
    current("bgncurve", args)
    st.open, st.curves = "curve", []


@gl_function(record=False)
def endcurve(*args) -> None:
    """endcurve(): draw the curves given since bgncurve, each as one line strip."""
    st = _need("endcurve", args, "curve")
    st.open = None
    curves, st.curves = st.curves, []
    ctx = current("endcurve", args)
    tol = st.props[GL.N_PIXEL_TOLERANCE]
    for ctrl, k, order in curves:
        steps = _steps(ctx, ctrl[None, :, :], axis=1, tol=tol, knots=k, order=order)
        ts = _samples(k, order, ctrl.shape[0], steps)
        _line_strip(N.curve_points(ctrl, k, order, ts), closed=False)


# -- tessellation ----------------------------------------------------------------------------
def _window_xy(ctx, homog: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    clip = apply(homog.reshape(-1, 4), ctx.matrices.mvp())
    w = clip[:, 3]
    ok = w > 1e-12
    l, r, b, t = ctx.raster.viewport
    x = np.where(ok, clip[:, 0] / np.where(ok, w, 1.0), 0.0) * (r - l + 1) / 2
    y = np.where(ok, clip[:, 1] / np.where(ok, w, 1.0), 0.0) * (t - b + 1) / 2
    return np.stack([x, y], axis=1).reshape(homog.shape[:-1] + (2,)), ok.reshape(
        homog.shape[:-1])


def _steps(ctx, control: np.ndarray, axis: int, tol: float, knots: np.ndarray,
           order: int) -> int:
    """Samples along ``axis`` of the control grid so that no projected control-polygon
    piece is longer than ``tol`` pixels (the module docstring's rule)."""
    xy, ok = _window_xy(ctx, control)
    if not np.all(ok):
        return 64  # part of the hull is behind the eye: no pixel measure; a fixed count
    seg = np.linalg.norm(np.diff(xy, axis=axis), axis=-1)
    length = float(seg.sum(axis=axis).max()) if seg.size else 0.0
    n = control.shape[axis]
    spans = max(1, int(np.count_nonzero(np.diff(np.unique(knots[order - 1:n + 1])))))
    return int(min(MAX_STEPS, max(spans, math.ceil(length / tol))))


def _samples(knots: np.ndarray, order: int, n: int, steps: int) -> np.ndarray:
    lo, hi = N.domain(knots, order, n)
    inner = knots[(knots > lo) & (knots < hi)]
    return np.unique(np.concatenate([np.linspace(lo, hi, steps + 1), inner]))


def _culled(ctx, homog: np.ndarray) -> bool:
    clip = apply(homog, ctx.matrices.mvp())
    x, y, z, w = clip.T
    return any(bool(np.all(c)) for c in (x < -w, x > w, y < -w, y > w, z < -w, z > w))


def _draw_surface(ctx, surf: Surface, loops: list[np.ndarray], props: dict) -> None:
    tol = props[GL.N_PIXEL_TOLERANCE]
    ns_, nt_ = surf.control.shape[:2]
    s_steps = _steps(ctx, surf.control, 0, tol, surf.sknots, surf.sorder)
    t_steps = _steps(ctx, surf.control, 1, tol, surf.tknots, surf.torder)
    if loops:
        s_steps, t_steps = max(s_steps, TRIM_MIN_STEPS), max(t_steps, TRIM_MIN_STEPS)
    ss = _samples(surf.sknots, surf.sorder, ns_, s_steps)
    ts = _samples(surf.tknots, surf.torder, nt_, t_steps)
    pts, nrm = N.surface_points(surf.control, surf.sknots, surf.tknots, surf.sorder,
                                surf.torder, ss, ts)
    mode = props[GL.N_DISPLAY]
    if mode == GL.N_OUTLINE_PATCH:
        _outline_patch(surf, loops, ss, ts, pts)
        return
    strip_tris = assembly.tmesh_triangles(2 * len(ss), [])
    for j in range(len(ts) - 1):
        # Strip order p(i, j+1), p(i, j), ...: every triangle runs counter-clockwise in
        # (s, t), so it faces the way dS/ds x dS/dt points.
        idx_s = np.repeat(np.arange(len(ss)), 2)
        idx_t = np.tile([j + 1, j], len(ss))
        if loops:
            cs = ss[idx_s][strip_tris].mean(axis=1)
            ct = ts[idx_t][strip_tris].mean(axis=1)
            keep = N.winding_numbers(np.stack([cs, ct], axis=1), loops) > 0
        else:
            keep = np.ones(len(strip_tris), bool)
        sp, sn = pts[idx_s, idx_t], nrm[idx_s, idx_t]
        if mode == GL.N_FILL and keep.all():
            _draw.bgntmesh()
            for p, n in zip(sp.tolist(), sn.tolist(), strict=True):
                _draw.n3f(n)
                _draw.v4f(p)
            _draw.endtmesh()
            continue
        for tri in strip_tris[keep].tolist():
            if mode == GL.N_FILL:
                _draw.bgnpolygon()
            else:
                _draw.bgnclosedline()
            for v in tri:
                _draw.n3f(sn[v].tolist())
                _draw.v4f(sp[v].tolist())
            if mode == GL.N_FILL:
                _draw.endpolygon()
            else:
                _draw.endclosedline()


def _outline_patch(surf: Surface, loops: list[np.ndarray], ss, ts, pts) -> None:
    if not loops:
        _line_strip(pts[:, 0], closed=False)
        _line_strip(pts[-1, :], closed=False)
        _line_strip(pts[::-1, -1], closed=False)
        _line_strip(pts[0, ::-1], closed=False)
        return
    for loop in loops:
        h = N.surface_at(surf.control, surf.sknots, surf.tknots, surf.sorder, surf.torder,
                         loop[:, 0], loop[:, 1])
        _line_strip(h, closed=True)


def _line_strip(points: np.ndarray, closed: bool) -> None:
    """Draw homogeneous points (k, 4) as a line through the public calls."""
    if points.shape[1] == 3:
        points = np.concatenate([points, np.ones((points.shape[0], 1))], axis=1)
    (_draw.bgnclosedline if closed else _draw.bgnline)()
    for p in points.tolist():
        _draw.v4f(p)
    (_draw.endclosedline if closed else _draw.endline)()
