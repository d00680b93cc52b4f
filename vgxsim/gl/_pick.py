"""IRIS GL picking and selecting: pick, gselect, endpick, endselect, picksize and the
name stack (initnames, pushname, popname, loadname).

In pick or select mode nothing is drawn (pick(3G)): every primitive is hit-tested
instead (:mod:`vgxsim.geometry.hit_test`, through the one hook
``Context.select_hook`` in ``Context.draw_arrays``; clears are skipped too).  A
primitive hits when any part of it lies inside the clip volume and on the inside of
every user clip plane that is on (clipplane(3G), as drawing clips):

* ``pick(n)``: the clip volume is narrowed to the *picking region*, ``picksize``
  pixels (default 10 x 10, picksize(3G)) centred on the cursor (MOUSEX/MOUSEY minus
  the window origin) within the viewport current at pick().  pick "places a special
  viewing matrix on the stack": the current clip-space matrices are composed with
  the pick matrix and so is every projection the program loads until endpick,
  which restores the matrices as they were
  (:meth:`vgxsim.state.matrices.MatrixState.begin_pick`; IGL composes the same way).
* ``gselect(n)``: the clip volume of the program's own projection (its "selecting
  region", gselect(3G)).

Hits are recorded as OpenGL's selection mode later copied from IRIS GL: a primitive
that hits sets a flag; the next name-stack call (loadname, pushname, popname,
initnames) or endpick/endselect writes the name stack as one hit record and clears
the flag.  The hit buffer has the CPython binding's format: ``endpick()`` returns a
flat list of ints, each hit being the count of names followed by the names, bottom
of the stack first (cpython_gl_module.md 1.6).  ``n`` is the buffer size in shorts;
hits that do not fit are dropped (the C call returned a negative count; the binding
made it positive, so the list just ends).  Names are C shorts (wrapped like the
binding's cast); the stack holds NAMESTACKDEPTH (1025) names.  ``loadname`` on an
empty stack pushes (vgxsim's choice: after ``initnames`` the common
``loadname(i)`` per object then works; IGL gets the same effect by keeping a 0 at
the bottom, which would show in every hit record).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from vgxsim import DEVICE, GL
from vgxsim.geometry import assembly
from vgxsim.geometry.hit_test import primitive_hits

from ._core import (
    GLUsageError,
    GLValueError,
    as_int,
    current,
    describe,
    gl_function,
    topic_state,
    window_of,
)
from ._events import event_queue

__all__ = ["pick", "gselect", "endpick", "endselect", "picksize", "initnames", "pushname",
           "popname", "loadname"]

DEFAULT_PICKSIZE = (10, 10)  # picksize(3G): "the default picking region is 10x10 pixels"


@dataclass
class PickState:
    """The session's pick/select mode: which call opened it, its buffer size, the name
    stack, the hit flag and the hit buffer."""

    mode: str | None = None  # 'pick' or 'select' while active
    ctx: object = None
    size: int = 0
    names: list[int] = field(default_factory=list)
    hit: bool = False
    buffer: list[int] = field(default_factory=list)
    overflow: bool = False
    picksize: tuple[int, int] = DEFAULT_PICKSIZE

    def record(self) -> None:
        """Write the name stack as one hit record if a primitive hit since the last."""
        if self.ctx is not None:
            # Primitives wait in the command stream until a flush: decode them now,
            # while the name stack they were drawn under is still in effect.
            self.ctx.flush()
        if not self.hit:
            return
        self.hit = False
        rec = [len(self.names), *self.names]
        if self.overflow or len(self.buffer) + len(rec) > self.size:
            self.overflow = True
            return
        self.buffer.extend(rec)

    def test(self, kind: str, clip: np.ndarray, swaps, indices, user=None) -> None:
        """Context.select_hook: hit-test one primitive given in clip space, against the
        clip volume and ``user``, the (K, 4) clip-space user planes that are on
        (clipplane(3G): what the planes clip away is not drawn, so it cannot hit)."""
        if self.hit or clip.shape[0] == 0:
            return  # already hit since the last record: nothing to learn
        n = clip.shape[0]
        if kind == "point":
            self.hit = primitive_hits("point", clip, user=user)
        elif kind in ("line", "closedline"):
            segs = assembly.line_segments(n, kind == "closedline")
            self.hit = primitive_hits("line", clip, segments=segs.tolist(), user=user)
        else:
            if kind == "polygon":
                polys = [list(range(n))]
            elif kind == "tmesh":
                polys = assembly.tmesh_triangles(n, list(swaps)).tolist()
            elif kind == "qstrip":
                polys = assembly.qstrip_triangles(n).tolist()
            else:  # 'triangles'
                polys = np.asarray(indices, np.int64).reshape(-1, 3).tolist()
            self.hit = primitive_hits("surface", clip, polygons=polys, user=user)


def pick_state() -> PickState:
    """The session's :class:`PickState` (dropped by ``session.reset()``)."""
    return topic_state("pick", PickState)


def pick_matrix(cx: float, cy: float, dx: float, dy: float,
                viewport: tuple[int, int, int, int]) -> np.ndarray:
    """The row-vector matrix that maps the ``dx`` x ``dy`` pixel region centred on
    pixel ``(cx, cy)`` onto the whole clip volume, applied after the projection.

    With viewport ``(l, r, b, t)`` (inclusive; NDC -1 is the edge ``l - 0.5``, as in
    docs/numeric_model.md) the region's centre in NDC is
    ``c = 2 (cx - l + 0.5) / (r - l + 1) - 1``; NDC x becomes ``(x - c) W / dx``, i.e.
    clip ``x' = (x - c w) W / dx`` (the form of gluPickMatrix).

    Returns
    -------
    ndarray, shape (4, 4), float64
    """
    l, r, b, t = viewport
    w, h = r - l + 1, t - b + 1
    sx, sy = w / dx, h / dy
    ncx = 2.0 * (cx - l + 0.5) / w - 1.0
    ncy = 2.0 * (cy - b + 0.5) / h - 1.0
    m = np.eye(4)
    m[0, 0], m[1, 1] = sx, sy
    m[3, 0], m[3, 1] = -ncx * sx, -ncy * sy
    return m


