"""The window-space recorder (vgxsim.reference.recorder), without Mesa.

What is recorded is checked against hand-computed window coordinates and colours,
and a recorded frame replayed on a fresh CommandBatch must reproduce the original
frame bit for bit.
"""

from __future__ import annotations

import numpy as np
import pytest

from vgxsim.batch import CLEAR_COLOUR, CLEAR_STENCIL, CLEAR_Z, CommandBatch
from vgxsim.examples import heidmann1991 as h91
from vgxsim.geometry.transform import orthographic
from vgxsim.gl._core import current, session
from vgxsim.pipeline.context import Context
from vgxsim.reference.recorder import ClearRecord, TriangleRecord, record_window_triangles
from vgxsim.state.planes import Framebuffer, PlaneConfig
from vgxsim.state.raster import FLAT, RasterState

W, H = 32, 24


def pixel_context(**kw) -> Context:
    """A Context whose integer object coordinates are pixel centres (z in [-1, 1])."""
    ctx = Context(W, H, stencil=8, **kw)
    ctx.matrices.load_projection(orthographic(-0.5, W - 0.5, -0.5, H - 0.5, -1.0, 1.0))
    return ctx


def test_triangle_is_recorded_in_window_coordinates_with_its_colours():
    ctx = pixel_context()
    obj = np.array([[3.0, 4.0, 0.0], [20.0, 5.0, 0.5], [7.0, 18.0, -0.5]])
    cols = np.array([[1, 0, 0, 1], [0, 1, 0, 1], [0, 0, 1, 0.5]], np.float64)
    with record_window_triangles() as rec:
        ctx.raster.set(zbuffer=True)
        ctx.draw_arrays("polygon", obj, cols)
        ctx.flush()
    assert rec.n_triangles == 1 and rec.n_clears == 0 and rec.sizes == [(W, H)]
    (item,) = rec.items
    assert isinstance(item, TriangleRecord)
    # x, y unchanged (the projection maps object units to pixel centres); z maps
    # [-1, 1] (near..far of the ortho, so z_ndc = -z) onto [GD_ZMIN, GD_ZMAX].
    zmin, zmax = -0x800000, 0x7FFFFF
    want_z = zmin + (-obj[:, 2] + 1) * (zmax - zmin) / 2
    assert np.array_equal(item.positions[0, :, :2], obj[:, :2])
    assert np.allclose(item.positions[0, :, 2], want_z, rtol=0, atol=1e-6)
    assert np.array_equal(item.colours[0], cols)
    assert item.state.zbuffer and item.state.scissor == (0, W - 1, 0, H - 1)
    cmd = rec.commands()[0]
    assert cmd[0] == "triangle" and cmd[2] is item.state
    assert cmd[1][1][:2] == (20.0, 5.0) and cmd[1][2][3] == (0.0, 0.0, 1.0, 0.5)


def test_snapping_and_flat_colour():
    ctx = pixel_context()
    ctx.raster.set(shademodel=FLAT)
    obj = np.array([[3.4, 4.6, 0.0], [20.5, 5.2, 0.0], [7.0, 18.49, 0.0], [2.0, 15.0, 0.0]])
    cols = np.array([[1, 0, 0, 1], [0, 1, 0, 1], [0, 0, 1, 1], [1, 1, 0, 1]], np.float64)
    with record_window_triangles() as rec:
        ctx.draw_arrays("polygon", obj, cols)  # a fan of two triangles
        ctx.flush()
    pos = rec.items[0].positions
    # subpixel(FALSE): nearest pixel centre, ties upward (20.5 -> 21).
    assert {tuple(p) for p in pos[:, :, :2].reshape(-1, 2).tolist()} == {
        (3.0, 5.0), (21.0, 5.0), (7.0, 18.0), (2.0, 15.0)}
    # shademodel(FLAT): every vertex carries the polygon's last vertex colour.
    assert np.array_equal(rec.items[0].colours, np.broadcast_to(cols[3], (2, 3, 4)))


def test_clears_and_triangles_keep_drawing_order():
    ctx = pixel_context()
    quad = np.array([[1.0, 1.0, 0.0], [9.0, 1.0, 0.0], [9.0, 9.0, 0.0], [1.0, 9.0, 0.0]])
    with record_window_triangles() as rec:
        ctx.clear_planes(CLEAR_COLOUR | CLEAR_STENCIL, 0x11223344, 0, 7)
        ctx.draw_arrays("polygon", quad)
        ctx.draw_arrays("polygon", quad + [10, 0, 0])  # same state: drawn together
        ctx.raster.set(wmpack=0x00FFFFFF)
        ctx.draw_arrays("polygon", quad + [20, 0, 0])
        ctx.clear_planes(CLEAR_Z, 0, 12345, 0)
        ctx.draw_arrays("polygon", quad)
        ctx.flush()
    kinds = [("clear" if isinstance(i, ClearRecord) else i.positions.shape[0])
             for i in rec.items]
    assert kinds == ["clear", 4, 2, "clear", 2]
    assert rec.items[1].positions[2:, 0, 0].tolist() == [11.0, 11.0]  # second quad
    assert rec.items[2].state.wmpack == 0x00FFFFFF
    first = rec.items[0].command()
    assert first[0] == "clear" and first[1] == {"color", "stencil"}
    assert first[2]["color"] == 0x11223344 and first[2]["stencil"] == 7
    assert rec.items[3].planes == {"z"} and rec.items[3].values["z"] == 12345
    cmds = rec.commands()
    assert len(cmds) == rec.n_triangles + rec.n_clears == 8 + 2
    assert [c[0] for c in cmds] == ["clear"] + ["triangle"] * 6 + ["clear"] + ["triangle"] * 2


