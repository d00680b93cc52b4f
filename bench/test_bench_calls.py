"""pytest-benchmark entries for the IRIS GL front end (issue 6).

Run with ``python -m pytest bench/test_bench_calls.py --benchmark-enable``; the
report script bench/calls.py prints the same figures per call beside PyOpenGL.
"""

import pytest

from vgxsim import GL, gl
from vgxsim.gl._core import current, session

N = 1000


@pytest.fixture
def window():
    session.reset()
    gl.prefsize(64, 64)
    gl.winopen("bench")
    gl.RGBmode()
    gl.stensize(8)
    gl.gconfig()
    gl.ortho2(-0.5, 63.5, -0.5, 63.5)
    yield current("bench")
    session.reset()


def test_shadow_face_groups(benchmark, window):
    """N groups of stencil + bgnpolygon + 4 v3f + endpolygon (the 1991 faces),
    recorded and decoded (raster excluded: z and colour writes off, tiny quads)."""
    gl.zwritemask(0)
    gl.wmpack(0)
    quad = ((1.0, 1.0, 0.0), (3.0, 1.0, 0.0), (3.0, 3.0, 0.0), (1.0, 3.0, 0.0))

    def run():
        for i in range(N):
            gl.stencil(1, 0, GL.SF_ALWAYS, 0xFF, GL.ST_KEEP, GL.ST_KEEP,
                       GL.ST_INCR if i & 1 else GL.ST_DECR)
            gl.bgnpolygon()
            for q in quad:
                gl.v3f(q)
            gl.endpolygon()
        window.flush()

    run()
    benchmark.extra_info["calls_per_round"] = 7 * N
    benchmark.pedantic(run, rounds=5, iterations=1)


def test_callobj_replay(benchmark, window):
    """N callobj of a 100-triangle object, decoded."""
    gl.makeobj(1)
    for k in range(100):
        gl.cpack(0xFF000000 | k)
        gl.bgnpolygon()
        gl.v2f(float(k % 60), 1.0)
        gl.v2f(float(k % 60) + 3.0, 1.0)
        gl.v2f(float(k % 60), 4.0)
        gl.endpolygon()
    gl.closeobj()

    def run():
        for _ in range(N // 10):
            gl.callobj(1)
        window.flush()

    run()
    benchmark.pedantic(run, rounds=5, iterations=1)
