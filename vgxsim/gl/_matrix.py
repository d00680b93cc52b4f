"""IRIS GL calls: matrix modes, viewing and modelling transforms, the matrix stack.

IRIS GL transforms points as row vectors, ``p' = p @ M``; modelling and viewing
calls (rotate, translate, scale, lookat, polarview, multmatrix) *premultiply* the
current matrix, ``current = T @ current`` (multmatrix(3G); MS "Porting Matrix and
Transformation Functions").  Projection calls (perspective, window, ortho, ortho2)
*load*: in MSINGLE they replace the single matrix, otherwise the projection matrix
(mmode(3G); irisgl_reference 1.7).  The matrix arithmetic lives in
:mod:`vgxsim.geometry.transform` and the stacks in :mod:`vgxsim.state.matrices`; this
module validates arguments the way CPython's ``gl`` binding did (Angles are ints in
tenths of a degree, Coord and float arguments take ints or floats, matrices are 16
flat numbers) and raises a :class:`GLError` naming the call.
"""

from __future__ import annotations

import math

import numpy as np

from vgxsim import GL
from vgxsim.geometry import transform as T
from vgxsim.state.matrices import STACK_DEPTH, MatrixModeError, MatrixStackError
from vgxsim.tokens import Token

from ._core import (
    _NO,
    GLTypeError,
    GLUsageError,
    GLValueError,
    as_angle,
    as_axis,
    as_float,
    as_int,
    check_token,
    current,
    describe,
    flat_numbers,
    given,
    gl_function,
    record_or_refuse,
    session,
    topic_state,
    window_of,
)

__all__ = [
    "mmode", "getmmode", "perspective", "window", "ortho", "ortho2", "lookat",
    "polarview", "rotate", "rot", "translate", "scale", "pushmatrix", "popmatrix",
    "loadmatrix", "multmatrix", "getmatrix", "pushviewport", "popviewport", "mapw", "mapw2",
    "gl_invertmat", "gl_sincos", "screenspace",
]

VPSTACKDEPTH = int(GL.VPSTACKDEPTH)

_MMODES = (0, 1, 2, 3)  # MSINGLE, MPROJECTION, MVIEWING, MTEXTURE (gl.h)


def _floats(name: str, args: tuple, what: tuple[str, ...], values: tuple | None = None
            ) -> list[float]:
    """Scalar Coord/float arguments: ``values`` (default ``args``), exactly
    ``len(what)`` of them; errors quote the whole call ``args``."""
    values = args if values is None else values
    if len(values) != len(what):
        raise GLTypeError(f"{describe(name, args)}: expected {len(what)} arguments "
                          f"({', '.join(what)}), got {len(args)}")
    return [as_float(name, args, w, v) for w, v in zip(what, values, strict=True)]


def _nargs(name: str, args: tuple, n: int) -> None:
    if len(args) != n:
        raise GLTypeError(f"{describe(name, args)}: expected {n} arguments, got {len(args)}")


def _matrix_arg(name: str, args: tuple) -> np.ndarray:
    """A Matrix: 16 numbers as one flat sequence or 16 arguments (the binding's
    ``float[16]``), or, as a convenience for library users, a (4, 4) numpy array.
    A nested 4x4 Python list is rejected as the binding rejected it."""
    if len(args) == 1 and isinstance(args[0], np.ndarray):
        a = args[0]
        if a.shape not in ((16,), (4, 4)):
            raise GLTypeError(f"{describe(name, args)}: a Matrix array must have shape "
                              f"(16,) or (4, 4), not {a.shape}")
        if not np.issubdtype(a.dtype, np.number) or np.issubdtype(a.dtype, np.complexfloating):
            raise GLTypeError(f"{describe(name, args)}: a Matrix array must be real numbers")
        return np.asarray(a, dtype=np.float64).reshape(4, 4).copy()
    if len(args) == 1 and isinstance(args[0], (list, tuple)) and args[0] and isinstance(
            args[0][0], (list, tuple, np.ndarray)):
        raise GLTypeError(f"{describe(name, args)}: a Matrix is 16 numbers in one flat "
                          f"sequence (row-major, as getmatrix() returns), not nested rows")
    return np.array(flat_numbers(name, args, 16), dtype=np.float64).reshape(4, 4)


