"""IRIS GL calls: the old-style drawing routines (rect, polf, pnt, move/draw, pmv/pdr,
circ, arc).

Each is defined by the new-style primitive it is equivalent to, so coverage, colour
and the fragment operations are exactly those of ``bgnpolygon``/``bgnline``...:

* ``rectf``/``polf``/``pmv``...``pclos`` are polygons (``polf`` honours concave(3G),
  as bgnpolygon does); ``rect``/``poly`` are closed lines; ``pnt`` is a point;
* ``move`` sets the current graphics position and starts a new polyline; ``draw``
  draws one segment from it to the new point, continuing the line-style pattern
  (docs/numeric_model.md s. 5: the pattern restarts at each move);
* ``circ``/``arc`` are closed/open polylines and ``circf``/``arcf`` fans of
  triangles around the centre.

Coverage of rectangles follows the tie rule of docs/numeric_model.md s. 3: under the
standard 2-D projection (``ortho2(-0.5, w-0.5, -0.5, h-0.5)``, subpixel off)
``rectf(2, 2, 5, 4)`` covers pixel columns 2..4 and rows 2..3 -- the left and bottom
edges, which pass through pixel centres, are inclusive, the right and top edges
exclusive, so abutting rectangles never overlap.  The outline ``rect(2, 2, 5, 4)``
(closed lines, both end pixels) covers columns 2..5 and rows 2..4.

The current graphics position is kept in object coordinates (``Context.gpos``) and is
transformed by the matrix current when ``draw`` is called (IRIS hardware kept it
transformed; changing the matrix between a move and a draw is therefore not
emulated exactly).  ``rect``, ``poly``, ``circ`` and ``arc`` leave it unchanged.

Circles and arcs (circ(3G), arc(3G)) are approximated by chords whose maximum
distance from the true circle is at most 1/8 pixel: a full circle of radius ``r``
pixels (measured through the current matrix and viewport) gets
``n = ceil(pi / acos(1 - 0.125 / r))`` segments, clamped to 16..1024 (16 if the circle
cannot be measured, e.g. it crosses the eye plane; 1024 for any radius too large for
the formula in doubles, so every finite radius draws a bounded polyline); an arc
gets that many times its fraction of the circle, at least 2.  Angles are Angles (int
tenths of a degree), measured counter-clockwise from +x; arcs go counter-clockwise
from ``startang`` to ``endang`` ("the arc from 10 degrees to 5 degrees is a nearly
complete circle", arcf(3G)); equal angles draw nothing, angles 3600 apart a full
circle.
"""

from __future__ import annotations

import math

import numpy as np

from vgxsim.geometry.transform import apply
from vgxsim.pipeline.decode import drain
from vgxsim.stream.opcodes import BGN, DRAW_RESTART, DRAW_SEG, END, KIND_OF, V
from vgxsim.stream.recorder import MAX_STREAM_OPS

from ._core import (
    _NO,
    INT_MAX,
    INT_MIN,
    GLTypeError,
    GLUsageError,
    GLValueError,
    as_angle,
    as_float,
    as_int,
    current,
    describe,
    flat_numbers,
    given,
    gl_function,
    record_or_refuse,
    session,
)
from ._draw import _restate_changed, apply_ops, coords, lit_mask, stream_call, sync

__all__ = [
    "rect", "recti", "rects", "rectf", "rectfi", "rectfs",
    "polf", "polfi", "polfs", "polf2", "polf2i", "polf2s",
    "poly", "polyi", "polys", "poly2", "poly2i", "poly2s",
    "pnt", "pnti", "pnts", "pnt2", "pnt2i", "pnt2s",
    "move", "movei", "moves", "move2", "move2i", "move2s",
    "draw", "drawi", "draws", "draw2", "draw2i", "draw2s",
    "rmv", "rmvi", "rmvs", "rmv2", "rmv2i", "rmv2s",
    "rdr", "rdri", "rdrs", "rdr2", "rdr2i", "rdr2s",
    "pmv", "pmvi", "pmvs", "pmv2", "pmv2i", "pmv2s",
    "pdr", "pdri", "pdrs", "pdr2", "pdr2i", "pdr2s",
    "rpmv", "rpmvi", "rpmvs", "rpmv2", "rpmv2i", "rpmv2s",
    "rpdr", "rpdri", "rpdrs", "rpdr2", "rpdr2i", "rpdr2s", "pclos",
    "circ", "circi", "circs", "circf", "circfi", "circfs",
    "arc", "arci", "arcs", "arcf", "arcfi", "arcfs", "getgpos",
]

