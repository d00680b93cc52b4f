"""Draw-state records: what a primitive is drawn with, interned once per value.

A STATE op of the command stream carries the index of one :class:`DrawState` in its
window's table.  Records are compared by identity: the parts are immutable
(RasterState snapshots, matrices and lighting definitions are replaced, never
mutated), so a record is made once per distinct combination, when a bgn* finds the
window's state changed since the last STATE op.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from vgxsim.kernels.clip import NO_PLANES
from vgxsim.state.raster import RasterState, needs_colour

from .depthcue import DepthCue, depthcue_state
from .fog import FogState


class LightingState(NamedTuple):
    """Everything per-vertex lighting reads (lmbind(3G)), without the lmcolor
    override, which the stream carries per primitive.

    Attributes
    ----------
    modelview : ndarray, shape (4, 4)
    normal_matrix : ndarray, shape (3, 3)
    material, lmodel : lighting definitions
    lights : tuple of bound lights, eye space
    back_material : the BACKMATERIAL or None
    """

    modelview: np.ndarray
    normal_matrix: np.ndarray
    material: object
    lmodel: object
    lights: tuple
    back_material: object


class DrawState(NamedTuple):
    """One interned draw state.

    Attributes
    ----------
    raster : RasterState
    mvp : ndarray, shape (4, 4), float64
    viewport : tuple of 4 int
    depth : tuple of 2 float
    lighting : LightingState or None
        None when lighting is off (or in cmode).
    lmcolor_mode : int
    concave : bool
    user_planes : ndarray, shape (K, 4), float64
        The user clip planes on (clipplane(3G)), in clip space (``NO_PLANES``, one
        shared object, when none is on).
    fog : FogState or None
        Vertex fog (fogvertex(3G)) when it is on in RGB mode, else None.
    depthcue : DepthCue or None
        The depth-cue ramp (RGB or colour index) when depthcue(TRUE), else None.
    resetls : bool
        Whether the line style restarts at each line (resetls(3G)).
    lsbackup : bool
        Whether the last two pixels of each line are drawn whatever the line style
        (lsbackup(3G)).
    texgen_eye : (modelview (4, 4), normal matrix (3, 3)) or None
        The eye space that TG_CONTOUR / TG_SPHEREMAP generation reads (texgen(3G)),
        when the bound texture generates a coordinate there, else None.  It changes
        only with the matrices, so the record's ``mvp`` identity stands for it.
    """

    raster: RasterState
    mvp: np.ndarray
    viewport: tuple
    depth: tuple
    lighting: LightingState | None
    lmcolor_mode: int
    concave: bool
    user_planes: np.ndarray = NO_PLANES
    fog: FogState | None = None
    depthcue: DepthCue | None = None
    resetls: bool = True
    lsbackup: bool = False
    texgen_eye: tuple | None = None


def texgen_eye(ctx, rs: RasterState) -> tuple | None:
    """(modelview, normal matrix) when the bound texture's texgen works in eye space."""
    if rs.texture == 0:
        return None
    from vgxsim.state.textures import binding

    if not binding(rs.texture).texgen.eye_space:
        return None
    return ctx.matrices.modelview_matrix(), ctx.matrices.normal_matrix()


def fog_state(ctx) -> FogState | None:
    """The window's vertex fog with the modelview it is measured in, or None."""
    if not ctx.fog_on or ctx.fog_def is None or not ctx.config.rgb:
        return None
    return ctx.fog_def._replace(modelview=ctx.matrices.modelview_matrix())


def same_fog(a: FogState | None, b: FogState | None) -> bool:
    if a is None or b is None:
        return a is b
    return a[:5] == b[:5] and a.modelview is b.modelview


def clip_space_planes(ctx) -> np.ndarray:
    """The window's user clip planes that are on, in clip space: (K, 4) float64.

    A plane is kept in eye coordinates (transformed by the modelview when it was
    defined, clipplane(3G)); a clip-space point ``c = e @ P`` is inside where
    ``e . q >= 0``, i.e. ``c . (P^-1 q) >= 0`` (OpenGL and Mesa clip user planes in
    clip space the same way).  In MSINGLE the single matrix is the projection and eye
    space is object space (the modelview is the identity there).
    """
    eye = ctx.user_planes
    if eye.shape[0] == 0:
        return NO_PLANES
    m = ctx.matrices
    proj = m.modelview[-1] if m.mode == 0 else m.projection  # MSINGLE: the single matrix
    try:
        inv = np.linalg.inv(proj)
    except np.linalg.LinAlgError:
        inv = np.linalg.pinv(proj)
    out = np.ascontiguousarray((inv @ eye.T).T)
    out.flags.writeable = False
    return out


