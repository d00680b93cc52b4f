"""IRIS GL calls: display objects -- genobj, makeobj, closeobj, callobj, delobj, isobj.

While ``makeobj`` is open, every recordable gl call is stored in the object instead
of being executed ("subsequent graphics routines are compiled into the display list
instead of executing", makeobj(3G)); queries still execute.  ``callobj`` replays the
object; "if callobj specifies an undefined object, the system ignores the routine"
(callobj(3G)), and state changed inside an object stays changed for the caller.
Objects are looked up when called, so an object may call one defined later; an object
that (directly or through others) calls itself raises :class:`GLUsageError`.

**Fast replay.**  Calling a recorded vertex call per vertex would cost as much as
immediate mode.  ``closeobj`` therefore compiles every maximal *run* of consecutive
vertex-stream calls -- bgn*/end*, v*, n3f, t2*, swaptmesh, varray, the old-style
polygon, rectangle and point calls, and the colour calls of :mod:`._color` -- into
numpy arrays, and ``callobj`` replays a run with one ``Context.draw_arrays`` per group
of primitives: consecutive polygons, tmeshes and qstrips become one 'triangles' draw
whose index array keeps each polygon's fan and whose ``provoking`` array keeps the
flat-shading vertex of each primitive (the polygon's last vertex, a tmesh triangle's
newest, a quad's fourth); consecutive point primitives become one point draw; lines
stay one draw each (their line-style pattern restarts at every bgnline).  Calls
between runs (matrix, raster, lighting calls, callobj, ...) are replayed as calls.
The result is pixel-identical to immediate mode (tests/gl/test_objects.py).

Colour calls inside a run are evaluated at compile time on a private 1x1 scratch
context that has the caller's colour-relevant state (RGB/cmode, whether lighting is
active, lmcolor mode, multimap): their effect (``colour``, ``colour_index``,
``last_sent``, ``lmcolor_set``) is read back, probing twice to find which attributes
they set and which they leave as the caller had them (LMC_NULL ignores colours, the
material modes leave ``last_sent``).  That evaluation is cached per such state, so a
changed lmcolor mode or lighting on/off recompiles the run's colours once.  Runs that
cannot be compiled this way (malformed, e.g. vertices of a primitive opened by the
caller, or a colour call whose effect depends on the caller's colour) are replayed as
calls, which is always correct.  While ``concave(TRUE)`` is in effect polygons are
drawn one by one (their triangulation depends on the window projection).
"""

from __future__ import annotations

import gc
from dataclasses import dataclass, field

import numpy as np

from vgxsim.geometry import assembly
from vgxsim.state.context import Context

from ._core import (
    GLError,
    GLTypeError,
    GLUsageError,
    GLValueError,
    as_int,
    current,
    describe,
    gl_function,
    session,
)
from ._draw import DRAW_KIND, lit_mask

__all__ = ["genobj", "makeobj", "closeobj", "callobj", "delobj", "isobj", "getopenobj"]

MAX_OBJECT = 2**31 - 1  # Object is a 31-bit integer (makeobj(3G))
COLOUR_CALLS = frozenset({"cpack", "RGBcolor", "c3f", "c4f", "c3i", "c4i", "c3s", "c4s",
                          "color", "colorf"})
#: Context attributes a colour call may change (see gl/_color.py).
TRACKED = ("colour", "colour_index", "last_sent", "lmcolor_set")
_INHERIT = object()  # "whatever the caller's value is when the run is replayed"
_PROBES = (
    {"colour": (0.125, 0.25, 0.375, 0.5), "colour_index": 1, "last_sent": "normal",
     "lmcolor_set": False},
    {"colour": (0.625, 0.75, 0.875, 1.0), "colour_index": 2, "last_sent": "colour",
     "lmcolor_set": True},
)
_SCRATCH_ID = "<vgxsim display-object scratch>"
_replaying: list[int] = []  # objects being replayed, innermost last


# -- the object store ----------------------------------------------------------------------
@dataclass
class DisplayObject:
    """A recorded object: the raw calls and the compiled program.

    Attributes
    ----------
    calls : list of (callable, tuple)
        What was recorded, in order.
    program : list
        ``('call', func, args)`` and ``('run', _Run)`` entries, in order.
    """

    calls: list = field(default_factory=list)
    program: list = field(default_factory=list)

    # Make an object look like the list _core's session.objects documents.
    def __len__(self) -> int:
        return len(self.calls)

    def __iter__(self):
        return iter(self.calls)