MIN_SEGMENTS, MAX_SEGMENTS = 16, 1024
CHORD_TOLERANCE = 0.125  # pixels: largest distance of a chord from the circle

_FORMS = {"": False, "i": True, "s": True}  # suffix -> integer arguments


def _point(vals) -> tuple[float, float, float, float]:
    if len(vals) == 2:
        return (vals[0], vals[1], 0.0, 1.0)
    return (vals[0], vals[1], vals[2], 1.0)


def _not_in_primitive(ctx, name: str, args: tuple) -> None:
    """Old-style routines may not be used between bgn* and end* (or pmv and pclos)."""
    if ctx.prim is not None:
        raise GLUsageError(f"{describe(name, args)}: not allowed while a primitive is open "
                           f"(close it first)")


def _family(base: str, two_d: bool, suffix: str) -> str:
    return f"{base}{'2' if two_d else ''}{suffix}"


# -- rectangles and polygons (stream calls: display objects compile them) -------------
def _rect_parse(name: str, filled: bool, integer: bool):
    def parse(args: tuple) -> list:
        x1, y1, x2, y2 = coords(name, args, 4, integer)
        corners = [(x1, y1, 0.0, 1.0), (x2, y1, 0.0, 1.0), (x2, y2, 0.0, 1.0),
                   (x1, y2, 0.0, 1.0)]
        prim = "polygon" if filled else "closedline"
        return [("bgn", prim)] + [("v", c) for c in corners] + [("end", prim)]

    return parse


def _record_closed(ctx, kind_ops: tuple, xyzw: tuple) -> None:
    """Record one closed primitive outside bgn*/end* -- begin(), the vertices and
    end() of its stream operations, inlined: a STATE op if the draw state changed, a
    SYNC if the colour, normal or lit flag did, then ``kind_ops`` (BGN, kind, one V
    per vertex, END) and the vertices' floats."""
    st = ctx.stream
    ops = st.ops
    if len(ops) > MAX_STREAM_OPS:  # (spliced parts are bounded in CommandStream.splice)
        drain(ctx)
    snap = ctx.raster._snapshot  # _draw.same_state, inlined (one call less)
    if not (snap is not None and snap is st.raster and ctx.matrices._mvp is st.mvp
            and ctx.depth_range is st.depth and ctx.lighting_serial == st.lighting_serial
            and ctx.concave is st.concave and ctx.vertex_serial == st.vertex_serial):
        _restate_changed(ctx, st)
    if (ctx.colour is not st.colour or ctx.normal is not st.normal
            or ctx.last_sent is not st.sent or ctx.lmcolor_set is not st.lmcolor_set):
        sync(ctx, st)
    ops.extend(kind_ops)
    st.fl.extend(xyzw)


_RECT_OPS = {True: (BGN, KIND_OF["polygon"], V, V, V, V, END),
             False: (BGN, KIND_OF["closedline"], V, V, V, V, END)}


