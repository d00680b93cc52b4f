"""IRIS GL calls: display objects -- genobj, makeobj, closeobj, callobj, delobj, isobj,
and their editing: editobj, maketag, gentag, istag, deltag, objinsert, objdelete,
objreplace, chunksize, compactify.

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

**Prepared replays** (``_core.REPLAY_OBJECTS``).  An object of stencil() calls and
small closed chunks (the 1991 program's cached shadow faces) is replayed from a
:class:`ReplayBlock`: what the first callobj appended, appended again while the
caller's state is the same (identities of the raster snapshot, matrices,
attributes; the lighting by value, StateTable.lighting_token), its STATE ops
re-indexed once per flush -- and under another composite matrix too, its STATE ops
pointed at the records of the same raster snapshots under the caller's matrix
(:func:`_rebase`): an object drawn under a moving transform is not traced again.
A block belongs to one DisplayObject, which is never edited in place, so makeobj,
editobj/closeobj and delobj of its number leave no stale block; an object that
nests others never has one.

**Nesting.**  callobj inside objects runs on an explicit stack, not Python's:
at most :data:`MAX_NESTING` objects deep (a GLUsageError past it).

**Editing** (editobj(3G), maketag(3G), objinsert(3G), objdelete(3G), objreplace(3G)).
An object's *routines* are its segments: each non-vertex call, and each run of
vertex-stream calls between two of them (one :class:`Chunk`); a tag is a marker
between routines.  ``editobj`` reopens an object with the editing pointer at its end
(new routines are appended); ``objinsert(t)`` moves the pointer to just after tag
``t``; ``objreplace(t)`` too, and then each routine recorded overwrites the routine
that follows the pointer, one for one (a tag there stops the overwriting and routines
are inserted again), until closeobj or another positioning call; ``objdelete(t1,
t2)`` removes the routines and tags between the two tags (not the tags themselves)
and leaves the pointer at the end of the object.  STARTTAG and ENDTAG are the
object's two ends.  A tag, an edit call or a closeobj ends the current chunk, so a
tag always falls between routines.
"""

from __future__ import annotations

import math

import numpy as np

from vgxsim import GL
from vgxsim.pipeline.decode import drain
from vgxsim.stream.opcodes import (
    BGN,
    CLEAR,
    CM,
    CRAW,
    CSKIP,
    END,
    KIND_OF,
    STATE,
    SWAP,
    SYNC,
    N,
    T,
    V,
)
from vgxsim.stream.opcodes import C as C_OP
from vgxsim.stream.recorder import MAX_STREAM_OPS, SPLICE_MIN_FLOATS, Chunk, Part, RecordedCall

from . import _core
from ._core import (
    _NO,
    GLTypeError,
    GLUsageError,
    GLValueError,
    as_float,
    as_int,
    check_types,
    current,
    describe,
    given,
    gl_function,
    record_or_refuse,
    session,
)
from ._draw import CLOSER, OPENER, _restate_changed, sync
from ._lighting import _BOUND_KEY, _PLAIN_INTS, _SHORT_MAX, lmbind
from ._raster import stencil

__all__ = ["genobj", "makeobj", "closeobj", "callobj", "delobj", "isobj", "getopenobj",
           "editobj", "maketag", "newtag", "gentag", "istag", "deltag", "objinsert",
           "objdelete", "callfunc", "bbox2", "bbox2i", "bbox2s",
           "objreplace", "chunksize", "compactify", "MAX_NESTING"]

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
        # The chunks, when the object holds nothing else (tags aside): callobj splices
        # them without walking its stack.  Segments never change after construction
        # (editobj edits a copy, closeobj builds a new object).
        self.chunks: list | None = None
        if all(isinstance(seg, (Chunk, Tag)) for seg in self.segments):
            self.chunks = [seg for seg in self.segments if isinstance(seg, Chunk)]
        # callobj's prepared replays (ReplayBlock) when the object is replayable, by
        # lighting token (an object drawn once per material or light keeps one each);
        # a new object (makeobj, closeobj after editobj) starts without any and delobj
        # drops them with the object, so no block outlives the segments it was made
        # from.
        self.blocks: dict[int, ReplayBlock] = {}
        self.replayable = _replayable(self.segments)
        # The one chunk of a chunk-only object that callobj's inlined splice takes
        # (small, closed, nothing rare), else None.
        self.single: Chunk | None = None
        if self.chunks is not None and len(self.chunks) == 1 and _replayable(self.chunks):
            self.single = self.chunks[0]
        # Whether nothing in it nests (only chunks, or a replayable object): a parent
        # walking its segments hands such an object to callobj's valid path
        # (_walk), which draws it without a stack.
        self.leaf = self.chunks is not None or self.replayable
        self.steps = _steps(self.segments)
        # Whether callobj may replay it from a ParentBlock (_parent_replayable).
        self.parent = _parent_replayable(self.steps)

    @property
    def program(self) -> list:
        """('run', chunk) and ('call', func, args) entries, in order."""
        return [("run", g) if isinstance(g, Chunk) else ("call", g[0], g[1])
                for g in self.segments if not isinstance(g, Tag)]

    def __len__(self) -> int:
        return len(self.segments)


class Tag:
    """A tag (maketag(3G)): a named position between an object's routines."""

    __slots__ = ("name",)

    def __init__(self, name: int):
        self.name = name


class ObjectRecorder:
    """What recordable calls append to while makeobj (or editobj) is open.

    ``pos`` is the editing pointer (an index into ``segments``); ``replacing`` says
    whether new routines overwrite the ones after it (objreplace(3G)).
    """

    def __init__(self, segments: list | None = None):
        self.segments: list = [] if segments is None else list(segments)
        self.pos = len(self.segments)
        self.replacing = False
        self.chunk: Chunk | None = None
        self.prim = None  # primitive open inside the chunk (None: as the chunk began)
        self.known = False  # whether ``prim`` is known (the chunk opened or closed one)

    def _put(self, seg) -> None:
        """Insert a routine at the pointer (overwriting the next one when replacing)."""
        if (self.replacing and self.pos < len(self.segments)
                and not isinstance(self.segments[self.pos], Tag)):
            self.segments[self.pos] = seg
        else:
            self.replacing = False
            self.segments.insert(self.pos, seg)
        self.pos += 1

    def tag_index(self, name: int) -> int:
        """Index of tag ``name``'s marker; STARTTAG is -1 (before everything), ENDTAG
        the end; -2 when there is no such tag."""
        if name == GL.STARTTAG:
            return -1
        if name == GL.ENDTAG:
            return len(self.segments)
        for i, seg in enumerate(self.segments):
            if isinstance(seg, Tag) and seg.name == name:
                return i
        return -2

    def move_to(self, index: int, replacing: bool) -> None:
        """Put the pointer just after the marker at ``index`` and end the chunk."""
        self.pos = min(index + 1, len(self.segments))
        self.replacing = replacing
        self.chunk = None

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
        self._put((call, args))

    def _current_chunk(self) -> Chunk:
        if self.chunk is None:
            self.chunk = Chunk()
            self._put(self.chunk)
            self.prim, self.known = None, False
        return self.chunk

    def _colour(self, name: str, args: tuple, rgba: tuple) -> None:
        ch = self._current_chunk()
        ch.ops.append(CRAW)
        ch.fl.extend(rgba)
        if ch.last_colour is None:
            ch.first_colour_call = RecordedCall(name, args)
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
            ch.needs, ch.needs_call = needs[0], RecordedCall(needs[1], needs[2])
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
                ch.open_ops, ch.open_fl = len(ch.ops), len(ch.fl)
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
def editobj(*args) -> None:
    """editobj(obj): reopen object ``obj`` for editing, the pointer at its end
    (editobj(3G)); closeobj ends the editing.  An undefined object is an error."""
    obj = _object_arg("editobj", args)
    current("editobj", args)
    if session.open_object is not None:
        raise GLUsageError(f"{describe('editobj', args)}: object {session.open_object} is "
                           f"still open (call closeobj first)")
    dobj = session.objects.get(obj)
    if dobj is None:
        raise GLValueError(f"{describe('editobj', args)}: object {obj} is not defined "
                           "(makeobj first)")
    session.open_object = obj
    session.recording = ObjectRecorder(dobj.segments)