def _short(v: int) -> int:
    return ((v + 0x8000) & 0xFFFF) - 0x8000


def _begin(name: str, args: tuple, mode: str) -> tuple[PickState, object]:
    if len(args) != 1:
        raise GLValueError(f"{describe(name, args)}: expected 1 argument (the buffer size "
                           f"in names), got {len(args)}")
    size = as_int(name, args, "numnames", args[0])
    if size < 0:
        raise GLValueError(f"{describe(name, args)}: the buffer size must be >= 0")
    st = pick_state()
    if st.mode is not None:
        opener = "pick" if st.mode == "pick" else "gselect"
        closer = "endpick" if st.mode == "pick" else "endselect"
        raise GLUsageError(f"{describe(name, args)}: {opener}() is already in effect (call "
                           f"{closer}() first)")
    ctx = current(name, args)
    st.mode, st.ctx, st.size = mode, ctx, size
    st.names, st.hit, st.buffer, st.overflow = [], False, [], False
    ctx.flush()  # what was drawn before pick/gselect is drawn, not hit-tested
    ctx.select_hook = st.test
    return st, ctx


def _end(name: str, args: tuple, mode: str) -> list[int]:
    st = pick_state()
    if st.mode != mode:
        opener = "pick" if mode == "pick" else "gselect"
        raise GLUsageError(f"{describe(name, args)}: without {opener}()")
    st.record()
    ctx = st.ctx
    ctx.select_hook = None
    if mode == "pick":
        ctx.matrices.end_pick()
    hits = list(st.buffer)
    st.mode, st.ctx, st.names, st.buffer = None, None, [], []
    return hits


@gl_function(record=False)
def pick(*args) -> None:
    """pick(numnames): enter picking mode with a hit buffer of ``numnames`` shorts
    (pick(3G); the binding's form, the C buffer argument dropped).

    Drawing then only hit-tests against the picking region around the cursor (see
    the module docstring); GLUsageError if pick or gselect is already in effect.
    """
    st, ctx = _begin("pick", args, "pick")
    q = event_queue()
    ox, oy = window_of(ctx).origin  # bare Contexts are at 0, 0
    cx = q.getvaluator(DEVICE.MOUSEX) - ox
    cy = q.getvaluator(DEVICE.MOUSEY) - oy
    dx, dy = st.picksize
    ctx.matrices.begin_pick(pick_matrix(cx, cy, dx, dy, ctx.raster.viewport))


@gl_function(record=False)
def gselect(*args) -> None:
    """gselect(numnames): enter selecting mode (gselect(3G)): primitives hit when any
    part lies inside the current viewing volume."""
    _begin("gselect", args, "select")


@gl_function(record=False)
def endpick(*args) -> list[int]:
    """endpick() -> list of int: leave picking mode and return the hit buffer (count,
    names..., count, names...), restoring the matrices pick() changed."""
    return _end("endpick", args, "pick")


@gl_function(record=False)
def endselect(*args) -> list[int]:
    """endselect() -> list of int: leave selecting mode and return the hit buffer."""
    return _end("endselect", args, "select")


@gl_function(record=False)
def picksize(deltax: int, deltay: int) -> None:
    """picksize(deltax, deltay): size in pixels of the picking region of the next
    pick() (picksize(3G); default 10 x 10)."""
    args = (deltax, deltay)
    dx = as_int("picksize", args, "deltax", deltax)
    dy = as_int("picksize", args, "deltay", deltay)
    if dx <= 0 or dy <= 0:
        raise GLValueError(f"{describe('picksize', args)}: the picking region must be at "
                           f"least 1 x 1 pixels")
    pick_state().picksize = (dx, dy)


def _active(name: str, args: tuple) -> PickState:
    st = pick_state()
    current(name, args)
    return st


@gl_function(record=True)
def initnames(*args) -> None:
    """initnames(): empty the name stack (a pending hit is recorded first)."""
    st = _active("initnames", args)
    st.record()
    st.names = []


@gl_function(record=True)
def pushname(name: int) -> None:
    """pushname(name): push ``name`` (a short) on the name stack."""
    args = (name,)
    st = _active("pushname", args)
    v = _short(as_int("pushname", args, "name", name))
    if len(st.names) >= GL.NAMESTACKDEPTH:
        raise GLUsageError(f"{describe('pushname', args)}: name stack overflow "
                           f"(NAMESTACKDEPTH is {int(GL.NAMESTACKDEPTH)})")
    st.record()
    st.names.append(v)


@gl_function(record=True)
def popname(*args) -> None:
    """popname(): pop the top name; GLUsageError on an empty stack."""
    st = _active("popname", args)
    if not st.names:
        raise GLUsageError(f"{describe('popname', args)}: the name stack is empty")
    st.record()
    st.names.pop()


@gl_function(record=True)
def loadname(name: int) -> None:
    """loadname(name): replace the top name with ``name`` (push on an empty stack)."""
    args = (name,)
    st = _active("loadname", args)
    v = _short(as_int("loadname", args, "name", name))
    st.record()
    if st.names:
        st.names[-1] = v
    else:
        st.names.append(v)
