"""The OpenGL backend against hand-computed planes and against the software backend.

Every test here draws on the OpenGL backend (skipped without PyOpenGL/libOSMesa);
the gl tests run on both backends through tests/conftest.py.
"""

from __future__ import annotations

import numpy as np
import pytest

import vgxsim.backends as backends
from vgxsim import GL
from vgxsim.backends.opengl import batch as gl_batch
from vgxsim.backends.opengl.surface import available
from vgxsim.batch import CommandBatch
from vgxsim.geometry.transform import orthographic
from vgxsim.gl import RGBwritemask, cpack, czclear, frontbuffer, stencil, zbuffer
from vgxsim.gl._core import session
from vgxsim.pipeline.context import Context
from vgxsim.state.planes import ZMAX

pytestmark = pytest.mark.skipif(not available(), reason="needs PyOpenGL and libOSMesa")

W = H = 8


@pytest.fixture
def gl_win():
    """Factory of current windows on the OpenGL backend (8 stencil planes, the
    pixel-centre ortho of subpixel(3G))."""
    def make(width, height, double=False):
        ctx = Context(width, height, double=double, stencil=8)
        session.reset()
        session.windows[1] = ctx
        session.current = 1
        ctx.matrices.load_projection(
            orthographic(-0.5, width - 0.5, -0.5, height - 0.5, -1, 1))
        return ctx

    backends.set_backend("opengl")
    yield make
    backends.set_backend(None)
    session.reset()


def square(x0, y0, x1, y1, z=0.0):
    """Covers pixels x0..x1-1, y0..y1-1 under the fixture's pixel-centre ortho
    (edges a quarter pixel off the centres: no tie rule involved)."""
    return np.array([[x0 - 0.5, y0 - 0.5, z], [x1 - 0.5, y0 - 0.5, z],
                     [x1 - 0.5, y1 - 0.5, z], [x0 - 0.5, y1 - 0.5, z]], float) + [0.25, 0.25, 0]


def test_backend_setting_and_env(monkeypatch):
    monkeypatch.setenv("VGXSIM_BACKEND", "opengl")
    backends.set_backend(None)
    assert backends.get_backend() == "opengl"
    monkeypatch.setenv("VGXSIM_BACKEND", "vulkan")
    with pytest.raises(backends.BackendError, match="VGXSIM_BACKEND='vulkan'"):
        backends.get_backend()
    with pytest.raises(backends.BackendError, match="unknown backend 'gles'"):
        backends.set_backend("gles")
    backends.set_backend("software")
    assert backends.get_backend() == "software"
    backends.set_backend(None)


def test_window_gets_the_opengl_batch(gl_win):
    ctx = gl_win(W, H)
    assert isinstance(ctx.raw_batch, gl_batch.OpenGLBatch)


def test_planes_round_trip_through_gl_exactly(gl_win):
    # Whatever the planes hold before a flush (written by the CPU: pixel writes,
    # acbuf, a previous software run) must come back bit for bit where GL draws
    # nothing: 24-bit signed z and 8-bit stencil travel packed as UNSIGNED_INT_24_8.
    ctx = gl_win(W, H, double=True)
    rng = np.random.default_rng(5)
    fb = ctx.fb
    fb.front[...] = rng.integers(0, 2**32, (H, W), dtype=np.uint64).astype(np.uint32)
    fb.back[...] = rng.integers(0, 2**32, (H, W), dtype=np.uint64).astype(np.uint32)
    fb.z[...] = rng.integers(-0x800000, 0x800000, (H, W))
    fb.stencil[...] = rng.integers(0, 256, (H, W), dtype=np.uint8)
    want = [p.copy() for p in (fb.front, fb.back, fb.z, fb.stencil)]
    ctx.raster.set(frontbuffer=True, backbuffer=True)
    ctx.draw_arrays("polygon", square(0, 0, 1, 1))  # one pixel, z-buffer off
    ctx.flush()
    for plane, old in zip((fb.front, fb.back, fb.z, fb.stencil), want, strict=True):
        assert np.array_equal(plane[1:], old[1:])