def _make_rect(filled: bool, suffix: str):
    name = f"rect{'f' if filled else ''}{suffix}"
    what = "fills" if filled else "outlines"
    integer = _FORMS[suffix]
    parse = _rect_parse(name, filled, integer)
    general = stream_call(name, parse,
                          f"{name}(x1, y1, x2, y2): {what} the rectangle with corners "
                          f"(x1, y1), (x2, y2) at z = 0 (rect(3G)); counter-clockwise "
                          f"when x1 < x2 and y1 < y2.")
    kind_ops = _RECT_OPS[filled]

    # Valid path (FAST_CALLS): four finite floats (rect, rectf) or four ints of 32
    # bits (the i/s forms, as float(v)), outside bgn*/end* (and, for the outline, no
    # move's pattern restart pending: begin() applies it); the corners in parse's
    # order.  Anything else takes the stream call, which validates and raises.
    def call(x1=_NO, y1=_NO, x2=_NO, y2=_NO, /, *more, **kw) -> None:
        ctx = session.imm
        if ctx is None or kw or more or ctx.prim is not None or (
                not filled and ctx.ls_restart):
            return general(*given((x1, y1, x2, y2), more), **kw)
        if integer:
            if not (type(x1) is int and type(y1) is int and type(x2) is int
                    and type(y2) is int and INT_MIN <= x1 <= INT_MAX
                    and INT_MIN <= y1 <= INT_MAX and INT_MIN <= x2 <= INT_MAX
                    and INT_MIN <= y2 <= INT_MAX):
                return general(*given((x1, y1, x2, y2), more))
            x1, y1, x2, y2 = float(x1), float(y1), float(x2), float(y2)
        elif not (type(x1) is float and type(y1) is float and type(x2) is float
                  and type(y2) is float and x1 - x1 == 0.0 and y1 - y1 == 0.0
                  and x2 - x2 == 0.0 and y2 - y2 == 0.0):  # (x - x: NaN, inf)
            return general(*given((x1, y1, x2, y2), more))
        _record_closed(ctx, kind_ops, (x1, y1, 0.0, 1.0, x2, y1, 0.0, 1.0,
                                       x2, y2, 0.0, 1.0, x1, y2, 0.0, 1.0))

    call.__name__ = call.__qualname__ = name
    call.__doc__ = general.__doc__
    call = gl_function(record=True, binds=(0, math.inf, ()))(call)
    call.stream = parse
    return call


rect, recti, rects = (_make_rect(False, s) for s in ("", "i", "s"))
rectf, rectfi, rectfs = (_make_rect(True, s) for s in ("", "i", "s"))


def _poly_parse(name: str, filled: bool, dim: int, integer: bool):
    def parse(args: tuple) -> list:
        vals = flat_numbers(name, args, None, integer=integer)
        if len(vals) % dim:
            raise GLTypeError(f"{describe(name, args)}: expected a flat list of {dim}n "
                              f"numbers, got {len(vals)}")
        if not all(math.isfinite(v) for v in vals):
            raise GLValueError(f"{describe(name, args)}: coordinates must be finite")
        if not vals:
            return []
        prim = "polygon" if filled else "closedline"
        pts = [_point(tuple(float(v) for v in vals[i:i + dim]))
               for i in range(0, len(vals), dim)]
        return [("bgn", prim)] + [("v", p) for p in pts] + [("end", prim)]

    return parse


def _make_poly(filled: bool, dim: int, suffix: str):
    name = _family("polf" if filled else "poly", dim == 2, suffix)
    what = "a filled" if filled else "the outline of a"
    return stream_call(
        name, _poly_parse(name, filled, dim, _FORMS[suffix]),
        f"{name}(coords): draw {what} polygon from a flat list of {dim}n numbers (the "
        f"count is implied, as in the historical binding); poly(3G)/polf(3G).")


polf, polfi, polfs = (_make_poly(True, 3, s) for s in ("", "i", "s"))
polf2, polf2i, polf2s = (_make_poly(True, 2, s) for s in ("", "i", "s"))
poly, polyi, polys = (_make_poly(False, 3, s) for s in ("", "i", "s"))
poly2, poly2i, poly2s = (_make_poly(False, 2, s) for s in ("", "i", "s"))


_PNT_OPS = (BGN, KIND_OF["point"], V, END)


