"""IRIS GL calls: display objects -- genobj, makeobj, closeobj, callobj, delobj, isobj.

While ``makeobj`` is open, every recordable gl call is stored in the object instead
of being executed ("subsequent graphics routines are compiled into the display list
instead of executing", makeobj(3G)); queries still execute.  ``callobj`` replays the
object; "if callobj specifies an undefined object, the system ignores the routine"
(callobj(3G)), and state changed inside an object stays changed for the caller.
Objects are looked up when called, so an object may call one defined later; an object
that (directly or through others) calls itself raises :class:`GLUsageError`.

**Recorded as a stream.**  An object is a list of *segments*: chunks of vertex-stream
calls (bgn*/end*, v*, n3f, t2*, swaptmesh, varray, the old-style polygon, rectangle
and point calls and the RGB colour calls), recorded with the opcodes of the
immediate-mode command stream (:mod:`vgxsim.stream`), and the other calls (matrix,
raster, lighting calls, callobj, ...) as (call, arguments).  ``callobj`` splices each
chunk into the window's stream -- two buffer copies -- and replays the calls, which
append to the stream themselves; the flush decodes everything alike, so an object
draws exactly what immediate mode draws (tests/gl/test_objects.py,
tests/stream/test_random_streams.py).  A colour call's effect depends on the
caller's lighting (lmcolor(3G)), so chunks record colours as CRAW ops, rewritten at
the splice for the caller's state.

**Validated when recorded.**  Every call is checked as it is recorded, as in
immediate mode (argument count, keywords, types, values of the stream calls,
bgn*/end* nesting inside the object); a call that fails raises at once and leaves the
object as it was.  What depends on the caller -- a vertex of a primitive the caller
opened, a colour call in a colour-map window -- is checked at the callobj.

**Nesting.**  callobj inside objects runs on an explicit stack, not Python's:
at most :data:`MAX_NESTING` objects deep (a GLUsageError past it).
"""

from __future__ import annotations

from vgxsim import GL
from vgxsim.stream.opcodes import BGN, CM, CRAW, CSKIP, END, KIND_OF, SWAP, N, T, V
from vgxsim.stream.opcodes import C as C_OP
from vgxsim.stream.recorder import Chunk

from ._core import (
    GLTypeError,
    GLUsageError,
    GLValueError,
    as_int,
    check_types,
    current,
    describe,
    gl_function,
    session,
)
from ._draw import CLOSER, OPENER, _restate, sync

__all__ = ["genobj", "makeobj", "closeobj", "callobj", "delobj", "isobj", "getopenobj",
           "MAX_NESTING"]

MAX_OBJECT = 2**31 - 1  # Object is a 31-bit integer (makeobj(3G))
#: Deepest callobj nesting (objects calling objects).  IRIS GL documents no limit;
#: this one keeps a runaway chain (an object calling a long list of others) bounded.
MAX_NESTING = 256
_ANY = "any"  # a chunk's first vertex needs some primitive open


# -- the object store ----------------------------------------------------------------------
class DisplayObject:
    """A recorded object: segments in order, each a :class:`Chunk` or (call, args)."""

    def __init__(self, segments: list | None = None):
        self.segments: list = segments if segments is not None else []

    @property
    def program(self) -> list:
        """('run', chunk) and ('call', func, args) entries, in order."""
        return [("run", g) if isinstance(g, Chunk) else ("call", g[0], g[1])
                for g in self.segments]

    def __len__(self) -> int:
        return len(self.segments)