def _editing(name: str, args: tuple) -> ObjectRecorder:
    """The recorder of the open object; GLUsageError when none is open."""
    current(name, args)
    if session.open_object is None:
        raise GLUsageError(f"{describe(name, args)}: no object is open (makeobj or "
                           "editobj first)")
    return session.recording


def _tag_arg(name: str, args: tuple, what: str, v) -> int:
    t = as_int(name, args, what, v)
    if not -3 <= t <= MAX_OBJECT:
        raise GLValueError(f"{describe(name, args)}: a Tag is a 31-bit integer "
                           f"(or STARTTAG / ENDTAG)")
    return t


def _find_tag(name: str, args: tuple, rec: ObjectRecorder, t: int) -> int:
    i = rec.tag_index(t)
    if i == -2:
        raise GLValueError(f"{describe(name, args)}: tag {t} is not in object "
                           f"{session.open_object}")
    return i


@gl_function(record=False)
def maketag(t: int) -> None:
    """maketag(t): put tag ``t`` at the editing pointer of the open object."""
    args = (t,)
    rec = _editing("maketag", args)
    t = _tag_arg("maketag", args, "t", t)
    if t < 0:
        raise GLValueError(f"{describe('maketag', args)}: STARTTAG and ENDTAG are "
                           "predefined")
    if rec.tag_index(t) != -2:
        raise GLValueError(f"{describe('maketag', args)}: tag {t} already exists in "
                           f"object {session.open_object}")
    rec.chunk = None
    rec.replacing = False
    rec.segments.insert(rec.pos, Tag(t))
    rec.pos += 1


@gl_function(record=False)
def newtag(newtg: int, oldtg: int, offset: int) -> None:
    """newtag(newtg, oldtg, offset): tag ``newtg`` ``offset`` routines after tag
    ``oldtg`` (newtag(3G)); tags between are not counted as routines."""
    args = (newtg, oldtg, offset)
    rec = _editing("newtag", args)
    t = _tag_arg("newtag", args, "newtg", newtg)
    if t < 0 or rec.tag_index(t) != -2:
        raise GLValueError(f"{describe('newtag', args)}: tag {t} is predefined or already "
                           f"exists in object {session.open_object}")
    i = _find_tag("newtag", args, rec, _tag_arg("newtag", args, "oldtg", oldtg))
    n = as_int("newtag", args, "offset", offset)
    j = i + 1
    while n > 0:
        if j >= len(rec.segments):
            raise GLValueError(f"{describe('newtag', args)}: fewer than {offset} routines "
                               f"follow tag {oldtg}")
        if not isinstance(rec.segments[j], Tag):
            n -= 1
        j += 1
    if n < 0:
        raise GLValueError(f"{describe('newtag', args)}: offset must be >= 0")
    rec.segments.insert(j, Tag(t))
    if rec.pos >= j:
        rec.pos += 1
    rec.chunk = None


@gl_function(record=False)
def gentag(*args) -> int:
    """gentag() -> int: a tag number not used in the open object (gentag(3G))."""
    rec = _editing("gentag", args)
    used = [seg.name for seg in rec.segments if isinstance(seg, Tag)]
    return max(used, default=0) + 1


@gl_function(record=False)
def istag(t: int) -> int:
    """istag(t) -> 1 if ``t`` is a tag of the open object, else 0."""
    args = (t,)
    rec = _editing("istag", args)
    return int(rec.tag_index(_tag_arg("istag", args, "t", t)) != -2)


@gl_function(record=False)
def deltag(t: int) -> None:
    """deltag(t): remove tag ``t`` (not the routines around it) from the open object."""
    args = (t,)
    rec = _editing("deltag", args)
    t = _tag_arg("deltag", args, "t", t)
    if t < 0:
        raise GLValueError(f"{describe('deltag', args)}: STARTTAG and ENDTAG cannot be "
                           "deleted")
    i = _find_tag("deltag", args, rec, t)
    del rec.segments[i]
    if rec.pos > i:
        rec.pos -= 1
    rec.chunk = None


@gl_function(record=False)
def objinsert(t: int) -> None:
    """objinsert(t): insert new routines just after tag ``t``."""
    args = (t,)
    rec = _editing("objinsert", args)
    rec.move_to(_find_tag("objinsert", args, rec, _tag_arg("objinsert", args, "t", t)),
                False)


@gl_function(record=False)
def objreplace(t: int) -> None:
    """objreplace(t): overwrite the routines after tag ``t``, one for one."""
    args = (t,)
    rec = _editing("objreplace", args)
    rec.move_to(_find_tag("objreplace", args, rec, _tag_arg("objreplace", args, "t", t)),
                True)


@gl_function(record=False)
def objdelete(tag1: int, tag2: int) -> None:
    """objdelete(tag1, tag2): remove what lies between the two tags; the pointer goes
    to the end of the object."""
    args = (tag1, tag2)
    rec = _editing("objdelete", args)
    i = _find_tag("objdelete", args, rec, _tag_arg("objdelete", args, "tag1", tag1))
    j = _find_tag("objdelete", args, rec, _tag_arg("objdelete", args, "tag2", tag2))
    if j < i:
        raise GLValueError(f"{describe('objdelete', args)}: tag2 comes before tag1 in "
                           f"object {session.open_object}")
    del rec.segments[i + 1:j]
    rec.move_to(len(rec.segments) - 1, False)


