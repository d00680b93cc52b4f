"""Large plain draws read the caller's arrays in place (``DIRECT_ARRAYS``,
vgxsim/pipeline/draw.py) and change no plane.

Random scenes of small triangles go through Context.draw_arrays with the switch on
and off: (N, 3) and (N, 4) coordinates, per-vertex and current colours, flat and
Gouraud shading, draws small enough to stay deferred between large ones, a state
change between draws, a z + stencil shadow pass (zwritemask 0, wmpack 0, stencil
INCR/DECR on front and back faces, then a lit pass at SF_EQUAL), on one and two
threads.  The caller overwrites its arrays after each call, before the flush: a
draw that kept the caller's arrays would draw the overwritten values.  Colour, z and
stencil must be identical with the switch on and off, and equal to the naive
reference (vgxsim/reference/naive.py) rendering the window-space triangles the
stage-by-stage front end hands the batch (vgxsim/reference/recorder.py), which
shares no code with the fused front end's (N, 3) rows.
"""

from __future__ import annotations

import numpy as np
import pytest

from vgxsim import threads
from vgxsim.geometry import pipeline as geometry
from vgxsim.geometry.transform import orthographic
from vgxsim.pipeline import draw
from vgxsim.pipeline.context import Context
from vgxsim.reference import naive
from vgxsim.reference.recorder import record_window_triangles
from vgxsim.state.codes import CLEAR_COLOUR, CLEAR_STENCIL, CLEAR_Z
from vgxsim.state.raster import FLAT, GOURAUD
from vgxsim.state.registers import StencilRegister

W, H = 64, 48
SF_ALWAYS, SF_EQUAL = 7, 2  # stencil(3G) functions (gl.h values)
ST_KEEP, ST_INCR, ST_DECR = 0, 4, 5


def _soup(rng, n, cols3: bool):
    """``n`` triangles of about 10 pixels: obj (3n, 3 or 4), colours (3n, 4), indices."""
    centre = rng.uniform([0, 0], [W, H], (n, 1, 2))
    xy = (centre + rng.uniform(-2.3, 2.3, (n, 3, 2))).reshape(-1, 2)
    z = rng.uniform(-0.9, 0.9, (3 * n, 1))
    obj = np.concatenate([xy, z], axis=1)
    if not cols3:
        obj = np.concatenate([obj, np.ones((3 * n, 1))], axis=1)
    return obj, rng.random((3 * n, 4)), np.arange(3 * n).reshape(-1, 3)


def _draws(rng):
    """A scene: a list of ("clear" | "set" | "draw", ...) steps."""
    steps = [("clear",)]
    for _ in range(6):
        u = rng.random()
        steps.append(("set", dict(zbuffer=True, shademodel=FLAT if u < 0.3 else GOURAUD,
                                  subpixel=bool(rng.random() < 0.5))))
        n = int(rng.choice([3, 20, 150, 400]))  # below and above the limit
        steps.append(("draw", *_soup(rng, n, rng.random() < 0.5), rng.random() < 0.8))
    # A shadow pass: counts on front and back faces, z and colour untouched, then
    # colour where the count is back to its clear value.
    vol = _soup(rng, 300, True)
    base = dict(zbuffer=True, zwritemask=0, wmpack=0, shademodel=GOURAUD)
    steps.append(("set", dict(base, backface=True, frontface=False,
                              stencil=StencilRegister(True, 0, SF_ALWAYS, 0xFF, ST_KEEP,
                                                      ST_KEEP, ST_INCR))))
    steps.append(("draw", *vol, False))
    steps.append(("set", dict(base, backface=False, frontface=True,
                              stencil=StencilRegister(True, 0, SF_ALWAYS, 0xFF, ST_KEEP,
                                                      ST_KEEP, ST_DECR))))
    steps.append(("draw", *vol, False))
    steps.append(("set", dict(zbuffer=True, zwritemask=0, wmpack=0xFFFFFFFF,
                              backface=False, frontface=False, zfunc=2,  # ZF_EQUAL
                              stencil=StencilRegister(True, 1, SF_EQUAL, 0xFF, ST_KEEP,
                                                      ST_KEEP, ST_KEEP))))
    steps.append(("draw", *_soup(rng, 500, False), True))
    return steps


def _render(steps, direct: bool, monkeypatch, fused: bool = True):
    monkeypatch.setattr(draw, "DIRECT_ARRAYS", direct)
    monkeypatch.setattr(draw, "DIRECT_MIN_VERTICES", 90)  # 30 triangles and up
    monkeypatch.setattr(geometry, "FUSED_FRONT", fused)
    ctx = Context(W, H, rgb=True, double=False, stencil=8)
    ctx.matrices.load_projection(orthographic(-0.5, W - 0.5, -0.5, H - 0.5, -1.0, 1.0))
    for step in steps:
        if step[0] == "clear":
            ctx.clear_planes(CLEAR_COLOUR | CLEAR_Z | CLEAR_STENCIL, 0x20304050, 0x7FFFFF, 1)
        elif step[0] == "set":
            ctx.raster.set(**step[1])
        else:
            obj, col, tris, with_colours = step[1:]
            obj, col, tris = obj.copy(), col.copy(), tris.copy()
            ctx.draw_arrays("triangles", obj, col if with_colours else None, indices=tris)
            # The caller is free to reuse its arrays once the call returns.
            obj[:, :2] = obj[::-1, :2]
            col[:] = 1.0 - col
            tris[:] = tris[::-1]
    ctx.flush()
    fb = ctx.fb
    return fb.front.copy(), fb.z.copy(), fb.stencil.copy()


def _assert_same(got, want, what):
    for name, a, b in zip(("colour", "z", "stencil"), got, want, strict=True):
        bad = np.argwhere(a != b)
        assert bad.size == 0, f"{what}: {name} differs at {bad[:5].tolist()}"


@pytest.mark.parametrize("nthreads", [1, 2])
def test_direct_arrays_change_no_plane(monkeypatch, nthreads):
    threads.set_threads(nthreads)
    try:
        rng = np.random.default_rng(31)
        for i in range(4):
            steps = _draws(rng)
            want = _render(steps, False, monkeypatch)
            got = _render(steps, True, monkeypatch)
            _assert_same(got, want, f"scene {i}, {nthreads} thread(s)")
            assert len(np.unique(want[0])) > 50  # the scene draws many colours
            assert np.count_nonzero(want[2] != 1) > 100  # and counts shadow faces
    finally:
        threads.set_threads(None)


def test_direct_arrays_match_the_naive_reference(monkeypatch):
    """The fused front end's (N, 3) rows against naive rendering of the window-space
    triangles of the stage-by-stage passes (FUSED_FRONT off, arrays copied)."""
    steps = _draws(np.random.default_rng(5))
    with record_window_triangles() as rec:  # a capture takes the stage-by-stage path
        _render(steps, False, monkeypatch, fused=False)
    assert rec.n_triangles > 1000
    fb = naive.NaiveFramebuffer(W, H, stencil_planes=8, zbits=24, double=False)
    naive.render(fb, rec.commands())
    got = _render(steps, True, monkeypatch)
    _assert_same(got, (fb.front, fb.z, fb.stencil), "naive reference")