def _finite(name: str, args: tuple, values) -> None:
    if not np.all(np.isfinite(np.asarray(values, dtype=np.float64))):
        raise GLValueError(f"{describe(name, args)}: arguments must be finite")


def load_window_projection(ctx) -> None:
    """The matrices of a new window (winopen): MSINGLE holding
    ``ortho2(-0.5, W - 0.5, -0.5, H - 0.5)``, so integer coordinates land on pixel
    centres (greset(3G): "loads a 2-D orthographic projection"; IGL does the same for
    every new window; irisgl_semantics_notes.md, Matrices)."""
    w, h = ctx.width, ctx.height
    ctx.matrices.reset(T.orthographic(-0.5, w - 0.5, -0.5, h - 0.5, -1.0, 1.0))


def _general_mmode(*args, **kwargs) -> None:
    if kwargs or session.recording is not None:
        return record_or_refuse(mmode, args, kwargs)
    _mmode(*args)


@gl_function(record=True, binds=(0, math.inf, ()))
def mmode(m=_NO, /, *more, **kw) -> None:
    """mmode(m): select MSINGLE, MPROJECTION, MVIEWING or MTEXTURE (mmode(3G)).

    Entering or leaving MSINGLE empties the matrix stacks and makes every matrix the
    identity (mmode(3G)); switching among the other three keeps every matrix."""
    # Valid path (FAST_CALLS): an int or GL token MSINGLE..MTEXTURE (0..3); anything
    # else takes the general path, which validates and raises as before.
    ctx = session.imm
    if (ctx is None or kw or more or (type(m) is not int and type(m) is not Token)
            or not 0 <= m <= 3):
        return _general_mmode(*given((m,), more), **kw)
    ctx.matrices.set_mode(int(m))


def _mmode(*args) -> None:
    """mmode(m): select MSINGLE, MPROJECTION, MVIEWING or MTEXTURE (mmode(3G)).

    Entering or leaving MSINGLE empties the matrix stacks and makes every matrix the
    identity ("when matrix mode MSINGLE is entered or left, all matrix stacks are
    forced to be empty, and all matrices are initialized to the identity matrix",
    mmode(3G)); switching among the other three modes keeps every matrix.
    """
    _nargs("mmode", args, 1)
    m = check_token("mmode", args, "mode", args[0], _MMODES, "M")
    current("mmode", args).matrices.set_mode(m)


@gl_function(record=False)
def getmmode(*args) -> int:
    """getmmode() -> int: the current matrix mode."""
    return int(current("getmmode", args).matrices.mode)


@gl_function(record=True)
def perspective(*args) -> None:
    """perspective(fovy, aspect, near, far): load a perspective projection.

    ``fovy`` is an Angle (int, tenths of a degree); perspective(3G) calls values
    below 2 (0.2 degrees) invalid.  ``near == far`` and ``aspect == 0`` would divide
    by zero and are rejected too.
    """
    name = "perspective"
    _nargs(name, args, 4)
    fovy = as_angle(name, args, args[0])
    aspect, near, far = _floats(name, args, ("aspect", "near", "far"), args[1:])
    _finite(name, args, (aspect, near, far))
    if fovy < 2 or fovy >= 1800:
        raise GLValueError(f"{describe(name, args)}: fovy must be 2..1799 tenths of a "
                           f"degree (perspective(3G))")
    if aspect == 0.0:
        raise GLValueError(f"{describe(name, args)}: aspect must not be 0")
    if near == far:
        raise GLValueError(f"{describe(name, args)}: near and far must differ")
    ctx = current(name, args)
    ctx.matrices.load_projection(T.perspective(fovy, aspect, near, far))


@gl_function(record=True)
def window(*args) -> None:
    """window(left, right, bottom, top, near, far): load a perspective frustum
    (window(3G); the IRIS form of glFrustum, loaded, not multiplied)."""
    name = "window"
    v = _floats(name, args, ("left", "right", "bottom", "top", "near", "far"))
    _finite(name, args, v)
    _check_ranges(name, args, v)
    current(name, args).matrices.load_projection(T.frustum(*v))