class ObjectRecorder:
    """What recordable calls append to while makeobj is open."""

    def __init__(self):
        self.segments: list = []
        self.chunk: Chunk | None = None
        self.prim = None  # primitive open inside the chunk (None: as the chunk began)
        self.known = False  # whether ``prim`` is known (the chunk opened or closed one)

    def append(self, item) -> None:
        call, args = item
        parse = getattr(call, "stream", None)
        if parse is not None:
            self._stream_ops(call.__name__, args, parse(args))
            return
        rgba = getattr(call, "stream_rgba", None)
        if rgba is not None:
            self._colour(call.__name__, args, rgba(args))
            return
        if getattr(call, "gl_arity", None) is not None:
            check_types(call, args)
        self.chunk = None
        self.segments.append((call, args))

    def _current_chunk(self) -> Chunk:
        if self.chunk is None:
            self.chunk = Chunk()
            self.segments.append(self.chunk)
            self.prim, self.known = None, False
        return self.chunk

    def _colour(self, name: str, args: tuple, rgba: tuple) -> None:
        ch = self._current_chunk()
        ch.ops.append(CRAW)
        ch.fl.extend(rgba)
        if ch.last_colour is None:
            ch.first_colour_call = (name, args)
        ch.last_colour = rgba
        ch.normal_after_colour = False

    def _stream_ops(self, name: str, args: tuple, ops: list) -> None:
        # Check the whole call before recording any of it: an error leaves the
        # object as it was.
        prim, known = self.prim, self.known
        needs = None
        for op in ops:
            tag = op[0]
            if tag == "bgn":
                if known and prim is not None or (not known and prim == _ANY):
                    cur = prim if prim != _ANY else "a primitive"
                    raise GLUsageError(f"{describe(name, args)}: "
                                       f"{OPENER.get(cur, cur)}() is still open")
                if not known:
                    needs = needs or ("closed", name, args)
                prim, known = op[1], True
            elif tag == "end":
                if known and prim != op[1]:
                    state = ("no primitive is open" if prim is None
                             else f"{OPENER[prim]}() is open")
                    raise GLUsageError(f"{describe(name, args)}: without "
                                       f"{OPENER[op[1]]}() ({state})")
                if not known:
                    needs = needs or (op[1], name, args)
                prim, known = None, True
            elif tag in ("v", "pv", "swap"):
                want = {"v": None, "pv": "pmv", "swap": "tmesh"}[tag]
                if known:
                    if prim is None or (want is not None and prim != want):
                        raise GLUsageError(f"{describe(name, args)}: "
                                           f"{'swaptmesh' if tag == 'swap' else 'vertex'} "
                                           f"outside its primitive")
                elif prim is None:
                    needs = needs or (want or _ANY, name, args)
                    prim = want or _ANY
        ch = self._current_chunk()
        if needs is not None and ch.needs is None and not self.known:
            ch.needs, ch.needs_call = needs[0], (needs[1], needs[2])
        self.prim, self.known = prim, known
        for op in ops:
            tag = op[0]
            if tag in ("v", "pv"):
                ch.ops.append(V)
                ch.fl.extend(op[1])
            elif tag == "n":
                ch.ops.append(N)
                ch.fl.extend(op[1])
                ch.last_normal = tuple(op[1])
                ch.normal_after_colour = True
            elif tag == "bgn":
                ch.touched_prim = True
                ch.open_at = (len(ch.ops), len(ch.fl))
                ch.ops.append(BGN)
                ch.ops.append(KIND_OF[op[1]])
                ch.open = op[1]
            elif tag == "end":
                ch.touched_prim = True
                ch.ops.append(END)
                ch.open = None
                if op[1] in ("line", "closedline"):
                    ch.has_lines = True
            elif tag == "swap":
                ch.ops.append(SWAP)
            elif tag == "t":
                ch.ops.append(T)
                ch.fl.extend(op[1])
                ch.texcoord = op[1]
            elif tag == "g":
                ch.gpos = op[1]


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
    n = session.next_object
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
    session.recording = ObjectRecorder()


@gl_function(record=False)
def closeobj(*args) -> None:
    """closeobj(): finish the open object."""
    current("closeobj", args)
    if session.open_object is None:
        raise GLUsageError(f"{describe('closeobj', args)}: no object is open (makeobj)")
    obj, rec = session.open_object, session.recording
    session.open_object = None
    session.recording = None
    session.objects[obj] = DisplayObject(rec.segments)


@gl_function(record=False)
def getopenobj(*args) -> int:
    """getopenobj() -> int: the object being defined, or -1."""
    return -1 if session.open_object is None else int(session.open_object)


