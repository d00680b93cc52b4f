"""Fast paths of the common calls (issue 6 per-call cost) against their general paths.

translate() defers its product (state/matrices.py DEFER_TRANSLATE; rot, rotate,
scale, multmatrix and loadmatrix join it, DEFER_PRODUCTS) and pushmatrix
shares the top matrix; cpack, c3f, lmbind, stencil and translate take inlined checks
for plain ints/floats.  Each must leave exactly the state and planes the general path
leaves: the deferral is switched off, the inlined checks are bypassed by passing the
same values as numpy scalars (which only the general path accepts).
"""

from __future__ import annotations

import random

import numpy as np
import pytest

from vgxsim import GL, gl
from vgxsim.gl._core import current
from vgxsim.state import matrices

W, H = 24, 20


@pytest.fixture
def ctx(gl_window):
    return gl_window(W, H)


def _scene(seed: int) -> dict[str, np.ndarray]:
    """Random lit and unlit quads under random push/translate/rotate/scale/pop and
    mmode switches; the colour, z and stencil planes afterwards."""
    rng = random.Random(seed)
    gl.mmode(GL.MVIEWING)
    gl.perspective(600, W / H, 0.5, 50.0)
    gl.lmdef(GL.DEFMATERIAL, 1, [GL.DIFFUSE, 0.8, 0.5, 0.2, GL.LMNULL])
    gl.lmdef(GL.DEFLMODEL, 1, [GL.LMNULL])
    gl.lmdef(GL.DEFLIGHT, 1, [GL.POSITION, 0.3, 0.5, 1.0, 0.0, GL.LMNULL])
    gl.zbuffer(1)
    gl.czclear(0, gl.getgdesc(GL.GD_ZMAX))
    gl.translate(0.0, 0.0, -6.0)
    depth = 0
    for _ in range(60):
        r = rng.random()
        if r < 0.15 and depth < 8:
            gl.pushmatrix()
            depth += 1
        elif r < 0.3 and depth:
            gl.popmatrix()
            depth -= 1
        elif r < 0.5:
            gl.translate(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1))
        elif r < 0.53:
            gl.rot(rng.uniform(-90, 90), rng.choice("xyz"))
        elif r < 0.55:
            gl.rotate(rng.randrange(-900, 900), rng.choice("xyzX"))
        elif r < 0.57:
            m = [1.0 + rng.uniform(-0.2, 0.2) if i in (0, 5, 10) else
                 rng.uniform(-0.2, 0.2) if i not in (3, 7, 11, 15) else 0.0
                 for i in range(16)]
            m[15] = 1.0
            gl.multmatrix(m if rng.random() < 0.5 else tuple(m))
        elif r < 0.58:
            gl.loadmatrix([1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0,
                           rng.uniform(-1, 1), rng.uniform(-1, 1), -6.0, 1.0])
        elif r < 0.6:
            gl.scale(rng.uniform(0.5, 1.5), rng.uniform(0.5, 1.5), 1.0)
        elif r < 0.63:
            gl.lmbind(GL.LIGHT0, 1)  # transformed by the modelview in effect now
        elif r < 0.66:
            gl.lmbind(GL.MATERIAL, rng.choice((0, 1)))
            gl.lmbind(GL.LMODEL, 1)
        elif r < 0.68:
            gl.mmode(GL.MPROJECTION)
            gl.translate(rng.uniform(-0.1, 0.1), 0.0, 0.0)
            gl.mmode(GL.MVIEWING)
        else:
            gl.cpack(rng.getrandbits(32))
            gl.bgnpolygon()
            gl.n3f(0.0, 0.0, 1.0)
            for x, y in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
                gl.v3f(x * 0.7, y * 0.5, rng.uniform(-0.2, 0.2))
            gl.endpolygon()
    out = {"color": gl.read_pixels(), "z": gl.read_pixels(plane="z"),
           "matrix": np.array(gl.getmatrix())}
    return out


@pytest.mark.parametrize("switches", [("DEFER_TRANSLATE",), ("DEFER_PRODUCTS",),
                                      ("DEFER_TRANSLATE", "DEFER_PRODUCTS")])
@pytest.mark.parametrize("seed", range(4))
def test_deferred_translate_gives_the_same_planes(gl_window, monkeypatch, seed, switches):
    gl_window(W, H, rgb=True)
    fast = _scene(seed)
    for switch in switches:
        monkeypatch.setattr(matrices, switch, False)
    gl_window(W, H, rgb=True)
    slow = _scene(seed)
    assert np.any(fast["color"] != 0)  # the scene draws something
    for k in fast:
        np.testing.assert_array_equal(fast[k], slow[k], err_msg=k)


