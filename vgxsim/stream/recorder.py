"""Growable command buffers: a window's immediate-mode stream and display-object chunks.

Both are two growable buffers (``ops``: opcodes and integer payload; ``fl``: float
payload, see :mod:`.opcodes`), converted to int64 and float64 arrays once, at the
flush that decodes them.  The buffers are Python lists: appending a vertex is one
``append`` and one ``extend`` of references to the float objects the call was
given -- nothing is allocated per vertex beyond the lists' amortised growth -- and
that is 3-4x cheaper than ``array.array.extend`` (CPython 3.11 converts item by
item there; measured 110 against 495 ns for one vertex), while the conversion at
the flush costs about 18 ns a float.

A display object's chunk is converted once, when it is first called: ``callobj``
appends the chunk's int64 and float64 arrays to the stream's ``parts`` (after the
lists recorded before it), so replaying the 1991 program's 640-vertex floor neither
copies its floats into the lists nor converts them again at every flush.  A chunk of
fewer than :data:`SPLICE_MIN_FLOATS` floats is copied into the lists instead: one
more part costs more at the flush (about 1 us) than copying a quad's numbers.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from .opcodes import BGN, CM, CRAW, CSKIP, END, SWAP, C, N, T, V

#: Attribute vector the decoder starts from (see kernels/decode.py).
ATTRS = 11
#: A stream holding more opcodes than this is decoded at the next bgn* (a "full
#: stream" flush: memory stays bounded for programs that never read back).
MAX_STREAM_OPS = 1 << 20
#: Chunks with at least this many floats are spliced as arrays (see the docstring).
SPLICE_MIN_FLOATS = 256


class Clear(NamedTuple):
    """A CLEAR op's arguments (``CommandStream.clears[index]``): the CLEAR_* plane
    bits, the packed colour, z and stencil values, and the clear state (the
    RasterState whose raster rectangle and write masks the clear honours)."""

    planes: int
    colour: int
    z: int
    stencil: int
    state: object


class StateMemo(NamedTuple):
    """An entry of ``CommandStream.state_memo``: the raster snapshot (kept, so its
    id is not reused), the record's index and the record."""

    snapshot: object
    index: int
    record: object


class LightMemo(NamedTuple):
    """An entry of ``CommandStream.light_memo``: the light definition, the modelview
    it was bound under and the eye-space entry lmbind bound."""

    light: object
    modelview: object
    entry: tuple


class Part(NamedTuple):
    """A stretch of the stream before its lists: opcodes and integer payload, and
    float payload (lists recorded before a splice, or a spliced chunk's read-only
    int64 and float64 arrays)."""

    ops: object
    fl: object


class ChunkArrays(NamedTuple):
    """A chunk's opcodes for one colour op as a read-only int64 array and as a list,
    and its floats as a read-only float64 array (:meth:`Chunk.arrays_for`)."""

    ops: np.ndarray
    fl: np.ndarray
    ops_list: list


class RecordedCall(NamedTuple):
    """A gl call as its error messages name it: its name and arguments."""

    name: str
    args: tuple


class CommandStream:
    """One window's stream of commands not yet decoded.

    Attributes
    ----------
    ops : list of int
    fl : list of float
    attrs : ndarray, shape (11,), float64
        The decoder's attributes at the start of ``ops`` (carried from the last
        decode).
    colour, normal, sent, lmcolor_set : object
        The immediate-mode attributes the stream last received (compared by
        identity with the window's current ones before each vertex).
    raster, mvp, depth, lighting_serial, concave, vertex_serial : object
        The draw state the last STATE op recorded (compared by identity at bgn*).
    plain_colour : bool
        True once a callobj has found, under that draw state, an RGB window with
        lighting off (colour calls colour the vertices: the chunk's C plan); reset
        with every STATE op (the colour mode and lighting binding are in its key).
    open_ops, open_fl : int
        Where the open primitive's BGN starts (a flush while a primitive is open
        decodes only what precedes it), counted from the start of ``parts``.
    clears : list of Clear
        The clears the stream's CLEAR ops name (emptied with the state table).
    parts : list of Part
        What precedes ``ops`` and ``fl`` in the stream: lists recorded before a
        splice and the int64 / float64 arrays of the chunks spliced
        (:meth:`splice`); ``parts_ops`` and ``parts_fl`` are their total lengths.
    """

    def __init__(self):
        self.ops: list = []
        self.fl: list = []
        self.parts: list = []
        self.parts_ops = 0
        self.parts_fl = 0
        # CLEAR ops' arguments, by index.
        self.clears: list[Clear] = []
        self.attrs = np.zeros(ATTRS)
        self.attrs[9] = -1.0
        self.attrs[10] = -1.0
        self.open_ops = -1
        self.open_fl = -1
        # t2*: the texture coordinate current at the start of ``ops``, and whether the
        # stream ever held a T op (only then is a texture coordinate decoded per vertex).
        self.tex_attrs = np.zeros(2)
        self.has_texcoords = False
        # The gl layer's memo of interned records by raster snapshot while only the
        # snapshot changes between STATE ops (vgxsim.gl._draw._restate):
        # id(snapshot) -> StateMemo.
        self.state_memo: dict[int, StateMemo] = {}
        # The gl layer's memo of lmbind(LIGHTn) entries (vgxsim.gl._lighting):
        # slot << 16 | index -> LightMemo; kept across flushes.
        self.light_memo: dict[int, LightMemo] = {}
        self.forget()

    def forget(self) -> None:
        """Make the next vertex and the next bgn* record attributes and state anew."""
        self.colour = self.normal = self.sent = self.lmcolor_set = None
        self.raster = self.mvp = self.depth = self.lighting_serial = self.concave = None
        self.vertex_serial = None
        self.plain_colour = False

    def __len__(self) -> int:
        return self.parts_ops + len(self.ops)

    def n_floats(self) -> int:
        """Floats in the whole stream (``parts`` and ``fl``)."""
        return self.parts_fl + len(self.fl)

    def splice(self, chunk: Chunk, colour_op: int) -> None:
        """Append a display-object chunk (callobj), its colour calls as ``colour_op``."""
        ops, fl, ops_list = chunk.arrays_for(colour_op)
        if fl.shape[0] < SPLICE_MIN_FLOATS:
            self.ops.extend(ops_list)
            self.fl.extend(chunk.fl)
            return
        if self.ops or self.fl:
            self.parts.append(Part(self.ops, self.fl))
            self.parts_ops += len(self.ops)
            self.parts_fl += len(self.fl)
            self.ops = []
            self.fl = []
        self.parts.append(Part(ops, fl))
        self.parts_ops += ops.shape[0]
        self.parts_fl += fl.shape[0]

    def arrays(self) -> tuple[np.ndarray, np.ndarray]:
        """The whole stream as one int64 and one float64 array."""
        ops = [np.asarray(p.ops, np.int64) for p in self.parts]
        ops.append(np.array(self.ops, np.int64))
        fl = [np.asarray(p.fl, np.float64) for p in self.parts]
        fl.append(np.array(self.fl, np.float64))
        if len(ops) == 1:
            return ops[0], fl[0]
        return np.concatenate(ops), np.concatenate(fl)

    def keep_from(self, ops: np.ndarray, fl: np.ndarray, cut_ops: int, cut_fl: int) -> None:
        """Drop everything before ``cut_ops`` / ``cut_fl`` (``ops`` and ``fl``: the
        stream as :meth:`arrays` gave it); the rest stays, as one part."""
        self.ops = []
        self.fl = []
        self.parts = []
        self.parts_ops = self.parts_fl = 0
        if cut_ops < ops.shape[0] or cut_fl < fl.shape[0]:
            self.parts.append(Part(ops[cut_ops:], fl[cut_fl:]))
            self.parts_ops = ops.shape[0] - cut_ops
            self.parts_fl = fl.shape[0] - cut_fl


