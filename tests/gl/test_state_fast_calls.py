"""afunction, lsetdepth, lmcolor, mmode, frontbuffer, backbuffer and setlinestyle's
valid paths (FAST_CALLS) store what their general paths store: random sequences of
them between lit and unlit polygons and styled lines give the same state after every
call and the same colour, z and stencil planes with the switch on and off, and from
display objects; hand-computed effects of each; bad values raise the GLError
naming the call."""

from __future__ import annotations

import numpy as np
import pytest

from vgxsim import GL, gl
from vgxsim.gl import _core
from vgxsim.gl._core import GLTypeError, GLUsageError, GLValueError, session

W, H = 24, 20

CALLS = [
    ("afunction", [(0, GL.AF_ALWAYS), (128, GL.AF_GREATER), (40, GL.AF_LESS),
                   (255, GL.AF_NOTEQUAL), (7, 2)]),
    ("lsetdepth", [(-0x800000, 0x7FFFFF),
                   (0, 0x7FFFFF), (0x100000, -0x200000), (5, 5)]),
    ("lmcolor", [(GL.LMC_COLOR,), (GL.LMC_DIFFUSE,), (GL.LMC_AD,), (GL.LMC_NULL,),
                 (GL.LMC_EMISSION,), (2,)]),
    ("mmode", [(GL.MVIEWING,), (GL.MSINGLE,), (GL.MPROJECTION,), (2,)]),
    ("frontbuffer", [(0,), (1,), (GL.TRUE,), (7,)]),
    ("backbuffer", [(1,), (0,), (1,)]),
    ("setlinestyle", [(0,), (1,), (2,)]),
]


def _window():
    gl.prefsize(W, H)
    gl.winopen("state")
    gl.doublebuffer()
    gl.RGBmode()
    gl.stensize(8)
    gl.gconfig()
    gl.zbuffer(1)
    gl.mmode(GL.MVIEWING)  # identity matrices: vertices in clip coordinates
    gl.deflinestyle(1, 0x3C3C)
    gl.deflinestyle(2, 0x5A0F)
    gl.lmdef(GL.DEFMATERIAL, 1, [GL.DIFFUSE, 0.8, 0.6, 0.4, GL.LMNULL])
    gl.lmdef(GL.DEFLMODEL, 1, [GL.LMNULL])
    gl.lmdef(GL.DEFLIGHT, 1, [GL.POSITION, 0.0, 0.0, 1.0, 0.0, GL.LMNULL])
    return session.windows[session.current]


def _state(ctx) -> tuple:
    return (repr(ctx.raster._key()), ctx.depth_range, ctx.lmcolor_mode, ctx.lmcolor_set,
            ctx.matrices.mode, ctx.linestyle_index)


def program(seed: int) -> list:
    rng = np.random.default_rng(seed)
    ops = []
    for _ in range(50):
        name, values = CALLS[int(rng.integers(0, len(CALLS)))]
        ops.append((name, values[int(rng.integers(0, len(values)))]))
        lit = rng.random() < 0.4
        ops.append(("draw", (int(rng.integers(0, 1 << 32)), lit,
                             tuple(float(v) for v in rng.uniform(-0.9, 0.5, 3)))))
    return ops


def _draw(word: int, lit: bool, xyz: tuple) -> None:
    gl.lmbind(GL.MATERIAL, 1 if lit else 0)
    gl.lmbind(GL.LMODEL, 1)
    gl.lmbind(GL.LIGHT0, 1)
    gl.cpack(word)
    gl.n3f(0.0, 0.0, 1.0)
    x, y, z = xyz
    gl.bgnpolygon()
    for p in ((x, y, z), (x + 0.5, y + 0.1, -z), (x + 0.2, y + 0.6, 0.0)):
        gl.v3f(p)
    gl.endpolygon()
    gl.bgnline()
    gl.v3f(x, y + 0.3, z)
    gl.v3f(x + 0.8, y - 0.2, 0.0)
    gl.endline()


def run(ops, ctx, states=None) -> None:
    for name, args in ops:
        if name == "draw":
            _draw(*args)
        else:
            getattr(gl, name)(*args)
        if states is not None:
            states.append(_state(ctx))


def planes(ctx) -> tuple:
    ctx.flush()
    return (ctx.colour_buffer("front").copy(), ctx.colour_buffer("back").copy(),
            ctx.fb.z.copy(), ctx.fb.stencil.copy())


@pytest.fixture
def fresh(monkeypatch):
    session.reset()
    yield
    session.reset()
    monkeypatch.setattr(_core, "FAST_CALLS", True)
    session.refresh()


@pytest.mark.parametrize("seed", range(4))
def test_valid_paths_store_what_the_general_paths_store(fresh, seed, monkeypatch):
    ops = program(seed)
    out = {}
    for fast in (True, False):
        monkeypatch.setattr(_core, "FAST_CALLS", fast)
        session.reset()
        ctx = _window()
        states: list = []
        run(ops, ctx, states)
        out[fast] = (states, planes(ctx))
    assert out[True][0] == out[False][0]
    for a, b in zip(out[True][1], out[False][1], strict=True):
        assert np.array_equal(a, b)
    assert out[True][1][0].any() or out[True][1][1].any()


