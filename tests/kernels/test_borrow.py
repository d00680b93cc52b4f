"""The band kernel and set-up on borrowed arrays (kernels/borrow.py,
CommandBatch.borrow_arrays) change nothing drawn and count the same work, and
borrowed arrays carry no reference counting at all.

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
    render_naive,
    render_switched,
)

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
    return render_switched(cmds, W, H, nthreads=nthreads, borrow_arrays=borrow)


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


def _counting_calls(dispatcher) -> int:
    """Calls of Numba's reference counting in the (one) compiled function's IR."""
    (ir,) = dispatcher.inspect_llvm().values()
    return sum(1 for line in ir.splitlines()
               if "call " in line and ("@NRT_incref(" in line or "@NRT_decref(" in line))


def test_borrowed_arrays_carry_no_reference_counting():
    """The mechanism itself: the set-up loop (its ``_setup_one`` inlined at the IR
    level binds every array argument once a triangle) compiled for plain arrays
    counts references in the loop; for borrowed arrays (kernels/borrow.py
    BorrowedArray, whose data model has no meminfo) Numba emits no counting at
    all.  Compiled afresh (no cache: cached code cannot be inspected)."""
    import numba

    from vgxsim.kernels import setup
    from vgxsim.kernels.borrow import BorrowedArray, borrow

    plain = numba.njit(error_model="numpy")(setup.setup_triangles_states.py_func)

    @numba.njit(error_model="numpy")
    def borrowed(xf, yf, zw, col, tris, src, flat_col, states, culls, t_edge, t_box, t_z,
                 t_zlim, t_col, t_state):
        return plain(borrow(xf), borrow(yf), borrow(zw), borrow(col), borrow(tris),
                     borrow(src), borrow(flat_col), borrow(states), borrow(culls), False,
                     True, borrow(t_edge), borrow(t_box), borrow(t_z), borrow(t_zlim),
                     borrow(t_col), borrow(t_state), 0)

    n = 4
    xf = np.array([0, 2560, 0, 0, 768, 0, 256, 512, 256, 0, 0, 0], np.int64)
    yf = np.array([0, 0, 2560, 0, 0, 768, 256, 256, 512, 0, 0, 0], np.int64)
    zw = np.linspace(-100.0, 100.0, 3 * n)
    col = np.linspace(0.0, 1.0, 12 * n).reshape(3 * n, 4)
    tris = np.arange(3 * n, dtype=np.int64).reshape(n, 3)
    idx = np.zeros(n, np.int64)

    def records():
        return (np.zeros((n, 3, 3), np.int64), np.zeros((n, 4), np.int64),
                np.zeros((n, 5)), np.zeros((n, 2), np.int64), np.zeros((n, 4, 3)),
                np.zeros(n, np.int32))

    want, got = records(), records()
    plain(xf, yf, zw, col, tris, idx, col, idx, idx, False, True, *want, 0)
    borrowed(xf, yf, zw, col, tris, idx, col, idx, idx, *got)
    for a, b in zip(got, want, strict=True):
        np.testing.assert_array_equal(a, b)
    assert want[1][0, 1] == 10 and want[1][3, 2] > want[1][3, 3]  # drawn, then dead
    assert len(plain.signatures) == 2  # plain, and borrowed through the wrapper
    kinds = {any(isinstance(a, BorrowedArray) for a in sig) for sig in plain.signatures}
    assert kinds == {True, False}
    counts = {}
    for sig in plain.signatures:
        one = numba.njit(error_model="numpy")(setup.setup_triangles_states.py_func)
        one.compile(sig)
        counts[any(isinstance(a, BorrowedArray) for a in sig)] = _counting_calls(one)
    assert counts[False] > 10, counts  # the bindings the borrowed form removes
    assert counts[True] == 0, counts
