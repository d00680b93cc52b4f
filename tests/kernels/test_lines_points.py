"""Lines and points against the naive oracle (docs/numeric_model.md section 5):
through kernels.lines + CommandBatch.add_fragments, and through the geometry
pipeline (draw_lines / draw_points) with a viewing set up so that window
coordinates are exact."""

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from kernel_helpers import (
    assert_planes_equal,
    full_state,
    kernel_framebuffer,
    planes_of,
    random_planes,
    render_kernels,
    render_naive,
)

from vgxsim.batch import CommandBatch
from vgxsim.geometry.pipeline import Viewing, draw_lines, draw_points
from vgxsim.reference.naive import GD_ZMAX, GD_ZMIN
from vgxsim.state.raster import (
    BF_MSA,
    BF_SA,
    CMP_ALWAYS,
    CMP_GREATER,
    CMP_LEQUAL,
    CMP_LESS,
    OP_INCR,
    OP_INVERT,
    RasterState,
)

W, H = 32, 32  # powers of two: the pipeline's viewport arithmetic is exact
CFG = dict(double=True, zbits=24, stencil=8)

coord = st.one_of(
    st.integers(-6 * 256, (W + 6) * 256).map(lambda v: v / 256),
    st.integers(-12, 2 * W + 12).map(lambda v: v / 2),
    st.floats(-6, W + 6),
)
zval = st.one_of(st.floats(GD_ZMIN, GD_ZMAX), st.integers(-2, 2).map(float),
                 st.floats(-1000, 1000))
chan = st.one_of(st.sampled_from([0.0, 1.0, 0.5]), st.floats(0, 1))
colour = st.tuples(chan, chan, chan, chan)
vertex = st.tuples(coord, coord, zval, colour)


@st.composite
def line_states(draw):
    blend = draw(st.booleans())
    return RasterState(
        linewidth=draw(st.integers(1, 4)),
        linestyle=draw(st.one_of(st.just(0xFFFF), st.integers(0, 0xFFFF),
                                 st.sampled_from([0x00FF, 0xAAAA, 0x0F0F, 0x8001]))),
        lsrepeat=draw(st.integers(1, 4)),
        pntsize=draw(st.integers(1, 4)),
        subpixel=draw(st.booleans()),
        shademodel=draw(st.integers(0, 1)),
        zbuffer=draw(st.booleans()),
        zfunc=draw(st.sampled_from([CMP_LEQUAL, CMP_LESS, CMP_GREATER, CMP_ALWAYS])),
        stencil=draw(st.booleans()),
        szpass=OP_INCR, spass=draw(st.sampled_from([OP_INCR, OP_INVERT])),
        blend_sf=BF_SA if blend else 1, blend_df=BF_MSA if blend else 0,
        logicop=draw(st.sampled_from([3, 3, 6])),
        afunc=draw(st.sampled_from([CMP_ALWAYS, CMP_ALWAYS, CMP_GREATER])),
        aref=draw(st.integers(0, 255)),
        draw_front=draw(st.booleans()), draw_back=True,
        scissor=draw(st.sampled_from([(0, W - 1, 0, H - 1), (3, 20, 5, 29)])),
    )


@st.composite
def line_commands(draw):
    pool = draw(st.lists(line_states(), min_size=1, max_size=2))
    cmds = []
    for _ in range(draw(st.integers(1, 6))):
        rs = pool[draw(st.integers(0, len(pool) - 1))]
        if draw(st.integers(0, 3)):
            cmds.append(("line", (draw(vertex), draw(vertex)), rs, draw(st.integers(0, 50))))
        else:
            cmds.append(("point", draw(vertex), rs))
    return cmds


@settings(max_examples=150, deadline=None)
@given(cmds=line_commands(), seed=st.integers(0, 2**32 - 1))
def test_lines_and_points_match_naive(cmds, seed):
    init = random_planes(np.random.default_rng(seed), W, H, **CFG)
    want = render_naive(cmds, W, H, init=init, **CFG)
    got = render_kernels(cmds, W, H, init=init, **CFG)
    assert_planes_equal(got, want)