def test_front_and_back_drawn_together_blend_with_their_own_destination(gl_win):
    ctx = gl_win(W, H, double=True)
    ctx.fb.front[...] = 0xFF000010  # red 16
    ctx.fb.back[...] = 0xFF000020  # red 32
    frontbuffer(GL.TRUE)  # backbuffer stays TRUE
    ctx.raster.set(blend=(GL.BF_ONE, GL.BF_ONE))
    ctx.colour = (64 / 255, 0.0, 0.0, 1.0)
    ctx.draw_arrays("polygon", square(0, 0, W, H))
    ctx.flush()
    assert np.all(ctx.fb.front & 0xFF == 80) and np.all(ctx.fb.back & 0xFF == 96)


def test_stencil_pass_applies_when_zbuffer_is_off(gl_win):
    # stencil(3G): zpass "is not significant when the z-buffer is not enabled";
    # a fragment passing the stencil test gets `pass` (here INCR), not zpass (ZERO).
    ctx = gl_win(W, H)
    czclear(0, ZMAX)
    zbuffer(GL.FALSE)
    stencil(GL.TRUE, 0, GL.SF_ALWAYS, 0xFF, GL.ST_KEEP, GL.ST_INCR, GL.ST_ZERO)
    ctx.draw_arrays("polygon", square(0, 0, 4, 8))
    ctx.draw_arrays("polygon", square(0, 0, 2, 8))
    ctx.flush()
    row = ctx.fb.stencil[3]
    assert row.tolist() == [2, 2, 1, 1, 0, 0, 0, 0]


def test_lines_and_points_take_the_iris_fragments(gl_win):
    ctx = gl_win(W, H)
    czclear(0, ZMAX)
    cpack(0xFF00FF00)
    ctx.draw_arrays("line", np.array([[0.0, 0.0, 0.0], [7.0, 3.0, 0.0]]))
    ctx.draw_arrays("point", np.array([[6.0, 6.0, 0.0]]))
    ctx.flush()
    lit = ctx.fb.front == 0xFF00FF00
    # Bresenham-style x-major line from (0,0) to (7,3): one pixel per column,
    # y = floor(3x/7 + 0.5); and the point's pixel.
    want = np.zeros((H, W), bool)
    for x in range(8):
        want[int(np.floor(3 * x / 7 + 0.5)), x] = True
    want[6, 6] = True
    assert np.array_equal(lit, want)


@pytest.mark.parametrize("emulate", [True, False])
def test_partial_write_mask_is_emulated_exactly(gl_win, monkeypatch, emulate):
    # wmpack is per bit; glColorMask per component: with the emulation the software
    # batch draws this state; without it OpenGL writes whole components.
    monkeypatch.setattr(gl_batch, "EMULATE_INEXPRESSIBLE", emulate)
    ctx = gl_win(W, H)
    czclear(0x00000000, ZMAX)
    RGBwritemask(0xF0, 0x00, 0x0F)
    ctx.colour = (0xAB / 255, 0xCD / 255, 0xEF / 255, 1.0)
    ctx.draw_arrays("polygon", square(0, 0, W, H))
    ctx.flush()
    r, g, b = (int(ctx.fb.front[2, 2] >> s) & 0xFF for s in (0, 8, 16))
    if emulate:
        assert (r, g, b) == (0xA0, 0x00, 0x0F)
    else:
        assert (r, g, b) == (0xAB, 0x00, 0xEF)


def test_inexpressible_names_its_reasons():
    from vgxsim.state.raster import RasterState

    rs = RasterState(wmpack=0xFF0F00F0, zbuffer=True, zwritemask=0xFF0000)
    assert gl_batch.inexpressible(rs, 8) == ["partial colour write mask",
                                             "partial zwritemask"]
    assert gl_batch.inexpressible(RasterState(), 8) == []


