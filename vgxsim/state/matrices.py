"""Matrix modes and stacks (mmode(3G)), with the composite derived once per change.

MSINGLE (the IRIS default) keeps one stack whose top is the whole transform;
MVIEWING keeps a modelview stack and a separate projection; MPROJECTION and
MTEXTURE select those matrices.  Projection calls (perspective, window, ortho,
ortho2) *load* -- they do not multiply -- and in MVIEWING they replace the
projection matrix (MS "Porting Matrix and Transformation Functions"; IGL).

Rules from mmode(3G):

* "when matrix mode MSINGLE is entered or left, all matrix stacks are forced to be
  empty, and all matrices are initialized to the identity matrix" (:meth:`set_mode`);
  a switch among MVIEWING, MPROJECTION and MTEXTURE keeps every matrix.
* "Both the single matrix and the ModelView matrix have a stack depth of 32.  The
  Projection and Texture matrices are not stacked.  Thus matrix commands pushmatrix
  and popmatrix should not be called while the matrix mode is MPROJECTION or
  MTEXTURE": :meth:`push`/:meth:`pop` raise :class:`MatrixModeError` there (the gl
  layer turns it into a GLUsageError), so a program that meant to save its projection
  learns at once that it must use getmatrix/loadmatrix instead of silently keeping
  the wrong matrix.

Speed (issue 6: pushmatrix/translate/popmatrix under 1 us each).  ``push`` shares the
top matrix instead of copying it: no matrix here is ever changed in place (every
load/mult stores a new array), so the two stack entries cannot diverge through
aliasing.  ``translate`` (:data:`DEFER_TRANSLATE`) only notes its offsets; the
product ``translation @ current`` is formed, with exactly the numpy operations
``mult`` would have used and in call order, when the matrix is next read or changed
(:meth:`MatrixState._settle`), and never when a ``popmatrix`` discards it first;
rot, rotate, scale, multmatrix and loadmatrix's valid paths defer theirs in the same
list (:data:`DEFER_PRODUCTS`: ``rotate_axis``, ``scale_by``, ``mult_by`` and the
load's store replayed in order).

A new window starts in MSINGLE with the pixel-unit 2-D projection loaded
(:meth:`reset`, called by winopen; greset(3G) "loads a 2-D orthographic projection", the
``ortho2(-0.5, W - 0.5, -0.5, H - 0.5)`` of subpixel(3G), as IGL does per window).
"""

from __future__ import annotations

import math

import numpy as np

MSINGLE, MPROJECTION, MVIEWING, MTEXTURE = 0, 1, 2, 3
STACK_DEPTH = 32  # MATRIXSTACKDEPTH (gl.h)
_IDENTITY = np.eye(4)
_IDENTITY.flags.writeable = False

#: Fast path switch: translate() defers its matrix product until the matrix is read
#: (False: every translate multiplies at once; the planes are the same either way).
DEFER_TRANSLATE = True
#: Fast path switch: rot, rotate, scale, multmatrix and loadmatrix's valid paths
#: (:meth:`MatrixState.rotate`, :meth:`~MatrixState.scale`,
#: :meth:`~MatrixState.mult_deferred`, :meth:`~MatrixState.load_deferred`) defer their
#: products with translate's, replayed in call order by the same rotate_axis,
#: scale_by, mult_by and store (False: they multiply at once; the matrices are the
#: same bit for bit either way).
DEFER_PRODUCTS = True

#: Fast path switch: the composite (:meth:`MatrixState.mvp`) is kept per top matrix
#: and projection, so a popmatrix finds again the mvp *object* of the matrix it
#: returns to (push/translate/draw/pop per object: the next primitive's draw state
#: is the one recorded before the push, not a new product and a new record), and
#: pushmatrix leaves the mvp as it is (the new top is the same matrix object).
#: False: pushmatrix and popmatrix drop the mvp and the next read multiplies anew
#: (the values are the same either way).
KEEP_MVPS = True

#: Kinds of a deferred product (MatrixState._pending entries: (kind, *arguments)).
_TRANSLATE, _ROTATE, _SCALE, _MULT, _LOAD = 0, 1, 2, 3, 4


def _translation(x: float, y: float, z: float) -> np.ndarray:
    """The row-vector translation matrix (geometry.transform.translation's layout)."""
    m = np.eye(4)
    m[3, :3] = (x, y, z)
    return m


def _matrix(m: tuple) -> np.ndarray:
    """The (4, 4) float64 array, no one else's, of 16 Python numbers, row-major."""
    return np.array(m, dtype=np.float64).reshape(4, 4)