@gl_function(record=True)
def ortho(*args) -> None:
    """ortho(left, right, bottom, top, near, far): load a parallel projection."""
    name = "ortho"
    v = _floats(name, args, ("left", "right", "bottom", "top", "near", "far"))
    _finite(name, args, v)
    _check_ranges(name, args, v)
    current(name, args).matrices.load_projection(T.orthographic(*v))


@gl_function(record=True)
def ortho2(*args) -> None:
    """ortho2(left, right, bottom, top): 2-D parallel projection, z in [-1, 1].

    With ``viewport(l, r, b, t)``, ``ortho2(l - 0.5, r + 0.5, b - 0.5, t + 0.5)`` is
    "the standard 2-D projection" of subpixel(3G): integer coordinates fall on pixel
    centres.
    """
    name = "ortho2"
    v = _floats(name, args, ("left", "right", "bottom", "top"))
    _finite(name, args, v)
    _check_ranges(name, args, v + [-1.0, 1.0])
    current(name, args).matrices.load_projection(T.orthographic(*v, -1.0, 1.0))


def _check_ranges(name: str, args: tuple, v) -> None:
    l, r, b, t, n, f = v
    if l == r or b == t or n == f:
        raise GLValueError(f"{describe(name, args)}: left/right, bottom/top and near/far "
                           f"must each differ (the projection would divide by zero)")


@gl_function(record=True)
def lookat(*args) -> None:
    """lookat(vx, vy, vz, px, py, pz, twist): view from (vx, vy, vz) toward
    (px, py, pz); ``twist`` is an Angle about the line of sight (lookat(3G)).
    Premultiplies the current matrix."""
    name = "lookat"
    _nargs(name, args, 7)
    v = _floats(name, args, ("vx", "vy", "vz", "px", "py", "pz"), args[:6])
    twist = as_angle(name, args, args[6])
    _finite(name, args, v)
    if v[:3] == v[3:]:
        raise GLValueError(f"{describe(name, args)}: viewpoint and reference point "
                           f"coincide")
    current(name, args).matrices.mult(T.lookat(*v, twist))


@gl_function(record=True)
def polarview(*args) -> None:
    """polarview(dist, azim, inc, twist): dist a Coord, the three angles Angles
    (tenths of a degree); the same as translate(0, 0, -dist); rotate(-twist, 'z');
    rotate(-inc, 'x'); rotate(-azim, 'z') (polarview(3G))."""
    name = "polarview"
    _nargs(name, args, 4)
    dist = as_float(name, args, "dist", args[0])
    _finite(name, args, (dist,))
    azim, inc, twist = (as_angle(name, args, a) for a in args[1:])
    current(name, args).matrices.mult(T.polarview(dist, azim, inc, twist))


#: The axis letters rot and rotate take, for their valid paths (as_axis: either case).
_AXES = {"x": "x", "y": "y", "z": "z", "X": "x", "Y": "y", "Z": "z"}


def _general_rotate(*args, **kwargs) -> None:
    if kwargs or session.recording is not None:
        return record_or_refuse(rotate, args, kwargs)
    name = "rotate"
    _nargs(name, args, 2)
    a = as_angle(name, args, args[0])
    axis = as_axis(name, args, args[1])
    current(name, args).matrices.mult(T.rotation(a / 10.0, axis))


@gl_function(record=True, binds=(0, math.inf, ()))
def rotate(a=_NO, axis=_NO, /, *more, **kw) -> None:
    """rotate(a, axis): rotate by the Angle ``a`` (int tenths of a degree) about
    'x', 'y' or 'z' (either case); counter-clockwise looking down the axis toward the
    origin (rotate(3G)).  A float angle is a GLTypeError: use rot()."""
    ctx = session.imm
    # Valid path (FAST_CALLS): an int Angle and an axis letter; the same matrix and
    # product through MatrixState.rotate_axis (no new rotation array, no copy).
    if ctx is None or kw or more or type(a) is not int or type(axis) is not str:
        return _general_rotate(*given((a, axis), more), **kw)
    ax = _AXES.get(axis)
    if ax is None:
        return _general_rotate(a, axis)
    ctx.matrices.rotate(a / 10.0, ax)  # (deferred: DEFER_PRODUCTS)


