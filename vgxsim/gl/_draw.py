"""IRIS GL calls: primitives (bgn*/end*) and vertex, normal and texture-coordinate calls.

A primitive is opened with ``bgnpolygon``, ``bgntmesh``, ``bgnqstrip``, ``bgnline``,
``bgnclosedline`` or ``bgnpoint`` and closed with the matching ``end*``.  Each vertex
call (``v2f``, ``v3i``, ``v4d``, ...) records its position together with the colour
current at that moment, the current normal and whether the vertex is lit -- so a
colour changed between vertices gives Gouraud shading, and with
``lmcolor(LMC_COLOR)`` "whichever of colour or normal was sent last" decides whether
the vertex is lit or coloured (lmcolor(3G); ``Context.last_sent``, which the colour
calls of :mod:`._color` set to ``'colour'`` and ``n3f`` to ``'normal'``).  ``end*``
records one END op; no array is made until the stream is decoded.

Argument conventions follow CPython's historical ``gl`` binding
(shared/reference/cpython_gl_module.md 1.4-1.6): ``v3f(x, y, z)`` and
``v3f((x, y, z))`` both work; the ``s``/``i`` forms take ints only; ``varray``,
``vnarray`` and ``nvarray`` take lists of point tuples.

Every call appends to the window's command stream (:mod:`vgxsim.stream`): a vertex
is one opcode and four floats; the current colour, normal and lit flag are sent as
one SYNC op before a vertex only when they changed since the last vertex (compared
by identity: the colour and normal calls store new tuples), and the draw state is
sent as one STATE op at bgn* only when it changed.  The stream is decoded at a flush
(:mod:`vgxsim.pipeline.decode`).

Every call here is also described to the display-object recorder (:mod:`._objects`)
by a ``stream`` attribute: a function from the call's arguments to a list of *stream
operations* (validated exactly as the call itself validates):

* ``('bgn', prim)`` / ``('end', prim)`` -- prim is 'polygon', 'tmesh', 'qstrip',
  'line', 'closedline', 'point' or 'pmv' (the old-style pmv/pdr/pclos polygon);
* ``('v', xyzw)`` a vertex; ``('pv', xyzw)`` a vertex that must be inside pmv (pdr);
* ``('n', nxyz)`` the current normal; ``('t', st)`` the texture coordinate;
* ``('swap',)`` swaptmesh; ``('g', xyzw)`` the current graphics position.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

from vgxsim.pipeline.decode import drain
from vgxsim.stream.opcodes import BGN, END, KIND_OF, STATE, SWAP, SYNC, T, V
from vgxsim.stream.recorder import MAX_STREAM_OPS, StateMemo

from . import _core
from ._core import (
    _NO,
    INT_MAX,
    INT_MIN,
    GLTypeError,
    GLUsageError,
    GLValueError,
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

__all__ = [
    "bgnpolygon", "endpolygon", "bgntmesh", "swaptmesh", "endtmesh", "bgnqstrip",
    "endqstrip", "bgnline", "endline", "bgnclosedline", "endclosedline", "bgnpoint",
    "endpoint",
    "v2s", "v2i", "v2f", "v2d", "v3s", "v3i", "v3f", "v3d", "v4s", "v4i", "v4f", "v4d",
    "n3f", "normal", "t2s", "t2i", "t2f", "t2d", "concave", "varray", "vnarray", "nvarray",
]

#: Which Context.draw_arrays kind each open primitive draws as.
DRAW_KIND = {"polygon": "polygon", "tmesh": "tmesh", "qstrip": "qstrip", "line": "line",
             "closedline": "closedline", "point": "point", "pmv": "polygon"}
#: The call that opens each primitive (for error messages).
OPENER = {"polygon": "bgnpolygon", "tmesh": "bgntmesh", "qstrip": "bgnqstrip",
          "line": "bgnline", "closedline": "bgnclosedline", "point": "bgnpoint",
          "pmv": "pmv"}
CLOSER = {"polygon": "endpolygon", "tmesh": "endtmesh", "qstrip": "endqstrip",
          "line": "endline", "closedline": "endclosedline", "point": "endpoint",
          "pmv": "pclos"}


# -- argument parsing (shared by immediate mode and the display-object compiler) -----
def coords(name: str, args: tuple, n: int, integer: bool = False) -> tuple[float, ...]:
    """``n`` coordinates as floats, from ``f(x, y, z)`` or ``f((x, y, z))``.

    Integer forms (``v3i``, ``v3s``, ...) accept only ints, as the binding's
    ``PyInt_Check`` did; every value must be finite (a NaN or infinite coordinate has
    no place on the screen; use w = 0 for points at infinity).
    """
    seq = args
    if len(args) == 1:
        a0 = args[0]
        if type(a0) in (tuple, list):
            seq = a0
        elif type(a0) is np.ndarray and a0.ndim == 1 and a0.dtype.kind == "f" and (
                not integer):
            seq = a0.tolist()  # numpy rows (library users, the 1991 example): floats
    if len(seq) == n:
        # Fast path for the common call with plain Python numbers.
        if integer:
            if all(type(a) is int for a in seq):
                return tuple(float(a) for a in seq)
        elif all(type(a) is float or type(a) is int for a in seq):
            vals = tuple(float(a) for a in seq)
            if all(math.isfinite(v) for v in vals):
                return vals
            _not_finite(name, args)
    vals = tuple(float(v) for v in flat_numbers(name, args, n, integer=integer))
    if not all(math.isfinite(v) for v in vals):
        _not_finite(name, args)
    return vals


def _not_finite(name: str, args: tuple) -> None:
    raise GLValueError(f"{describe(name, args)}: coordinates must be finite numbers")


def _no_args(name: str, args: tuple) -> None:
    """Calls without parameters.  The historical binding never looked at the
    arguments of such stubs (``bgnpolygon(1)`` worked); here they are ignored too."""


def _xyzw(vals: tuple[float, ...]) -> tuple[float, float, float, float]:
    if len(vals) == 2:
        return (vals[0], vals[1], 0.0, 1.0)
    if len(vals) == 3:
        return (vals[0], vals[1], vals[2], 1.0)
    return vals  # type: ignore[return-value]


# -- appending to the window's stream -------------------------------------------------
def same_state(ctx, st) -> bool:
    """Whether the stream's last STATE op still describes the window's draw state
    (identity of the raster snapshot, the composite matrix and the depth range, which
    are replaced, never mutated, on change; equality of the serials)."""
    snap = ctx.raster._snapshot
    return (snap is not None and snap is st.raster and ctx.matrices._mvp is st.mvp
            and ctx.depth_range is st.depth and ctx.lighting_serial == st.lighting_serial
            and ctx.concave is st.concave and ctx.vertex_serial == st.vertex_serial)


def _restate(ctx, st) -> None:
    """Record the window's draw state (a STATE op) if it changed since the last one."""
    if same_state(ctx, st):
        return
    _restate_changed(ctx, st)