def test_push_shares_and_translate_is_exact(ctx):
    # Hand-computed: the window's ortho2 single matrix, translated by (2, 3, 0) under a
    # pushmatrix, is row 3 + 2 * row 0 + 3 * row 1; popmatrix brings the original back.
    base = np.array(gl.getmatrix())
    gl.pushmatrix()
    gl.translate(2.0, 3.0, 0.0)
    gl.translate(-1.0, 0.0, 0.0)
    moved = np.array(gl.getmatrix()).reshape(4, 4)
    b = base.reshape(4, 4)
    np.testing.assert_allclose(moved[3], b[3] + 1.0 * b[0] + 3.0 * b[1])
    np.testing.assert_array_equal(moved[:3], b[:3])
    gl.popmatrix()
    np.testing.assert_array_equal(np.array(gl.getmatrix()), base)
    gl.pushmatrix()
    gl.translate(5.0, 0.0, 0.0)
    gl.popmatrix()  # the deferred translation is dropped with its matrix
    np.testing.assert_array_equal(np.array(gl.getmatrix()), base)


@pytest.mark.parametrize("call, plain, numpy_form", [
    ("cpack", (0x80FF4020,), (np.uint32(0x80FF4020),)),
    ("c3f", (0.25, 0.5, 1.0), (np.float64(0.25), np.float64(0.5), np.float64(1.0))),
])
def test_colour_fast_paths_match_the_general_path(ctx, call, plain, numpy_form):
    getattr(gl, call)(*plain)
    fast = (ctx.colour, ctx.last_sent)
    ctx.colour = None
    getattr(gl, call)(*numpy_form)
    assert (ctx.colour, ctx.last_sent) == fast


def test_cpack_fast_path_values(ctx):
    gl.cpack(0x80FF4020)  # 0xAABBGGRR: red 0x20, green 0x40, blue 0xFF, alpha 0x80
    assert ctx.colour == (0x20 / 255, 0x40 / 255, 1.0, 0x80 / 255)
    gl.cpack(-1)  # an unsigned long: -1 is 0xFFFFFFFF
    assert ctx.colour == (1.0, 1.0, 1.0, 1.0)


def test_lmbind_fast_path_matches_the_general_path(ctx):
    gl.lmdef(GL.DEFMATERIAL, 3, [GL.DIFFUSE, 0.1, 0.2, 0.3, GL.LMNULL])
    gl.lmdef(GL.DEFLMODEL, 2, [GL.LMNULL])
    for target, index in ((GL.MATERIAL, 3), (GL.LMODEL, 2), (GL.BACKMATERIAL, 3),
                          (GL.MATERIAL, 0)):
        before, serial = dict(ctx.bound), ctx.lighting_serial
        ctx.lmcolor_set = True
        gl.lmbind(target, index)
        fast = (dict(ctx.bound), ctx.lmcolor_set, ctx.lighting_serial - serial)
        ctx.bound.clear()
        ctx.bound.update(before)
        ctx.lmcolor_set, serial = True, ctx.lighting_serial
        gl.lmbind(np.int64(target), np.int64(index))
        assert (dict(ctx.bound), ctx.lmcolor_set, ctx.lighting_serial - serial) == fast
        assert ctx.bound[{GL.MATERIAL: "material", GL.LMODEL: "lmodel",
                          GL.BACKMATERIAL: "backmaterial"}[target]] == index
    with pytest.raises(gl.GLValueError, match=r"material 4 is not defined"):
        gl.lmbind(GL.MATERIAL, 4)
    with pytest.raises(gl.GLValueError, match=r"outside 0..32767"):
        gl.lmbind(GL.MATERIAL, 1 << 20)
    with pytest.raises(gl.GLTypeError):
        gl.lmbind(float(GL.MATERIAL), 1)  # 1.0 hashes as 1: not a token


def test_stencil_fast_path_matches_the_general_path(ctx):
    args = (1, 5, GL.SF_EQUAL, 0xF0, GL.ST_KEEP, GL.ST_INCR, GL.ST_DECR)
    gl.stencil(*args)
    fast = tuple(ctx.raster.stencil)
    gl.stencil(0, 0, 0, 0, 0, 0, 0)
    gl.stencil(*(np.int64(a) for a in args))
    assert tuple(ctx.raster.stencil) == fast == (True, 5, GL.SF_EQUAL, 0xF0, GL.ST_KEEP,
                                                  GL.ST_INCR, GL.ST_DECR)


def test_translate_fast_path_matches_the_general_path(gl_window):
    planes = []
    for form in (float, np.float64):
        gl_window(W, H)
        gl.pushmatrix()
        gl.translate(form(0.5), form(-2.0), form(3.25))
        gl.rot(form(30.0), "z")
        gl.translate(form(1.0 / 3.0), form(7.0), form(0.0))
        planes.append(np.array(gl.getmatrix()))
    np.testing.assert_array_equal(planes[0], planes[1])
    for bad in ((float("nan"), 0.0, 0.0), (0.0, float("inf"), 0.0)):
        with pytest.raises(gl.GLValueError, match=r"^translate\("):
            gl.translate(*bad)


@pytest.mark.parametrize("call", ["pushmatrix", "popmatrix"])
def test_stack_calls_take_no_arguments(ctx, call):
    with pytest.raises(gl.GLTypeError, match=rf"^{call}\(1\): expected 0 arguments"):
        getattr(gl, call)(1)
    assert current("t").matrices.modelview[-1] is not None