@pytest.mark.parametrize("seed", range(3))
def test_display_objects_draw_what_immediate_mode_draws(fresh, seed):
    ops = program(seed)
    ctx = _window()
    run(ops, ctx)
    want = planes(ctx)
    want_state = _state(ctx)
    session.reset()
    ctx = _window()
    gl.makeobj(3)
    run(ops, ctx)
    gl.closeobj()
    gl.callobj(3)
    got = planes(ctx)
    assert _state(ctx) == want_state
    for a, b in zip(want, got, strict=True):
        assert np.array_equal(a, b)


def _quad(z: float = 0.0) -> None:
    gl.bgnpolygon()
    for p in ((-1.0, -1.0, z), (1.0, -1.0, z), (1.0, 1.0, z), (-1.0, 1.0, z)):
        gl.v3f(p)
    gl.endpolygon()


def test_hand_computed_effects(fresh):
    ctx = _window()
    gl.backbuffer(0)
    gl.frontbuffer(1)  # only the front buffer is drawn
    gl.afunction(128, GL.AF_GREATER)  # alpha 0x80 = 128 fails, 0x81 passes
    gl.cpack(0x800000FF)
    _quad()
    front = ctx.colour_buffer("front")
    assert not front.any()
    gl.cpack(0x810000FF)
    _quad()
    assert (ctx.colour_buffer("front") == 0x810000FF).all()
    assert not ctx.colour_buffer("back").any()
    # lsetdepth(0, 1000): z = 0 in clip space lands half-way, at 500 (the far plane
    # z = 1 at 1000); zfunction LEQUAL keeps it.
    gl.afunction(0, GL.AF_ALWAYS)
    gl.lsetdepth(0, 1000)
    _quad(0.0)
    gl.lsetdepth(-1000, 0)
    _quad(1.0)
    ctx.flush()
    assert (ctx.fb.z == 0).all()  # (-1000 + (1 + 1) * 1000 / 2 = 0, the second quad's)
    gl.mmode(GL.MPROJECTION)
    assert gl.getmmode() == GL.MPROJECTION
    gl.lmcolor(GL.LMC_DIFFUSE)
    assert ctx.lmcolor_mode == int(GL.LMC_DIFFUSE)
    gl.setlinestyle(2)
    assert gl.getlstyle() == 2 and ctx.raster.linestyle == 0x5A0F


@pytest.mark.parametrize("call, args, error, pattern", [
    ("afunction", (256, GL.AF_GREATER), GLValueError, r"afunction\(256, AF_GREATER\): ref 256"),
    ("afunction", (1, 8), GLValueError, r"afunction\(1, 8\): func 8"),
    ("afunction", (1.0, 2), GLTypeError, r"afunction\(1.0, 2\)"),
    ("afunction", (1,), GLTypeError, r"afunction\(1\): expected 2"),
    ("lsetdepth", (0, 0x800000), GLValueError, r"lsetdepth\(0, 8388608\): far"),
    ("lsetdepth", (0.5, 1), GLTypeError, r"lsetdepth\(0.5, 1\)"),
    ("lmcolor", (7,), GLValueError, r"lmcolor\(7\): mode 7"),
    ("lmcolor", ("a",), GLTypeError, r"lmcolor\('a'\)"),
    ("mmode", (4,), GLValueError, r"mmode\(4\): mode 4"),
    ("mmode", (), GLTypeError, r"mmode\(\): expected 1"),
    ("frontbuffer", (1.5,), GLTypeError, r"frontbuffer\(1.5\)"),
    ("frontbuffer", (1 << 40,), GLValueError, r"frontbuffer\(1099511627776\)"),
    ("backbuffer", (1, 2), GLTypeError, r"backbuffer\(1, 2\): expected 1"),
    ("setlinestyle", (9,), GLValueError, r"setlinestyle\(9\): line style 9 is not"),
    ("setlinestyle", (1.0,), GLTypeError, r"setlinestyle\(1.0\)"),
])
def test_bad_values_raise_naming_the_call(fresh, call, args, error, pattern):
    _window()
    with pytest.raises(error, match=pattern):
        getattr(gl, call)(*args)
    with pytest.raises(GLTypeError, match=call + r"\("):
        getattr(gl, call)(*args, x=1)


def test_lsetdepth_under_zrangemap_takes_the_general_range(fresh):
    _window()
    gl.glcompat(GL.GLC_ZRANGEMAP, 1)
    with pytest.raises(GLValueError, match=r"lsetdepth\(-1, 5\): near -1"):
        gl.lsetdepth(-1, 5)
    gl.lsetdepth(0, 0x7FFFFF)
    assert session.windows[session.current].depth_range == (0, 0x7FFFFF)


def test_frontbuffer_under_zdraw_takes_the_general_path(fresh):
    _window()
    gl.zbuffer(0)
    gl.zdraw(1)
    # zdraw draws the z-buffer and one colour buffer: the back one already.
    with pytest.raises(GLUsageError, match=r"frontbuffer\(1\): zdraw with both"):
        gl.frontbuffer(1)