@gl_function(record=False)
def chunksize(chunk: int) -> None:
    """chunksize(chunk): the allocation unit of display objects, in bytes
    (chunksize(3G): called before makeobj).  vgxsim grows objects as Python lists, so
    the size changes nothing; the value is validated only."""
    args = (chunk,)
    n = as_int("chunksize", args, "chunk", chunk)
    if n <= 0:
        raise GLValueError(f"{describe('chunksize', args)}: the chunk size must be "
                           "positive")
    if session.open_object is not None:
        raise GLUsageError(f"{describe('chunksize', args)}: an object is open (chunksize "
                           "is called before makeobj)")


@gl_function(record=False)
def compactify(*args) -> None:
    """compactify(obj): store an edited object compactly (compactify(3G)).  Drawing is
    unchanged by definition, and vgxsim's objects (Python lists) keep no gaps after
    editing, so there is nothing to reclaim: the object is validated only."""
    obj = _object_arg("compactify", args)
    current("compactify", args)
    if obj not in session.objects:
        raise GLValueError(f"{describe('compactify', args)}: object {obj} is not defined")


@gl_function(record=False)
def getopenobj(*args) -> int:
    """getopenobj() -> int: the object being defined, or -1."""
    return -1 if session.open_object is None else int(session.open_object)


@gl_function(record=True, binds=(0, math.inf, ()))
def callobj(obj=_NO, /, *more, **kw) -> None:
    """callobj(obj): draw an instance of ``obj``; undefined objects are ignored.

    Nested objects run on an explicit stack, at most MAX_NESTING deep."""
    ctx = session.imm
    if ctx is not None and not kw and not more and type(obj) is int:
        dobj = session.objects.get(obj)  # (no number outside 0..MAX_OBJECT is stored)
        if dobj is None:
            if not 0 <= obj <= MAX_OBJECT:
                _object_arg("callobj", (obj,))  # raises
            return
        ch = dobj.single
        if ch is not None and ctx.prim is None and _core.REPLAY_OBJECTS:
            # splice() of the object's one chunk, inlined (a quad's callobj is mostly
            # the calls around the copy): what its checks decide -- no primitive need
            # be open, none is left open, nothing rare -- was decided at closeobj.
            st = ctx.stream
            ops = st.ops
            # (Only the lists grow here; parts are bounded where a big splice appends
            # them, as at bgn*: the stream stays under twice MAX_STREAM_OPS.)
            if len(ops) > MAX_STREAM_OPS:
                drain(ctx)
                ops = st.ops
            snap = ctx.raster._snapshot
            same = (snap is st.raster and snap is not None
                    and ctx.matrices._mvp is st.mvp and ctx.depth_range is st.depth
                    and ctx.lighting_serial == st.lighting_serial
                    and ctx.concave is st.concave and ctx.vertex_serial == st.vertex_serial)
            if ch.last_colour is None:
                plan = ch.plan_c
            elif same and st.plain_colour:
                # RGB and unlit, as found at an earlier callobj since the last STATE op
                # (the colour mode and lighting binding are in its key).
                plan = ch.plan_c
            elif not ctx.config.rgb:
                return splice(ctx, ch)  # raises: RGB colour calls in colour map mode
            else:
                bound = ctx.bound
                if bound["material"] != 0 and bound["lmodel"] != 0:  # lighting_active
                    plan = ch.plans.get(_colour_op(ctx))
                else:
                    plan = ch.plan_c
                    if same:
                        st.plain_colour = True
            if plan is None:  # (first call for this colour op; closed chunks never grow)
                plan = plan_of(ch, C_OP if ch.last_colour is None else _colour_op(ctx))
            if not same:
                _restate_changed(ctx, st)
            if plan.leads:
                # The chunk starts with a C op, which sets the decoder's colour and
                # clears its normal-sent flag: the caller's colour and last_sent reach
                # no vertex, so only the normal and lmcolor_set need be in the stream.
                if ctx.normal is not st.normal or ctx.lmcolor_set is not st.lmcolor_set:
                    sync(ctx, st)
            elif (ctx.colour is not st.colour or ctx.normal is not st.normal
                    or ctx.last_sent is not st.sent or ctx.lmcolor_set is not st.lmcolor_set):
                sync(ctx, st)
            ops.extend(plan.ops)
            st.fl.extend(plan.fl)
            if plan.plain:  # sets the colour and last_sent only (a colour, no normal)
                ctx.colour = st.colour = plan.colour
                ctx.last_sent = st.sent = plan.last_sent
                return
            if plan.colour is not None:
                ctx.colour = st.colour = plan.colour
                if plan.lmcolor_set:
                    ctx.lmcolor_set = st.lmcolor_set = True
            if plan.normal is not None:
                ctx.normal = st.normal = plan.normal
            if plan.last_sent is not None:
                ctx.last_sent = st.sent = plan.last_sent
            return
        chunks = dobj.chunks
        if chunks is not None:  # only vertex-stream calls: nothing nests
            for ch in chunks:
                splice(ctx, ch)
            return
        if dobj.replayable and ctx.prim is None and _core.REPLAY_OBJECTS:
            if not _replay(ctx, dobj):
                _trace(ctx, dobj)
            return
        if dobj.parent and ctx.prim is None and _core.REPLAY_OBJECTS and REPLAY_PARENTS:
            if not _replay_parent(ctx, dobj):
                _trace_parent(ctx, obj, dobj)
            return
        return _walk(ctx, (obj,), obj, dobj)  # (session.imm: the current window)
    _general_callobj(*given((obj,), more), **kw)


def _general_callobj(*args, **kwargs) -> None:
    if kwargs or session.recording is not None:
        return record_or_refuse(callobj, args, kwargs)
    obj = _object_arg("callobj", args)
    ctx = current("callobj", args)
    dobj = session.objects.get(obj)
    if dobj is None:
        return
    if dobj.chunks is not None:
        for ch in dobj.chunks:
            splice(ctx, ch)
        return
    _walk(ctx, args, obj, dobj)


#: Kinds of a :attr:`DisplayObject.steps` entry: a gl call, a chunk, callobj of a
#: valid object number, callobj of anything else (refused when it is reached, as
#: the call would be), a bbox2* call.
_CALL, _RUN, _OBJ, _BADOBJ, _BBOXSTEP = range(5)


def _steps(segments: list) -> tuple:
    """An object's segments as (kind, a, b) steps, tags left out, for :func:`_walk`:
    (_CALL, func, args), (_RUN, chunk, None), (_OBJ, number, args), (_BADOBJ, None,
    args), (_BBOXSTEP, func, args).  Worked out once per object (segments never
    change after construction), so the walk tests one small int per routine."""
    steps = []
    for seg in segments:
        if isinstance(seg, Tag):
            continue
        if isinstance(seg, Chunk):
            steps.append((_RUN, seg, None))
            continue
        func, fargs = seg
        if func is callobj:
            if (len(fargs) == 1 and type(fargs[0]) is int
                    and 0 <= fargs[0] <= MAX_OBJECT):
                steps.append((_OBJ, fargs[0], fargs))
            else:
                steps.append((_BADOBJ, None, fargs))
        elif func in _BBOX:
            steps.append((_BBOXSTEP, func, fargs))
        else:
            steps.append((_CALL, func, fargs))
    return tuple(steps)


