"""The common calls' valid paths (gl/_core.py FAST_CALLS) hand every argument they do
not take to the general path, which raises the GLError naming the call and the
argument: keywords, wrong counts, wrong types, non-finite or out-of-range values."""

from __future__ import annotations

import math

import pytest

from vgxsim import GL, gl
from vgxsim.gl._core import session

W, H = 16, 12
NAN, INF = math.nan, math.inf


@pytest.fixture
def ctx(gl_window):
    c = gl_window(W, H)
    gl.lmdef(GL.DEFMATERIAL, 1, [GL.LMNULL])
    assert session.imm is c  # the valid paths are in effect
    return c


@pytest.mark.parametrize("call, args, kwargs, error, pattern", [
    ("v3f", (1.0, "y", 0.0), {}, gl.GLTypeError, r"v3f\(1.0, 'y', 0.0\)"),
    ("v3f", (1.0, NAN, 0.0), {}, gl.GLValueError, r"v3f\(1.0, nan, 0.0\): coordinates"),
    ("v3f", ((1.0, 2.0, INF),), {}, gl.GLValueError, r"v3f\(\(1.0, 2.0, inf\)\)"),
    ("v3f", ((1.0, 2.0),), {}, gl.GLTypeError, r"v3f\(\(1.0, 2.0\)\): expected 3"),
    ("v3f", (1.0, 2.0, 3.0, 4.0), {}, gl.GLTypeError, r"v3f\(1.0, 2.0, 3.0, 4.0\)"),
    ("v3f", (1.0, 2.0), {"z": 3.0}, gl.GLTypeError, r"v3f\(1.0, 2.0, z=3.0\)"),
    ("n3f", (0.0, 1.0), {}, gl.GLTypeError, r"n3f\(0.0, 1.0\): expected 3"),
    ("n3f", (0.0, INF, 1.0), {}, gl.GLValueError, r"n3f\(0.0, inf, 1.0\)"),
    ("n3f", (), {"x": 1.0}, gl.GLTypeError, r"n3f\(x=1.0\)"),
    ("c3f", (0.5, None, 0.5), {}, gl.GLTypeError, r"c3f\(0.5, None, 0.5\)"),
    ("c3f", (0.5, NAN, 0.5), {}, gl.GLValueError, r"c3f\(0.5, nan, 0.5\): element 1"),
    ("cpack", (1.5,), {}, gl.GLTypeError, r"cpack\(1.5\): abgr must be an int"),
    ("cpack", (1, 2), {}, gl.GLTypeError, r"cpack\(1, 2\): expected 1 argument"),
    ("stencil", (1, 0, 7.0, 0xFF, 0, 0, 1), {}, gl.GLTypeError,
     r"stencil\(1, 0, 7.0, 255, 0, 0, 1\): func must be an int"),
    ("stencil", (1, 0, 9, 0xFF, 0, 0, 1), {}, gl.GLValueError, r"func 9 is not a valid"),
    ("stencil", (1, 0, 7, 0xFF, 0, 0, 6), {}, gl.GLValueError, r"zpass 6 is not a valid"),
    ("lmbind", (GL.MATERIAL, 7), {}, gl.GLValueError, r"lmbind\(MATERIAL, 7\): material 7 "
                                                      r"is not defined"),
    ("lmbind", (GL.MATERIAL, 1.0), {}, gl.GLTypeError, r"index must be an int"),
    ("lmbind", (GL.MATERIAL, 0x8000), {}, gl.GLValueError, r"index 32768 is outside"),
    ("zwritemask", ("all",), {}, gl.GLTypeError, r"zwritemask\('all'\): mask"),
    ("wmpack", (1.0,), {}, gl.GLTypeError, r"wmpack\(1.0\): mask"),
    ("translate", (1.0, NAN, 0.0), {}, gl.GLValueError, r"translate\(1.0, nan, 0.0\)"),
    ("translate", (1.0, 2.0), {}, gl.GLTypeError, r"translate\(1.0, 2.0\)"),
    ("pushmatrix", (1,), {}, gl.GLTypeError, r"pushmatrix\(1\)"),
    ("popmatrix", (), {}, gl.GLUsageError, r"popmatrix\(\): matrix stack underflow"),
    ("callobj", (-1,), {}, gl.GLValueError, r"callobj\(-1\): an Object is a 31-bit"),
    ("callobj", (2**31,), {}, gl.GLValueError, r"callobj\(2147483648\)"),
    ("callobj", (1.0,), {}, gl.GLTypeError, r"callobj\(1.0\): obj must be an int"),
    ("blendfunction", (1, 15), {}, gl.GLValueError, r"blendfunction\(1, 15\): dfactr 15 "
                                                    r"is not a valid token \(BF_\*\)"),
    ("blendfunction", (9, 0), {}, gl.GLValueError, r"sfactr 9 \(BF_CA..BF_MAX\) is a later"),
    ("blendfunction", (1, 8), {}, gl.GLValueError, r"BF_MIN_SA_MDA is a source factor only"),
    ("blendfunction", (1.0, 0), {}, gl.GLTypeError, r"sfactr must be an int, not float"),
    ("blendfunction", (1,), {}, gl.GLTypeError, r"blendfunction\(1\): expected 2 arguments"),
    ("blendfunction", (1, 0), {"x": 1}, gl.GLTypeError, r"blendfunction\(1, 0, x=1\)"),
    ("bgnpolygon", (), {"x": 1}, gl.GLTypeError, r"bgnpolygon\(x=1\)"),
    ("endpolygon", (), {}, gl.GLUsageError, r"endpolygon\(\): without bgnpolygon"),
])
def test_bad_arguments_raise_naming_the_call(ctx, call, args, kwargs, error, pattern):
    if call == "v3f":
        gl.bgnpolygon()  # a vertex's place: only its arguments are wrong
    with pytest.raises(error, match=pattern):
        getattr(gl, call)(*args, **kwargs)


