"""The small-triangle path (kernels/small.py, CommandBatch.small_path) changes
nothing drawn and counts the same work.

Scenes of triangles at most a few pixels wide (the path's), slivers and big ones
(the span path's), piled on the same pixels, run under every mode the path takes
(z only; z + stencil by table and by saturating INCR/DECR; colour with the z test,
replace or add blend, with and without a stencil test; write masks) and a few it
leaves to the span loops (alpha blend, no z test), switched between triangles;
planes are compared with the path on and off, on one and two threads, and against
the naive reference.
"""

import numpy as np
import pytest
from kernel_helpers import (
    assert_planes_equal,
    full_state,
    render_naive,
    render_switched,
)

import vgxsim.kernels.small as small
from vgxsim.state.raster import (
    BF_MSA,
    BF_ONE,
    BF_SA,
    CMP_EQUAL,
    CMP_GEQUAL,
    CMP_LEQUAL,
    CMP_LESS,
    CMP_NOTEQUAL,
    OP_DECR,
    OP_INCR,
    OP_INVERT,
    OP_REPLACE,
)

W, H = 180, 200


def _states():
    return [
        full_state(W, H, zbuffer=True, zfunc=CMP_LEQUAL),  # colour, replace
        full_state(W, H, zbuffer=True, zfunc=CMP_LESS, wmpack=0),  # z only
        full_state(W, H, zbuffer=True, zfunc=CMP_LESS, zwritemask=0, wmpack=0,
                   stencil=True, szpass=OP_INCR, spass=OP_DECR),  # z + stencil add
        full_state(W, H, zbuffer=True, zfunc=CMP_GEQUAL, zwritemask=0, wmpack=0,
                   stencil=True, szpass=OP_REPLACE, spass=OP_INVERT, sref=5),  # table
        full_state(W, H, zbuffer=True, zfunc=CMP_EQUAL, stencil=True, sfunc=CMP_NOTEQUAL,
                   sref=2, blend_sf=BF_ONE, blend_df=BF_ONE),  # lit pass
        full_state(W, H, zbuffer=True, zfunc=CMP_LEQUAL, zwritemask=0, wmpack=0x00FF00FF,
                   blend_sf=BF_ONE, blend_df=BF_ONE),  # add, masked, no z write
        full_state(W, H, zbuffer=True, blend_sf=BF_SA, blend_df=BF_MSA),  # span path
        full_state(W, H, blend_sf=BF_ONE, blend_df=BF_ONE),  # no z test: span path
        full_state(W, H, zbuffer=True, scissor=(30, 120, 50, 160)),
    ]


def _tri(rng, centre, w, h):
    p = centre + rng.uniform([-w, -h], [w, h], (3, 2))
    z = float(rng.uniform(-4000, 4000))
    return tuple((float(x), float(y), z + float(rng.uniform(-800, 800)),
                  tuple(float(v) for v in rng.uniform(0, 1, 4))) for x, y in p)


def _scene(rng, n):
    states = _states()
    spots = rng.uniform([0, 0], [W, H], (5, 2))
    cmds = [("clear", {"color", "z", "stencil"}, {"color": 0x40302010, "z": 0x7FFFFF,
                                                  "stencil": 2}, full_state(W, H))]
    rs = states[0]
    for _ in range(n):
        u = rng.random()
        if u < 0.15:
            rs = states[int(rng.integers(len(states)))]
        c = spots[int(rng.integers(len(spots)))] + rng.normal(0, 3, 2)
        if u < 0.03:
            tri = _tri(rng, c, 60.0, 60.0)  # big
        elif u < 0.08:
            tri = _tri(rng, c, 2.0, 40.0)  # a sliver: narrow, tall (classified or not)
        else:
            tri = _tri(rng, c, float(rng.uniform(0.5, 4.5)), float(rng.uniform(0.5, 5)))
        cmds.append(("triangle", tri, rs))
    return cmds


def _render(cmds, nthreads, **switches):
    return render_switched(cmds, W, H, nthreads=nthreads, **switches)


@pytest.mark.parametrize("seed", range(2))
@pytest.mark.parametrize("nthreads", [1, 2])
def test_small_path_changes_no_plane(seed, nthreads):
    assert small.NARROW == 8
    cmds = _scene(np.random.default_rng(70 + seed), 1200)
    want, want_work = _render(cmds, nthreads, small_path=False)
    got, got_work = _render(cmds, nthreads, small_path=True)
    assert_planes_equal(got, want, f"small_path, {nthreads} thread(s)")
    assert got_work == want_work and got_work["fragments"] > 0
    if nthreads == 1 and seed == 0:
        naive = render_naive(cmds, W, H, double=True, zbits=24, stencil=8)
        assert_planes_equal(got, naive, "naive reference")