def _object_arg(name: str, args: tuple) -> int:
    if len(args) != 1:
        raise GLTypeError(f"{describe(name, args)}: expected 1 argument, got {len(args)}")
    obj = as_int(name, args, "obj", args[0])
    if not 0 <= obj <= MAX_OBJECT:
        raise GLValueError(f"{describe(name, args)}: an Object is a 31-bit integer "
                           f"(0..{MAX_OBJECT})")
    return obj


@gl_function(record=False)
def genobj(*args) -> int:
    """genobj() -> int: an object number not in use (genobj(3G))."""
    current("genobj", args)
    n = getattr(session, "next_object", 1)
    while n in session.objects or n == session.open_object:
        n += 1
    session.next_object = n + 1
    return n


@gl_function(record=False)
def makeobj(*args) -> None:
    """makeobj(obj): start recording object ``obj``, deleting any object of that number.
    Not allowed while another object is open (makeobj(3G): immediate mode only)."""
    obj = _object_arg("makeobj", args)
    current("makeobj", args)
    if session.open_object is not None:
        raise GLUsageError(f"{describe('makeobj', args)}: object {session.open_object} is "
                           f"still open (call closeobj first; objects cannot be nested)")
    session.objects[obj] = DisplayObject()  # entered in the symbol table now
    session.open_object = obj
    session.recording = []


@gl_function(record=False)
def closeobj(*args) -> None:
    """closeobj(): finish the open object and compile it for fast replay."""
    ctx = current("closeobj", args)
    if session.open_object is None:
        raise GLUsageError(f"{describe('closeobj', args)}: no object is open (makeobj)")
    obj, calls = session.open_object, session.recording
    session.open_object = None
    session.recording = None
    # Compiling allocates many small tuples that all survive; the cyclic garbage
    # collector would rescan them again and again (more than half the time for a
    # 10k-triangle object), so it is paused meanwhile.
    was_enabled = gc.isenabled()
    gc.disable()
    try:
        dobj = DisplayObject(calls=list(calls), program=compile_calls(calls))
        session.objects[obj] = dobj
        for entry in dobj.program:  # prepare the colours for the window it is made in
            if entry[0] == "run":
                entry[1].compiled(ctx)
    finally:
        if was_enabled:
            gc.enable()


@gl_function(record=False)
def getopenobj(*args) -> int:
    """getopenobj() -> int: the object being defined, or -1."""
    return -1 if session.open_object is None else int(session.open_object)


@gl_function(record=True)
def callobj(*args) -> None:
    """callobj(obj): draw an instance of ``obj``; undefined objects are ignored."""
    obj = _object_arg("callobj", args)
    ctx = current("callobj", args)
    dobj = session.objects.get(obj)
    if dobj is None:
        return
    if obj in _replaying:
        chain = " -> ".join(str(o) for o in _replaying + [obj])
        raise GLUsageError(f"{describe('callobj', args)}: object {obj} calls itself "
                           f"({chain}); recursive objects would never end")
    _replaying.append(obj)
    try:
        replay(ctx, dobj)
    finally:
        _replaying.pop()


@gl_function(record=False)
def delobj(*args) -> None:
    """delobj(obj): delete an object (unknown numbers are ignored)."""
    obj = _object_arg("delobj", args)
    current("delobj", args)
    if obj == session.open_object:
        raise GLUsageError(f"{describe('delobj', args)}: object {obj} is open (closeobj "
                           f"first)")
    session.objects.pop(obj, None)


@gl_function(record=False)
def isobj(*args) -> int:
    """isobj(obj) -> 1 if ``obj`` is a defined object, else 0."""
    obj = _object_arg("isobj", args)
    current("isobj", args)
    return int(obj in session.objects)


# -- compiling -----------------------------------------------------------------------------
def _is_colour_call(func) -> bool:
    inner = getattr(func, "__wrapped__", func)
    return (getattr(inner, "__module__", "") == "vgxsim.gl._color"
            and getattr(inner, "__name__", "") in COLOUR_CALLS)


def _stream_ops(func, args) -> list | None:
    """The stream operations of a recorded call, or None if it is not one of them
    (or its arguments are bad: then it stays a call and fails when replayed)."""
    parse = getattr(func, "stream", None)
    if parse is not None:
        try:
            return parse(args)
        except GLError:
            return None
    if _is_colour_call(func):
        return [("c", func, args)]
    return None


def compile_calls(calls: list) -> list:
    """Split recorded calls into replayed calls and compiled runs."""
    program: list = []
    pending: list = []  # (func, args, ops) of the current run

    def close_run():
        if not pending:
            return
        run = _Run.build(pending)
        if run is None:
            program.extend(("call", f, a) for f, a, _ in pending)
        else:
            program.append(("run", run))
        pending.clear()

    for func, args in calls:
        ops = _stream_ops(func, args)
        if ops is None:
            close_run()
            program.append(("call", func, args))
        else:
            pending.append((func, args, ops))
    close_run()
    return program