def test_vertex_outside_a_primitive_and_bgn_twice(ctx):
    with pytest.raises(gl.GLUsageError, match=r"v3f\(1.0, 2.0, 3.0\): vertex outside"):
        gl.v3f(1.0, 2.0, 3.0)
    gl.bgnpolygon()
    with pytest.raises(gl.GLUsageError, match=r"bgnpolygon\(\): bgnpolygon\(\) is still"):
        gl.bgnpolygon()
    with pytest.raises(gl.GLUsageError, match=r"endline\(\): without bgnline"):
        gl.endline()
    gl.endpolygon()


def test_a_rejected_call_changes_nothing(ctx):
    gl.stencil(1, 0, GL.SF_ALWAYS, 0xFF, GL.ST_KEEP, GL.ST_KEEP, GL.ST_INCR)
    reg = ctx.raster.stencil
    with pytest.raises(gl.GLTypeError):
        gl.stencil(1, 0, 7.0, 0xFF, 0, 0, 3)  # equal to the remembered valid tuple, a float
    assert ctx.raster.stencil is reg
    gl.stencil(1, 0, 7, 0xFF, 0, 0, 0)
    gl.stencil(1, 0, 7, 0xFF, 0, 0, 3)  # the same values as ints: the remembered register
    assert ctx.raster.stencil is reg
    colour = ctx.colour
    with pytest.raises(gl.GLTypeError):
        gl.cpack(2.0)
    assert ctx.colour is colour


def test_cpack_interns_colours(ctx):
    # One RGBA tuple per packed word: a repeated cpack leaves the same object, so the
    # command stream sends no new SYNC for it.
    gl.cpack(0xFF00FF00)
    first = ctx.colour
    gl.cpack(0xFF0000FF)
    gl.cpack(0xFF00FF00)
    assert ctx.colour is first
    assert ctx.colour == (0.0, 1.0, 0.0, 1.0)