_DONE = iter(())  # (an exhausted iterator: what a culled object's walk resumes)


def _walk(ctx, args: tuple, obj: int, dobj: DisplayObject) -> None:
    """callobj of an object that calls others, or of one that cannot be replayed:
    its steps in order, nested objects on an explicit stack of iterators (never
    Python's), at most MAX_NESTING deep.  With REPLAY_OBJECTS, a nested object in
    which nothing nests (:attr:`DisplayObject.leaf`) is drawn by callobj's valid
    path, as a callobj of it in immediate mode would be (inlined splice, prepared
    replay), instead of segment by segment."""
    objects = session.objects
    chain = [obj]
    stack = [iter(dobj.steps)]
    while stack:
        for kind, a, b in stack[-1]:
            if kind == _CALL:
                a(*b)
                continue
            if kind == _RUN:
                splice(ctx, a)
                continue
            if kind == _BBOXSTEP:
                if _bbox_culls(ctx, a.__name__, b):
                    stack[-1] = _DONE  # bbox2(3G): the rest of this object is not drawn
                    break
                continue
            inner = a if kind == _OBJ else _object_arg("callobj", b)
            inner_obj = objects.get(inner)
            if inner_obj is None:
                continue
            if inner in chain:
                path = " -> ".join(str(o) for o in chain + [inner])
                raise GLUsageError(f"{describe('callobj', args)}: object {inner} calls "
                                   f"itself ({path}); recursive objects would never end")
            if len(chain) >= MAX_NESTING:
                raise GLUsageError(f"{describe('callobj', args)}: objects nested more than "
                                   f"{MAX_NESTING} deep (vgxsim's limit, MAX_NESTING)")
            if inner_obj.leaf and session.imm is ctx and _core.REPLAY_OBJECTS:
                callobj(inner)  # (nothing in it nests: no deeper than this frame)
                continue
            chain.append(inner)
            stack.append(iter(inner_obj.steps))
            break
        else:
            stack.pop()
            chain.pop()


@gl_function()
def callfunc(fctn, *args) -> None:
    """callfunc(fctn, arg, ...): call the Python callable ``fctn(arg, ...)``, in
    immediate mode at once and from a display object each time it is drawn
    (callfunc(3G); the C form's ``nargs`` is implied by the arguments)."""
    if not callable(fctn):
        raise GLTypeError(f"{describe('callfunc', (fctn, *args))}: fctn must be callable")
    fctn(*args)


def _bbox_args(name: str, args: tuple, integer: bool) -> tuple:
    conv = as_int if integer else as_float
    names = ("xmin", "ymin", "x1", "y1", "x2", "y2")
    vals = [as_int(name, args, n, v) for n, v in zip(names[:2], args[:2], strict=True)]
    vals += [conv(name, args, n, v) for n, v in zip(names[2:], args[2:], strict=True)]
    return tuple(vals)


@gl_function()
def bbox2(xmin: int, ymin: int, x1: float, y1: float, x2: float, y2: float) -> None:
    """bbox2(xmin, ymin, x1, y1, x2, y2): in a display object, stop drawing the rest of
    the object when the box (x1, y1)-(x2, y2) (object coordinates, z = 0) lies
    wholly outside the viewport, or covers fewer than ``xmin`` pixels across and fewer
    than ``ymin`` up (bbox2(3G)).  Outside objects it has no effect."""
    _bbox_args("bbox2", (xmin, ymin, x1, y1, x2, y2), False)


@gl_function()
def bbox2i(xmin: int, ymin: int, x1: int, y1: int, x2: int, y2: int) -> None:
    """:func:`bbox2` with integer coordinates."""
    _bbox_args("bbox2i", (xmin, ymin, x1, y1, x2, y2), True)


@gl_function()
def bbox2s(xmin: int, ymin: int, x1: int, y1: int, x2: int, y2: int) -> None:
    """:func:`bbox2` with short coordinates."""
    _bbox_args("bbox2s", (xmin, ymin, x1, y1, x2, y2), True)


_BBOX = (bbox2, bbox2i, bbox2s)


def _bbox_culls(ctx, name: str, fargs: tuple) -> bool:
    """Whether a bbox2 routine culls the rest of its object, in the caller's state.

    The corners go through the current matrices to window coordinates (numeric
    model s. 1); a corner at or behind the eye (w <= 0) never culls, since its box
    has no bounded window extent."""
    xmin, ymin, x1, y1, x2, y2 = _bbox_args(name, fargs, name != "bbox2")
    corners = np.array([[x1, y1, 0.0, 1.0], [x2, y1, 0.0, 1.0], [x1, y2, 0.0, 1.0],
                        [x2, y2, 0.0, 1.0]]) @ ctx.matrices.mvp()
    w = corners[:, 3]
    if not (w > 0).all():
        return False
    l, r, b, t = ctx.raster.viewport
    wx = (l - 0.5) + (corners[:, 0] / w + 1.0) * (r - l + 1) / 2.0
    wy = (b - 0.5) + (corners[:, 1] / w + 1.0) * (t - b + 1) / 2.0
    outside = (wx.max() < l - 0.5 or wx.min() > r + 0.5 or wy.max() < b - 0.5
               or wy.min() > t + 0.5)
    small = (wx.max() - wx.min()) < xmin and (wy.max() - wy.min()) < ymin
    return bool(outside or small)


def _colour_op(ctx) -> int:
    """What a recorded RGB colour call does in the caller's state (lmcolor(3G))."""
    bound = ctx.bound
    if bound["material"] == 0 or bound["lmodel"] == 0:  # not Context.lighting_active()
        return C_OP
    mode = ctx.lmcolor_mode
    if mode == _LMC_NULL:
        return CSKIP
    return C_OP if mode == _LMC_COLOR else CM


_LMC_NULL, _LMC_COLOR = int(GL.LMC_NULL), int(GL.LMC_COLOR)


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


class SplicePlan:
    """What splicing one chunk with one colour op appends and leaves behind, worked
    out once (:func:`plan_of`) so that callobj only copies and assigns.

    Attributes
    ----------
    ops, fl : list
        The chunk's opcodes (CRAW rewritten to the colour op) and floats, appended to
        the stream's lists when the chunk is small; ``arrays`` is set instead
        (``big``) when it is spliced as arrays (CommandStream.splice).
    colour, normal, last_sent : object or None
        The caller's current colour, normal and ``last_sent`` after the chunk (None:
        unchanged); ``lmcolor_set`` True when a colour call reached the material.
    rare : bool
        The chunk sets a texture coordinate or the graphics position, or draws lines.
    plain : bool
        The chunk leaves a new colour and ``last_sent`` only (no normal, no material).
    leads : bool
        The chunk's first op is a C op (``colour_op`` C): the decoder takes its colour
        and clears the normal-sent flag before any vertex, so the caller's colour and
        ``last_sent`` need not be sent before it (callobj's inlined splice).
    """

    __slots__ = ("ops", "fl", "big", "colour", "normal", "last_sent", "lmcolor_set",
                 "rare", "n_ops", "plain", "leads")