class MatrixStackError(RuntimeError):
    """Push beyond MATRIXSTACKDEPTH or pop of the last matrix."""


class MatrixModeError(RuntimeError):
    """pushmatrix/popmatrix in MPROJECTION or MTEXTURE, whose matrices have no stack."""


class MatrixState:
    """Stacks of 4x4 float64 row-vector matrices."""

    def __init__(self):
        self.mode = MSINGLE
        self.modelview = [np.eye(4)]  # MSINGLE and MVIEWING share this stack
        self.projection = np.eye(4)
        self.texture = np.eye(4)
        self.pick: np.ndarray | None = None  # pick(3G) region matrix while picking
        self._saved = None
        self._mvp = None
        self._mv_inv_t = None
        self._flat: tuple | None = None  # (the mvp, its 16 entries): mvp_flat's memo
        self._pending: list | None = None  # deferred products (kind, *args), call order
        # rotate_axis and scale_by's matrices, overwritten at each call (only their
        # products are kept): identity but for the entries a call writes.
        self._scratch = {k: np.eye(4) for k in "xyzs"}
        # mvp()'s products by top matrix (KEEP_MVPS): id(top) -> (top, projection
        # or None in MSINGLE, mvp); top and projection are kept so their ids cannot
        # be reused, and no matrix here is changed in place, so identity is value.
        self._kept: dict[int, tuple] = {}
        self._kept_normal: dict[int, tuple] = {}  # id(modelview) -> (it, normal matrix)

    def _touch(self) -> None:
        self._mvp = None
        self._mv_inv_t = None

    def _settle(self) -> None:
        """Apply the deferred translations to the current matrix, as mult would have."""
        pending = self._pending
        if pending is not None:
            self._pending = None
            for op in pending:
                kind = op[0]
                if kind == _TRANSLATE:
                    self.mult(_translation(op[1], op[2], op[3]))
                elif kind == _ROTATE:
                    self.rotate_axis(op[1], op[2])
                elif kind == _SCALE:
                    self.scale_by(op[1], op[2], op[3])
                elif kind == _MULT:
                    self.mult_by(_matrix(op[1]))
                else:
                    self._store(_matrix(op[1]))  # (load_owned, settled already)

    def _defer(self, op: tuple) -> None:
        """Note a product (kind, *arguments) for :meth:`_settle`, in call order."""
        if self._pending is None:
            self._pending = [op]
        else:
            self._pending.append(op)
        self._mvp = None
        self._mv_inv_t = None

    def translate(self, x: float, y: float, z: float) -> None:
        """``mult(translation(x, y, z))``, deferred (see the module docstring)."""
        if not DEFER_TRANSLATE or self.pick is not None:
            self.mult(_translation(x, y, z))
            return
        self._defer((_TRANSLATE, x, y, z))

    def rotate(self, degrees: float, axis: str) -> None:
        """:meth:`rotate_axis`, deferred with the translations (:data:`DEFER_PRODUCTS`;
        not while picking, as translate)."""
        if not DEFER_PRODUCTS or self.pick is not None:
            self.rotate_axis(degrees, axis)
            return
        self._defer((_ROTATE, degrees, axis))

    def mult_deferred(self, m: tuple) -> None:
        """:meth:`mult_by` of the matrix of 16 numbers ``m`` (a tuple of Python
        numbers, row-major; multmatrix's valid path), deferred as :meth:`rotate`;
        the float64 array is made when the product is formed."""
        if not DEFER_PRODUCTS or self.pick is not None:
            self.mult_by(_matrix(m))
            return
        self._defer((_MULT, m))

    def load_deferred(self, m: tuple) -> None:
        """:meth:`load_owned` of the matrix of 16 numbers ``m`` (as
        :meth:`mult_deferred`; loadmatrix's valid path), deferred as :meth:`rotate`:
        the products noted before it are dropped, as the load would overwrite them."""
        if not DEFER_PRODUCTS or self.pick is not None:
            self.load_owned(_matrix(m))
            return
        self._pending = [(_LOAD, m)]
        self._mvp = None
        self._mv_inv_t = None

    def scale(self, x: float, y: float, z: float) -> None:
        """:meth:`scale_by`, deferred as :meth:`rotate`."""
        if not DEFER_PRODUCTS or self.pick is not None:
            self.scale_by(x, y, z)
            return
        self._defer((_SCALE, x, y, z))

    # current matrix of the active mode
    def current(self) -> np.ndarray:
        if self._pending is not None:
            self._settle()
        if self.mode == MPROJECTION:
            return self.projection
        if self.mode == MTEXTURE:
            return self.texture
        return self.modelview[-1]

    def _picked(self, m: np.ndarray) -> np.ndarray:
        """A matrix that ends in clip space, composed with the pick matrix while
        picking (the pick region then fills the clip volume)."""
        return m if self.pick is None else m @ self.pick

    def load(self, m: np.ndarray) -> None:
        if self._pending is not None:
            self._settle()
        self._store(np.array(m, dtype=np.float64).reshape(4, 4))

    def _store(self, m: np.ndarray) -> None:
        """Make ``m``, a (4, 4) float64 array no one else holds, the current matrix."""
        if self.mode in (MSINGLE, MPROJECTION):
            m = self._picked(m)
        if self.mode == MPROJECTION:
            self.projection = m
        elif self.mode == MTEXTURE:
            self.texture = m
        else:
            self.modelview[-1] = m
        self._touch()

    def mult(self, m: np.ndarray) -> None:
        """multmatrix: current := m @ current (IRIS premultiplies)."""
        self.load(np.asarray(m, dtype=np.float64).reshape(4, 4) @ self.current())

    def mult_by(self, m: np.ndarray) -> None:
        """:meth:`mult` for a (4, 4) float64 array ``m`` (multmatrix's valid path): the
        product (np.dot, the dgemm of ``@``), a new array no one else holds, is stored
        without :meth:`load`'s copy."""
        self._store(np.dot(m, self.current()))

    def load_owned(self, m: np.ndarray) -> None:
        """:meth:`load` of a (4, 4) float64 array no one else holds (loadmatrix's valid
        path, which made it): stored without a copy."""
        if self._pending is not None:
            self._settle()
        self._store(m)

    def rotate_axis(self, degrees: float, axis: str) -> None:
        """``mult(rotation(degrees, axis))`` for axis ``'x'``, ``'y'`` or ``'z'`` (rot
        and rotate's valid paths): the rotation's entries are written into this
        state's scratch matrix for the axis -- the values
        :func:`vgxsim.geometry.transform.rotation` gives -- and the product, a new
        array no one else holds, is stored without :meth:`load`'s copy."""
        a = math.radians(degrees)
        c, s = math.cos(a), math.sin(a)
        m = self._scratch[axis]
        if axis == "x":
            m[1, 1] = c
            m[1, 2] = s
            m[2, 1] = -s
            m[2, 2] = c
        elif axis == "y":
            m[0, 0] = c
            m[0, 2] = -s
            m[2, 0] = s
            m[2, 2] = c
        else:
            m[0, 0] = c
            m[0, 1] = s
            m[1, 0] = -s
            m[1, 1] = c
        self._store(np.dot(m, self.current()))

    def scale_by(self, x: float, y: float, z: float) -> None:
        """``mult(scaling(x, y, z))`` (scale's valid path), through the scratch
        diagonal matrix, as :meth:`rotate_axis`."""
        m = self._scratch["s"]
        m[0, 0] = x
        m[1, 1] = y
        m[2, 2] = z
        self._store(np.dot(m, self.current()))

    def load_projection(self, m: np.ndarray) -> None:
        """perspective/window/ortho/ortho2: in MSINGLE they load the single matrix,
        otherwise the projection matrix."""
        if self._pending is not None:
            self._settle()
        m = self._picked(np.array(m, dtype=np.float64))
        if self.mode == MSINGLE:
            self.modelview[-1] = m
        else:
            self.projection = m
        self._touch()

    def begin_pick(self, pick: np.ndarray) -> None:
        """pick(3G) "places a special viewing matrix on the stack": every matrix that
        ends in clip space (the single matrices, or the projection) is composed with
        ``pick``, and so is every projection loaded until :meth:`end_pick`, which
        restores the matrices as they were at pick()."""
        self._settle()
        self._saved = (self.mode, [m.copy() for m in self.modelview],
                       self.projection.copy(), self.texture.copy())
        self.pick = np.array(pick, dtype=np.float64).reshape(4, 4)
        if self.mode == MSINGLE:
            self.modelview = [m @ self.pick for m in self.modelview]
        else:
            self.projection = self.projection @ self.pick
        self._touch()

    def end_pick(self) -> None:
        """endpick: the matrices as they were before pick()."""
        self._settle()
        if self._saved is not None:
            self.mode, self.modelview, self.projection, self.texture = self._saved
        self._saved = None
        self.pick = None
        self._touch()

    def reset(self, single: np.ndarray | None = None) -> None:
        """MSINGLE with empty stacks and ``single`` (default identity) as the single
        matrix; every other matrix the identity.  A new window passes its
        ``ortho2(-0.5, W - 0.5, -0.5, H - 0.5)`` (greset(3G), subpixel(3G))."""
        self._pending = None  # every matrix is replaced
        self.mode = MSINGLE
        self.modelview = [np.eye(4) if single is None else
                          np.array(single, dtype=np.float64).reshape(4, 4)]
        self.projection = np.eye(4)
        self.texture = np.eye(4)
        self._touch()

    def push(self) -> None:
        if self.mode in (MPROJECTION, MTEXTURE):
            raise MatrixModeError("the projection and texture matrices are not stacked "
                                  "(mmode(3G))")
        if len(self.modelview) >= STACK_DEPTH:
            raise MatrixStackError("matrix stack overflow (MATRIXSTACKDEPTH 32)")
        if self._pending is not None:
            self._settle()
        # Shared, not copied: matrices are never changed in place (module docstring).
        self.modelview.append(self.modelview[-1])
        if not KEEP_MVPS:  # (else the mvp and normal matrix of the same top stay)
            self._mvp = None  # _touch(), inlined (issue 6 per-call cost)
            self._mv_inv_t = None

    def pop(self) -> None:
        if self.mode in (MPROJECTION, MTEXTURE):
            raise MatrixModeError("the projection and texture matrices are not stacked "
                                  "(mmode(3G))")
        if len(self.modelview) <= 1:
            raise MatrixStackError("matrix stack underflow")
        self._pending = None  # translations of the discarded top
        self.modelview.pop()
        self._mvp = None  # _touch(), inlined
        self._mv_inv_t = None

    def set_mode(self, mode: int) -> None:
        """mmode(mode): entering or leaving MSINGLE empties the stacks and makes every
        matrix the identity (mmode(3G)); other switches keep all matrices."""
        self._settle()
        if (mode == MSINGLE) != (self.mode == MSINGLE):
            base = self._picked(np.eye(4))  # while picking the pick matrix underlies all
            self.modelview = [base.copy() if mode == MSINGLE else np.eye(4)]
            self.projection = np.eye(4) if mode == MSINGLE else base
            self.texture = np.eye(4)
        self.mode = mode
        self._touch()

    def modelview_matrix(self) -> np.ndarray:
        if self._pending is not None:
            self._settle()
        if self.mode == MSINGLE:
            return _IDENTITY  # one shared read-only object: callers compare by identity
        return self.modelview[-1]

    def mvp(self) -> np.ndarray:
        """Object -> clip transform (derived once per change)."""
        if self._mvp is None:
            if self._pending is not None:
                self._settle()
            top = self.modelview[-1]
            proj = None if self.mode == MSINGLE else self.projection
            if KEEP_MVPS:
                hit = self._kept.get(id(top))
                if hit is not None and hit[0] is top and hit[1] is proj:
                    self._mvp = hit[2]
                    return hit[2]
            self._mvp = mvp = top.copy() if proj is None else top @ proj
            if KEEP_MVPS:
                kept = self._kept
                if len(kept) >= 64:
                    kept.clear()
                kept[id(top)] = (top, proj, mvp)
        return self._mvp

    def mvp_flat(self) -> list[float]:
        """The :meth:`mvp`'s 16 entries as Python floats, row-major (``m[4 * r + c]``),
        kept while the mvp object is the same (it is replaced on change, never
        mutated): for the one-point transforms of the gl layer (cmov(3G))."""
        m = self.mvp()
        memo = self._flat
        if memo is None or memo[0] is not m:
            memo = self._flat = (m, m.ravel().tolist())
        return memo[1]

    def normal_matrix(self) -> np.ndarray:
        """Inverse transpose of the modelview's upper 3x3 (row-vector form)."""
        if self._mv_inv_t is None:
            mv = self.modelview_matrix()
            if KEEP_MVPS:  # (kept per modelview as the mvp is: mvp())
                hit = self._kept_normal.get(id(mv))
                if hit is not None and hit[0] is mv:
                    self._mv_inv_t = hit[1]
                    return hit[1]
            m = mv[:3, :3]
            try:
                self._mv_inv_t = np.linalg.inv(m).T
            except np.linalg.LinAlgError:
                self._mv_inv_t = np.eye(3)
            if KEEP_MVPS:
                kept = self._kept_normal
                if len(kept) >= 64:
                    kept.clear()
                kept[id(mv)] = (mv, self._mv_inv_t)
        return self._mv_inv_t

    def get(self) -> np.ndarray:
        """getmatrix(): in MSINGLE the single matrix, else the current mode's."""
        return self.current().copy()
