"""Thread count does not change a single bit: each band of rows belongs to one
thread, which walks the primitives in order, so order-dependent operations (blending,
stencil INCR/INVERT, logicop XOR, z tests with writes) come out the same whatever
the number of threads or band groups."""

import numba
import numpy as np
import pytest
from kernel_helpers import (
    assert_planes_equal,
    full_state,
    random_planes,
    render_kernels,
    render_naive,
)

from vgxsim import threads
from vgxsim.reference.naive import GD_ZMAX, GD_ZMIN
from vgxsim.state.raster import (
    BF_DA,
    BF_MDC,
    BF_MSA,
    BF_ONE,
    BF_SA,
    CMP_ALWAYS,
    CMP_EQUAL,
    CMP_GREATER,
    CMP_LEQUAL,
    CMP_LESS,
    CMP_NOTEQUAL,
    OP_DECR,
    OP_INCR,
    OP_INVERT,
    OP_REPLACE,
)

MAX_THREADS = numba.config.NUMBA_NUM_THREADS


def heavy_scene(rng, w, h, ntris):
    """Heavy overdraw with order-dependent operations, plus lines, points, clears."""
    states = [
        full_state(w, h, blend_sf=BF_SA, blend_df=BF_MSA, zbuffer=True, zfunc=CMP_ALWAYS,
                   stencil=True, szpass=OP_INCR),
        full_state(w, h, logicop=6, stencil=True, spass=OP_INVERT, draw_front=True),
        full_state(w, h, blend_sf=BF_MDC, blend_df=BF_DA, zbuffer=True, zfunc=CMP_LEQUAL,
                   stencil=True, sfunc=CMP_NOTEQUAL, sref=3, sfail=OP_REPLACE,
                   spass=OP_DECR, szpass=OP_INCR, shademodel=0),
        full_state(w, h, zbuffer=True, zfunc=CMP_LESS, zwritemask=0, stencil=True,
                   szpass=OP_INCR, spass=OP_DECR, wmpack=0),  # z/stencil fast path
        full_state(w, h, zbuffer=True, zfunc=CMP_GREATER, wmpack=0),  # z-only fast path
        full_state(w, h, zbuffer=True, zfunc=CMP_EQUAL, stencil=True, sfunc=CMP_EQUAL,
                   sref=1, blend_sf=BF_ONE, blend_df=BF_ONE, subpixel=True),
        full_state(w, h, afunc=CMP_GREATER, aref=100, blend_sf=8, blend_df=BF_ONE,
                   subpixel=True, wmpack=0x00FFFF0F),
    ]
    cmds = []
    for i in range(ntris):
        rs = states[int(rng.integers(len(states)))]
        r = rng.random()
        if r < 0.8:
            size = rng.uniform(4, max(w, h))
            c = rng.uniform([-4, -4], [w + 4, h + 4])
            verts = tuple((float(c[0] + rng.uniform(-size, size)),
                           float(c[1] + rng.uniform(-size, size)),
                           float(rng.choice([rng.uniform(GD_ZMIN, GD_ZMAX),
                                             float(rng.integers(-2, 3))])),
                           tuple(float(x) for x in rng.uniform(0, 1, 4))) for _ in range(3))
            cmds.append(("triangle", verts, rs))
        elif r < 0.9:
            verts = tuple((float(rng.uniform(-4, w + 4)), float(rng.uniform(-4, h + 4)),
                           float(rng.uniform(-1e6, 1e6)),
                           tuple(float(x) for x in rng.uniform(0, 1, 4))) for _ in range(2))
            lw = full_state(w, h, blend_sf=BF_SA, blend_df=BF_MSA, linewidth=3,
                            stencil=True, spass=OP_INCR)
            cmds.append(("line", verts, lw, int(rng.integers(16))))
        elif r < 0.97:
            pt = full_state(w, h, logicop=6, pntsize=4, zbuffer=True, zfunc=CMP_ALWAYS)
            cmds.append(("point", (float(rng.uniform(0, w)), float(rng.uniform(0, h)), 0.0,
                                   tuple(float(x) for x in rng.uniform(0, 1, 4))), pt))
        else:
            x0, y0 = int(rng.integers(0, w // 2)), int(rng.integers(0, h // 2))
            cs = full_state(w, h, scissor=(x0, x0 + w // 3, y0, y0 + h // 3),
                            swritemask=0x0F, wmpack=0xFF00FF00)
            cmds.append(("clear", {"color", "z", "stencil"},
                         {"color": int(rng.integers(1 << 32)), "z": 0, "stencil": 0xFF}, cs))
        if i % 97 == 96:
            cmds.append(("flush",))
    return cmds


@pytest.fixture
def restore_threads():
    n = numba.get_num_threads()
    yield
    numba.set_num_threads(n)
    threads.set_threads(None)


def test_one_and_two_numba_threads_identical(restore_threads):
    """vgxsim.threads follows numba.set_num_threads."""
    if MAX_THREADS < 2:
        pytest.skip("numba has a single thread here")
    w, h = 128, 112  # several bands of rows (32 rows each with two threads)
    rng = np.random.default_rng(31)
    cmds = heavy_scene(rng, w, h, 400)
    cfg = dict(double=True, zbits=24, stencil=8)
    init = random_planes(rng, w, h, **cfg)
    results = {}
    for n in (1, 2, 1, 2):
        numba.set_num_threads(n)
        assert threads.get_threads() == n
        for mode in ("span", "general"):
            got = render_kernels(cmds, w, h, init=init, mode=mode, **cfg)
            if mode in results:
                assert_planes_equal(got, results[mode], f"{n} threads, {mode}")
            else:
                results[mode] = got
    assert_planes_equal(results["general"], results["span"], "general vs span")
    # The scene is order dependent: reversing it changes the picture.
    rev = render_kernels(cmds[::-1], w, h, init=init, **cfg)
    assert not np.array_equal(rev["back"], results["span"]["back"])


_NAIVE = {}


@pytest.mark.parametrize("n", [1, 2, 3, 5, 8])
def test_any_thread_count_matches_naive(n, restore_threads):
    """Each worker strides the bands by the worker count; any count (more workers
    than bands or cores too) must give the naive oracle's planes."""
    threads.set_threads(n)
    w, h = 40, 150  # 3-5 bands depending on the thread count, the last one partial
    rng = np.random.default_rng(5)
    cmds = heavy_scene(rng, w, h, 90)
    cfg = dict(double=True, zbits=24, stencil=8)
    init = random_planes(rng, w, h, **cfg)
    if "want" not in _NAIVE:
        _NAIVE["want"] = render_naive(cmds, w, h, init=init, **cfg)
    for mode in ("span", "edge"):
        got = render_kernels(cmds, w, h, init=init, mode=mode, **cfg)
        assert_planes_equal(got, _NAIVE["want"], f"{n} threads, {mode}")


def test_parallel_setup_of_one_large_call_equals_serial():
    """A call with more than PARALLEL_SETUP triangles is set up in chunks on worker
    threads (culled triangles keep dead slots); the planes must equal a serial run."""
    from vgxsim import threads
    from vgxsim.batch import PARALLEL_SETUP, CommandBatch
    from vgxsim.state.planes import Framebuffer, PlaneConfig
    from vgxsim.state.raster import CULL_BACK, RasterState

    rng = np.random.default_rng(7)
    n = PARALLEL_SETUP + 5000
    w, h = 200, 150
    pts = (rng.uniform([0, 0], [w, h], (n, 1, 2)) + rng.uniform(-4, 4, (n, 3, 2))).reshape(-1, 2)
    z = rng.uniform(-1e5, 1e5, 3 * n)
    col = rng.random((3 * n, 4))
    tris = np.arange(3 * n).reshape(n, 3)
    rs = RasterState(scissor=(0, w - 1, 0, h - 1), zbuffer=True, draw_front=True,
                     cull=CULL_BACK, stencil=True, sfunc=7, szpass=3, blend_sf=1, blend_df=1)
    planes = []
    for count in (1, 2):
        threads.set_threads(count)
        try:
            fb = Framebuffer(PlaneConfig(w, h, stencil=8))
            batch = CommandBatch(fb)
            batch.add_window_triangles(pts[:, 0], pts[:, 1], z, col, tris, rs)
            batch.flush()
        finally:
            threads.set_threads(None)
        planes.append((fb.front.copy(), fb.z.copy(), fb.stencil.copy()))
    for a, b in zip(planes[0], planes[1], strict=True):
        assert np.array_equal(a, b)
    assert (planes[0][2] > 0).sum() > 0.3 * w * h  # the scene really drew