def _make_pnt(dim: int, suffix: str):
    name = _family("pnt", dim == 2, suffix)
    integer = _FORMS[suffix]

    def parse(args: tuple) -> list:
        p = _point(coords(name, args, dim, integer))
        return [("bgn", "point"), ("v", p), ("end", "point"), ("g", p)]

    general = stream_call(name, parse, f"{name}(...): draw a point (pnt(3G)) and make "
                                       f"it the current graphics position.")

    # Valid path (FAST_CALLS): dim finite floats (pnt, pnt2) or ints of 32 bits (the
    # i/s forms, as float(v)), outside bgn*/end*; anything else (one tuple too)
    # takes the stream call, which validates and raises.
    def call(x=_NO, y=_NO, z=_NO, /, *more, **kw) -> None:
        ctx = session.imm
        if ctx is None or kw or more or ctx.prim is not None or (
                (z is _NO) != (dim == 2)):
            return general(*given((x, y, z), more), **kw)
        if dim == 2:
            z = 0.0
        if integer:
            if not (type(x) is int and type(y) is int and (dim == 2 or type(z) is int)
                    and INT_MIN <= x <= INT_MAX and INT_MIN <= y <= INT_MAX
                    and (dim == 2 or INT_MIN <= z <= INT_MAX)):
                return general(*given((x, y, z) if dim == 3 else (x, y), more))
            p = (float(x), float(y), float(z), 1.0)
        elif (type(x) is float and type(y) is float and type(z) is float
                and x - x == 0.0 and y - y == 0.0 and z - z == 0.0):
            p = (x, y, z, 1.0)
        else:
            return general(*given((x, y, z) if dim == 3 else (x, y), more))
        _record_closed(ctx, _PNT_OPS, p)
        ctx.gpos = p

    call.__name__ = call.__qualname__ = name
    call.__doc__ = general.__doc__
    call = gl_function(record=True, binds=(0, math.inf, ()))(call)
    call.stream = parse
    return call


pnt, pnti, pnts = (_make_pnt(3, s) for s in ("", "i", "s"))
pnt2, pnt2i, pnt2s = (_make_pnt(2, s) for s in ("", "i", "s"))


# -- pmv / pdr / pclos: an old-style polygon, vertex by vertex --------------------------
def _make_pmv(dim: int, suffix: str):
    name = _family("pmv", dim == 2, suffix)

    def parse(args: tuple) -> list:
        p = _point(coords(name, args, dim, _FORMS[suffix]))
        return [("bgn", "pmv"), ("v", p), ("g", p)]

    return stream_call(name, parse, f"{name}(...): start a filled polygon at this point "
                                    f"(pmv(3G)); continue with pdr, close with pclos. "
                                    f"Colour, normal and v* calls may come in between.")


def _make_pdr(dim: int, suffix: str):
    name = _family("pdr", dim == 2, suffix)

    def parse(args: tuple) -> list:
        p = _point(coords(name, args, dim, _FORMS[suffix]))
        return [("pv", p), ("g", p)]

    return stream_call(name, parse, f"{name}(...): the next vertex of the polygon "
                                    f"started by pmv (pdr(3G)).")


pmv, pmvi, pmvs = (_make_pmv(3, s) for s in ("", "i", "s"))
pmv2, pmv2i, pmv2s = (_make_pmv(2, s) for s in ("", "i", "s"))
pdr, pdri, pdrs = (_make_pdr(3, s) for s in ("", "i", "s"))
pdr2, pdr2i, pdr2s = (_make_pdr(2, s) for s in ("", "i", "s"))


def _pclos_parse(args: tuple) -> list:
    return [("end", "pmv")]


pclos = stream_call("pclos", _pclos_parse,
                    "pclos(): close and fill the polygon started by pmv (pclos(3G)).")


def _relative(ctx, d: tuple[float, ...]) -> tuple[float, float, float, float]:
    x, y, z, w = ctx.gpos
    dz = d[2] if len(d) == 3 else 0.0
    return (x + d[0], y + d[1], z + dz, w)


def _make_rpoly(dim: int, suffix: str, first: bool):
    name = _family("rpmv" if first else "rpdr", dim == 2, suffix)
    integer = _FORMS[suffix]

    @gl_function(record=True)
    def call(*args) -> None:
        ctx = current(name, args)
        p = _relative(ctx, coords(name, args, dim, integer))
        ops = [("bgn", "pmv"), ("v", p), ("g", p)] if first else [("pv", p), ("g", p)]
        apply_ops(ctx, name, args, ops)

    call.__name__ = call.__qualname__ = name
    call.__doc__ = (f"{name}(...): like {'pmv' if first else 'pdr'}, relative to the "
                    f"current graphics position.")
    return call


rpmv, rpmvi, rpmvs = (_make_rpoly(3, s, True) for s in ("", "i", "s"))
rpmv2, rpmv2i, rpmv2s = (_make_rpoly(2, s, True) for s in ("", "i", "s"))
rpdr, rpdri, rpdrs = (_make_rpoly(3, s, False) for s in ("", "i", "s"))
rpdr2, rpdr2i, rpdr2s = (_make_rpoly(2, s, False) for s in ("", "i", "s"))