def _restate_changed(ctx, st) -> None:
    """:func:`_restate` where the caller has found the state changed (``same_state``
    false)."""
    mats = ctx.matrices
    if mats._mvp is None and st.mvp is not None:
        # No composite since the last matrix change: form it now (intern would), and
        # if it is the very one recorded -- a popmatrix back to the matrix of the last
        # STATE op, matrices.KEEP_MVPS -- the recorded state still holds.
        mats.mvp()
        if same_state(ctx, st):
            return
    regs = ctx.raster
    snap = regs._snapshot
    idx = -1
    if (snap is not None and st.raster is not None and ctx.matrices._mvp is st.mvp
            and st.mvp is not None and ctx.depth_range is st.depth
            and ctx.lighting_serial == st.lighting_serial and ctx.concave is st.concave
            and ctx.vertex_serial == st.vertex_serial):
        # Only the raster snapshot changed since the last STATE op (the 1991 shadow
        # faces: stencil() before each): the record interned for this snapshot under
        # the same other parts, if the table still holds it (FAST_CALLS).
        hit = st.state_memo.get(id(snap))
        if hit is not None and hit.snapshot is snap:
            recs = ctx.states.records
            if hit.index < len(recs) and recs[hit.index] is hit.record:
                idx = hit.index
    else:
        st.state_memo.clear()  # other parts changed: the records found so far differ
    if idx < 0:
        if session.imm is ctx and _core.REPLAY_OBJECTS:  # (immediate mode)
            # A record made before for this state, kept across flushes (a frame
            # draws the states of the last one again).
            idx = ctx.states.intern_kept(ctx)
        else:
            idx = ctx.states.intern(ctx)
        snap = regs._snapshot
        if session.imm is ctx:
            if len(st.state_memo) >= 256:
                st.state_memo.clear()
            st.state_memo[id(snap)] = StateMemo(snap, idx, ctx.states.records[idx])
    st.raster = regs._snapshot
    st.mvp = ctx.matrices._mvp
    st.depth = ctx.depth_range
    st.lighting_serial = ctx.lighting_serial
    st.plain_colour = False  # (callobj finds it anew under this state)
    st.concave = ctx.concave
    st.vertex_serial = ctx.vertex_serial
    st.ops.append(STATE)
    st.ops.append(idx)


