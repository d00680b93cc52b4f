"""Display objects (gl/_objects.py): recording, replay equal to immediate mode, errors."""

from __future__ import annotations

import numpy as np
import pytest

from vgxsim import GL, gl
from vgxsim.gl import _core
from vgxsim.state.raster import FLAT

W, H = 48, 40


@pytest.fixture
def ctx(gl_window):
    c = gl_window(W, H, projection=False)
    gl.ortho2(-0.5, W - 0.5, -0.5, H - 0.5)
    return c


def planes(c) -> tuple[np.ndarray, np.ndarray]:
    return c.read_rgba().copy(), c.fb.z.copy()


def same_in_object(c, draw) -> tuple:
    """Pixels and z of ``draw()`` run immediately, then of an object holding it."""
    draw()
    immediate = planes(c)
    c.fb.front[:] = 0
    c.fb.z[:] = np.iinfo(np.int32).max >> 8
    gl.makeobj(7)
    draw()
    gl.closeobj()
    gl.callobj(7)
    return immediate, planes(c)


def scene():
    """A bit of everything the compiler handles, with Gouraud colours per vertex."""
    rng = np.random.default_rng(5)
    gl.bgnpolygon()
    for (x, y), col in zip([(2, 3), (20, 1), (25, 15), (9, 19)], rng.random((4, 3)),
                           strict=True):
        gl.c3f(col)
        gl.v3f(x, y, 0.25)
    gl.endpolygon()
    gl.cpack(0xFF3070F0)
    gl.bgntmesh()
    gl.v2i(30, 2)
    gl.v2i(45, 4)
    gl.swaptmesh()
    gl.c3f(0.2, 0.9, 0.1)
    gl.v2i(44, 18)
    gl.swaptmesh()
    gl.v2i(33, 20)
    gl.endtmesh()
    gl.bgnqstrip()
    for p in [(2, 24), (2, 30), (12, 25), (12, 31), (22, 24), (22, 32)]:
        gl.c4f(p[0] / 30, p[1] / 40, 0.5, 1.0)
        gl.v2i(p)
    gl.endqstrip()
    gl.rectf(26, 24, 40, 30)
    gl.polf2([30, 32, 46, 33, 40, 38])
    gl.pmv2i(14, 33)
    gl.pdr2i(24, 33)
    gl.pdr2i(20, 38)
    gl.pclos()
    gl.bgnclosedline()
    gl.varray([(1, 1), (46, 1), (46, 38), (1, 38)])
    gl.endclosedline()
    gl.bgnpoint()
    gl.v2i(5, 35)
    gl.v2i(7, 35)
    gl.endpoint()


@pytest.mark.parametrize("flat", [False, True])
def test_replay_is_pixel_identical_to_immediate_mode(ctx, flat):
    ctx.raster.set(zbuffer=True, shademodel=FLAT if flat else 1)
    (img_a, z_a), (img_b, z_b) = same_in_object(ctx, scene)
    assert img_a[..., :3].any()
    assert np.array_equal(img_a, img_b) and np.array_equal(z_a, z_b)


def test_runs_become_few_draws(ctx, monkeypatch):
    gl.makeobj(1)
    scene()
    gl.closeobj()
    program = _core.session.objects[1].program
    assert [e[0] for e in program] == ["run"]
    calls = []
    # What the stream decoder hands the geometry passes: triangle groups are
    # deferred as one list, lines and points drawn one primitive each.
    from vgxsim.pipeline import decode, draw

    monkeypatch.setattr(draw, "FLUSH_FRONT", False)  # the group path, which this spies on
    real_draw, real_defer = decode.draw_arrays, decode.defer_triangles
    monkeypatch.setattr(decode, "draw_arrays", lambda c, s, lms, kind, *a, **k: (
        calls.append(kind), real_draw(c, s, lms, kind, *a, **k)))
    monkeypatch.setattr(decode, "defer_triangles", lambda *a, **k: (
        calls.append("triangles"), real_defer(*a, **k)))
    gl.callobj(1)
    ctx.flush()
    # polygon+tmesh+qstrip+rectf+polf+pmv merge into one triangle draw; then the
    # closed line, then both points in one draw.
    assert calls == ["triangles", "closedline", "point"]