@gl_function(record=True)
def callobj(*args) -> None:
    """callobj(obj): draw an instance of ``obj``; undefined objects are ignored.

    Nested objects run on an explicit stack, at most MAX_NESTING deep."""
    obj = _object_arg("callobj", args)
    ctx = current("callobj", args)
    dobj = session.objects.get(obj)
    if dobj is None:
        return
    chain = [obj]
    stack = [(dobj.segments, 0)]
    while stack:
        segments, i = stack.pop()
        if i >= len(segments):
            chain.pop()
            continue
        stack.append((segments, i + 1))
        seg = segments[i]
        if isinstance(seg, Chunk):
            splice(ctx, seg)
            continue
        func, fargs = seg
        if func is callobj:
            inner = _object_arg("callobj", fargs)
            inner_obj = session.objects.get(inner)
            if inner_obj is None:
                continue
            if inner in chain:
                path = " -> ".join(str(o) for o in chain + [inner])
                raise GLUsageError(f"{describe('callobj', args)}: object {inner} calls "
                                   f"itself ({path}); recursive objects would never end")
            if len(chain) >= MAX_NESTING:
                raise GLUsageError(f"{describe('callobj', args)}: objects nested more than "
                                   f"{MAX_NESTING} deep (vgxsim's limit, MAX_NESTING)")
            chain.append(inner)
            stack.append((inner_obj.segments, 0))
            continue
        func(*fargs)


def _colour_op(ctx) -> int:
    """What a recorded RGB colour call does in the caller's state (lmcolor(3G))."""
    if not ctx.lighting_active():
        return C_OP
    if ctx.lmcolor_mode == GL.LMC_NULL:
        return CSKIP
    return C_OP if ctx.lmcolor_mode == GL.LMC_COLOR else CM


def _check_needs(ctx, ch: Chunk) -> None:
    need = ch.needs
    if need is None:
        return
    prim = ctx.prim
    name, args = ch.needs_call
    if need == "closed":
        if prim is not None:
            raise GLUsageError(f"{describe(name, args)}: {OPENER[prim]}() is still open "
                               f"(call {CLOSER[prim]}() first)")
    elif prim is None or (need != _ANY and prim != need):
        state = "no primitive is open" if prim is None else f"{OPENER[prim]}() is open"
        raise GLUsageError(f"{describe(name, args)}: needs {OPENER.get(need, 'bgn*')}() "
                           f"open ({state})")


def splice(ctx, ch: Chunk) -> None:
    """Append a chunk to the window's stream and leave the caller's current
    attributes as the chunk's calls would have."""
    _check_needs(ctx, ch)
    colour_op = C_OP
    if ch.last_colour is not None:
        if not ctx.config.rgb:
            name, args = ch.first_colour_call
            raise GLUsageError(f"{describe(name, args)}: it is an error to call {name} while "
                               "the framebuffer is in colour map mode (cpack(3G)); use "
                               "color()")
        colour_op = _colour_op(ctx)
    st = ctx.stream
    if ch.touched_prim and ctx.prim is None:
        _restate(ctx, st)
    sync(ctx, st)
    base_ops, base_fl = len(st.ops), len(st.fl)
    st.ops.extend(ch.ops_for(colour_op))
    st.fl.extend(ch.fl)
    if ch.touched_prim:
        ctx.prim = ch.open
        if ch.open is not None:
            st.open_ops, st.open_fl = base_ops + ch.open_at[0], base_fl + ch.open_at[1]
    if ch.last_colour is not None and colour_op != CSKIP:
        ctx.colour = ch.last_colour
        if colour_op == CM:
            ctx.lmcolor_set = True
    if ch.last_normal is not None:
        ctx.normal = ch.last_normal
    if colour_op == C_OP and ch.last_colour is not None and not ch.normal_after_colour:
        ctx.last_sent = "colour"
    elif ch.last_normal is not None:
        ctx.last_sent = "normal"
    if ch.texcoord is not None:
        ctx.texcoord = ch.texcoord
        st.has_texcoords = True
    if ch.gpos is not None:
        ctx.gpos = ch.gpos
    st.colour = None  # the decoder's attributes are the chunk's now: sync anew
    if ch.has_lines:
        from vgxsim.pipeline.decode import drain

        drain(ctx)


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


