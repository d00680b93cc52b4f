"""Workloads shared by the pytest-benchmark suite and bench/report.py.

Each builder returns a callable that renders one batch and flushes it, so the
timed region is exactly "queue + render"; set-up (allocation, first compile) is
done before timing.
"""

from __future__ import annotations

import numpy as np

from vgxsim.batch import CommandBatch
from vgxsim.geometry.transform import orthographic
from vgxsim.kernels.options import jit
from vgxsim.pipeline.context import Context
from vgxsim.state.planes import Framebuffer, PlaneConfig
from vgxsim.state.raster import RasterState

W, H = 1280, 1024


def fullscreen_quads(n: int, w: int = W, h: int = H):
    """n window-filling quads (2 triangles each) as window-space arrays."""
    xw = np.tile([-5.0, w + 5.0, w + 5.0, -5.0], n)
    yw = np.tile([-5.0, -5.0, h + 5.0, h + 5.0], n)
    zw = np.repeat(np.linspace(-1000.0, 1000.0, n), 4)
    base = np.array([[0, 1, 2], [0, 2, 3]])
    tris = np.concatenate([base + 4 * i for i in range(n)])
    return xw, yw, zw, tris


def zstencil_fill(layers: int = 20):
    """Heidmann's volume pass: z test, stencil INCR on z pass, no colour, no z write."""
    fb = Framebuffer(PlaneConfig(W, H, stencil=8))
    batch = CommandBatch(fb)
    rs = RasterState(scissor=(0, W - 1, 0, H - 1), zbuffer=True, stencil=True, sfunc=7,
                     szpass=3, wmpack=0, zwritemask=0, draw_front=True)
    xw, yw, zw, tris = fullscreen_quads(layers)

    def run():
        batch.add_window_triangles(xw, yw, zw, None, tris, rs)
        batch.flush()

    run.batch = batch
    return run, layers * W * H


def zstencil_hidden_fill(layers: int = 20):
    """The volume pass over a scene in front of it (z cleared to -2000 first): every
    face fails the z test with ST_KEEP on z fail, the case exact work skipping decides
    tile by tile (units: the fragments a rasterizer without it would test)."""
    fb = Framebuffer(PlaneConfig(W, H, stencil=8))
    batch = CommandBatch(fb)
    rs = RasterState(scissor=(0, W - 1, 0, H - 1), zbuffer=True, stencil=True, sfunc=7,
                     szpass=3, wmpack=0, zwritemask=0, draw_front=True)
    clear = RasterState(scissor=(0, W - 1, 0, H - 1))
    xw, yw, zw, tris = fullscreen_quads(layers)

    def run():
        batch.add_clear(2, 0, -2000, 0, clear)
        batch.add_window_triangles(xw, yw, zw, None, tris, rs)
        batch.flush()

    run.batch = batch
    return run, layers * W * H


def colour_blend_fill(layers: int = 5):
    """Heidmann's lit pass: Gouraud colour, stencil EQUAL test, blend ONE+ONE."""
    fb = Framebuffer(PlaneConfig(W, H, stencil=8))
    batch = CommandBatch(fb)
    rs = RasterState(scissor=(0, W - 1, 0, H - 1), zbuffer=True, stencil=True, sfunc=2,
                     blend_sf=1, blend_df=1, draw_front=True)
    xw, yw, zw, tris = fullscreen_quads(layers)
    col = np.random.default_rng(1).random((xw.shape[0], 4))

    def run():
        batch.add_window_triangles(xw, yw, zw, col, tris, rs)
        batch.flush()

    run.batch = batch
    return run, layers * W * H