# -- move / draw -----------------------------------------------------------------------
# A draw is recorded in the command stream as one two-vertex segment (BGN DRAW_SEG, the
# current graphics position and the new point, END), drawn at the flush with the
# line-style pattern continued from where the last line drawn before it left it;
# a move under resetls(TRUE) makes the next one a DRAW_RESTART (pattern at 0).  So
# the pattern runs exactly as when each draw was drawn at its call, which drained
# the stream and rasterized the segment there (~90 us a call).
_SEG_OPS = (BGN, DRAW_SEG, V, V, END)
_RESTART_OPS = (BGN, DRAW_RESTART, V, V, END)


def _move_to(ctx, p) -> None:
    ctx.gpos = p
    if ctx.resetls:
        ctx.ls_restart = True  # a move starts a new polyline: the pattern restarts


def _draw_to(ctx, p) -> None:
    """One segment from the current graphics position, continuing the pattern, in
    the current colour at both ends (and normal, lit as the last colour/normal call
    says), transformed by the matrix current now."""
    if ctx.ls_restart:
        ctx.ls_restart = False
        _record_closed(ctx, _RESTART_OPS, ctx.gpos + p)
    else:
        _record_closed(ctx, _SEG_OPS, ctx.gpos + p)
    ctx.gpos = p


def _make_move(base: str, dim: int, suffix: str):
    name = _family(base, dim == 2, suffix)
    integer = _FORMS[suffix]
    relative = base.startswith("r")
    drawing = base.endswith("dr") or base.endswith("draw")

    def body(*args) -> None:
        ctx = current(name, args)
        _not_in_primitive(ctx, name, args)
        vals = coords(name, args, dim, integer)
        p = _relative(ctx, vals) if relative else _point(vals)
        if drawing:
            _draw_to(ctx, p)
        else:
            _move_to(ctx, p)

    def general(*args, **kwargs) -> None:
        if kwargs or session.recording is not None:
            return record_or_refuse(call, args, kwargs)
        body(*args)

    # Valid paths (FAST_CALLS): two or three finite floats (the float forms) or ints
    # of 32 bits (the i/s forms, as float(v), coords' value), outside bgn*/end*;
    # anything else -- one tuple, a keyword, a wrong count or type, recording --
    # takes the general path, which validates and raises as it always did.
    step = _draw_to if drawing else _move_to

    def call2(x=_NO, y=_NO, /, *more, **kw) -> None:
        ctx = session.imm
        if (ctx is None or kw or more or ctx.prim is not None
                or type(x) is not float or type(y) is not float
                or x - x != 0.0 or y - y != 0.0):  # (x - x: NaN for NaN and inf)
            return general(*given((x, y), more), **kw)
        step(ctx, (x, y, 0.0, 1.0))

    def call3(x=_NO, y=_NO, z=_NO, /, *more, **kw) -> None:
        ctx = session.imm
        if (ctx is None or kw or more or ctx.prim is not None
                or type(x) is not float or type(y) is not float or type(z) is not float
                or x - x != 0.0 or y - y != 0.0 or z - z != 0.0):
            return general(*given((x, y, z), more), **kw)
        step(ctx, (x, y, z, 1.0))

    def call2i(x=_NO, y=_NO, /, *more, **kw) -> None:
        ctx = session.imm
        if (ctx is None or kw or more or ctx.prim is not None
                or type(x) is not int or type(y) is not int
                or not (INT_MIN <= x <= INT_MAX and INT_MIN <= y <= INT_MAX)):
            return general(*given((x, y), more), **kw)
        step(ctx, (float(x), float(y), 0.0, 1.0))

    def call3i(x=_NO, y=_NO, z=_NO, /, *more, **kw) -> None:
        ctx = session.imm
        if (ctx is None or kw or more or ctx.prim is not None
                or type(x) is not int or type(y) is not int or type(z) is not int
                or not (INT_MIN <= x <= INT_MAX and INT_MIN <= y <= INT_MAX
                        and INT_MIN <= z <= INT_MAX)):
            return general(*given((x, y, z), more), **kw)
        step(ctx, (float(x), float(y), float(z), 1.0))

    if relative:
        call = general
    else:
        call = {(2, False): call2, (3, False): call3,
                (2, True): call2i, (3, True): call3i}[dim, integer]
    call.__name__ = call.__qualname__ = name
    if drawing:
        call.__doc__ = (f"{name}(...): draw a line from the current graphics position to "
                        f"{'it plus ' if relative else ''}this point, which becomes the "
                        f"current graphics position (draw(3G)).")
    else:
        call.__doc__ = (f"{name}(...): move the current graphics position "
                        f"{'by' if relative else 'to'} this point; starts a new polyline "
                        f"(move(3G)).")
    return gl_function(record=True, binds=(0, math.inf, ()))(call)