def sync(ctx, st) -> None:
    """Send the current colour, normal and lit flag (a SYNC op)."""
    c, nrm, ls, lms = ctx.colour, ctx.normal, ctx.last_sent, ctx.lmcolor_set
    ops = st.ops
    ops.append(SYNC)
    ops.append(1 if ls == "normal" else 0)
    ops.append(1 if lms else 0)
    st.fl.extend(c)
    st.fl.extend(nrm)
    st.colour, st.normal, st.sent, st.lmcolor_set = c, nrm, ls, lms


def begin(ctx, name: str, args: tuple, prim: str) -> None:
    """Open a primitive; GLUsageError if one is already open."""
    if ctx.prim is not None:
        raise GLUsageError(f"{describe(name, args)}: {OPENER[ctx.prim]}() is still open "
                           f"(call {CLOSER[ctx.prim]}() first)")
    st = ctx.stream
    if ctx.ls_restart and prim in ("line", "closedline"):
        ctx.restart_pattern()  # a move under resetls(TRUE) came before this line
    if len(st.ops) > MAX_STREAM_OPS:  # (spliced parts are bounded in CommandStream.splice)
        drain(ctx)
    _restate(ctx, st)
    ctx.prim = prim
    st.open_ops = st.parts_ops + len(st.ops)
    st.open_fl = st.parts_fl + len(st.fl)
    st.ops.append(BGN)
    st.ops.append(KIND_OF[prim])


def _outside(name: str, args: tuple, prim, need) -> None:
    where = "outside bgn*/end*" if prim is None else f"inside {OPENER[prim]}()"
    hint = f"call {OPENER[need]}() first" if need else "call bgnpolygon(), bgnline(), ... first"
    raise GLUsageError(f"{describe(name, args)}: vertex {where} ({hint})")


def vertex(ctx, name: str, args: tuple, xyzw, need: str | None = None) -> None:
    """Record one vertex with the current colour and normal (per-vertex Gouraud)."""
    prim = ctx.prim
    if prim is None or (need is not None and prim != need):
        _outside(name, args, prim, need)
    st = ctx.stream
    if (ctx.colour is not st.colour or ctx.normal is not st.normal
            or ctx.last_sent is not st.sent or ctx.lmcolor_set is not st.lmcolor_set):
        sync(ctx, st)
    st.ops.append(V)
    st.fl.extend(xyzw)


def end(ctx, name: str, args: tuple, prim: str) -> None:
    """Close the open primitive (drawn at the next flush)."""
    if ctx.prim != prim:
        state = "no primitive is open" if ctx.prim is None else f"{OPENER[ctx.prim]}() is open"
        raise GLUsageError(f"{describe(name, args)}: without {OPENER[prim]}() ({state})")
    ctx.prim = None
    # (No drain for lines: a draw after this line continues its pattern from
    # Context.linestyle_pos when the stream is decoded, its DRAW_SEG row.)
    ctx.stream.ops.append(END)


def swap(ctx, name: str, args: tuple) -> None:
    if ctx.prim != "tmesh":
        raise GLUsageError(f"{describe(name, args)}: swaptmesh outside "
                           f"bgntmesh()/endtmesh()")
    ctx.stream.ops.append(SWAP)


def lit_mask(ctx, normal_sent: np.ndarray) -> np.ndarray:
    """Which vertices are lit: with LMC_COLOR those whose normal was sent after the
    last colour; in every other lmcolor mode colour calls change the material (or are
    ignored, LMC_NULL), so every vertex is lit (lmcolor(3G))."""
    if ctx.lmcolor_mode != 0:
        return np.ones(normal_sent.shape[0], dtype=bool)
    return normal_sent