def test_replay_with_lighting_and_lmcolor(ctx):
    gl.lmdef(GL.DEFMATERIAL, 1, [GL.DIFFUSE, 0.8, 0.6, 0.4, GL.SPECULAR, 0.5, 0.5, 0.5,
                                 GL.SHININESS, 20.0, GL.LMNULL])
    gl.lmdef(GL.DEFLIGHT, 1, [GL.POSITION, 0.3, 0.4, 1.0, 0.0, GL.LMNULL])
    gl.lmdef(GL.DEFLMODEL, 1, [GL.LMNULL])
    gl.lmbind(GL.MATERIAL, 1)
    gl.lmbind(GL.LIGHT0, 1)
    gl.lmbind(GL.LMODEL, 1)

    def draw():
        rng = np.random.default_rng(9)
        for i in range(6):
            gl.bgnpolygon()
            for j in range(4):
                if (i + j) % 3 == 0:
                    gl.c3f(rng.random(3))  # coloured vertex (LMC_COLOR)
                else:
                    gl.n3f(rng.normal(size=3))  # lit vertex
                gl.v2f(3 + 7 * i + 6 * (j in (1, 2)), 5 + 20 * (j >= 2))
            gl.endpolygon()

    for mode in (GL.LMC_COLOR, GL.LMC_AD, GL.LMC_NULL):
        gl.lmcolor(mode)
        ctx.fb.front[:] = 0
        (img_a, _), (img_b, _) = same_in_object(ctx, draw)
        assert img_a[..., :3].any()
        assert np.array_equal(img_a, img_b), mode


def test_object_inherits_and_changes_caller_state(ctx):
    gl.makeobj(3)
    gl.rectf(2, 2, 6, 6)
    gl.closeobj()
    gl.makeobj(4)
    gl.cpack(0xFF00FF00)
    gl.n3f(0, 1, 0)
    gl.t2f(0.5, 0.25)
    gl.pnt2i(20, 20)
    gl.closeobj()
    gl.cpack(0xFF0000FF)
    gl.callobj(3)
    gl.translate(10, 0, 0)
    gl.cpack(0xFFFF0000)
    gl.callobj(3)
    img = ctx.read_rgba()
    assert tuple(img[3, 3]) == (255, 0, 0, 255) and tuple(img[3, 13]) == (0, 0, 255, 255)
    gl.callobj(4)
    assert ctx.colour == (0.0, 1.0, 0.0, 1.0) and ctx.normal == (0.0, 1.0, 0.0)
    assert ctx.last_sent == "normal" and ctx.texcoord == (0.5, 0.25)
    assert ctx.gpos == (20.0, 20.0, 0.0, 1.0)
    assert tuple(ctx.read_rgba()[20, 30]) == (0, 255, 0, 255)  # translated by 10


def test_state_calls_between_runs_are_replayed(ctx):
    def draw():
        gl.pushmatrix()
        gl.rectf(1, 1, 4, 4)
        gl.translate(10, 0, 0)
        gl.rectf(1, 1, 4, 4)
        gl.popmatrix()
        gl.rectf(1, 10, 4, 14)

    (img_a, _), (img_b, _) = same_in_object(ctx, draw)
    assert np.array_equal(img_a, img_b)
    assert img_b[2, 12, 0] == 255 and img_b[12, 2, 0] == 255
    kinds = [e[0] for e in _core.session.objects[7].program]
    assert kinds == ["call", "run", "call", "run", "call", "run"]


def test_concave_state_at_replay_is_honoured(ctx):
    ell = [(12, 2), (12, 6), (6, 6), (6, 12), (2, 12), (2, 2)]

    def draw():
        gl.cpack(0xFFFFFFFF)
        gl.bgnpolygon()
        for p in ell:
            gl.v2i(p)
        gl.endpolygon()

    gl.concave(1)
    (img_a, _), (img_b, _) = same_in_object(ctx, draw)
    assert np.array_equal(img_a, img_b) and (img_b[..., 0] > 0).sum() == 64


def test_vertices_of_a_primitive_opened_by_the_caller(ctx):
    gl.makeobj(5)
    gl.v2i(2, 2)
    gl.v2i(8, 2)
    gl.v2i(8, 6)
    gl.closeobj()
    gl.cpack(0xFFFFFFFF)
    gl.bgnpolygon()
    gl.callobj(5)
    gl.v2i(2, 6)
    gl.endpolygon()
    assert (ctx.read_rgba()[..., 0] > 0).sum() == 6 * 4


