"""Call binding (issue 11 item 1): wrong counts, keywords and types are GLTypeErrors
naming the call and its arguments; calls inside makeobj are validated when recorded;
callobj nesting is bounded."""

from __future__ import annotations

import numpy as np
import pytest

from vgxsim import GL, gl
from vgxsim.gl import _core, _objects

W, H = 16, 12


@pytest.fixture
def ctx(gl_window):
    return gl_window(W, H)


@pytest.mark.parametrize("call, args, kwargs, pattern", [
    ("zbuffer", (1, 2), {}, r"zbuffer\(1, 2\): expected 1 argument, got 2"),
    ("acbuf", (1,), {}, r"acbuf\(1\): expected 2 arguments, got 1"),
    ("stencil", (1, 0), {}, r"stencil\(1, 0\): expected 7 arguments, got 2"),
    ("stencil", (), {"enable": 1}, r"stencil\(enable=1\): .*positional arguments only"),
    ("cpack", (), {}, r"cpack\(\): expected 1 argument, got 0"),
    ("v3f", (1.0, 2.0, 3.0), {"w": 1.0}, r"v3f\(1.0, 2.0, 3.0, w=1.0\)"),
    ("bgnpolygon", (), {"x": 1}, r"bgnpolygon\(x=1\)"),
])
def test_bad_binding_is_a_gl_type_error(ctx, call, args, kwargs, pattern):
    with pytest.raises(gl.GLTypeError, match=pattern):
        getattr(gl, call)(*args, **kwargs)


def test_wrong_type_names_the_call(ctx):
    with pytest.raises(gl.GLTypeError, match=r"zwritemask\(1.5\)"):
        gl.zwritemask(1.5)


def test_makeobj_validates_when_recorded_and_keeps_the_object(ctx):
    gl.makeobj(1)
    gl.cpack(0xFFFFFFFF)
    gl.rectf(1, 1, 5, 5)
    for bad, error in ((lambda: gl.cpack(), gl.GLTypeError),
                       (lambda: gl.cpack("red"), gl.GLTypeError),
                       (lambda: gl.stencil(1, 0), gl.GLTypeError),
                       (lambda: gl.zbuffer(1.5), gl.GLTypeError),
                       (lambda: gl.v3f(float("nan"), 0.0, 0.0), gl.GLValueError),
                       (lambda: gl.n3f(1.0, 2.0), gl.GLTypeError)):
        with pytest.raises(error):
            bad()
    gl.bgnpolygon()
    with pytest.raises(gl.GLUsageError, match="still open"):
        gl.bgnpolygon()
    with pytest.raises(gl.GLUsageError, match="endline"):
        gl.endline()
    gl.endpolygon()  # the polygon without vertices: draws nothing
    gl.closeobj()
    assert gl.isobj(1)
    gl.callobj(1)
    img = ctx.read_rgba()
    # Only the rectf drew: 4 x 4 pixels of white.
    assert (img[..., 0] == 255).sum() == 16


def test_callobj_nesting_limit(ctx):
    depth = _objects.MAX_NESTING + 1
    gl.makeobj(1)
    gl.cpack(0xFFFFFFFF)
    gl.rectf(0, 0, 2, 2)
    gl.closeobj()
    for k in range(2, depth + 1):  # object k calls object k - 1
        gl.makeobj(k)
        gl.callobj(k - 1)
        gl.closeobj()
    gl.callobj(depth - 1)  # MAX_NESTING deep: allowed
    assert (ctx.read_rgba()[..., 0] == 255).sum() == 4
    with pytest.raises(gl.GLUsageError, match=f"nested more than {_objects.MAX_NESTING}"):
        gl.callobj(depth)


def test_long_chain_does_not_use_the_python_stack(ctx, monkeypatch):
    """500 objects each calling the previous (issue 11's RecursionError case) with the
    limit raised: the explicit stack runs it."""
    monkeypatch.setattr(_objects, "MAX_NESTING", 2000)
    gl.makeobj(1)
    gl.cpack(0xFF0000FF)
    gl.rectf(0, 0, 1, 1)
    gl.closeobj()
    for k in range(2, 501):
        gl.makeobj(k)
        gl.callobj(k - 1)
        gl.closeobj()
    import sys

    limit = sys.getrecursionlimit()
    sys.setrecursionlimit(200)
    try:
        gl.callobj(500)
    finally:
        sys.setrecursionlimit(limit)
    assert tuple(ctx.read_rgba()[0, 0]) == (255, 0, 0, 255)


def test_colour_call_in_object_called_in_cmode_window(gl_window):
    gl_window(W, H)
    gl.makeobj(3)
    gl.c3f(1.0, 0.0, 0.0)
    gl.closeobj()
    obj = _core.session.objects[3]
    gl_window(W, H, rgb=False)
    _core.session.objects[3] = obj
    with pytest.raises(gl.GLUsageError, match=r"c3f\(1.0, 0.0, 0.0\).*colour map mode"):
        gl.callobj(3)


def test_object_colours_follow_the_callers_lmcolor(ctx):
    """A colour call recorded in an object sets the caller's colour in LMC_COLOR and
    is ignored in LMC_NULL, as in immediate mode (lmcolor(3G))."""
    gl.lmdef(GL.DEFMATERIAL, 1, [GL.LMNULL])
    gl.lmdef(GL.DEFLMODEL, 1, [GL.LMNULL])
    gl.makeobj(4)
    gl.c3f(0.0, 1.0, 0.0)
    gl.closeobj()
    gl.lmbind(GL.MATERIAL, 1)
    gl.lmbind(GL.LMODEL, 1)
    gl.cpack(0xFF0000FF)
    gl.lmcolor(GL.LMC_NULL)
    gl.callobj(4)
    assert ctx.colour == (1.0, 0.0, 0.0, 1.0)
    gl.lmcolor(GL.LMC_COLOR)
    gl.callobj(4)
    assert ctx.colour == (0.0, 1.0, 0.0, 1.0) and ctx.last_sent == "colour"
    assert np.isfinite(ctx.colour).all()