def _general_rot(*args, **kwargs) -> None:
    if kwargs or session.recording is not None:
        return record_or_refuse(rot, args, kwargs)
    name = "rot"
    _nargs(name, args, 2)
    a = as_float(name, args, "angle", args[0])
    _finite(name, args, (a,))
    axis = as_axis(name, args, args[1])
    current(name, args).matrices.mult(T.rotation(a, axis))


@gl_function(record=True, binds=(0, math.inf, ()))
def rot(a=_NO, axis=_NO, /, *more, **kw) -> None:
    """rot(a, axis): rotate by ``a`` degrees (a float) about 'x', 'y' or 'z'."""
    ctx = session.imm
    # Valid path (FAST_CALLS): a finite float (a - a is 0.0 only then) and an axis
    # letter.
    if (ctx is None or kw or more or type(a) is not float or a - a != 0.0
            or type(axis) is not str):
        return _general_rot(*given((a, axis), more), **kw)
    ax = _AXES.get(axis)
    if ax is None:
        return _general_rot(a, axis)
    ctx.matrices.rotate(a, ax)  # (deferred: DEFER_PRODUCTS)


def _general_translate(*args, **kwargs) -> None:
    if kwargs or session.recording is not None:
        return record_or_refuse(translate, args, kwargs)
    name = "translate"
    v = _floats(name, args, ("x", "y", "z"))
    _finite(name, args, v)
    current(name, args).matrices.translate(*v)


@gl_function(record=True, binds=(0, math.inf, ()))
def translate(x=_NO, y=_NO, z=_NO, /, *more, **kw) -> None:
    """translate(x, y, z): premultiply a translation."""
    ctx = session.imm
    # Valid path: three finite floats (x - x is 0.0 only for finite x).
    if (ctx is None or kw or more or type(x) is not float or type(y) is not float
            or type(z) is not float or x - x != 0.0 or y - y != 0.0 or z - z != 0.0):
        return _general_translate(*given((x, y, z), more), **kw)
    ctx.matrices.translate(x, y, z)


def _general_scale(*args, **kwargs) -> None:
    if kwargs or session.recording is not None:
        return record_or_refuse(scale, args, kwargs)
    name = "scale"
    v = _floats(name, args, ("x", "y", "z"))
    _finite(name, args, v)
    current(name, args).matrices.mult(T.scaling(*v))


@gl_function(record=True, binds=(0, math.inf, ()))
def scale(x=_NO, y=_NO, z=_NO, /, *more, **kw) -> None:
    """scale(x, y, z): premultiply a scaling (negative factors mirror)."""
    ctx = session.imm
    # Valid path (FAST_CALLS): three finite floats, as translate's.
    if (ctx is None or kw or more or type(x) is not float or type(y) is not float
            or type(z) is not float or x - x != 0.0 or y - y != 0.0 or z - z != 0.0):
        return _general_scale(*given((x, y, z), more), **kw)
    ctx.matrices.scale(x, y, z)  # (deferred: DEFER_PRODUCTS)


def _general_pushmatrix(*args, **kwargs) -> None:
    if kwargs or session.recording is not None:
        return record_or_refuse(pushmatrix, args, kwargs)
    if args:
        _nargs("pushmatrix", args, 0)
    _pushmatrix(current("pushmatrix", args), args)


def _pushmatrix(ctx, args: tuple) -> None:
    try:
        ctx.matrices.push()
    except MatrixModeError:
        _not_stacked("pushmatrix", args, ctx)
    except MatrixStackError:
        raise GLUsageError(f"{describe('pushmatrix', args)}: matrix stack overflow "
                           f"(MATRIXSTACKDEPTH is {STACK_DEPTH})") from None