move, movei, moves = (_make_move("move", 3, s) for s in ("", "i", "s"))
move2, move2i, move2s = (_make_move("move", 2, s) for s in ("", "i", "s"))
draw, drawi, draws = (_make_move("draw", 3, s) for s in ("", "i", "s"))
draw2, draw2i, draw2s = (_make_move("draw", 2, s) for s in ("", "i", "s"))
rmv, rmvi, rmvs = (_make_move("rmv", 3, s) for s in ("", "i", "s"))
rmv2, rmv2i, rmv2s = (_make_move("rmv", 2, s) for s in ("", "i", "s"))
rdr, rdri, rdrs = (_make_move("rdr", 3, s) for s in ("", "i", "s"))
rdr2, rdr2i, rdr2s = (_make_move("rdr", 2, s) for s in ("", "i", "s"))


@gl_function(record=False)
def getgpos(*args) -> tuple[float, float, float, float]:
    """getgpos() -> (fx, fy, fz, fw): the current graphics position "after
    transformation by the current matrix" (getgpos(3G)), i.e. in clip coordinates."""
    ctx = current("getgpos", args)
    clip = apply(np.array([ctx.gpos], dtype=np.float64), ctx.matrices.mvp())[0]
    return tuple(float(c) for c in clip)


# -- circles and arcs ---------------------------------------------------------------------
def circle_segments(ctx, x: float, y: float, r: float) -> int:
    """Chords for a full circle so that none is more than 1/8 pixel inside the circle
    (see the module docstring), from its radius in pixels under the current matrix."""
    pts = np.array([[x, y, 0.0, 1.0], [x + r, y, 0.0, 1.0], [x, y + r, 0.0, 1.0]])
    view = ctx.viewing()
    with np.errstate(all="ignore"):  # huge radii overflow to inf: handled below
        clip = apply(pts, view.mvp)
        if not np.all(clip[:, 3] > 0):
            return MIN_SEGMENTS
        l, rt, b, t = view.viewport
        win = np.stack([clip[:, 0] / clip[:, 3] * (rt - l + 1) / 2,
                        clip[:, 1] / clip[:, 3] * (t - b + 1) / 2], axis=1)
        r_px = float(max(np.hypot(*(win[1] - win[0])), np.hypot(*(win[2] - win[0]))))
    if not math.isfinite(r_px) or r_px <= CHORD_TOLERANCE:
        return MIN_SEGMENTS
    half_angle = math.acos(1.0 - CHORD_TOLERANCE / r_px)
    # Past ~1e15 pixels 1 - 0.125/r rounds to 1 and the angle to 0: the clamp applies.
    if half_angle <= math.pi / MAX_SEGMENTS:
        return MAX_SEGMENTS
    n = math.ceil(math.pi / half_angle)
    return max(MIN_SEGMENTS, min(MAX_SEGMENTS, n))


def _sweep(startang: int, endang: int) -> int:
    """Counter-clockwise sweep in tenths of a degree (0 = nothing to draw)."""
    sweep = (endang - startang) % 3600
    if sweep == 0 and endang != startang:
        sweep = 3600
    return sweep


def _arc_points(x: float, y: float, r: float, start: float, sweep: float, n: int
                ) -> np.ndarray:
    a = np.radians((start + sweep * np.arange(n + 1) / n) / 10.0)
    pts = np.zeros((n + 1, 4))
    pts[:, 0] = x + r * np.cos(a)
    pts[:, 1] = y + r * np.sin(a)
    pts[:, 3] = 1.0
    return pts