def same_planes(a: np.ndarray, b: np.ndarray) -> bool:
    """Whether two records clip against the same user planes."""
    return a is b or (a.shape == b.shape and bool(np.array_equal(a, b)))


def lighting_state(ctx) -> LightingState | None:
    """The window's lighting, or None when it is off (lmbind(3G))."""
    if not ctx.lighting_active() or not ctx.config.rgb:
        return None
    lights = tuple(entry for _slot, (_i, entry) in sorted(ctx.bound["lights"].items()))
    back = ctx.bound.get("backmaterial", 0)
    return LightingState(ctx.matrices.modelview_matrix(), ctx.matrices.normal_matrix(),
                         ctx.lighting.material(ctx.bound["material"]),
                         ctx.lighting.lmodel(ctx.bound["lmodel"]), lights,
                         ctx.lighting.material(back) if back else None)


def same_lighting(a: LightingState | None, b: LightingState | None) -> bool:
    if a is None or b is None:
        return a is b
    if len(a.lights) != len(b.lights) or a.back_material is not b.back_material:
        return False
    return (a.modelview is b.modelview and a.normal_matrix is b.normal_matrix
            and a.material is b.material and a.lmodel is b.lmodel
            and all(x is y for x, y in zip(a.lights, b.lights, strict=True)))


def same_state(a: DrawState, b: DrawState) -> bool:
    """Whether two records draw alike (identity of their immutable parts)."""
    if a is b:
        return True
    return (a.raster is b.raster and a.mvp is b.mvp and a.viewport == b.viewport
            and a.depth == b.depth and a.lmcolor_mode == b.lmcolor_mode
            and a.concave == b.concave and same_lighting(a.lighting, b.lighting)
            and same_planes(a.user_planes, b.user_planes) and same_fog(a.fog, b.fog)
            and a.depthcue == b.depthcue and a.resetls == b.resetls
            and a.lsbackup == b.lsbackup)


def same_geometry(a: DrawState, b: DrawState) -> bool:
    """Whether two records differ at most in what only the fragment stage reads
    (stencil, z and blend functions, write masks, cull): then their triangles share
    one geometry pass (transform, lighting, clipping, projection, snapping)."""
    ra, rb = a.raster, b.raster
    return (a.mvp is b.mvp and a.viewport == b.viewport and a.depth == b.depth
            and a.lmcolor_mode == b.lmcolor_mode and a.concave == b.concave
            and ra.subpixel == rb.subpixel and ra.shademodel == rb.shademodel
            and needs_colour(ra) == needs_colour(rb) and ra.texture == rb.texture
            and same_lighting(a.lighting, b.lighting)
            and same_planes(a.user_planes, b.user_planes) and same_fog(a.fog, b.fog)
            and a.depthcue == b.depthcue and a.resetls == b.resetls
            and a.lsbackup == b.lsbackup)


def same_projection(a: DrawState, b: DrawState) -> bool:
    """Whether the lit vertices of two records go through one geometry pass alike:
    the same transform, viewport, depth range, snapping and shading model, and both
    with or both without vertex colour (lighting is applied before, per part)."""
    ra, rb = a.raster, b.raster
    return (a.mvp is b.mvp and a.viewport == b.viewport and a.depth == b.depth
            and ra.subpixel == rb.subpixel and ra.shademodel == rb.shademodel
            and needs_colour(ra) == needs_colour(rb) and ra.texture == rb.texture
            and same_planes(a.user_planes, b.user_planes))


class LightingMemo(NamedTuple):
    """StateTable's last LightingState and what it was made under."""

    serial: int
    modelview: np.ndarray
    normal_matrix: np.ndarray
    state: LightingState | None


class Placed(NamedTuple):
    """A kept record's index in this generation of the table (and the record, which
    keeps its id from being reused)."""

    index: int
    record: DrawState


class Joined(NamedTuple):
    """Whether a kept record draws as the one before it: 2 same_state, 1
    same_geometry, 0 neither (the records keep their ids)."""

    last: DrawState
    record: DrawState
    joins: int


class TokenEntry(NamedTuple):
    """A lighting binding's token and its bound (index, eye-space entry) pairs
    (kept, so the ids in the binding's key are not reused)."""

    token: int
    lights: tuple


class TokenMove(NamedTuple):
    """A binding call's move between tokens, armed by gl lmbind: its code
    (token << 20 | target << 16 | index) and the lighting serial after the call."""

    code: int
    serial: int