def apply_ops(ctx, name: str, args: tuple, ops) -> None:
    """Execute stream operations (see the module docstring) on ``ctx``."""
    for op in ops:
        tag = op[0]
        if tag == "v":
            vertex(ctx, name, args, op[1])
        elif tag == "pv":
            vertex(ctx, name, args, op[1], need="pmv")
        elif tag == "n":
            ctx.normal = tuple(op[1])
            ctx.last_sent = "normal"
        elif tag == "t":
            ctx.texcoord = op[1]
            # Recorded only when called: untextured streams carry nothing more.
            ctx.stream.ops.append(T)
            ctx.stream.fl.extend(op[1])
            ctx.stream.has_texcoords = True
        elif tag == "g":
            ctx.gpos = op[1]
        elif tag == "bgn":
            begin(ctx, name, args, op[1])
        elif tag == "end":
            end(ctx, name, args, op[1])
        elif tag == "swap":
            swap(ctx, name, args)
        else:  # pragma: no cover - programming error
            raise AssertionError(tag)


def stream_call(name: str, parse: Callable[[tuple], list], doc: str):
    """Build a recordable gl call from its stream parser: the call validates its
    arguments with ``parse`` and applies the operations to the current window."""

    def call(*args):
        ops = parse(args)
        apply_ops(current(name, args), name, args, ops)

    call.__name__ = call.__qualname__ = name
    call.__doc__ = doc
    wrapped = gl_function(record=True)(call)
    wrapped.stream = parse
    return wrapped


# -- primitives ------------------------------------------------------------------------
def _bgn(prim: str):
    name = OPENER[prim]
    code = KIND_OF[prim]
    lines = prim in ("line", "closedline")  # (a pending move's restart: general path)

    def parse(args: tuple) -> list:
        _no_args(name, args)
        return [("bgn", prim)]

    def general(*args, **kwargs):
        if session.recording is not None or kwargs:
            return record_or_refuse(call, args, kwargs)
        begin(current(name, args), name, args, prim)

    def call(*args, **kwargs):
        ctx = session.imm
        if ctx is None or kwargs or ctx.prim is not None or (lines and ctx.ls_restart):
            return general(*args, **kwargs)
        st = ctx.stream
        ops = st.ops
        if len(ops) > MAX_STREAM_OPS:  # (spliced parts are bounded in CommandStream.splice)
            return general(*args)
        snap = ctx.raster._snapshot  # same_state(ctx, st), inlined (one call less)
        if not (snap is not None and snap is st.raster and ctx.matrices._mvp is st.mvp
                and ctx.depth_range is st.depth
                and ctx.lighting_serial == st.lighting_serial
                and ctx.concave is st.concave and ctx.vertex_serial == st.vertex_serial):
            _restate(ctx, st)
        ctx.prim = prim
        st.open_ops = st.parts_ops + len(ops)
        st.open_fl = st.parts_fl + len(st.fl)
        ops.append(BGN)
        ops.append(code)

    call.__name__ = call.__qualname__ = name
    call.__doc__ = f"{name}(): open a {prim} primitive ({name}(3G))."
    call = gl_function(record=True, binds=(0, math.inf, ()))(call)
    call.stream = parse
    return call


def _end(prim: str):
    name = CLOSER[prim]

    def parse(args: tuple) -> list:
        _no_args(name, args)
        return [("end", prim)]

    def general(*args, **kwargs):
        if session.recording is not None or kwargs:
            return record_or_refuse(call, args, kwargs)
        end(current(name, args), name, args, prim)

    def call(*args, **kwargs):
        ctx = session.imm
        # (ctx.prim holds the very string begin stored: identity is equality here.)
        if ctx is None or kwargs or ctx.prim is not prim:
            return general(*args, **kwargs)
        ctx.prim = None
        ctx.stream.ops.append(END)

    call.__name__ = call.__qualname__ = name
    call.__doc__ = (f"{name}(): close the {prim} and draw it; GLUsageError without "
                    f"{OPENER[prim]}().")
    call = gl_function(record=True, binds=(0, math.inf, ()))(call)
    call.stream = parse
    return call


bgnpolygon, endpolygon = _bgn("polygon"), _end("polygon")
bgntmesh, endtmesh = _bgn("tmesh"), _end("tmesh")
bgnqstrip, endqstrip = _bgn("qstrip"), _end("qstrip")
bgnline, endline = _bgn("line"), _end("line")
bgnclosedline, endclosedline = _bgn("closedline"), _end("closedline")
bgnpoint, endpoint = _bgn("point"), _end("point")