def test_gouraud_colours_keep_constant_triangles_exact():
    corners = np.array([[0.3, 0.3, 0.3, 1.0]] * 3 + [[0.0, 0, 0, 1], [1.0, 0, 0, 1],
                                                     [0.5, 0, 0, 1]])
    out = gl_batch.gouraud_colours(corners)
    assert np.allclose(out[:3, 0] * 255, 77)  # floor(76.5 + 0.5), not llvmpipe's 76
    assert np.allclose(out[3:, 0], [0.0, 1.0, 0.5])  # interpolated unquantized


def test_software_backend_is_the_default(monkeypatch):
    monkeypatch.delenv("VGXSIM_BACKEND", raising=False)
    backends.set_backend(None)
    from vgxsim.state.planes import Framebuffer, PlaneConfig

    batch = backends.make_batch(Framebuffer(PlaneConfig(4, 4)))
    assert type(batch) is CommandBatch


def _frames_with_swaps_and_cpu_writes(make):
    """Three frames of flat squares with swapbuffers between them and a CPU write
    into the planes (as acbuf or lrectwrite would) before the last: the planes
    after each frame."""
    from vgxsim.gl import swapbuffers

    ctx = make(W, H, double=True)
    out = []
    zbuffer(GL.TRUE)
    for frame, colour in enumerate((0xFF0000FF, 0xFF00FF00, 0xFFFF0000)):
        if frame == 2:
            ctx.flush()
            ctx.fb.back[0, :] = 0xFF123456
            ctx.fb.z[0, :] = -5
        cpack(colour)
        ctx.draw_arrays("polygon", square(frame, frame, frame + 4, frame + 4, z=0.1 * frame))
        swapbuffers()
        out.append([p.copy() for p in (ctx.fb.front, ctx.fb.back, ctx.fb.z, ctx.fb.stencil)])
    return out


@pytest.mark.parametrize("changed_only", [True, False])
def test_upload_switch_keeps_planes_equal_to_software(gl_win, monkeypatch, changed_only):
    from vgxsim.backends.opengl import surface

    monkeypatch.setattr(surface, "UPLOAD_CHANGED_ONLY", changed_only)
    got = _frames_with_swaps_and_cpu_writes(gl_win)
    backends.set_backend("software")
    want = _frames_with_swaps_and_cpu_writes(gl_win)
    for g, s in zip(got, want, strict=True):
        for i, (a, b) in enumerate(zip(g, s, strict=True)):
            if i == 2:  # z: float32 vertex depth, within 1 unit (D2, docs/opengl_backend.md)
                assert np.abs(a.astype(np.int64) - b).max() <= 1
            else:
                assert np.array_equal(a, b)


def _binding(nc=3, minf=0, magf=0, env=0):
    from vgxsim.state import codes as C
    from vgxsim.state.textures import TexEnv, TexGen, Texture, binding_id

    texels = np.zeros((2, 2, 4), np.uint8)
    tex = Texture(texels, nc, minf, magf, C.TEXW_REPEAT, C.TEXW_CLAMP)
    return binding_id(tex, TexEnv(env), TexGen())


def test_texture_states_gl_draws_and_those_it_leaves_to_software(monkeypatch):
    from vgxsim.state import codes as C

    point, bilinear = C.TEXF_POINT, C.TEXF_BILINEAR
    assert gl_batch.texture_inexpressible(_binding()) == []
    assert gl_batch.texture_inexpressible(_binding(4, point, point, C.TEV_BLEND)) == []
    assert gl_batch.texture_inexpressible(_binding(1, point, bilinear)) == [
        "unequal minify and magnify texture filters"]
    assert gl_batch.texture_inexpressible(_binding(1, point, point, C.TEV_DECAL)) == [
        "TV_DECAL on a 1- or 2-component texture"]
    assert gl_batch.texture_inexpressible(_binding(3, 7, 7)) == [
        "texture filter not point or bilinear"]  # e.g. a mipmap filter
    both = _binding(3, bilinear, bilinear)
    assert gl_batch.texture_inexpressible(both) == []
    monkeypatch.setattr(gl_batch, "NATIVE_BILINEAR", False)
    assert gl_batch.texture_inexpressible(both) == [
        "bilinear texture filter (NATIVE_BILINEAR off)"]