@gl_function(record=True, binds=(0, math.inf, ()))
def pushmatrix(*args, **kwargs) -> None:
    """pushmatrix(): duplicate the top of the matrix stack (MATRIXSTACKDEPTH 32).

    Only the single matrix (MSINGLE) and the ModelView matrix (MVIEWING) are stacked.
    mmode(3G): "The Projection and Texture matrices are not stacked.  Thus matrix
    commands pushmatrix and popmatrix should not be called while the matrix mode is
    MPROJECTION or MTEXTURE."  vgxsim raises GLUsageError there rather than doing
    nothing, because a silent no-op would leave the program with the wrong matrix
    after its popmatrix; save the projection with getmatrix and restore it with
    loadmatrix instead.
    """
    ctx = session.imm
    if ctx is None or args or kwargs:
        return _general_pushmatrix(*args, **kwargs)
    try:
        ctx.matrices.push()
    except (MatrixModeError, MatrixStackError):
        _pushmatrix(ctx, args)  # push fails again before changing anything: the GLUsageError


def _general_popmatrix(*args, **kwargs) -> None:
    if kwargs or session.recording is not None:
        return record_or_refuse(popmatrix, args, kwargs)
    if args:
        _nargs("popmatrix", args, 0)
    _popmatrix(current("popmatrix", args), args)


def _popmatrix(ctx, args: tuple) -> None:
    try:
        ctx.matrices.pop()
    except MatrixModeError:
        _not_stacked("popmatrix", args, ctx)
    except MatrixStackError:
        raise GLUsageError(f"{describe('popmatrix', args)}: matrix stack underflow "
                           f"(popmatrix without a matching pushmatrix)") from None


@gl_function(record=True, binds=(0, math.inf, ()))
def popmatrix(*args, **kwargs) -> None:
    """popmatrix(): discard the top of the matrix stack; GLUsageError in MPROJECTION
    and MTEXTURE, whose matrices are not stacked (see :func:`pushmatrix`)."""
    ctx = session.imm
    if ctx is None or args or kwargs:
        return _general_popmatrix(*args, **kwargs)
    try:
        ctx.matrices.pop()
    except (MatrixModeError, MatrixStackError):
        _popmatrix(ctx, args)  # pop fails again before changing anything: the GLUsageError


def _not_stacked(name: str, args: tuple, ctx) -> None:
    mode = "MPROJECTION" if ctx.matrices.mode == 1 else "MTEXTURE"
    raise GLUsageError(f"{describe(name, args)}: the {mode} matrix is not stacked "
                       f"(mmode(3G): pushmatrix and popmatrix should not be called in "
                       f"MPROJECTION or MTEXTURE); save it with getmatrix() and restore "
                       f"it with loadmatrix()") from None


def _plain_matrix(m) -> tuple | None:
    """A Matrix given as one list or tuple of 16 plain numbers, all finite, as a
    tuple of them (a copy: the caller may change its list), else None (the general
    path decides).  One sum decides it: it is a float only when the elements are
    ints, bools and at least one float -- what flat_numbers takes, each then worth
    float(v) -- (a string, None, a nested row or a numpy scalar gives an error or
    another type), and a non-finite element makes it non-finite (as does an
    overflowing sum of finite ones, which the general path then accepts).  The
    float64 array is made from the tuple where the product is formed
    (MatrixState._settle), with the values ``np.array`` gives such a list: no
    array per call that a popmatrix discards."""
    if (type(m) is not list and type(m) is not tuple) or len(m) != 16:
        return None
    try:
        t = sum(m)
    except (TypeError, OverflowError):  # (an int past float range: general path)
        return None
    if type(t) is not float or t - t != 0.0:
        return None
    return tuple(m)


def _general_loadmatrix(*args, **kwargs) -> None:
    if kwargs or session.recording is not None:
        return record_or_refuse(loadmatrix, args, kwargs)
    m = _matrix_arg("loadmatrix", args)
    _finite("loadmatrix", args, m)
    current("loadmatrix", args).matrices.load(m)