def lit_equal_fill(layers: int = 5):
    """Heidmann's lit pass as the frame runs it: a depth pass lays a tilted
    full-screen quad (z written, colour masked), then ``layers`` lit layers of the
    same quad draw with zfunction(ZF_EQUAL), stencil EQUAL 0, blend ONE+ONE and no
    z write: every fragment is tested (no tile's bounds decide EQUAL) and passes.
    Units: the lit layers' fragments (the depth pass is timed with them)."""
    fb = Framebuffer(PlaneConfig(W, H, stencil=8))
    batch = CommandBatch(fb)
    depth = RasterState(scissor=(0, W - 1, 0, H - 1), zbuffer=True, wmpack=0,
                        draw_front=True)
    lit = RasterState(scissor=(0, W - 1, 0, H - 1), zbuffer=True, zfunc=2, zwritemask=0,
                      stencil=True, sfunc=2, blend_sf=1, blend_df=1, draw_front=True)
    xw, yw, _, tris = fullscreen_quads(1)
    zw = np.array([-3000.0, 1000.0, 2500.0, -1500.0])
    col = np.random.default_rng(1).random((xw.shape[0], 4))
    clear = RasterState(scissor=(0, W - 1, 0, H - 1))

    def run():
        batch.add_clear(2, 0, 0x7FFFFF, 0, clear)
        batch.add_window_triangles(xw, yw, zw, col, tris, depth)
        for _ in range(layers):
            batch.add_window_triangles(xw, yw, zw, col, tris, lit)
        batch.flush()

    run.batch = batch
    return run, layers * W * H


def small_triangles(count: int = 200_000, area: float = 10.0, seed: int = 0,
                    tile_order: int = 0):
    """``count`` random triangles of about ``area`` pixels through the array path
    (Context.draw_arrays: transform, clip, snap, setup, bin, raster).  ``tile_order``
    > 0 submits them sorted by the ``tile_order``-pixel tile of their centre (a
    different image: it measures what framebuffer locality is worth)."""
    ctx = Context(W, H, rgb=True, double=False)
    ctx.matrices.load_projection(orthographic(-0.5, W - 0.5, -0.5, H - 0.5, -1.0, 1.0))
    ctx.raster.set(zbuffer=True)
    rng = np.random.default_rng(seed)
    side = np.sqrt(2.0 * area)
    centre = rng.uniform([0, 0], [W, H], size=(count, 2))
    if tile_order > 0:
        tile = (centre // tile_order).astype(np.int64)
        centre = centre[np.argsort(tile[:, 1] * W + tile[:, 0], kind="stable")]
    offs = rng.uniform(-side / 2, side / 2, size=(count, 3, 2))
    pts = (centre[:, None, :] + offs).reshape(-1, 2)
    obj = np.concatenate([pts, rng.uniform(-0.9, 0.9, (pts.shape[0], 1))], axis=1)
    col = rng.random((pts.shape[0], 4))
    idx = np.arange(pts.shape[0]).reshape(-1, 3)

    def run():
        ctx.draw_arrays("triangles", obj, col, indices=idx)
        ctx.flush()

    run.batch = ctx.batch
    return run, count


@jit
def touch_zstencil(zbuf, sten, layers):
    """The memory traffic of a z+stencil pass with no raster work: read z, read and
    write stencil, for every pixel of every layer (the floor a fill loop could reach)."""
    h, w = zbuf.shape
    for _ in range(layers):
        for y in range(h):
            zr = zbuf[y]
            sr = sten[y]
            for x in range(w):
                ux = np.uintp(x)
                sr[ux] = sr[ux] + (zr[ux] > 0)


@jit
def touch_colour(buf, zbuf, sten, layers):
    """The memory traffic of the lit pass: read stencil and z, read-modify-write colour."""
    h, w = buf.shape
    for _ in range(layers):
        for y in range(h):
            br = buf[y]
            zr = zbuf[y]
            sr = sten[y]
            for x in range(w):
                ux = np.uintp(x)
                br[ux] = br[ux] + ((zr[ux] > 0) & (sr[ux] == 0))


def touch_zstencil_run(layers: int = 20):
    z = np.zeros((H, W), np.int32)
    s = np.zeros((H, W), np.uint8)
    return (lambda: touch_zstencil(z, s, layers)), layers * W * H


def touch_colour_run(layers: int = 5):
    b = np.zeros((H, W), np.uint32)
    z = np.zeros((H, W), np.int32)
    s = np.zeros((H, W), np.uint8)
    return (lambda: touch_colour(b, z, s, layers)), layers * W * H