def plan_of(ch: Chunk, colour_op: int) -> SplicePlan:
    """The :class:`SplicePlan` of ``ch`` for ``colour_op`` (made once per chunk, colour
    op and length: a chunk grows only while its object is recorded)."""
    plan = ch.plans.get(colour_op)
    if plan is not None and plan.n_ops == len(ch.ops):
        return plan
    plan = SplicePlan()
    codes, floats, ops_list = ch.arrays_for(colour_op)
    plan.n_ops = len(ch.ops)
    plan.big = floats.shape[0] >= SPLICE_MIN_FLOATS
    plan.ops, plan.fl = ops_list, list(ch.fl)
    coloured = ch.last_colour is not None
    plan.colour = ch.last_colour if coloured and colour_op != CSKIP else None
    plan.lmcolor_set = coloured and colour_op == CM
    plan.normal = ch.last_normal
    if colour_op == C_OP and coloured and not ch.normal_after_colour:
        plan.last_sent = "colour"
    elif ch.last_normal is not None:
        plan.last_sent = "normal"
    else:
        plan.last_sent = None
    plan.rare = ch.texcoord is not None or ch.gpos is not None or ch.has_lines
    plan.plain = (plan.colour is not None and not plan.lmcolor_set and plan.normal is None
                  and plan.last_sent is not None)
    plan.leads = colour_op == C_OP and len(ops_list) > 0 and ops_list[0] == C_OP
    ch.plans[colour_op] = plan
    if colour_op == C_OP:
        ch.plan_c = plan
    return plan


def splice(ctx, ch: Chunk) -> None:
    """Append a chunk to the window's stream and leave the caller's current
    attributes as the chunk's calls would have."""
    plan, colour_op = _prologue(ctx, ch)
    _append(ctx, ch, plan, colour_op)


def _prologue(ctx, ch: Chunk) -> tuple:
    """splice()'s checks and the STATE and SYNC ops before the chunk's own:
    (plan, colour op)."""
    if ch.needs is not None:
        _check_needs(ctx, ch)
    if ch.has_lines and ctx.ls_restart:
        ctx.restart_pattern()  # a move under resetls(TRUE) came before its lines
    colour_op = C_OP
    if ch.last_colour is not None:
        if not ctx.config.rgb:
            name, args = ch.first_colour_call
            raise GLUsageError(f"{describe(name, args)}: it is an error to call {name} while "
                               "the framebuffer is in colour map mode (cpack(3G)); use "
                               "color()")
        bound = ctx.bound
        if bound["material"] != 0 and bound["lmodel"] != 0:  # Context.lighting_active
            colour_op = _colour_op(ctx)
    plan = ch.plans.get(colour_op)
    # (Every float a chunk records comes with an opcode, so the opcode count tells
    # whether the chunk grew since the plan was made.)
    if plan is None or plan.n_ops != len(ch.ops):
        plan = plan_of(ch, colour_op)
    st = ctx.stream
    if ctx.prim is None:
        if st.parts_ops + len(st.ops) > MAX_STREAM_OPS:
            drain(ctx)  # a full stream (callobj in a loop that never reads back)
        if ch.touched_prim:
            snap = ctx.raster._snapshot  # _draw.same_state, inlined (two calls less)
            if not (snap is not None and snap is st.raster
                    and ctx.matrices._mvp is st.mvp and ctx.depth_range is st.depth
                    and ctx.lighting_serial == st.lighting_serial
                    and ctx.concave is st.concave
                    and ctx.vertex_serial == st.vertex_serial):
                _restate_changed(ctx, st)
    if (ctx.colour is not st.colour or ctx.normal is not st.normal
            or ctx.last_sent is not st.sent or ctx.lmcolor_set is not st.lmcolor_set):
        sync(ctx, st)  # the chunk's vertices start from the caller's attributes
    return plan, colour_op


def _append(ctx, ch: Chunk, plan: SplicePlan, colour_op: int) -> None:
    """splice() after its prologue: the chunk's ops, and the caller's attributes as
    the chunk leaves them."""
    st = ctx.stream
    opened = ch.open
    if opened is not None:
        base_ops, base_fl = len(st), st.n_floats()
    if plan.big:
        st.splice(ch, colour_op)
    else:  # CommandStream.splice's copy of a small chunk, without its calls
        st.ops.extend(plan.ops)
        st.fl.extend(plan.fl)
    if ch.touched_prim:
        ctx.prim = opened
        if opened is not None:
            st.open_ops, st.open_fl = base_ops + ch.open_ops, base_fl + ch.open_fl
    # The decoder leaves the chunk with the attributes set here (a C op clears the
    # normal-sent flag, an N op sets it, a CM op sets lmcolor_set), so the stream has
    # them too: the next vertex or splice need not sync again (tests/stream: objects
    # draw what immediate mode draws).  The sync above made st's fields ctx's.
    if plan.colour is not None:
        ctx.colour = st.colour = plan.colour
        if plan.lmcolor_set:
            ctx.lmcolor_set = st.lmcolor_set = True
    if plan.normal is not None:
        ctx.normal = st.normal = plan.normal
    if plan.last_sent is not None:
        ctx.last_sent = st.sent = plan.last_sent
    if plan.rare:
        if ch.texcoord is not None:
            ctx.texcoord = ch.texcoord
            st.has_texcoords = True
        if ch.gpos is not None:
            ctx.gpos = ch.gpos


# -- prepared replays ----------------------------------------------------------------------
def _replayable(segments: list) -> bool:
    """Whether callobj may replay an object from a :class:`ReplayBlock`: it holds only
    chunks that open and close their primitives, need none open (callobj replays
    blocks only outside bgn*/end*, where "closed" holds), and are copied into
    the stream's lists (not spliced as arrays), tags, and stencil() calls -- whose
    whole effect is the stencil register and the raster snapshot, both functions of
    the registers before and the arguments (the 1991 shadow faces: stencil, then a
    quad, per edge).  Nothing in it nests, so editing another object cannot change
    what it draws."""
    chunks = 0
    for seg in segments:
        if isinstance(seg, Chunk):
            if (seg.needs not in (None, "closed") or seg.open is not None or not seg.touched_prim
                    or seg.texcoord is not None or seg.gpos is not None or seg.has_lines
                    or len(seg.fl) >= SPLICE_MIN_FLOATS):
                return False
            chunks += 1
        elif not isinstance(seg, Tag) and seg[0] is not stencil:
            return False
    return chunks > 0