@dataclass
class _Prim:
    prim: str  # 'polygon', 'tmesh', 'qstrip', 'line', 'closedline', 'point', 'pmv'
    v0: int
    v1: int
    swaps: list


class _Run:
    """A well-formed stretch of vertex-stream calls, compiled to arrays."""

    def __init__(self, calls, ops, obj, prims, has_colour):
        self.calls = calls  # [(func, args)] for replay as calls
        self.ops = ops
        self.obj = obj  # (N, 4) float64
        self.prims = prims
        self.has_colour = has_colour
        self._cache: dict = {}

    @classmethod
    def build(cls, pending) -> _Run | None:
        """Check the run is well formed (every vertex inside a primitive it opens and
        closes) and build the vertex array; None if it is not."""
        ops, pos, prims = [], [], []
        prim, v0, swaps = None, 0, []
        for _f, _a, fops in pending:
            for op in fops:
                tag = op[0]
                if tag == "bgn":
                    if prim is not None:
                        return None
                    prim, v0, swaps = op[1], len(pos), []
                elif tag == "end":
                    if prim != op[1]:
                        return None
                    prims.append(_Prim(prim, v0, len(pos), swaps))
                    prim = None
                elif tag in ("v", "pv"):
                    if prim is None or (tag == "pv" and prim != "pmv"):
                        return None
                    pos.append(op[1])
                elif tag == "swap":
                    if prim != "tmesh":
                        return None
                    swaps.append(len(pos) - v0)
                ops.append(op)
        if prim is not None:
            return None
        obj = np.array(pos, dtype=np.float64).reshape(-1, 4)
        has_colour = any(op[0] == "c" for op in ops)
        return cls([(f, a) for f, a, _ in pending], ops, obj, prims, has_colour)

    # -- per-state compilation ------------------------------------------------------
    def compiled(self, ctx) -> _Compiled | None:
        """The arrays for the caller's colour state (cached); None if this run must be
        replayed as calls in that state."""
        key = _colour_key(ctx) if self.has_colour else None
        if key not in self._cache:
            self._cache[key] = _compile_run(self, ctx, key)
        return self._cache[key]


@dataclass
class _Compiled:
    colours: np.ndarray  # (N, 4)
    colour_inherit: np.ndarray  # (N,) bool: use the caller's colour
    normals: np.ndarray  # (N, 3)
    normal_inherit: np.ndarray
    sent: np.ndarray  # (N,) bool: normal sent after the last colour
    sent_inherit: np.ndarray
    groups: list  # (kind, v0, v1, indices, provoking, prims, lmcolor_set or _INHERIT)
    final: dict  # attribute -> value to leave in the context


def _colour_key(ctx) -> tuple:
    """Everything gl/_color.py reads when it sets the current colour."""
    return (bool(ctx.config.rgb), bool(ctx.lighting_active()), int(ctx.lmcolor_mode),
            bool(getattr(ctx, "multimap", False)), int(getattr(ctx, "curmap", 0)))


_scratches: dict = {}


def _scratch(key: tuple) -> Context:
    ctx = _scratches.get(key)
    if ctx is None:
        rgb, lit, lmcolor, multimap, curmap = key
        ctx = Context(1, 1, rgb=rgb, zbits=0)
        ctx.lmcolor_mode = lmcolor
        ctx.multimap = multimap
        ctx.curmap = curmap
        ctx.lighting_active = lambda: lit  # shadows the method: no lmdef tables needed
        _scratches[key] = ctx
    return ctx


def _run_colour_call(scratch: Context, func, args, prior: dict) -> dict:
    for k, v in prior.items():
        setattr(scratch, k, v)
    saved = session.current, session.windows.get(_SCRATCH_ID)
    session.windows[_SCRATCH_ID] = scratch
    session.current = _SCRATCH_ID
    try:
        getattr(func, "__wrapped__", func)(*args)
    finally:
        session.current = saved[0]
        del session.windows[_SCRATCH_ID]
    return {k: getattr(scratch, k) for k in prior}


class _NotCompilable(Exception):
    pass


def _freeze(v):
    """A hashable stand-in for call arguments (lists and arrays become tuples)."""
    if isinstance(v, np.ndarray):
        return ("array", v.dtype.str, v.shape, tuple(v.reshape(-1).tolist()))
    if isinstance(v, (list, tuple)):
        return (type(v).__name__,) + tuple(_freeze(x) for x in v)
    hash(v)
    return (type(v).__name__, v)