bgnpolygon.__doc__ += (" Polygons must be convex unless concave(TRUE); they are fanned "
                       "from the first vertex; shademodel(FLAT) uses the last vertex's "
                       "colour.")
bgntmesh.__doc__ += (" Each vertex after the second forms a triangle with the two saved "
                     "vertices and replaces the older; swaptmesh() exchanges them.")


def _swap_parse(args: tuple) -> list:
    _no_args("swaptmesh", args)
    return [("swap",)]


swaptmesh = stream_call(
    "swaptmesh", _swap_parse,
    "swaptmesh(): exchange the two saved tmesh vertices, so the next triangle pivots "
    "on the other one (fans: swaptmesh before every vertex after the third).")


# -- vertices ----------------------------------------------------------------------------
_W = {2: (0.0, 1.0), 3: (1.0,), 4: ()}  # what a vertex call appends after its values


# Fast-path tests: n plain floats, all finite (x - x is NaN for NaN and inf).
def _plain2(s) -> bool:
    if len(s) != 2:
        return False
    x, y = s
    return type(x) is float and type(y) is float and x - x == 0.0 and y - y == 0.0


def _plain3(s) -> bool:
    if len(s) != 3:
        return False
    x, y, z = s
    return (type(x) is float and type(y) is float and type(z) is float
            and x - x == 0.0 and y - y == 0.0 and z - z == 0.0)


def _plain4(s) -> bool:
    if len(s) != 4:
        return False
    x, y, z, w = s
    return (type(x) is float and type(y) is float and type(z) is float and type(w) is float
            and x - x == 0.0 and y - y == 0.0 and z - z == 0.0 and w - w == 0.0)


def _never(s) -> bool:
    return False


_PLAIN = {2: _plain2, 3: _plain3, 4: _plain4}


def _vertex_call(n: int, suffix: str):
    name = f"v{n}{suffix}"
    integer = suffix in ("s", "i")
    tail = _W[n]
    fast = _never if integer else _PLAIN[n]

    def parse(args: tuple) -> list:
        return [("v", _xyzw(coords(name, args, n, integer)))]

    def emit(ctx, args: tuple) -> None:
        seq = args
        if len(args) == 1:
            a0 = args[0]
            if type(a0) is tuple or type(a0) is list:
                seq = a0
            elif type(a0) is np.ndarray and not integer and a0.ndim == 1:
                seq = a0.tolist()
        vals = seq if fast(seq) else coords(name, args, n, integer)
        st = ctx.stream
        if (ctx.colour is not st.colour or ctx.normal is not st.normal
                or ctx.last_sent is not st.sent or ctx.lmcolor_set is not st.lmcolor_set):
            sync(ctx, st)
        st.ops.append(V)
        fl = st.fl
        fl.extend(vals)
        if tail:
            fl.extend(tail)

    def general(*args, **kwargs):
        if session.recording is not None or kwargs:
            return record_or_refuse(call, args, kwargs)
        ctx = current(name, args)
        if ctx.prim is None:
            _outside(name, args, None, None)
        emit(ctx, args)

    def call(*args, **kwargs):
        ctx = session.imm
        if ctx is None or kwargs or ctx.prim is None:
            return general(*args, **kwargs)
        emit(ctx, args)

    def call3(x=_NO, y=_NO, z=_NO, /, *more, **kw):
        # v3f/v3d, the hottest call there is: three finite floats, or one tuple or
        # list of them, into an open primitive, with a SYNC only when the colour,
        # normal or lit flag changed; everything else takes the general path.
        ctx = session.imm
        p = None
        if z is _NO and y is _NO and (type(x) is tuple or type(x) is list) and len(x) == 3:
            p = x
            x, y, z = p
        if (ctx is None or kw or more or ctx.prim is None
                or type(x) is not float or type(y) is not float or type(z) is not float
                or x - x != 0.0 or y - y != 0.0 or z - z != 0.0):  # (x - x: NaN, inf)
            return general(*((p,) if p is not None else given((x, y, z), more)), **kw)
        st = ctx.stream
        if (ctx.colour is not st.colour or ctx.normal is not st.normal
                or ctx.last_sent is not st.sent or ctx.lmcolor_set is not st.lmcolor_set):
            sync(ctx, st)
        st.ops.append(V)
        fl = st.fl
        fl.append(x)
        fl.append(y)
        fl.append(z)
        fl.append(1.0)

    def call3i(x=_NO, y=_NO, z=_NO, /, *more, **kw):
        # v3i/v3s: three ints 32-bit or smaller (as the IRIS GL long is) into an open
        # primitive; float(v) is the general path's coords() value.
        ctx = session.imm
        if (ctx is None or kw or more or ctx.prim is None
                or type(x) is not int or type(y) is not int or type(z) is not int
                or not (INT_MIN <= x <= INT_MAX and INT_MIN <= y <= INT_MAX
                        and INT_MIN <= z <= INT_MAX)):
            return general(*given((x, y, z), more), **kw)
        st = ctx.stream
        if (ctx.colour is not st.colour or ctx.normal is not st.normal
                or ctx.last_sent is not st.sent or ctx.lmcolor_set is not st.lmcolor_set):
            sync(ctx, st)
        st.ops.append(V)
        fl = st.fl
        fl.append(float(x))
        fl.append(float(y))
        fl.append(float(z))
        fl.append(1.0)

    if n == 3 and not integer:
        call = call3  # noqa: F811 - the specialised form replaces the generic one
    elif n == 3:
        call = call3i  # noqa: F811
    kind = "ints" if integer else "numbers"
    call.__name__ = call.__qualname__ = name
    call.__doc__ = (f"{name}(...): a vertex from {n} {kind}, as {name}(x, ...) or "
                    f"{name}((x, ...)); only between bgn* and end* (v(3G)).")
    call = gl_function(record=True, binds=(0, math.inf, ()))(call)
    call.stream = parse
    return call