def test_nested_objects_and_recursion(ctx):
    gl.makeobj(1)
    gl.rectf(1, 1, 3, 3)
    gl.closeobj()
    gl.makeobj(2)
    gl.cpack(0xFFFFFFFF)
    gl.callobj(1)
    gl.translate(5, 0, 0)
    gl.callobj(1)
    gl.closeobj()
    gl.callobj(2)
    assert (ctx.read_rgba()[..., 0] > 0).sum() == 8
    gl.makeobj(3)
    gl.callobj(4)
    gl.closeobj()
    gl.makeobj(4)
    gl.callobj(3)
    gl.closeobj()
    with pytest.raises(gl.GLUsageError, match=r"callobj\(3\).*3 -> 4 -> 3"):
        gl.callobj(3)
    gl.callobj(99)  # undefined objects are ignored (callobj(3G))


def test_object_bookkeeping(ctx):
    a = gl.genobj()
    b = gl.genobj()
    assert a != b and not gl.isobj(a)
    gl.makeobj(a)
    assert gl.isobj(a) and gl.getopenobj() == a
    m = gl.getmatrix()  # queries execute while recording
    assert len(m) == 16
    gl.rectf(1, 1, 3, 3)  # recorded, not drawn
    gl.closeobj()
    assert not ctx.read_rgba()[..., :3].any()
    assert gl.getopenobj() == -1 and gl.genobj() not in (a, b)
    gl.makeobj(a)  # redefining replaces the contents
    gl.closeobj()
    gl.callobj(a)
    assert not ctx.read_rgba()[..., :3].any()
    gl.delobj(a)
    assert not gl.isobj(a)


def test_object_errors(ctx):
    with pytest.raises(gl.GLUsageError, match="closeobj.*no object"):
        gl.closeobj()
    gl.makeobj(1)
    with pytest.raises(gl.GLUsageError, match=r"makeobj\(2\).*still open"):
        gl.makeobj(2)
    with pytest.raises(gl.GLUsageError, match="delobj"):
        gl.delobj(1)
    gl.rectf(1, 1, 3, 3)
    with pytest.raises(gl.GLTypeError, match="v3f"):
        gl.v3f("bad", 0, 0)  # validated when recorded (issue 11): the object is unchanged
    gl.closeobj()
    assert len(_core.session.objects[1].program) == 1
    gl.callobj(1)
    assert (ctx.read_rgba()[..., 0] > 0).sum() == 4  # the rectf recorded before it
    with pytest.raises(gl.GLValueError, match="makeobj"):
        gl.makeobj(-1)
    with pytest.raises(gl.GLTypeError, match="callobj"):
        gl.callobj(1.0)
    _core.session.reset()
    with pytest.raises(gl.GLUsageError, match="makeobj.*winopen"):
        gl.makeobj(1)


def test_large_mesh_replays_identically(ctx):
    rng = np.random.default_rng(2)
    pts = rng.uniform(0, W, size=(600, 3, 2))
    cols = rng.random((600, 3))

    def draw():
        for tri, col in zip(pts, cols, strict=True):
            gl.bgnpolygon()
            gl.c3f(col)
            for p in tri:
                gl.v2f(p)
            gl.endpolygon()

    (img_a, _), (img_b, _) = same_in_object(ctx, draw)
    assert np.array_equal(img_a, img_b)


def test_draw_arrays_copies_caller_arrays_before_deferring():
    """Immediate-mode triangles are queued for a combined geometry pass; a library
    caller that reuses its vertex array right after draw_arrays must not change what
    was drawn."""
    import numpy as np

    from vgxsim.geometry.transform import orthographic
    from vgxsim.pipeline.context import Context

    ctx = Context(8, 8)
    ctx.matrices.load_projection(orthographic(-0.5, 7.5, -0.5, 7.5, -1.0, 1.0))
    obj = np.array([[0, 0, 0, 1], [7, 0, 0, 1], [7, 7, 0, 1], [0, 7, 0, 1]], float)
    col = np.ones((4, 4))
    ctx.draw_arrays("polygon", obj, col)
    obj[:] = 100.0  # reuse the arrays before the batch is flushed
    col[:] = 0.0
    img = ctx.read_rgba()
    assert (img[1:6, 1:6, :3] == 255).all()