def _payload(op: int) -> tuple[int, int]:
    """(int payload, float payload) sizes of an opcode."""
    if op == V or op in (C, CM, CSKIP, CRAW):
        return 0, 4
    if op == N:
        return 0, 3
    if op == T:
        return 0, 2
    if op == BGN:
        return 1, 0
    return 0, 0


class Chunk:
    """Vertex-stream calls recorded in a display object between two other calls.

    Recorded with the same opcodes as immediate mode, except that colour calls are
    CRAW (their effect depends on the caller's lighting state, lmcolor(3G)) and no
    STATE op appears (a chunk is drawn with the caller's state).  What a chunk leaves
    in the caller's current attributes is summarised when it is recorded, so a
    callobj need not walk it.
    """

    def __init__(self):
        self.ops: list = []
        self.fl: list = []
        self.needs: str | None = None  # primitive the caller must have open, or None
        self.needs_call = RecordedCall("", ())  # the call that needs it (error messages)
        self.open: str | None = None  # primitive opened and still open in the chunk
        self.open_ops = self.open_fl = 0  # where that primitive's BGN is in ops, fl
        self.touched_prim = False  # whether the chunk opens or closes primitives
        self.has_lines = False  # lines or points: decoded at once (line-style position)
        self.last_colour: tuple | None = None  # rgba of the last colour call
        self.first_colour_call = RecordedCall("", ())
        self.last_normal: tuple | None = None
        self.normal_after_colour = False
        self.texcoord: tuple | None = None
        self.gpos: tuple | None = None
        self._variants: dict[tuple, ChunkArrays] = {}
        # callobj's splice plans by colour op (vgxsim.gl._objects.plan_of).
        self.plans: dict[int, object] = {}
        self.plan_c = None  # plans[C] (callobj's inlined splice reads it directly)

    def arrays_for(self, colour_op: int) -> ChunkArrays:
        """The chunk's opcodes, with every CRAW rewritten to ``colour_op``, and its
        floats, as read-only int64 and float64 arrays, and the opcodes as a list
        (made once per colour op and length: a chunk grows only while its object is
        recorded)."""
        key = (colour_op if self.last_colour is not None else -1, len(self.ops), len(self.fl))
        out = self._variants.get(key)
        if out is None:
            codes = np.array(self.ops, dtype=np.int64)
            if self.last_colour is not None:
                mask = np.zeros(codes.shape[0], bool)
                i = 0
                n = codes.shape[0]
                while i < n:  # only opcodes, never payload, are rewritten
                    op = int(codes[i])
                    if op == CRAW:
                        mask[i] = True
                    i += 1 + _payload(op)[0]
                codes[mask] = colour_op
            floats = np.array(self.fl, dtype=np.float64)
            codes.flags.writeable = False
            floats.flags.writeable = False
            out = self._variants[key] = ChunkArrays(codes, floats, codes.tolist())
        return out

    def empty(self) -> bool:
        return len(self.ops) == 0


__all__ = ["CommandStream", "Chunk", "ChunkArrays", "Clear", "LightMemo", "Part",
           "RecordedCall", "StateMemo", "ATTRS", "BGN", "END",
           "SWAP", "SPLICE_MIN_FLOATS"]