def _colour_effect(scratch: Context, func, args, state: dict, memo: dict) -> dict:
    """The state after a colour call, attribute by attribute known or _INHERIT
    (memoised: meshes repeat the same few colours)."""
    try:
        key = (func, _freeze(args), tuple((k, _freeze(v) if v is not _INHERIT else None)
                                          for k, v in state.items()))
    except TypeError:
        return _colour_effect_uncached(scratch, func, args, state)
    out = memo.get(key)
    if out is None:
        out = memo[key] = _colour_effect_uncached(scratch, func, args, state)
    return dict(out)


def _colour_effect_uncached(scratch: Context, func, args, state: dict) -> dict:
    if all(v is not _INHERIT for v in state.values()):
        return _run_colour_call(scratch, func, args, dict(state))
    priors = [{k: (p[k] if v is _INHERIT else v) for k, v in state.items()} for p in _PROBES]
    post = [_run_colour_call(scratch, func, args, p) for p in priors]
    out = {}
    for k, v in state.items():
        if post[0][k] == post[1][k]:
            out[k] = post[0][k]
        elif v is _INHERIT and post[0][k] == priors[0][k] and post[1][k] == priors[1][k]:
            out[k] = _INHERIT
        else:
            raise _NotCompilable(k)
    return out


def _compile_run(run: _Run, ctx, key) -> _Compiled | None:
    n = run.obj.shape[0]
    colours = np.zeros((n, 4))
    col_inh = np.zeros(n, bool)
    normals = np.zeros((n, 3))
    nrm_inh = np.zeros(n, bool)
    sent = np.zeros(n, bool)
    sent_inh = np.zeros(n, bool)
    tracked = [k for k in TRACKED if hasattr(ctx, k)]
    state = {k: _INHERIT for k in tracked}
    normal, texcoord, gpos = _INHERIT, _INHERIT, _INHERIT
    scratch = _scratch(key) if key is not None else None
    prim_state = []  # lmcolor_set when each primitive is drawn
    memo: dict = {}
    v = 0
    try:
        for op in run.ops:
            tag = op[0]
            if tag in ("v", "pv"):
                c = state.get("colour", _INHERIT)
                if c is _INHERIT:
                    col_inh[v] = True
                else:
                    colours[v] = c
                if normal is _INHERIT:
                    nrm_inh[v] = True
                else:
                    normals[v] = normal
                ls = state.get("last_sent", _INHERIT)
                if ls is _INHERIT:
                    sent_inh[v] = True
                else:
                    sent[v] = ls == "normal"
                v += 1
            elif tag == "c":
                state = _colour_effect(scratch, op[1], op[2], state, memo)
            elif tag == "n":
                normal = op[1]
                if "last_sent" in state:
                    state["last_sent"] = "normal"
            elif tag == "t":
                texcoord = op[1]
            elif tag == "g":
                gpos = op[1]
            elif tag == "end":
                prim_state.append(state.get("lmcolor_set", _INHERIT))
    except (GLError, _NotCompilable):
        return None
    final = {k: val for k, val in state.items() if val is not _INHERIT}
    for k, val in (("normal", normal), ("texcoord", texcoord), ("gpos", gpos)):
        if val is not _INHERIT:
            final[k] = val
    return _Compiled(colours, col_inh, normals, nrm_inh, sent, sent_inh,
                     _groups(run, prim_state), final)


_TRIANGLE_PRIMS = ("polygon", "pmv", "tmesh", "qstrip")


def _same(a, b) -> bool:
    if a is _INHERIT or b is _INHERIT:
        return a is b
    return a == b


