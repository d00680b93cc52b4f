"""Primitives and vertex calls (gl/_draw.py) against hand-computed pixels."""

from __future__ import annotations

import numpy as np
import pytest

from vgxsim import GL, gl
from vgxsim.gl import _core
from vgxsim.state.raster import FLAT

W, H = 24, 20


@pytest.fixture
def ctx(gl_window):
    c = gl_window(W, H, projection=False)
    gl.ortho2(-0.5, W - 0.5, -0.5, H - 0.5)  # integer coordinates on pixel centres
    return c


def lit_pixels(c, channel=None) -> set[tuple[int, int]]:
    img = c.read_rgba()
    mask = img[..., :3].any(axis=2) if channel is None else img[..., channel] > 0
    ys, xs = np.nonzero(mask)
    return {(int(x), int(y)) for x, y in zip(xs, ys, strict=True)}


def box(x0, x1, y0, y1) -> set[tuple[int, int]]:
    return {(x, y) for x in range(x0, x1 + 1) for y in range(y0, y1 + 1)}


def polygon(*pts):
    gl.bgnpolygon()
    for p in pts:
        gl.v2f(p)
    gl.endpolygon()


def test_polygon_covers_left_bottom_inclusive(ctx):
    gl.cpack(0xFFFFFFFF)
    polygon((2, 2), (5, 2), (5, 4), (2, 4))
    # Tie rule (numeric model s.3): left/bottom edges inclusive, right/top exclusive.
    assert lit_pixels(ctx) == box(2, 4, 2, 3)


def test_vertex_forms_are_equivalent(ctx):
    gl.cpack(0xFFFFFFFF)
    gl.bgnpolygon()
    gl.v3f(2, 2, 0)
    gl.v3f((9.0, 2.0, 0.0))
    gl.v3i(9, 7, 0)
    gl.v4f(4, 14, 0, 2)  # homogeneous: (2, 7)
    gl.endpolygon()
    a = ctx.read_rgba().copy()
    ctx.fb.front[:] = 0
    polygon((2, 2), (9, 2), (9, 7), (2, 7))
    assert np.array_equal(a, ctx.read_rgba())
    assert lit_pixels(ctx) == box(2, 8, 2, 6)


def test_gouraud_uses_the_colour_current_at_each_vertex(ctx):
    gl.bgnpolygon()
    gl.c3f(0, 0, 0)
    gl.v2i(0, 0)
    gl.c3f(1, 0, 0)
    gl.v2i(10, 0)
    gl.v2i(10, 10)
    gl.c3f(0, 0, 0)
    gl.v2i(0, 10)
    gl.endpolygon()
    img = ctx.read_rgba()
    # red = 255 * x / 10 along every row: x = 5 gives floor(127.5 + 0.5) = 128.
    assert img[5, 5, 0] == 128
    assert img[3, 2, 0] == 51  # 255 * 0.2
    assert img[7, 0, 0] == 0


def test_flat_polygon_takes_last_vertex_colour(ctx):
    ctx.raster.set(shademodel=FLAT)
    gl.bgnpolygon()
    gl.cpack(0xFF0000FF)
    gl.v2i(0, 0)
    gl.v2i(10, 0)
    gl.cpack(0xFF00FF00)
    gl.v2i(10, 10)
    gl.v2i(0, 10)
    gl.endpolygon()
    img = ctx.read_rgba()
    assert (img[0:10, 0:10, 1] == 255).all() and (img[0:10, 0:10, 0] == 0).all()


def test_tmesh_equals_polygons(ctx):
    pts = [(1, 1), (4, 12), (8, 2), (11, 15), (16, 3), (20, 13)]
    cols = [(1, 0, 0), (0, 1, 0), (0, 0, 1), (1, 1, 0), (0, 1, 1), (1, 0, 1)]
    gl.bgntmesh()
    for p, c in zip(pts, cols, strict=True):
        gl.c3f(c)
        gl.v2i(p)
    gl.endtmesh()
    mesh = ctx.read_rgba().copy()
    ctx.fb.front[:] = 0
    for i in range(len(pts) - 2):
        gl.bgnpolygon()
        for j in (i, i + 1, i + 2):
            gl.c3f(cols[j])
            gl.v2i(pts[j])
        gl.endpolygon()
    assert np.array_equal(mesh, ctx.read_rgba())