@gl_function(record=True, binds=(0, math.inf, ()))
def loadmatrix(m=_NO, /, *more, **kw) -> None:
    """loadmatrix(m): replace the current matrix with ``m`` (16 numbers, row-major,
    translation in m[12:15]; also accepted: 16 separate arguments or a (4, 4) array)."""
    ctx = session.imm
    a = None if (ctx is None or kw or more) else _plain_matrix(m)
    if a is None:
        return _general_loadmatrix(*given((m,), more), **kw)
    ctx.matrices.load_deferred(a)  # (DEFER_PRODUCTS)


def _general_multmatrix(*args, **kwargs) -> None:
    if kwargs or session.recording is not None:
        return record_or_refuse(multmatrix, args, kwargs)
    m = _matrix_arg("multmatrix", args)
    _finite("multmatrix", args, m)
    current("multmatrix", args).matrices.mult(m)


@gl_function(record=True, binds=(0, math.inf, ()))
def multmatrix(m=_NO, /, *more, **kw) -> None:
    """multmatrix(m): current := m @ current (IRIS premultiplies)."""
    ctx = session.imm
    a = None if (ctx is None or kw or more) else _plain_matrix(m)
    if a is None:
        return _general_multmatrix(*given((m,), more), **kw)
    ctx.matrices.mult_deferred(a)  # (DEFER_PRODUCTS)


@gl_function(record=False)
def getmatrix(*args) -> list[float]:
    """getmatrix() -> list of 16 floats, row-major (``m[i][j]`` at ``4*i + j``), the
    form the historical binding returned; it round-trips with loadmatrix."""
    # (tolist of a float64 matrix: a new list of the same Python floats as float(x))
    return current("getmatrix", args).matrices.current().ravel().tolist()


# -- the viewport stack and screen-to-world mapping (issue 10) ------------------------------
def _viewport_stack(ctx) -> list:
    stacks = topic_state("viewport-stacks", dict)  # gid -> [(viewport, scrmask), ...]
    return stacks.setdefault(id(ctx), [])


@gl_function(record=True)
def pushviewport(*args) -> None:
    """pushviewport(): save the viewport and the screen mask (pushviewport(3G));
    the stack holds VPSTACKDEPTH (8) entries."""
    ctx = current("pushviewport", args)
    stack = _viewport_stack(ctx)
    if len(stack) >= VPSTACKDEPTH:
        raise GLUsageError(f"{describe('pushviewport', args)}: viewport stack overflow "
                           f"(VPSTACKDEPTH is {VPSTACKDEPTH})")
    stack.append((tuple(ctx.raster.viewport), tuple(ctx.raster.scrmask)))


@gl_function(record=True)
def popviewport(*args) -> None:
    """popviewport(): restore the viewport and screen mask saved last."""
    ctx = current("popviewport", args)
    stack = _viewport_stack(ctx)
    if not stack:
        raise GLUsageError(f"{describe('popviewport', args)}: viewport stack underflow "
                           f"(popviewport without pushviewport)")
    vp, mask = stack.pop()
    ctx.raster.set(viewport=vp, scrmask=mask)


def _viewing_of(name: str, args: tuple, obj) -> tuple:
    """Run display object ``obj`` with drawing turned off and return the transform
    it leaves (mvp) and the viewport; the matrices are put back afterwards (mapw(3G):
    obj holds the viewing transformations)."""
    import copy

    from ._objects import callobj

    ctx = current(name, args)
    as_int(name, args, "obj", obj)
    saved = copy.deepcopy(ctx.matrices.__dict__)
    ctx.flush()  # what was drawn before is drawn
    hook = ctx.select_hook
    ctx.select_hook = lambda *a: None  # nothing the object draws reaches the planes
    try:
        callobj(obj)
        ctx.flush()  # decode what the object queued while drawing is still off
        mvp = ctx.matrices.mvp().copy()
        vp = tuple(ctx.raster.viewport)
    finally:
        ctx.select_hook = hook
        ctx.matrices.__dict__.update(saved)
        ctx.matrices._touch()
    return ctx, mvp, vp