def test_line_patterns_hand_checked():
    """A horizontal closed line from pixel 0 to 19 with linestyle 0x00F3 (bits 0, 1,
    4..7 set) and lsrepeat 2: positions 0..19 use bits pos//2 % 16."""
    rs = full_state(W, H, linestyle=0x00F3, lsrepeat=2)
    white = (1.0, 1.0, 1.0, 1.0)
    cmds = [("line", ((0.0, 5.0, 0.0, white), (19.0, 5.0, 0.0, white)), rs, 0)]
    got = render_kernels(cmds, W, H, **CFG)["back"]
    drawn = [x for x in range(W) if got[5, x]]
    bits = [0, 1, 4, 5, 6, 7]
    assert drawn == [x for x in range(20) if (x // 2) % 16 in bits]
    # Started 3 positions into the pattern.
    cmds = [("line", ((0.0, 5.0, 0.0, white), (19.0, 5.0, 0.0, white)), rs, 3)]
    got = render_kernels(cmds, W, H, **CFG)["back"]
    assert [x for x in range(W) if got[5, x]] == [
        x for x in range(20) if ((x + 3) // 2) % 16 in bits]


def test_wide_lines_and_points_hand_checked():
    white = (1.0, 1.0, 1.0, 1.0)
    for width, offs in ((1, [0]), (2, [0, 1]), (3, [-1, 0, 1]), (4, [-1, 0, 1, 2])):
        rs = full_state(W, H, linewidth=width)
        cmds = [("line", ((2.0, 10.0, 0.0, white), (12.0, 11.0, 0.0, white)), rs, 0)]
        got = render_kernels(cmds, W, H, **CFG)["back"]
        # x-major, y(X) = 10 + (X - 2)/10 rounds to 10 for X <= 6, 11 from X = 7.
        for X in range(2, 13):
            Y = 10 if X <= 6 else 11
            col = [y for y in range(H) if got[y, X]]
            assert col == [Y + o for o in offs], (width, X, col)
    for size in (1, 2, 3, 4):
        rs = full_state(W, H, pntsize=size)
        got = render_kernels([("point", (10.4, 20.6, 0.0, white), rs)], W, H, **CFG)["back"]
        lo = -((size - 1) // 2)
        ys, xs = np.nonzero(got)
        assert set(zip(xs.tolist(), ys.tolist(), strict=True)) == {
            (10 + lo + i, 21 + lo + j) for i in range(size) for j in range(size)}


# ---------------------------------------------------------- through the pipeline


def _ndc(v, n):
    """Exact inverse of the viewport map for a power-of-two size n (dyadic v)."""
    return (v + 0.5) * 2.0 / n - 1.0


def _window_z(z_ndc):
    lo, hi = float(GD_ZMIN), float(GD_ZMAX)
    return lo + (z_ndc + 1.0) * ((hi - lo) / 2.0)


dyadic = st.integers(-4 * 256, (W + 4) * 256).map(lambda v: v / 256)
z_ndc = st.integers(-1024, 1024).map(lambda v: v / 1024)


@settings(max_examples=80, deadline=None)
@given(pts=st.lists(st.tuples(dyadic, dyadic, z_ndc, colour), min_size=2, max_size=7),
       rs=line_states(), closed=st.booleans(), seed=st.integers(0, 2**32 - 1))
def test_pipeline_polyline_and_points_match_naive(pts, rs, closed, seed):
    """draw_lines (clip_segments + project_snap + line_fragments) and draw_points on
    a polyline whose window coordinates are exact, against the naive oracle."""
    view = Viewing(np.eye(4), (0, W - 1, 0, H - 1), (float(GD_ZMIN), float(GD_ZMAX)))
    obj = np.array([[_ndc(x, W), _ndc(y, H), z, 1.0] for x, y, z, _ in pts])
    rgba = np.array([c for *_, c in pts], np.float64)
    n = len(pts)
    segs = np.array([[i, (i + 1) % n] for i in range(n if closed else n - 1)])
    starts = np.arange(len(segs), dtype=np.int64) * 7
    init = random_planes(np.random.default_rng(seed), W, H, **CFG)
    fb = kernel_framebuffer(W, H, init=init, **CFG)
    batch = CommandBatch(fb)
    draw_lines(batch, rs, view, obj, rgba, segs, starts)
    draw_points(batch, rs, view, obj, rgba)
    batch.flush()
    win = [(x, y, _window_z(z), c) for x, y, z, c in pts]
    cmds = [("line", (win[a], win[b]), rs, int(s)) for (a, b), s in zip(segs, starts,
                                                                      strict=True)]
    cmds += [("point", v, rs) for v in win]
    assert_planes_equal(planes_of(fb), render_naive(cmds, W, H, init=init, **CFG))