def test_swaptmesh_fan_faces_one_way(ctx):
    # A fan around (10, 10): v0 v1 swap v2 swap v3 ...; with backface(TRUE) nothing
    # may go missing, so every triangle must be counter-clockwise.
    ctx.raster.set(backface=True)
    gl.cpack(0xFFFFFFFF)
    centre = (10, 10)
    rim = [(18, 10), (15, 17), (7, 16), (3, 9), (8, 3), (15, 4)]
    gl.bgntmesh()
    gl.v2i(centre)
    gl.v2i(rim[0])
    for p in rim[1:]:
        gl.swaptmesh()
        gl.v2i(p)
    gl.endtmesh()
    fan = lit_pixels(ctx)
    ctx.fb.front[:] = 0
    ctx.raster.set(backface=False)
    for a, b in zip(rim, rim[1:], strict=False):
        polygon(centre, a, b)
    assert fan == lit_pixels(ctx) and len(fan) > 100


def test_qstrip_is_quads(ctx):
    gl.cpack(0xFFFFFFFF)
    gl.bgnqstrip()
    for p in [(2, 2), (2, 8), (6, 2), (6, 8), (12, 2), (12, 8)]:
        gl.v2i(p)
    gl.endqstrip()
    assert lit_pixels(ctx) == box(2, 11, 2, 7)


def test_flat_qstrip_takes_each_quads_last_vertex(ctx):
    ctx.raster.set(shademodel=FLAT)
    gl.bgnqstrip()
    colours = [0xFF0000FF, 0xFF0000FF, 0xFF0000FF, 0xFF00FF00, 0xFF0000FF, 0xFFFF0000]
    for p, c in zip([(2, 2), (2, 8), (6, 2), (6, 8), (12, 2), (12, 8)], colours,
                    strict=True):
        gl.cpack(c)
        gl.v2i(p)
    gl.endqstrip()
    img = ctx.read_rgba()
    assert (img[2:8, 2:6, 1] == 255).all() and (img[2:8, 2:6, 0] == 0).all()
    assert (img[2:8, 6:12, 2] == 255).all() and (img[2:8, 6:12, 1] == 0).all()


def test_concave_polygon_covers_its_area(ctx):
    ell = [(12, 2), (12, 6), (6, 6), (6, 12), (2, 12), (2, 2)]
    gl.cpack(0xFFFFFFFF)
    gl.concave(1)
    polygon(*ell)
    expected = box(2, 11, 2, 5) | box(2, 5, 6, 11)
    assert lit_pixels(ctx) == expected and len(expected) == 64
    ctx.fb.front[:] = 0
    gl.concave(0)
    polygon(*ell)  # fanned from (12, 2): the fan covers part of the notch too
    assert lit_pixels(ctx) != expected


def test_lines_closed_and_half_open(ctx):
    gl.cpack(0xFFFFFFFF)
    gl.bgnline()
    gl.v2i(2, 3)
    gl.v2i(8, 3)
    gl.endline()
    assert lit_pixels(ctx) == box(2, 8, 3, 3)  # subpixel(FALSE): both end pixels
    ctx.fb.front[:] = 0
    ctx.raster.set(subpixel=True)
    gl.bgnline()
    gl.v2i(2, 3)
    gl.v2i(8, 3)
    gl.endline()
    assert lit_pixels(ctx) == box(2, 7, 3, 3)  # subpixel(TRUE): half-open


def test_closedline_outlines(ctx):
    gl.cpack(0xFFFFFFFF)
    gl.bgnclosedline()
    for p in [(2, 2), (8, 2), (8, 6), (2, 6)]:
        gl.v2i(p)
    gl.endclosedline()
    assert lit_pixels(ctx) == box(2, 8, 2, 6) - box(3, 7, 3, 5)


def test_points(ctx):
    gl.cpack(0xFFFFFFFF)
    gl.bgnpoint()
    gl.v2i(1, 1)
    gl.v3s(5, 7, 0)
    gl.v2d(10.4, 3.6)  # snaps to the nearest pixel centre
    gl.endpoint()
    assert lit_pixels(ctx) == {(1, 1), (5, 7), (10, 4)}


