"""IRIS GL lighting calls: lmdef, lmbind, lmcolor.

The definitions and the equation live in :mod:`vgxsim.lighting`; these calls add the
IRIS GL argument conventions and the binding rules of lmbind(3G):

* lighting is on iff a MATERIAL and an LMODEL are bound (index 0 unbinds);
* a light's POSITION and SPOTDIRECTION go through the modelview current *at
  lmbind* (moving the modelview afterwards does not move the light), and again when
  a bound light is redefined with lmdef (project note irisgl_reference.md 1.6);
* binding a material forgets lmcolor changes (lmcolor(3G): "lmcolor changes are
  lost whenever a new material is bound").

Errors of :mod:`vgxsim.lighting` come back as :class:`GLValueError` naming the call.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from vgxsim import GL
from vgxsim.lighting import LightingError, light_to_eye
from vgxsim.pipeline.records import TokenMove
from vgxsim.stream.recorder import LightMemo
from vgxsim.tokens import Token

from . import _core
from ._core import (
    _NO,
    GLTypeError,
    GLValueError,
    as_int,
    check_token,
    current,
    describe,
    given,
    gl_function,
    record_or_refuse,
    session,
)

__all__ = ["lmdef", "lmbind", "lmcolor"]

_DEFTYPES = (int(GL.DEFMATERIAL), int(GL.DEFLIGHT), int(GL.DEFLMODEL))
_LIGHTS = {int(GL.LIGHT0) + i: i for i in range(8)}
_TARGETS = (int(GL.MATERIAL), int(GL.BACKMATERIAL), int(GL.LMODEL), *_LIGHTS)
_TARGET_DEF = {int(GL.MATERIAL): (int(GL.DEFMATERIAL), "material", "DEFMATERIAL"),
               int(GL.BACKMATERIAL): (int(GL.DEFMATERIAL), "material", "DEFMATERIAL"),
               int(GL.LMODEL): (int(GL.DEFLMODEL), "lighting model", "DEFLMODEL")}
_SHORT_MAX = 0x7FFF
_PLAIN_INTS = (int, Token)  # exact types lmbind's fast path takes (not bool, not numpy)


def _reason(err: LightingError) -> str:
    """The message of a LightingError without its own "lmdef(...): " prefix."""
    msg = str(err)
    head, sep, tail = msg.partition("): ")
    return tail if sep and "(" in head else msg


def _props(args: tuple, props) -> list:
    if isinstance(props, (str, bytes)) or not isinstance(props, (Sequence, np.ndarray)):
        raise GLTypeError(f"{describe('lmdef', args)}: props must be a flat sequence of "
                          f"numbers, not {type(props).__name__}")
    return list(np.asarray(props).reshape(-1).tolist()) if isinstance(
        props, np.ndarray) else list(props)


@gl_function()
def lmdef(deftype: int, index: int, *rest) -> None:
    """Define or change a material, light or lighting model (lmdef(3G)).

    Two forms are accepted:

    * ``lmdef(deftype, index, props)`` -- the historical Python binding's form, the
      count being ``len(props)``;
    * ``lmdef(deftype, index, np, props)`` -- the C form: ``np`` floats of
      ``props`` are read, or, with ``np`` 0, the list up to its LMNULL.

    ``props`` is a flat list ``token, values..., token, values..., LMNULL``; an
    existing definition keeps the properties not listed.  Index 0 is reserved.
    """
    args = (deftype, index) + rest
    ctx = current("lmdef", args)
    ctx.lighting_serial += 1  # the stream records the draw state anew (gl/_draw.py)
    dt = as_int("lmdef", args, "deftype", deftype)
    if dt not in _DEFTYPES:
        raise GLValueError(f"{describe('lmdef', args)}: deftype {dt} is not a valid token "
                           "(DEFMATERIAL, DEFLIGHT or DEFLMODEL)")
    idx = as_int("lmdef", args, "index", index)
    if len(rest) == 1:
        props = _props(args, rest[0])
    elif len(rest) == 2:
        count = as_int("lmdef", args, "np", rest[0])
        props = _props(args, rest[1])
        if count < 0 or count > len(props):
            raise GLValueError(f"{describe('lmdef', args)}: np {count} is outside "
                               f"0..{len(props)} (the length of props)")
        if count:
            props = props[:count]
    else:
        raise GLTypeError(f"{describe('lmdef', args)}: expected lmdef(deftype, index, props)"
                          " or lmdef(deftype, index, np, props)")
    try:
        ctx.lighting.lmdef(dt, idx, props)
    except LightingError as err:
        raise GLValueError(f"{describe('lmdef', args)}: {_reason(err)}") from None
    if dt == int(GL.DEFLIGHT):
        # A bound light that is redefined is re-sent, through the current modelview.
        for slot, (bound_index, _entry) in list(ctx.bound["lights"].items()):
            if bound_index == idx:
                ctx.bind_light(slot, idx)
    elif dt == int(GL.DEFMATERIAL) and ctx.bound["material"] == idx:
        ctx.lmcolor_set = False  # the hardware material is reloaded


def _general_lmbind(*args, **kwargs) -> None:
    if kwargs or session.recording is not None or len(args) != 2:
        return record_or_refuse(lmbind, args, kwargs)
    target, index = args
    ctx = current("lmbind", args)
    ctx.lighting_serial += 1  # the stream records the draw state anew (gl/_draw.py)
    t = as_int("lmbind", args, "target", target)
    if t not in _TARGETS:
        raise GLValueError(f"{describe('lmbind', args)}: target {t} is not a valid token "
                           "(MATERIAL, BACKMATERIAL, LIGHT0..LIGHT7 or LMODEL)")
    idx = as_int("lmbind", args, "index", index)
    if not 0 <= idx <= _SHORT_MAX:
        raise GLValueError(f"{describe('lmbind', args)}: index {idx} is outside "
                           f"0..{_SHORT_MAX}")
    if t in _LIGHTS:
        if idx and not ctx.lighting.is_defined(int(GL.DEFLIGHT), idx):
            raise GLValueError(f"{describe('lmbind', args)}: light {idx} is not defined "
                               f"(define it with lmdef(DEFLIGHT, {idx}, ...))")
        ctx.bind_light(_LIGHTS[t], idx)
        return
    deftype, what, dname = _TARGET_DEF[t]
    if idx and not ctx.lighting.is_defined(deftype, idx):
        raise GLValueError(f"{describe('lmbind', args)}: {what} {idx} is not defined "
                           f"(define it with lmdef({dname}, {idx}, ...))")
    ctx.bound[_BOUND_KEY[t]] = idx
    if t == _MATERIAL:
        ctx.lmcolor_set = False


@gl_function(binds=(2, 2, ("int", "int")))
def lmbind(target=_NO, index=_NO, /, *more, **kw) -> None:
    """lmbind(target, index): bind definition ``index`` to MATERIAL, BACKMATERIAL,
    LIGHT0..LIGHT7 or LMODEL (lmbind(3G)); index 0 unbinds.  Binding an undefined
    index is an error.

    A light is transformed to eye space here, by the current modelview.
    With a lighting model whose TWOSIDE is set, back-facing polygons are lit from
    the back (flipped normal) with the BACKMATERIAL when one is bound, else with the
    front material (lmdef(3G)).
    """
    ctx = session.imm
    # Valid path: a material, lighting-model or light token (int or GL token) and a
    # plain int index in range that is defined (or 0); everything else takes the
    # general path.
    if (ctx is not None and not kw and not more and type(target) in _PLAIN_INTS
            and type(index) is int and 0 <= index <= _SHORT_MAX):
        key = _BOUND_KEY.get(target)
        if key is not None and (not index or ctx.lighting.is_defined(_TARGET_DEF[target][0],
                                                                       index)):
            tbl = ctx.states
            if tbl.token_serial == ctx.lighting_serial and _core.REPLAY_OBJECTS:
                # The lighting token before this call is known: the one after it is
                # a function of it and (target, index), found once
                # (StateTable.lighting_token names bindings by value).
                code = (tbl.token << 20) | (_MOVE_OF[target] << 16) | index
                ctx.lighting_serial += 1
                moved = tbl.moves.get(code)
                if moved is not None:
                    tbl.token_serial, tbl.token = ctx.lighting_serial, moved
                else:
                    tbl.move = TokenMove(code, ctx.lighting_serial)
            else:
                ctx.lighting_serial += 1  # the stream records the draw state anew
            ctx.bound[key] = index
            if key == "material":
                ctx.lmcolor_set = False
            return
        slot = _LIGHTS.get(target)
        if slot is not None and _core.REPLAY_OBJECTS:
            if not index:  # Context.bind_light(slot, 0)
                ctx.lighting_serial += 1
                ctx.bound["lights"].pop(slot, None)
                return
            light = ctx.lighting.light(index)
            if light is not None:
                _bind_light(ctx, slot, index, light)
                return
    _general_lmbind(*given((target, index), more), **kw)


def _bind_light(ctx, slot: int, index: int, light) -> None:
    """Context.bind_light for a defined light, with the eye-space entry of the same
    definition under the same modelview handed back (the position is "transformed by
    the current ModelView matrix" at lmbind, lmbind(3G), so it is a function of the
    two, which are replaced, never mutated): rebinding a light each frame then binds
    the same entry, computes no product, and lets the state table name the binding
    by value (StateTable.lighting_token)."""
    mv = ctx.matrices.modelview_matrix()
    memo = ctx.stream.light_memo
    k = slot << 16 | index  # (index <= _SHORT_MAX)
    hit = memo.get(k)
    if hit is not None and hit.light is light and hit.modelview is mv:
        pair = hit.entry
    else:
        pair = (index, light_to_eye(light, mv))
        if len(memo) >= 256:
            memo.clear()
        memo[k] = LightMemo(light, mv, pair)
    ctx.lighting_serial += 1
    ctx.bound["lights"][slot] = pair


_MATERIAL = int(GL.MATERIAL)
#: Each non-light target's number in a lighting-token move code (StateTable.moves).
_MOVE_OF = {int(GL.MATERIAL): 0, int(GL.BACKMATERIAL): 1, int(GL.LMODEL): 2}
#: Which ``Context.bound`` entry each non-light lmbind target sets.
_BOUND_KEY = {int(GL.MATERIAL): "material", int(GL.BACKMATERIAL): "backmaterial",
              int(GL.LMODEL): "lmodel"}


def _general_lmcolor(*args, **kwargs) -> None:
    if kwargs or session.recording is not None or len(args) != 1:
        return record_or_refuse(lmcolor, args, kwargs)
    _lmcolor(*args)


@gl_function(binds=(1, 1, ("int",)))
def lmcolor(mode=_NO, /, *more, **kw) -> None:
    """lmcolor(mode): what RGB colour commands do while lighting is on (lmcolor(3G)).

    LMC_COLOR (default) sets the current colour; LMC_EMISSION, LMC_AMBIENT,
    LMC_DIFFUSE, LMC_SPECULAR and LMC_AD set that property of the bound material
    (DIFFUSE and AD take alpha as ALPHA) from the next colour command on; LMC_NULL
    ignores colour commands.
    """
    # Valid path (FAST_CALLS): an int or GL token LMC_COLOR..LMC_AD (0..6), stored
    # as the general path does; anything else takes the general path.
    ctx = session.imm
    if (ctx is None or kw or more or (type(mode) is not int and type(mode) is not Token)
            or not 0 <= mode <= 6):
        return _general_lmcolor(*given((mode,), more), **kw)
    ctx.lighting_serial += 1  # the stream records the draw state anew (gl/_draw.py)
    ctx.lmcolor_mode = int(mode)
    ctx.lmcolor_set = False


def _lmcolor(mode: int) -> None:
    args = (mode,)
    ctx = current("lmcolor", args)
    ctx.lighting_serial += 1  # the stream records the draw state anew (gl/_draw.py)
    ctx.lmcolor_mode = check_token("lmcolor", args, "mode", mode, range(7), "LMC_")
    ctx.lmcolor_set = False