class ReplayBlock:
    """What one callobj of a replayable object appended and left behind, kept to be
    appended again while the caller's state is the same (:func:`_replay`).

    The first chunk's draw state and attributes are recorded live at each replay
    (what they depend on -- the stream's last STATE op and attributes -- is the
    caller's); everything after that is a function of the key attributes:

    Attributes
    ----------
    ctx, entry_snap, mvp, depth, token, concave, vertex_serial, rgb, lmcolor_mode :
        The key: the window, its raster snapshot before the call, composite matrix,
        depth range, lighting token (StateTable.lighting_token), concave flag,
        vertex serial, colour mode and lmcolor mode.  A caller whose key differs in
        the composite matrix alone replays the block after :func:`_rebase` (which
        makes ``mvp`` the caller's), with REBASE_REPLAYS.
    colour, normal, last_sent, lmcolor_set : object
        The key's current attributes (identity).
    first_reg, first_snap : object
        The stencil register and raster snapshot at the first chunk.
    ops, fl : list
        What the object appends after the first chunk's STATE and SYNC ops.
    states : list of (DrawState, list of int)
        Each record of the STATE ops in ``ops``, in order of first use, and where
        ``ops`` holds its index; ``generation`` is the state table generation the
        indices in ``ops`` were found in.
    exit_reg, exit_snap, exit_raster, exit_colour, exit_normal, exit_sent, exit_lms :
        The stencil register, raster snapshot, the stream's last recorded snapshot
        and the current attributes after the call.
    """

    __slots__ = ("ctx", "entry_snap", "mvp", "depth", "token", "concave", "vertex_serial",
                 "rgb", "lmcolor_mode", "colour", "normal", "last_sent", "lmcolor_set", "first_reg",
                 "first_snap", "ops", "fl", "states", "generation", "exit_reg", "exit_snap",
                 "exit_raster", "exit_colour", "exit_normal", "exit_sent", "exit_lms")


def _replay(ctx, dobj: DisplayObject) -> bool:
    """callobj of a replayable object from a block, if the caller's state is the
    block's key (True); else False, and nothing is done."""
    blk = dobj.blocks.get(ctx.states.lighting_token(ctx))
    if blk is None:
        return False
    regs = ctx.raster
    snap = regs._snapshot
    if snap is None:
        snap = regs.snapshot()  # (a cache of the registers: filling it changes nothing)
    mvp = ctx.matrices._mvp
    if mvp is None:  # (the same for the matrices; after a popmatrix, KEEP_MVPS gives
        mvp = ctx.matrices.mvp()  # back the product of the matrix popped back to)
    if not (blk.ctx is ctx and blk.entry_snap is snap
            and (mvp is blk.mvp or REBASE_REPLAYS) and ctx.depth_range is blk.depth
            and ctx.concave is blk.concave
            and ctx.vertex_serial == blk.vertex_serial and ctx.colour is blk.colour
            and ctx.normal is blk.normal and ctx.last_sent is blk.last_sent
            and ctx.lmcolor_set is blk.lmcolor_set and ctx.config.rgb is blk.rgb
            and ctx.lmcolor_mode == blk.lmcolor_mode):
        return False
    st = ctx.stream
    if st.parts_ops + len(st.ops) > MAX_STREAM_OPS:
        return False  # (the general replay drains first)
    if mvp is not blk.mvp:
        _rebase(ctx, blk, mvp)
    regs.stencil = blk.first_reg
    regs._snapshot = first = blk.first_snap
    # splice()'s prologue of the first chunk: record the draw state and attributes
    # the stream does not hold yet.
    if not (first is st.raster and blk.mvp is st.mvp and blk.depth is st.depth
            and ctx.lighting_serial == st.lighting_serial and blk.concave is st.concave
            and blk.vertex_serial == st.vertex_serial):
        _restate_changed(ctx, st)
    if (blk.colour is not st.colour or blk.normal is not st.normal
            or blk.last_sent is not st.sent or blk.lmcolor_set is not st.lmcolor_set):
        sync(ctx, st)
    table = ctx.states
    ops = blk.ops
    if blk.generation != table.generation:  # a flush emptied the table: index anew
        adopt = table.adopt
        for rec, slots in blk.states:
            i = adopt(rec)
            for pos in slots:
                ops[pos] = i
        blk.generation = table.generation
    st.ops.extend(ops)
    st.fl.extend(blk.fl)
    regs.stencil = blk.exit_reg
    regs._snapshot = blk.exit_snap
    st.raster = blk.exit_raster
    ctx.colour = st.colour = blk.exit_colour
    ctx.normal = st.normal = blk.exit_normal
    ctx.last_sent = st.sent = blk.exit_sent
    ctx.lmcolor_set = st.lmcolor_set = blk.exit_lms
    return True


#: Rebase switch (in effect with _core.REPLAY_OBJECTS).  True: a block traced under
#: one composite matrix is replayed under another (an object drawn under a moving
#: transform, or at several places) with its draw-state records interned anew for
#: the caller's matrix (:func:`_rebase`); False: the matrix is part of the block's
#: key and the object is traced again (the planes are the same either way,
#: tests/stream/test_random_streams.py).
REBASE_REPLAYS = True


def _rebase(ctx, blk: ReplayBlock, mvp) -> None:
    """Make ``blk`` the block its object would trace under the composite matrix
    ``mvp``, the rest of its key being the caller's.

    Inside a replayable object only its stencil() calls change the draw state, so
    every record of the block is a function of its raster snapshot and of the key
    (matrices, depth range, lighting binding, vertex stage): the record for the
    same snapshot under ``mvp`` is found as a STATE op of the trace would find it
    (StateTable.intern_kept, which keeps it across flushes), and written into the
    STATE ops' index slots.  The ops and floats (object coordinates) and what the
    block leaves behind do not depend on the matrix."""
    regs, table = ctx.raster, ctx.states
    ops = blk.ops
    states = []
    for rec, slots in blk.states:
        regs._snapshot = rec.raster  # (its registers' snapshot: intern reads only it)
        i = table.intern_kept(ctx)
        for pos in slots:
            ops[pos] = i
        states.append((table.records[i], slots))
    blk.states, blk.mvp, blk.generation = states, mvp, table.generation


def _keep_key(blk, ctx) -> None:
    """Store the caller's state that a :class:`ReplayBlock` or :class:`ParentBlock`
    is keyed by (their ``ctx`` to ``lmcolor_set`` attributes), before the call.
    (The replays compare them inline: they are the callobj fast path.)"""
    blk.ctx = ctx
    blk.entry_snap = ctx.raster.snapshot()
    blk.mvp = ctx.matrices.mvp()
    blk.depth, blk.concave = ctx.depth_range, ctx.concave
    blk.vertex_serial, blk.rgb = ctx.vertex_serial, ctx.config.rgb
    blk.lmcolor_mode = ctx.lmcolor_mode  # (in the token too; a program may set it alone)
    blk.token = ctx.states.lighting_token(ctx)
    blk.colour, blk.normal = ctx.colour, ctx.normal
    blk.last_sent, blk.lmcolor_set = ctx.last_sent, ctx.lmcolor_set