v2s, v2i, v2f, v2d = (_vertex_call(2, s) for s in "sifd")
v3s, v3i, v3f, v3d = (_vertex_call(3, s) for s in "sifd")
v4s, v4i, v4f, v4d = (_vertex_call(4, s) for s in "sifd")


def _normal_call(name: str, doc: str):
    def parse(args: tuple) -> list:
        return [("n", coords(name, args, 3))]

    def general(*args, **kwargs):
        if session.recording is not None or kwargs:
            return record_or_refuse(call, args, kwargs)
        ctx = current(name, args)
        seq = args
        if len(args) == 1:
            a0 = args[0]
            if type(a0) is tuple:
                seq = a0
            elif type(a0) is np.ndarray and a0.ndim == 1:
                seq = tuple(a0.tolist())
        if not _plain3(seq):
            seq = coords(name, args, 3)
        ctx.normal = seq  # a tuple of 3 floats, new at every call (the stream's sync)
        ctx.last_sent = "normal"

    def call(x=_NO, y=_NO, z=_NO, /, *more, **kw):
        ctx = session.imm
        p = None
        if z is _NO and y is _NO and type(x) is tuple and len(x) == 3:
            p = x  # the caller's tuple is the normal (tuples never change)
            x, y, z = p
        if (ctx is None or kw or more
                or type(x) is not float or type(y) is not float or type(z) is not float
                or x - x != 0.0 or y - y != 0.0 or z - z != 0.0):
            return general(*((p,) if p is not None else given((x, y, z), more)), **kw)
        ctx.normal = (x, y, z) if p is None else p  # new: the next vertex syncs
        ctx.last_sent = "normal"

    call.__name__ = call.__qualname__ = name
    call.__doc__ = doc
    call = gl_function(record=True, binds=(0, math.inf, ()))(call)
    call.stream = parse
    return call


n3f = _normal_call("n3f", "n3f((nx, ny, nz)) or n3f(nx, ny, nz): the current normal; with "
                          "lmcolor(LMC_COLOR) the following vertices are lit (n3f(3G)).")
normal = _normal_call("normal", "normal((nx, ny, nz)): the obsolete form of n3f.")