def test_runs_merge_consecutive_triangles_of_equal_state():
    fb = Framebuffer(PlaneConfig(W, H, stencil=8))
    batch = CommandBatch(fb)
    a = RasterState(scissor=(0, W - 1, 0, H - 1))
    b = RasterState(scissor=(0, W - 1, 0, H - 1), wmpack=0)
    x, y, z = np.array([1.0, 9.0, 5.0]), np.array([1.0, 1.0, 8.0]), np.zeros(3)
    tri = np.array([[0, 1, 2]])
    with record_window_triangles() as rec:
        for rs, dx in ((a, 0), (RasterState(scissor=(0, W - 1, 0, H - 1)), 1), (b, 2),
                       (a, 3), (a, 4)):
            batch.add_window_triangles(x + dx, y, z, None, tri, rs)
        batch.add_clear(CLEAR_STENCIL, 0, 0, 3, a)
        batch.add_window_triangles(x, y, z, None, tri, a)
    runs = rec.runs()
    shape = [("clear" if isinstance(r, ClearRecord) else r.positions[:, 0, 0].tolist())
             for r in runs]
    assert shape == [[1.0, 2.0], [3.0], [4.0, 5.0], "clear", [1.0]]
    assert [r.state for r in runs] == [a, b, a, a, a]
    assert len(rec.items) == 7  # runs() does not change the items


def test_planes_absent_from_the_framebuffer_are_not_recorded():
    fb = Framebuffer(PlaneConfig(W, H, zbits=0, stencil=0))
    batch = CommandBatch(fb)
    rs = RasterState(scissor=(0, W - 1, 0, H - 1))
    with record_window_triangles() as rec:
        batch.add_clear(CLEAR_Z | CLEAR_STENCIL, 0, 0, 0, rs)  # nothing to clear
        batch.add_clear(CLEAR_COLOUR | CLEAR_Z, 5, 0, 0, rs)
    assert rec.n_clears == 1 and rec.items[0].planes == {"color"}


def test_methods_are_restored_and_fragments_counted():
    before = (CommandBatch.add_triangles, CommandBatch.add_clear, CommandBatch.add_fragments)
    ctx = pixel_context()
    with pytest.raises(RuntimeError), record_window_triangles() as rec:
        assert CommandBatch.add_triangles is not before[0]
        ctx.draw_arrays("line", np.array([[1.0, 1.0, 0.0], [10.0, 4.0, 0.0]]))
        raise RuntimeError("inside the block")
    assert (CommandBatch.add_triangles, CommandBatch.add_clear,
            CommandBatch.add_fragments) == before
    assert rec.skipped_fragment_runs == 1 and rec.items == []
    with record_window_triangles() as later:
        pass
    ctx.draw_arrays("polygon", np.array([[1.0, 1.0, 0.0], [9.0, 1.0, 0.0], [5.0, 8.0, 0.0]]))
    ctx.flush()
    assert later.n_triangles == 0 and rec.n_triangles == 0


@pytest.mark.parametrize("subpixel", [False, True])
def test_replayed_heidmann_frame_is_bit_identical(subpixel):
    w, h = 160, 128
    stencils = {}

    def hook(i):
        ctx = current("test")
        ctx.flush()
        stencils[i] = ctx.fb.stencil.copy()

    try:
        with record_window_triangles() as rec:
            image = h91.render(w, h, subpixel_mode=subpixel, stencil_hook=hook)
    finally:
        session.reset()
    assert rec.sizes == [(w, h)] and rec.skipped_fragment_runs == 0
    # Clears: czclear, then one sclear(MYZERO) per light.
    assert rec.n_clears == 1 + len(stencils)
    assert rec.n_triangles > 500
    for runs in (None, rec.runs()):
        fb = Framebuffer(PlaneConfig(w, h, stencil=8))
        batch = CommandBatch(fb)
        rec.replay(batch, runs)
        batch.flush()
        assert np.array_equal(fb.front, image.view("<u4")[..., 0])
        assert np.array_equal(fb.stencil, stencils[max(stencils)])