def test_fragments_under_a_texture_binding_are_not_textured(gl_win):
    # numeric_model section 14: only triangles are textured.  The texture's texels
    # are all zero, so a textured (modulated) fragment would come out black.
    from vgxsim.state.raster import RasterState

    ctx = gl_win(W, H)
    rs = RasterState(scissor=(0, W - 1, 0, H - 1), texture=_binding())
    xy = np.array([[1, 1], [2, 3]], np.int64)
    ctx.raw_batch.add_fragments(xy, np.zeros(2, np.int64),
                                np.full(2, 0xFF336699, np.int64), rs)
    ctx.flush()
    assert ctx.fb.front[1, 1] == ctx.fb.front[3, 2] == 0xFF336699
    assert (ctx.fb.front == 0xFF336699).sum() == 2


def test_merged_draws_join_only_neighbours_of_one_state_and_layout():
    from vgxsim.state.raster import RasterState

    a, b = RasterState(), RasterState(zbuffer=True)
    pos = [np.full((3, 3), k, np.float32) for k in range(5)]
    flat = np.zeros(3, np.uint32)
    smooth = np.zeros((3, 4), np.float32)
    ops = [(gl_batch._TRIANGLES, a, pos[0], flat, None),
           (gl_batch._TRIANGLES, RasterState(), pos[1], flat, None),  # equal to a
           (gl_batch._TRIANGLES, a, pos[2], smooth, None),  # another colour layout
           (gl_batch._TRIANGLES, b, pos[3], smooth, None),  # another state
           (gl_batch._TRIANGLES, b, pos[4], smooth, None)]
    out = gl_batch.merged_draws(ops)
    assert [op[2][:, 0].tolist() for op in out] == [[0] * 3 + [1] * 3, [2] * 3,
                                                     [3] * 3 + [4] * 3]
    assert [op[1] for op in out] == [a, a, b] and out[0][3].shape == (6,)


@pytest.mark.parametrize("mode", ["shadows", "volumes"])
def test_merging_draws_gives_the_planes_of_separate_draws(monkeypatch, mode):
    # The shadows program queues hundreds of draws per pass (one per polygon, many
    # states); with MERGE_DRAWS off each is its own glDrawArrays.
    from vgxsim.examples import heidmann1991 as h91

    out = []
    for merge in (True, False):
        monkeypatch.setattr(gl_batch, "MERGE_DRAWS", merge)
        stencils = []

        def hook(_i, stencils=stencils):
            from vgxsim.gl._core import current

            ctx = current("test")
            ctx.flush()
            stencils.append(ctx.fb.stencil.copy())

        backends.set_backend("opengl")
        try:
            image = h91.render(80, 64, mode=mode, stencil_hook=hook)
        finally:
            backends.set_backend(None)
            session.reset()
        out.append((image, stencils))
    assert np.array_equal(out[0][0], out[1][0])
    assert len(out[0][1]) == len(out[1][1])
    for s0, s1 in zip(out[0][1], out[1][1], strict=True):
        assert np.array_equal(s0, s1)
    assert out[0][0][..., :3].any()


def test_closing_another_surface_mid_batch_keeps_this_one_current(gl_win):
    # A surface's close also runs from __del__, whenever the garbage collector
    # runs: between this window's begin and its draws it must leave this window's
    # context current (once, a full-suite run failed here with PyOpenGL's "no
    # valid context").
    from vgxsim.backends.opengl.surface import Surface
    from vgxsim.state.planes import Framebuffer

    ctx = gl_win(W, H)
    other = gl_win(4, 4)
    session.windows[1] = ctx  # the first window is the current one again
    surface = Surface(ctx.fb)
    doomed = Surface(other.fb)
    surface.begin()
    doomed.close()
    cpack(0xFF0000FF)
    ctx.draw_arrays("polygon", square(0, 0, W, H))
    ctx.flush()  # a flush of the window's own batch after the close
    assert isinstance(Framebuffer, type)
    surface.close()
    assert np.all(ctx.fb.front == 0xFF0000FF)