def _trace(ctx, dobj: DisplayObject) -> None:
    """callobj of a replayable object, segment by segment as the general replay does
    it, keeping what it appends and leaves as the object's :class:`ReplayBlock`
    (only when nothing flushed the stream meanwhile)."""
    regs, st, table = ctx.raster, ctx.stream, ctx.states
    blk = ReplayBlock()
    _keep_key(blk, ctx)
    generation, parts = table.generation, len(st.parts)
    start = None
    states = []
    for seg in dobj.segments:
        if isinstance(seg, Tag):
            continue
        if not isinstance(seg, Chunk):
            seg[0](*seg[1])
            continue
        if start is None:
            blk.first_reg, blk.first_snap = regs.stencil, regs.snapshot()
        before = len(st.ops)
        plan, colour_op = _prologue(ctx, seg)
        if start is None:
            start = (len(st.ops), len(st.fl))
        elif len(st.ops) > before and st.ops[before] == STATE:
            states.append((before + 1 - start[0], st.ops[before + 1]))  # STATE's index
        _append(ctx, seg, plan, colour_op)
    if (table.generation != generation or len(st.parts) != parts or start is None
            or ctx.prim is not None):
        return
    records = table.records
    slots: dict[int, tuple] = {}  # id(record) -> (record, its STATE ops' index slots)
    for pos, idx in states:
        rec = records[idx]
        slots.setdefault(id(rec), (rec, []))[1].append(pos)
    blk.states = list(slots.values())
    if any(rec.raster.texture != 0 for rec, _slots in blk.states):
        return  # (such records are made by StateTable.intern, not kept)
    blk.ops, blk.fl = st.ops[start[0]:], st.fl[start[1]:]
    blk.generation = generation
    blk.exit_reg, blk.exit_snap, blk.exit_raster = regs.stencil, regs._snapshot, st.raster
    blk.exit_colour, blk.exit_normal = ctx.colour, ctx.normal
    blk.exit_sent, blk.exit_lms = ctx.last_sent, ctx.lmcolor_set
    if len(dobj.blocks) >= 8:
        dobj.blocks.clear()
    dobj.blocks[blk.token] = blk


# -- prepared replays of parents -----------------------------------------------------------
#: Parent replay switch (in effect with _core.REPLAY_OBJECTS).  True: callobj of an
#: object of lmbind(MATERIAL / BACKMATERIAL / LMODEL) and stencil() calls and
#: callobj of leaf objects (a scene's DrawObjects recorded once, Heidmann 1991) is
#: replayed from a :class:`ParentBlock` while the caller's state is its key; False:
#: it is walked (:func:`_walk`) every time (the planes are the same either way,
#: tests/stream/test_fast_calls.py).
REPLAY_PARENTS = True


def _parent_replayable(steps: tuple) -> bool:
    """Whether an object's steps are a parent :func:`_replay_parent` may replay:
    lmbind of a material, back material or lighting model (plain int arguments; what
    they change -- ``Context.bound``, the lighting serial and token -- the block
    sets), stencil() calls, and callobj of valid numbers (whose objects are checked
    to be leaves at each trace, and to be the same objects at each replay); the
    first step an lmbind, so the first object drawn records its draw state anew
    whatever the stream held before (the lighting serial moved)."""
    if not steps or steps[0][1] is not lmbind:
        return False
    objs = 0
    for kind, a, b in steps:
        if kind == _OBJ:
            objs += 1
        elif kind != _CALL:
            return False
        elif a is lmbind:
            if not (len(b) == 2 and type(b[0]) in _PLAIN_INTS and int(b[0]) in _BOUND_KEY
                    and type(b[1]) is int and 0 <= b[1] <= _SHORT_MAX):
                return False
        elif a is not stencil:
            return False
    return objs > 0


def _plain_leaf(d: DisplayObject) -> bool:
    """A leaf whose chunks open and close their primitives and set no texture
    coordinate or graphics position and draw no lines (what callobj does with it is
    a function of the caller's state and the stream's last state and attributes)."""
    if not d.leaf:
        return False
    chunks = d.chunks if d.chunks is not None else [s for s in d.segments
                                                   if isinstance(s, Chunk)]
    return all(ch.needs in (None, "closed") and ch.open is None and ch.texcoord is None
               and ch.gpos is None and not ch.has_lines for ch in chunks)


#: Integer payload of each opcode (kernels/decode.py _int_payload; tested alike).
_INT_PAYLOAD = {SYNC: 2, BGN: 1, STATE: 1, CLEAR: 1}


def _state_slots(ops: list) -> list:
    """Where the STATE ops of a stretch of opcodes hold their record index."""
    out = []
    i, n = 0, len(ops)
    get = _INT_PAYLOAD.get
    while i < n:
        op = ops[i]
        if op == STATE:
            out.append(i + 1)
        i += 1 + get(op, 0)
    return out


class ParentBlock:
    """What one callobj of a parent (:func:`_parent_replayable`) appended and left
    behind, kept to be appended again while the caller's state is its key.

    Attributes
    ----------
    ctx, entry_snap, mvp, depth, token, concave, vertex_serial, rgb, lmcolor_mode,
    colour, normal, last_sent, lmcolor_set :
        The key, as :class:`ReplayBlock`'s (no rebasing: ``mvp`` is compared).
    st_colour, st_normal, st_sent, st_lms : object
        The stream's attributes before the call (the first SYNC op depends on them).
    inner : tuple of (int, DisplayObject or None)
        Each object called, by number, as found when traced.
    pieces : list of (list, list) or Part
        What the call appended, in order: stretches of the lists (copied into the
        stream's lists) and chunks spliced as arrays (appended as parts, as
        CommandStream.splice appends them).
    states : list of (DrawState, list of (int, int))
        Each record of the STATE ops in ``pieces`` and where (piece, position) its
        index is; ``generation`` is the table generation the indices hold for.
    bound : tuple of (str, int)
        The ``Context.bound`` entries the lmbind calls leave.
    serial_step, st_serial_step : int
        How far the calls move the lighting serial, and where the stream's last
        STATE op leaves ``st.lighting_serial``, from the serial before the call.
    exit_reg, exit_snap, exit_raster, exit_plain, exit_token :
        The stencil register, raster snapshot, stream's last recorded snapshot, the
        stream's ``plain_colour`` and the lighting token after the call.
    exit_attrs, exit_st_attrs : tuple
        The caller's (colour, normal, last_sent, lmcolor_set) after the call, and the
        stream's (which differ where an lmbind of a material followed the last
        draw).
    """

    __slots__ = ("ctx", "entry_snap", "mvp", "depth", "token", "concave", "vertex_serial",
                 "rgb", "lmcolor_mode", "colour", "normal", "last_sent", "lmcolor_set",
                 "st_colour", "st_normal", "st_sent", "st_lms", "inner", "pieces", "states",
                 "generation", "bound", "serial_step", "st_serial_step", "exit_reg",
                 "exit_snap", "exit_raster", "exit_attrs", "exit_st_attrs", "exit_plain",
                 "exit_token")