def test_varray_and_vnarray(ctx):
    gl.cpack(0xFFFFFFFF)
    gl.bgnpolygon()
    gl.varray([(2, 2), (5, 2), (5, 4), (2, 4)])
    gl.endpolygon()
    assert lit_pixels(ctx) == box(2, 4, 2, 3)
    gl.bgnline()
    gl.vnarray([((1, 10, 0), (0, 0, 1)), ((4, 10, 0), (0, 1, 0))])
    gl.endline()
    assert ctx.normal == (0.0, 1.0, 0.0) and ctx.last_sent == "normal"
    gl.bgnline()
    gl.nvarray([((0, 0, 1), (1, 12, 0)), ((1, 0, 0), (4, 12, 0))])
    gl.endline()
    assert ctx.normal == (1.0, 0.0, 0.0)
    assert box(1, 4, 10, 10) | box(1, 4, 12, 12) <= lit_pixels(ctx)
    with pytest.raises(gl.GLTypeError, match="nvarray.*2-tuple"):
        gl.nvarray([[(0, 0, 1), (1, 2, 3)]])
    with pytest.raises(gl.GLTypeError, match="varray"):
        gl.varray([(1, 2), (1, 2, 3)])


def test_vertex_record_colour_normal_and_lit(ctx, monkeypatch):
    seen = []
    # What the stream decoder hands the geometry pass for a single primitive.
    from vgxsim.pipeline import decode, draw

    monkeypatch.setattr(draw, "FLUSH_FRONT", False)  # the group path, which this spies on
    monkeypatch.setattr(decode, "draw_arrays",
                        lambda _ctx, _state, _lms, *a, **k: seen.append((a[:5], k)))
    gl.bgnpolygon()
    gl.cpack(0xFF0000FF)
    gl.v3f(0, 0, 0)
    gl.n3f(0, 0, 1)
    gl.v3f(1, 0, 0)  # normal sent last: lit
    gl.c3f(0, 1, 0)
    gl.v3f(1, 1, 0)  # colour sent last: coloured
    gl.endpolygon()
    ctx.flush()
    (kind, obj, cols, nrms, lit), _ = seen[0]
    assert kind == "polygon"
    np.testing.assert_array_equal(obj, [[0, 0, 0, 1], [1, 0, 0, 1], [1, 1, 0, 1]])
    np.testing.assert_array_equal(cols[:, :3], [[1, 0, 0], [1, 0, 0], [0, 1, 0]])
    np.testing.assert_array_equal(nrms[1:], [[0, 0, 1], [0, 0, 1]])
    assert lit.tolist() == [False, True, False]
    ctx.lmcolor_mode = GL.LMC_AD  # colours change the material: every vertex lit
    gl.bgnpoint()
    gl.v2f(0, 0)
    gl.endpoint()
    ctx.flush()
    assert seen[-1][0][4].tolist() == [True]


def test_texcoord_and_normal_state(ctx):
    gl.t2f(0.25, 0.5)
    assert ctx.texcoord == (0.25, 0.5)
    gl.t2i((1, 2))
    assert ctx.texcoord == (1.0, 2.0)
    gl.normal((0, 1, 0))
    assert ctx.normal == (0.0, 1.0, 0.0) and ctx.last_sent == "normal"
    with pytest.raises(gl.GLTypeError, match="t2s"):
        gl.t2s(0.5, 1)


def test_usage_errors(ctx):
    with pytest.raises(gl.GLUsageError, match=r"v3f\(1, 2, 3\).*outside"):
        gl.v3f(1, 2, 3)
    with pytest.raises(gl.GLUsageError, match="endpolygon.*without bgnpolygon"):
        gl.endpolygon()
    with pytest.raises(gl.GLUsageError, match="swaptmesh"):
        gl.swaptmesh()
    gl.bgnpolygon()
    with pytest.raises(gl.GLUsageError, match="bgnline.*bgnpolygon.*still open"):
        gl.bgnline()
    with pytest.raises(gl.GLUsageError, match="endline.*bgnpolygon"):
        gl.endline()
    gl.endpolygon()
    _core.session.reset()
    with pytest.raises(gl.GLUsageError, match="bgnpolygon.*winopen"):
        gl.bgnpolygon()


def test_argument_errors(ctx):
    gl.bgnpoint()
    with pytest.raises(gl.GLTypeError, match=r"v3i\(1.5, 2, 3\)"):
        gl.v3i(1.5, 2, 3)
    with pytest.raises(gl.GLTypeError, match="v3f"):
        gl.v3f("a", 2, 3)
    with pytest.raises(gl.GLTypeError, match="v2f"):
        gl.v2f(1, 2, 3)
    with pytest.raises(gl.GLValueError, match="v3f.*finite"):
        gl.v3f(float("nan"), 2, 3)
    gl.endpoint()
    with pytest.raises(gl.GLTypeError, match="n3f"):
        gl.n3f(1, 2)
    with pytest.raises(gl.GLTypeError, match="concave"):
        gl.concave(0.5)