def _unproject(ctx, mvp, vp, sx: float, sy: float, zndc: float) -> np.ndarray:
    l, r, b, t = vp
    x = 2.0 * (sx - window_of(ctx).origin[0] - l + 0.5) / (r - l + 1) - 1.0
    y = 2.0 * (sy - window_of(ctx).origin[1] - b + 0.5) / (t - b + 1) - 1.0
    try:
        inv = np.linalg.inv(mvp)
    except np.linalg.LinAlgError:
        raise GLValueError("the object's transformation is singular") from None
    p = np.array([x, y, zndc, 1.0]) @ inv
    return p[:3] / p[3]


@gl_function(record=False)
def mapw(*args) -> tuple[float, float, float, float, float, float]:
    """mapw(obj, sx, sy) -> (wx1, wy1, wz1, wx2, wy2, wz2): the line of world points
    that the transformation in display object ``obj`` maps onto screen point
    (sx, sy), from the near to the far clipping plane (mapw(3G))."""
    name = "mapw"
    _nargs(name, args, 3)
    sx, sy = (as_float(name, args, w, v) for w, v in zip(("sx", "sy"), args[1:], strict=True))
    ctx, mvp, vp = _viewing_of(name, args, args[0])
    try:
        near = _unproject(ctx, mvp, vp, sx, sy, -1.0)
        far = _unproject(ctx, mvp, vp, sx, sy, 1.0)
    except GLValueError as exc:
        raise GLValueError(f"{describe(name, args)}: {exc}") from None
    return tuple(float(v) for v in (*near, *far))


@gl_function(record=False)
def mapw2(*args) -> tuple[float, float]:
    """mapw2(obj, sx, sy) -> (wx, wy): the 2-D world point the transformation in
    ``obj`` maps onto screen point (sx, sy) (mapw2(3G); for 2-D transforms)."""
    name = "mapw2"
    _nargs(name, args, 3)
    sx, sy = (as_float(name, args, w, v) for w, v in zip(("sx", "sy"), args[1:], strict=True))
    ctx, mvp, vp = _viewing_of(name, args, args[0])
    try:
        p = _unproject(ctx, mvp, vp, sx, sy, -1.0)
    except GLValueError as exc:
        raise GLValueError(f"{describe(name, args)}: {exc}") from None
    return float(p[0]), float(p[1])


@gl_function(record=False)
def gl_invertmat(*args) -> list[float]:
    """gl_invertmat(m) -> the inverse of Matrix ``m`` as 16 floats (libgl's helper;
    the C form wrote it to its second argument)."""
    m = _matrix_arg("gl_invertmat", args)
    try:
        inv = np.linalg.inv(m)
    except np.linalg.LinAlgError:
        raise GLValueError(f"{describe('gl_invertmat', args)}: the matrix is singular") from None
    return [float(x) for x in inv.reshape(-1)]


@gl_function(record=False)
def gl_sincos(angle: int) -> tuple[float, float]:
    """gl_sincos(a) -> (sin, cos) of the Angle ``a`` in tenths of a degree (libgl)."""
    a = as_angle("gl_sincos", (angle,), angle) * np.pi / 1800.0
    return float(np.sin(a)), float(np.cos(a))


@gl_function(record=True)
def screenspace(*args) -> None:
    """screenspace(): draw in absolute screen coordinates (screenspace(3G)): the
    viewport covers the whole 1280x1024 screen placed at the window's origin, with
    ``ortho2(-0.5, XMAXSCREEN + 0.5, -0.5, YMAXSCREEN + 0.5)`` loaded, so screen pixel
    (x, y) is window pixel (x - xorigin, y - yorigin).  The screen mask stays the
    window (nothing outside it can be drawn)."""
    from ._window import scrmask, viewport

    ctx = current("screenspace", args)
    ox, oy = window_of(ctx).origin
    viewport(-ox, int(GL.XMAXSCREEN) - ox, -oy, int(GL.YMAXSCREEN) - oy)
    scrmask(0, ctx.width - 1, 0, ctx.height - 1)
    ortho2(-0.5, int(GL.XMAXSCREEN) + 0.5, -0.5, int(GL.YMAXSCREEN) + 0.5)