def _draw_shape(ctx, kind: str, obj: np.ndarray, indices=None) -> None:
    n = obj.shape[0]
    cols = np.broadcast_to(np.asarray(ctx.colour, np.float64), (n, 4))
    nrms = np.broadcast_to(np.asarray(ctx.normal, np.float64), (n, 3))
    lit = lit_mask(ctx, np.full(n, ctx.last_sent == "normal"))
    ctx.draw_arrays(kind, obj, cols, nrms, lit, indices=indices)


def _circle_args(name: str, args: tuple, integer: bool, with_angles: bool):
    n = 5 if with_angles else 3
    if len(args) == 1 and isinstance(args[0], (list, tuple)):
        args = tuple(args[0])  # the binding accepted one tuple for several arguments
    if len(args) != n:
        raise GLTypeError(f"{describe(name, args)}: expected {n} arguments, got {len(args)}")
    if integer:
        x, y, r = (float(as_int(name, args, w, v)) for w, v in zip("xyr", args, strict=False))
    else:
        x, y, r = (as_float(name, args, w, v) for w, v in zip("xyr", args, strict=False))
    if not all(math.isfinite(v) for v in (x, y, r)):
        raise GLValueError(f"{describe(name, args)}: x, y and radius must be finite")
    if r < 0:
        raise GLValueError(f"{describe(name, args)}: radius must not be negative")
    angles = tuple(as_angle(name, args, a) for a in args[3:]) if with_angles else ()
    return (x, y, r) + angles


def _make_circle(filled: bool, suffix: str):
    name = f"circ{'f' if filled else ''}{suffix}"
    integer = _FORMS[suffix]

    @gl_function(record=True)
    def call(*args) -> None:
        ctx = current(name, args)
        x, y, r = _circle_args(name, args, integer, False)
        _not_in_primitive(ctx, name, args)
        if r == 0:
            return
        n = circle_segments(ctx, x, y, r)
        pts = _arc_points(x, y, r, 0.0, 3600.0, n)[:-1]
        _draw_shape(ctx, "polygon" if filled else "closedline", pts)

    call.__name__ = call.__qualname__ = name
    call.__doc__ = (f"{name}(x, y, radius): {'fill' if filled else 'outline'} a circle "
                    f"in the plane z = 0 (circ(3G)); segment count in the module "
                    f"docstring.")
    return call


def _make_arc(filled: bool, suffix: str):
    name = f"arc{'f' if filled else ''}{suffix}"
    integer = _FORMS[suffix]

    @gl_function(record=True)
    def call(*args) -> None:
        ctx = current(name, args)
        x, y, r, sa, ea = _circle_args(name, args, integer, True)
        _not_in_primitive(ctx, name, args)
        sweep = _sweep(sa, ea)
        if r == 0 or sweep == 0:
            return
        full = circle_segments(ctx, x, y, r)
        n = max(2, math.ceil(full * sweep / 3600))
        pts = _arc_points(x, y, r, float(sa), float(sweep), n)
        if not filled:
            _draw_shape(ctx, "line", pts)
            return
        obj = np.concatenate([[[x, y, 0.0, 1.0]], pts])
        i = np.arange(1, n + 1, dtype=np.int64)
        fan = np.stack([np.zeros_like(i), i, i + 1], axis=1)  # counter-clockwise slices
        _draw_shape(ctx, "triangles", obj, indices=fan)

    call.__name__ = call.__qualname__ = name
    call.__doc__ = (f"{name}(x, y, radius, startang, endang): "
                    f"{'a filled pie section' if filled else 'an arc'} counter-clockwise "
                    f"from startang to endang (Angles, tenths of a degree from +x), z = 0 "
                    f"(arc(3G)).")
    return call


circ, circi, circs = (_make_circle(False, s) for s in ("", "i", "s"))
circf, circfi, circfs = (_make_circle(True, s) for s in ("", "i", "s"))
arc, arci, arcs = (_make_arc(False, s) for s in ("", "i", "s"))
arcf, arcfi, arcfs = (_make_arc(True, s) for s in ("", "i", "s"))