def _groups(run: _Run, prim_state: list) -> list:
    """Merge consecutive primitives that can share one draw_arrays call."""
    groups = []
    for p, lms in zip(run.prims, prim_state, strict=True):
        if p.v1 == p.v0:
            continue  # bgn*/end* without vertices draws nothing
        cls = ("tri" if p.prim in _TRIANGLE_PRIMS else "point" if p.prim == "point"
               else "line")
        last = groups[-1] if groups else None
        if (last is not None and cls != "line" and last["cls"] == cls
                and _same(last["lms"], lms) and last["v1"] == p.v0):
            last["prims"].append(p)
            last["v1"] = p.v1
        else:
            groups.append({"cls": cls, "lms": lms, "v0": p.v0, "v1": p.v1, "prims": [p]})
    out = []
    for g in groups:
        indices = provoking = None
        if g["cls"] == "tri":
            tris, prov, fans = [], [], []
            for p in g["prims"] + [None]:
                if p is not None and p.prim in ("polygon", "pmv"):
                    fans.append((p.v0 - g["v0"], p.v1 - p.v0))
                    continue
                if fans:  # a block of consecutive polygons, fanned in one go
                    t, pv = _fans(fans)
                    tris.append(t)
                    prov.append(pv)
                    fans = []
                if p is not None:
                    t, pv = _prim_triangles(p)
                    tris.append(t + (p.v0 - g["v0"]))
                    prov.append(pv + (p.v0 - g["v0"]))
            indices = np.concatenate(tris).astype(np.int64)
            provoking = np.concatenate(prov).astype(np.int64)
            kind = "triangles"
        elif g["cls"] == "point":
            kind = "point"
        else:
            kind = DRAW_KIND[g["prims"][0].prim]
        out.append((kind, g["v0"], g["v1"], indices, provoking, g["prims"], g["lms"]))
    return out


def _fans(polys: list[tuple[int, int]]) -> tuple[np.ndarray, np.ndarray]:
    """Fan triangles (first, i, i + 1) of consecutive polygons given as (start, size),
    in order, with each polygon's last vertex as the flat-shading vertex -- what
    assembly.polygon_fan gives each polygon, for many polygons at once."""
    start, size = (np.array(v, dtype=np.int64) for v in zip(*polys, strict=True))
    ntri = np.maximum(size - 2, 0)
    first = np.repeat(start, ntri)
    # k = 0 .. ntri-1 within each polygon
    k = np.arange(int(ntri.sum()), dtype=np.int64) - np.repeat(np.cumsum(ntri) - ntri, ntri)
    tris = np.stack([first, first + 1 + k, first + 2 + k], axis=1)
    return tris, np.repeat(start + size - 1, ntri)


def _prim_triangles(p: _Prim) -> tuple[np.ndarray, np.ndarray]:
    """Triangles of one primitive (local indices) and each one's flat-shading vertex,
    as Context.draw_arrays builds them for that primitive."""
    n = p.v1 - p.v0
    if p.prim in ("polygon", "pmv"):
        tris = assembly.polygon_fan(n)
        return tris, np.full(tris.shape[0], n - 1, np.int64)
    if p.prim == "tmesh":
        tris = assembly.tmesh_triangles(n, list(p.swaps))
        return tris, tris[:, 2].copy()
    tris = assembly.qstrip_triangles(n)
    return tris, tris.max(axis=1) if tris.shape[0] else np.zeros(0, np.int64)


# -- replaying -------------------------------------------------------------------------------
def replay(ctx, dobj: DisplayObject) -> None:
    """Execute a compiled object on ``ctx``."""
    for entry in dobj.program:
        if entry[0] == "call":
            entry[1](*entry[2])
        else:
            _replay_run(ctx, entry[1])


def _replay_calls(run: _Run) -> None:
    for func, args in run.calls:
        func(*args)


def _replay_run(ctx, run: _Run) -> None:
    comp = run.compiled(ctx) if ctx.prim is None else None
    if comp is None:
        _replay_calls(run)
        return
    cols = comp.colours
    if comp.colour_inherit.any():
        cols = cols.copy()
        cols[comp.colour_inherit] = ctx.colour
    nrms = comp.normals
    if comp.normal_inherit.any():
        nrms = nrms.copy()
        nrms[comp.normal_inherit] = ctx.normal
    sent = comp.sent
    if comp.sent_inherit.any():
        sent = sent.copy()
        sent[comp.sent_inherit] = ctx.last_sent == "normal"
    lit = lit_mask(ctx, sent)
    obj = run.obj
    for kind, v0, v1, indices, provoking, prims, lms in comp.groups:
        if lms is not _INHERIT:
            ctx.lmcolor_set = lms
        sl = slice(v0, v1)
        if kind == "triangles" and ctx.concave and any(
                p.prim in ("polygon", "pmv") and p.v1 - p.v0 > 3 for p in prims):
            # concave(TRUE): triangulation depends on the projection; draw one by one.
            for p in prims:
                ps = slice(p.v0, p.v1)
                ctx.draw_arrays(DRAW_KIND[p.prim], obj[ps], cols[ps], nrms[ps], lit[ps],
                                swaps=list(p.swaps))
            continue
        ctx.draw_arrays(kind, obj[sl], cols[sl], nrms[sl], lit[sl], indices=indices,
                        provoking=provoking)
    for k, val in comp.final.items():
        setattr(ctx, k, val)