def _replay_parent(ctx, dobj: DisplayObject) -> bool:
    """callobj of a parent from its block, if the caller's state is the block's key
    and the objects it calls are the ones it was traced with (True); else False,
    and nothing is done."""
    table = ctx.states
    blk = dobj.blocks.get(table.lighting_token(ctx))
    if blk is None:
        return False
    regs = ctx.raster
    snap = regs._snapshot
    if snap is None:
        snap = regs.snapshot()
    mvp = ctx.matrices._mvp
    if mvp is None:
        mvp = ctx.matrices.mvp()
    st = ctx.stream
    if not (blk.ctx is ctx and blk.entry_snap is snap and mvp is blk.mvp
            and ctx.depth_range is blk.depth and ctx.concave is blk.concave
            and ctx.vertex_serial == blk.vertex_serial and ctx.colour is blk.colour
            and ctx.normal is blk.normal and ctx.last_sent is blk.last_sent
            and ctx.lmcolor_set is blk.lmcolor_set and ctx.config.rgb is blk.rgb
            and ctx.lmcolor_mode == blk.lmcolor_mode and st.colour is blk.st_colour
            and st.normal is blk.st_normal and st.sent is blk.st_sent
            and st.lmcolor_set is blk.st_lms):
        return False
    objects = session.objects
    for n, d in blk.inner:
        if objects.get(n) is not d:
            return False
    if st.parts_ops + len(st.ops) > MAX_STREAM_OPS:
        return False
    pieces = blk.pieces
    if blk.generation != table.generation:  # a flush emptied the table: index anew
        adopt = table.adopt
        for rec, slots in blk.states:
            i = adopt(rec)
            for piece, pos in slots:
                pieces[piece][0][pos] = i
        blk.generation = table.generation
    for piece in pieces:
        if type(piece) is tuple:
            st.ops.extend(piece[0])
            st.fl.extend(piece[1])
            continue
        if st.ops or st.fl:  # CommandStream.splice of a chunk's arrays
            st.parts.append(Part(st.ops, st.fl))
            st.parts_ops += len(st.ops)
            st.parts_fl += len(st.fl)
            st.ops = []
            st.fl = []
        st.parts.append(piece)
        st.parts_ops += piece.ops.shape[0]
        st.parts_fl += piece.fl.shape[0]
    bound = ctx.bound
    for key, index in blk.bound:
        bound[key] = index
    serial = ctx.lighting_serial
    ctx.lighting_serial = serial + blk.serial_step
    table.token_serial, table.token = ctx.lighting_serial, blk.exit_token
    regs.stencil = blk.exit_reg
    regs._snapshot = blk.exit_snap
    # The stream's last STATE op, as the calls' last one left it (under the key's
    # matrices, depth and vertex stage, and the serial moved as they moved it).
    st.raster = blk.exit_raster
    st.mvp, st.depth, st.concave = mvp, ctx.depth_range, ctx.concave
    st.vertex_serial = ctx.vertex_serial
    st.lighting_serial = serial + blk.st_serial_step
    st.plain_colour = blk.exit_plain
    st.state_memo.clear()  # (its records were found under another lighting serial)
    # (The caller's attributes and the stream's apart: lmbind(MATERIAL) clears the
    # caller's lmcolor_set only, lmbind(3G) / lmcolor(3G).)
    ctx.colour, ctx.normal, ctx.last_sent, ctx.lmcolor_set = blk.exit_attrs
    st.colour, st.normal, st.sent, st.lmcolor_set = blk.exit_st_attrs
    return True


def _trace_parent(ctx, obj: int, dobj: DisplayObject) -> None:
    """callobj of a parent, walked (:func:`_walk`), keeping what it appends and
    leaves as the object's :class:`ParentBlock` when the objects it calls are plain
    leaves (:func:`_plain_leaf`) and nothing flushed the stream meanwhile."""
    objects = session.objects
    inner = tuple((a, objects.get(a)) for kind, a, _b in dobj.steps if kind == _OBJ)
    if not all(d is None or _plain_leaf(d) for _n, d in inner):
        _walk(ctx, (obj,), obj, dobj)
        return
    regs, st, table = ctx.raster, ctx.stream, ctx.states
    blk = ParentBlock()
    _keep_key(blk, ctx)
    blk.st_colour, blk.st_normal, blk.st_sent, blk.st_lms = (st.colour, st.normal, st.sent,
                                                             st.lmcolor_set)
    blk.inner = inner
    generation, parts0 = table.generation, len(st.parts)
    ops0, fl0 = len(st.ops), len(st.fl)
    serial0 = ctx.lighting_serial
    _walk(ctx, (obj,), obj, dobj)
    if (table.generation != generation or ctx.prim is not None or len(st.parts) < parts0
            or st.lighting_serial is None or not serial0 < st.lighting_serial
            or any(objects.get(n) is not d for n, d in inner)):
        return  # (flushed, left open, or nothing drawn: no block)
    if len(st.parts) == parts0:
        pieces = [(st.ops[ops0:], st.fl[fl0:])]
    else:
        new = st.parts[parts0:]
        pieces = []
        if isinstance(new[0].ops, list):  # the lists the first splice put aside
            pieces.append((new[0].ops[ops0:], new[0].fl[fl0:]))
            new = new[1:]
        elif ops0 or fl0:
            return
        for part in new:
            pieces.append((list(part.ops), list(part.fl)) if isinstance(part.ops, list)
                          else part)
        pieces.append((st.ops[:], st.fl[:]))
    records = table.records
    slots: dict[int, tuple] = {}  # id(record) -> (record, its STATE ops' index slots)
    for k, piece in enumerate(pieces):
        if type(piece) is tuple:
            for pos in _state_slots(piece[0]):
                rec = records[piece[0][pos]]
                slots.setdefault(id(rec), (rec, []))[1].append((k, pos))
    blk.states = list(slots.values())
    if any(rec.raster.texture != 0 for rec, _slots in blk.states):
        return  # (such records are made by StateTable.intern, not kept)
    blk.pieces, blk.generation = pieces, generation
    blk.bound = tuple((key, ctx.bound.get(key, 0)) for key in
                      sorted({_BOUND_KEY[int(b[0])] for kind, a, b in dobj.steps
                              if kind == _CALL and a is lmbind}))
    blk.serial_step = ctx.lighting_serial - serial0
    blk.st_serial_step = st.lighting_serial - serial0
    blk.exit_reg, blk.exit_snap, blk.exit_raster = regs.stencil, regs._snapshot, st.raster
    blk.exit_attrs = (ctx.colour, ctx.normal, ctx.last_sent, ctx.lmcolor_set)
    blk.exit_st_attrs = (st.colour, st.normal, st.sent, st.lmcolor_set)
    blk.exit_plain = st.plain_colour
    blk.exit_token = table.lighting_token(ctx)
    if len(dobj.blocks) >= 8:
        dobj.blocks.clear()
    dobj.blocks[blk.token] = blk


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


