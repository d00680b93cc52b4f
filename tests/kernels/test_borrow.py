"""The band kernel on borrowed views (kernels/borrow.py, CommandBatch.borrow_arrays)
changes nothing drawn and counts the same work.

Every array the band kernel reads or writes is borrowed: the set-up records, the
state tables, the four planes (colour to the front and to the back buffer), the
work counters, its own scratch arrays (tile bounds, tile runs, stored spans: big
triangles classify tiles and store spans).  Random scenes of small and big
triangles, lines and clears switched between the states of the 1991 passes run with
the switch on and off, on one and two threads, against each other and the naive
reference; the Heidmann 1991 frame (scene, shadow volumes, lit pass) is compared
with the switch on and off.
"""

from __future__ import annotations

import numpy as np
import pytest
from kernel_helpers import (
    assert_planes_equal,
    full_state,
    kernel_batch,
    kernel_framebuffer,
    planes_of,
    queue_commands,
    render_naive,
)

from vgxsim import threads
from vgxsim.batch import CommandBatch
from vgxsim.state.raster import BF_MSA, BF_ONE, BF_SA, CMP_EQUAL, CMP_LESS, OP_DECR, OP_INCR

W, H = 160, 140


def _states():
    return [
        full_state(W, H, zbuffer=True),  # back buffer
        full_state(W, H, zbuffer=True, draw_front=True, draw_back=False),
        full_state(W, H, zbuffer=True, zfunc=CMP_LESS, wmpack=0),
        full_state(W, H, zbuffer=True, zwritemask=0, wmpack=0, stencil=True,
                   szpass=OP_INCR, spass=OP_DECR),
        full_state(W, H, zbuffer=True, zfunc=CMP_EQUAL, zwritemask=0, stencil=True,
                   sfunc=CMP_EQUAL, sref=0, blend_sf=BF_ONE, blend_df=BF_ONE),
        full_state(W, H, zbuffer=True, blend_sf=BF_SA, blend_df=BF_MSA),
    ]


def _tri(rng, c, size):
    p = c + rng.uniform(-size, size, (3, 2))
    z = float(rng.uniform(-5000, 5000))
    return tuple((float(x), float(y), z + float(rng.uniform(-900, 900)),
                  tuple(float(v) for v in rng.uniform(0, 1, 4))) for x, y in p)


def _scene(rng, n):
    states = _states()
    cmds = [("clear", {"color", "z", "stencil"}, {"color": 0x30405060, "z": 0x7FFFFF,
                                                  "stencil": 0}, full_state(W, H))]
    rs = states[0]
    for _ in range(n):
        u = rng.random()
        if u < 0.03:
            rs = states[int(rng.integers(len(states)))]
        if u < 0.004:
            cmds.append(("clear", {"stencil"}, {"stencil": 1}, full_state(W, H)))
        elif u < 0.01:
            cmds.append(("line", ((float(rng.uniform(0, W)), float(rng.uniform(0, H)), 0.0,
                                   (1.0, 0.5, 0.2, 1.0)),
                                  (float(rng.uniform(0, W)), float(rng.uniform(0, H)), 0.0,
                                   (0.2, 0.5, 1.0, 1.0))), rs))
        size = float(rng.choice([1.5, 3.0, 3.0, 3.0, 60.0]))
        cmds.append(("triangle", _tri(rng, rng.uniform([0, 0], [W, H]), size), rs))
    return cmds


def _render(cmds, nthreads, borrow):
    threads.set_threads(nthreads)
    try:
        fb = kernel_framebuffer(W, H, double=True, zbits=24, stencil=8)
        batch = kernel_batch(fb)
        batch.borrow_arrays = borrow
        queue_commands(batch, cmds)
        batch.flush()
        return planes_of(fb), batch.work()
    finally:
        threads.set_threads(None)


@pytest.mark.parametrize("nthreads", [1, 2])
def test_borrowed_views_change_no_plane(nthreads):
    cmds = _scene(np.random.default_rng(90 + nthreads), 5000)
    want, want_work = _render(cmds, nthreads, False)
    got, got_work = _render(cmds, nthreads, True)
    assert_planes_equal(got, want, f"borrow_arrays, {nthreads} thread(s)")
    assert got_work == want_work and got_work["blocks_covered"] > 0  # big ones classify
    assert np.count_nonzero(want["front"] != 0x30405060) > 1000  # both buffers drawn
    assert np.count_nonzero(want["back"] != 0x30405060) > 1000
    if nthreads == 1:
        naive = render_naive(cmds, W, H, double=True, zbits=24, stencil=8)
        assert_planes_equal(got, naive, "naive reference")


def _heidmann(monkeypatch, borrow: bool):
    from vgxsim.examples import heidmann1991 as h91
    from vgxsim.gl._core import current, session

    monkeypatch.setattr(CommandBatch, "borrow_arrays", borrow)
    session.reset()
    planes = {}

    def hook(i):
        ctx = current("test")
        ctx.flush()
        planes[i] = (ctx.fb.stencil.copy(), ctx.fb.z.copy())

    try:
        img = h91.render(320, 256, stencil_hook=hook)
    finally:
        session.reset()
    return img, planes


def test_borrowed_views_give_the_same_heidmann_frame(monkeypatch):
    want_img, want = _heidmann(monkeypatch, False)
    img, got = _heidmann(monkeypatch, True)
    assert want and got.keys() == want.keys()
    np.testing.assert_array_equal(img, want_img)
    for light in want:
        np.testing.assert_array_equal(got[light][0], want[light][0])
        np.testing.assert_array_equal(got[light][1], want[light][1])