class StateTable:
    """A window's interned DrawState records (indices of STATE ops).

    ``geometry[i]`` numbers the geometry class of record ``i``: consecutive records
    that :func:`same_geometry` joins share a number.
    """

    def __init__(self):
        self.records: list[DrawState] = []
        self.geometry: list[int] = []
        self._last: DrawState | None = None
        self._index: dict[tuple, int] = {}
        self._lighting_memo: LightingMemo | None = None
        # Bumped by every clear(): an index found under one generation names the same
        # record until the next clear (callers of adopt() keep indices by generation).
        self.generation = 0
        # adopt()'s index of each kept record in this generation: id -> (index,
        # record), and whether a kept record draws as the one before it:
        # (id(last), id(record)) -> (last, record, 2: same_state, 1: same_geometry,
        # 0: neither).  (The records in the values keep their ids from being reused.)
        self._where: dict[int, Placed] = {}
        self._pairs: dict[tuple, Joined] = {}
        # intern_kept()'s records by value, kept across clear(): key -> DrawState.
        self._kept: dict[tuple, DrawState] = {}
        # lighting_token()'s memo: (lighting serial, token), and the token of each
        # lighting binding seen (binding key -> (token, the bound lights), which keeps
        # the entries whose ids the key holds alive, so no id is reused meanwhile).
        self.token_serial: int | None = None
        self.token = 0
        # Moves between tokens that one binding call makes (move_code() -> token),
        # filled in by lighting_token after the call that armed ``move``: (code,
        # serial after the call), set by the gl layer's lmbind.
        self.moves: dict[int, int] = {}
        self.move: TokenMove | None = None
        self._tokens: dict[tuple, TokenEntry] = {}
        # The last token handed out: tokens only grow, and are never reset (not by
        # clear(), not when _tokens is emptied), so a token kept in a key of this
        # table never names another binding.  (Display objects key their replay
        # blocks by token across windows; a block also holds its window, so equal
        # tokens of two windows never replay one's block in the other.)
        self.last_token = 0

    def intern(self, ctx) -> int:
        """Index of the window's current draw state (one record per distinct value:
        the key holds the identities of its immutable parts, the lighting
        serial, which every lighting call bumps, and the vertex-stage serial, which
        every clipplane and fogvertex call bumps)."""
        rs = ctx.raster.snapshot()
        mvp = ctx.matrices.mvp()
        key = (id(rs), id(mvp), ctx.raster.viewport, ctx.depth_range, ctx.lighting_serial,
               ctx.lmcolor_mode, ctx.concave, ctx.config.rgb, id(ctx.bound["lights"]),
               ctx.vertex_serial)
        idx = self._index.get(key)
        if idx is not None and self.records[idx].raster is rs and self.records[idx].mvp is mvp:
            return idx
        idx = self._new(ctx, rs, mvp)
        self._index[key] = idx
        return idx

    def _lighting(self, ctx) -> LightingState | None:
        """:func:`lighting_state`, made once per lighting serial and modelview: the
        faces of a shadow volume differ in stencil state only, and one LightingState
        object lets :func:`same_lighting` answer by identity.  Every lighting call
        bumps the serial; a new modelview is a new object, and so is its normal
        matrix (the parts are replaced, never mutated)."""
        if not ctx.lighting_active() or not ctx.config.rgb:
            return None
        mv, nm = ctx.matrices.modelview_matrix(), ctx.matrices.normal_matrix()
        memo = self._lighting_memo
        if (memo is not None and memo.serial == ctx.lighting_serial and memo.modelview is mv
                and memo.normal_matrix is nm):
            return memo.state
        ls = lighting_state(ctx)
        self._lighting_memo = LightingMemo(ctx.lighting_serial, mv, nm, ls)
        return ls

    def _new(self, ctx, rs: RasterState, mvp: np.ndarray) -> int:
        rec = DrawState(rs, mvp, ctx.raster.viewport,
                        ctx.depth_range, self._lighting(ctx), int(ctx.lmcolor_mode),
                        bool(ctx.concave), clip_space_planes(ctx), fog_state(ctx),
                        depthcue_state(ctx),
                        bool(ctx.resetls), bool(ctx.lsbackup),
                        texgen_eye(ctx, rs))
        last = self._last
        if last is not None and same_state(last, rec):
            return len(self.records) - 1
        if last is not None and same_geometry(last, rec):
            self.geometry.append(self.geometry[-1])
        else:
            self.geometry.append(len(self.records))
        self.records.append(rec)
        self._last = rec
        return len(self.records) - 1

    def lighting_token(self, ctx) -> int:
        """A number that names the window's lighting binding by value, the same for
        the same binding however often it is rebound: the lmdef generation (every
        lmdef makes new definitions), the bound material, back material, lighting
        model and lmcolor mode and the bound lights' (index, eye-space entry) pairs
        (by identity: gl lmbind hands the same pair back for the same light and
        modelview).  ``lighting_serial``, which every lighting call bumps, only
        says when to look again (and a binding call that knows where it moves the
        token, :attr:`moves`, sets it at once: gl lmbind)."""
        serial = ctx.lighting_serial
        if self.token_serial == serial:
            return self.token
        bound = ctx.bound
        lights = bound["lights"]
        # (The slots in binding order and their (index, entry) pairs by identity: the
        # same mapping gives the same key as long as it is bound in the same order.)
        bound_lights = tuple(lights.values())
        key = (id(ctx.lighting), ctx.lighting.generation, bound["material"],
               bound.get("backmaterial", 0), bound["lmodel"], ctx.lmcolor_mode,
               tuple(lights), tuple(map(id, bound_lights)))
        hit = self._tokens.get(key)
        if hit is None:
            if len(self._tokens) >= 4096:  # (tokens are never reused: see last_token)
                self._tokens.clear()
                self._kept.clear()
                self.moves.clear()
            self.last_token += 1
            hit = self._tokens[key] = TokenEntry(self.last_token, bound_lights)
        token = hit.token
        move = self.move
        if move is not None and move.serial == serial:
            if len(self.moves) >= 4096:
                self.moves.clear()
            self.moves[move.code] = token
        self.move = None
        self.token_serial, self.token = serial, token
        return token

    def intern_kept(self, ctx) -> int:
        """:meth:`intern` for a program that draws the same states frame after frame:
        the record made once for a state is kept across :meth:`clear` and put back in
        the table (:meth:`adopt`) instead of being made again.  The key is
        :meth:`intern`'s with :meth:`lighting_token` for the lighting serial (which
        changes at every lmbind, even of what was bound before); the user planes,
        fog, depth cue and line flags are named by the vertex serial, which only
        grows.  A state with a texture bound takes :meth:`intern` (its texgen eye
        space reads the texture's definition, which no key here names)."""
        rs = ctx.raster.snapshot()
        mvp = ctx.matrices.mvp()
        if rs.texture != 0:
            return self.intern(ctx)
        key = (id(rs), id(mvp), ctx.raster.viewport, ctx.depth_range,
               self.lighting_token(ctx), ctx.lmcolor_mode, ctx.concave, ctx.config.rgb,
               id(ctx.bound["lights"]), ctx.vertex_serial)
        rec = self._kept.get(key)
        if rec is not None and rec.raster is rs and rec.mvp is mvp:
            return self.adopt(rec)
        idx = self.intern(ctx)
        rec = self.records[idx]
        if rec.raster is rs and rec.mvp is mvp:
            if len(self._kept) >= 4096:  # (a program under a moving matrix makes new
                self._kept.clear()       #  ones every frame: keep the table bounded)
            self._kept[key] = rec
            self._where[id(rec)] = Placed(idx, rec)
        return idx

    def adopt(self, rec: DrawState) -> int:
        """Index of a record made for the window's current state (by
        :meth:`intern_kept`, possibly before a clear): the one it got first in this
        generation, else it is appended as :meth:`_new` appends a new record (or
        given the last one's index when that draws alike)."""
        hit = self._where.get(id(rec))
        if hit is not None and hit.record is rec:
            return hit.index
        records = self.records
        last = self._last
        if last is None:
            joins = 0
        else:
            pair = self._pairs.get((id(last), id(rec)))
            if pair is not None and pair.last is last and pair.record is rec:
                joins = pair.joins
            else:  # same_state and same_geometry, once per pair of kept records
                joins = 2 if same_state(last, rec) else 1 if same_geometry(last, rec) else 0
                if len(self._pairs) >= 4096:
                    self._pairs.clear()
                self._pairs[(id(last), id(rec))] = Joined(last, rec, joins)
        if joins == 2:
            i = len(records) - 1
        else:
            self.geometry.append(self.geometry[-1] if joins else len(records))
            records.append(rec)
            self._last = rec
            i = len(records) - 1
        self._where[id(rec)] = Placed(i, rec)
        return i

    def clear(self) -> None:
        self.records.clear()
        self.geometry.clear()
        self._index.clear()
        self._where.clear()
        self._last = None
        self._lighting_memo = None
        self.generation += 1