def _tex_call(suffix: str):
    name = f"t2{suffix}"
    integer = suffix in ("s", "i")
    doc = (f"{name}((s, t)): the current texture coordinate (t2(3G)); stored in "
           f"Context.texcoord.")

    def parse(args: tuple) -> list:
        return [("t", coords(name, args, 2, integer))]

    if integer:
        return stream_call(name, parse, doc)

    def general(*args, **kwargs):
        if kwargs or session.recording is not None:
            return record_or_refuse(call, args, kwargs)
        apply_ops(current(name, args), name, args, parse(args))

    def call(s=_NO, t=_NO, /, *more, **kw):
        # t2f/t2d (per vertex in a textured program): two finite floats, or one tuple
        # or list of them; apply_ops' "t" operation, inlined.
        ctx = session.imm
        p = None
        if t is _NO and (type(s) is tuple or type(s) is list) and len(s) == 2:
            p = s
            s, t = p
        if (ctx is None or kw or more or type(s) is not float or type(t) is not float
                or s - s != 0.0 or t - t != 0.0):
            return general(*((p,) if p is not None else given((s, t), more)), **kw)
        ctx.texcoord = (s, t)
        st = ctx.stream
        st.ops.append(T)
        fl = st.fl
        fl.append(s)
        fl.append(t)
        st.has_texcoords = True

    call.__name__ = call.__qualname__ = name
    call.__doc__ = doc
    call = gl_function(record=True, binds=(0, math.inf, ()))(call)
    call.stream = parse
    return call


t2s, t2i, t2f, t2d = (_tex_call(s) for s in "sifd")


@gl_function(record=True)
def concave(*args) -> None:
    """concave(b): TRUE lets bgnpolygon/endpolygon (and polf) draw concave polygons,
    triangulated in window space by ear clipping; FALSE (the default) fans them."""
    if len(args) != 1:
        raise GLTypeError(f"{describe('concave', args)}: expected 1 argument, got "
                          f"{len(args)}")
    b = as_int("concave", args, "b", args[0])
    current("concave", args).concave = bool(b)


# -- hand-written array helpers of the historical binding --------------------------
def _seq(name: str, args: tuple, what: str):
    if len(args) != 1:
        raise GLTypeError(f"{describe(name, args)}: expected 1 argument ({what}), got "
                          f"{len(args)}")
    seq = args[0]
    if isinstance(seq, np.ndarray):
        seq = seq.tolist()
    if not isinstance(seq, (list, tuple)):
        raise GLTypeError(f"{describe(name, args)}: {what} must be a list or tuple, not "
                          f"{type(seq).__name__}")
    return seq


def _point(name: str, args: tuple, p, width: int | None) -> tuple[float, ...]:
    if not isinstance(p, (list, tuple)):
        raise GLTypeError(f"{describe(name, args)}: each point must be a list or tuple, "
                          f"not {type(p).__name__}")
    if width is not None and len(p) != width:
        raise GLTypeError(f"{describe(name, args)}: points must all have {width} "
                          f"coordinates (the first point's), got {len(p)}")
    if len(p) not in (2, 3):
        raise GLTypeError(f"{describe(name, args)}: points have 2 or 3 coordinates, got "
                          f"{len(p)}")
    vals = tuple(as_float(name, args, "coordinate", v) for v in p)
    if not all(math.isfinite(v) for v in vals):
        _not_finite(name, args)
    return vals


def _varray_parse(args: tuple) -> list:
    pts = _seq("varray", args, "points")
    if not pts:
        return []
    width = len(pts[0]) if isinstance(pts[0], (list, tuple)) else None
    return [("v", _xyzw(_point("varray", args, p, width))) for p in pts]


varray = stream_call(
    "varray", _varray_parse,
    "varray(points): send each point of a list of 2- or 3-tuples as a vertex (v3d, "
    "z = 0 for 2-D); all points as wide as the first (the binding's hand-written helper).")


def _pairs_parse(name: str, normal_first: bool):
    def parse(args: tuple) -> list:
        ops = []
        order = "(normal, vertex)" if normal_first else "(vertex, normal)"
        for pair in _seq(name, args, "pairs"):
            if not isinstance(pair, tuple) or len(pair) != 2:
                raise GLTypeError(f"{describe(name, args)}: each element must be a "
                                  f"2-tuple {order}")
            nrm, vtx = (pair[0], pair[1]) if normal_first else (pair[1], pair[0])
            n3 = _point(name, args, nrm, 3)
            ops.append(("n", n3))
            ops.append(("v", _xyzw(_point(name, args, vtx, 3))))
        return ops

    return parse


nvarray = stream_call(
    "nvarray", _pairs_parse("nvarray", True),
    "nvarray(pairs): for each 2-tuple (normal, vertex) call n3f(normal) then "
    "v3f(vertex).")
vnarray = stream_call(
    "vnarray", _pairs_parse("vnarray", False),
    "vnarray(pairs): for each 2-tuple (vertex, normal) call n3f(normal) then "
    "v3f(vertex).")
