"""NaN, infinities and enormous coordinates: no crash, no hang, documented results.

* Window-space path (CommandBatch.add_window_triangles): a triangle with a
  non-finite vertex (x, y or z) is dropped; finite coordinates are clamped to
  +-COORD_LIMIT (65536) pixels before snapping (kernels/clip.py), so an enormous
  vertex still gives the triangle that clamped vertex draws.
* Clip-space path (geometry.pipeline): non-finite vertices drop their triangles,
  segments and points; enormous finite ones are cut by the guard band, so the pixels
  in the window are those of the exact clipped geometry.

Everything runs in-process under a watchdog (faulthandler) that aborts the run with
a traceback if a call hangs; no call's wall time is asserted (machines are shared).
Instead each flush's work counters show the raster stayed inside the window: at
most one tested fragment per window pixel and primitive, so an enormous vertex
never makes the kernel walk its unclamped box.
"""

import faulthandler
import math

import numpy as np
import pytest
from kernel_helpers import (
    assert_planes_equal,
    clip_planes,
    clip_reference,
    full_state,
    guard,
    kernel_batch,
    kernel_framebuffer,
    planes_of,
    render_naive,
    snap_point,
    winding_numbers,
)

from vgxsim.geometry.pipeline import Viewing, draw_lines, draw_points, draw_triangles
from vgxsim.reference.naive import line_pixels
from vgxsim.state.raster import BF_MSA, BF_SA, CMP_ALWAYS, CMP_LEQUAL, OP_INCR

W, H = 48, 40
VIEWPORT = (0, W - 1, 0, H - 1)
DEPTH = (-8388608.0, 8388607.0)
LIMIT = 65536.0  # kernels.clip.COORD_LIMIT, in pixels
ENORMOUS = [1e30, -1e30, 1e300, -1e300, 1.7e308, -1.7e308]
NONFINITE = [math.nan, math.inf, -math.inf]
COUNT = dict(stencil=True, sfunc=CMP_ALWAYS, spass=OP_INCR, wmpack=0)


@pytest.fixture(autouse=True)
def watchdog():
    faulthandler.dump_traceback_later(300, exit=True)
    yield
    faulthandler.cancel_dump_traceback_later()


def flush_within_window(batch, primitives: int) -> None:
    """Flush, then check the kernels tested at most W x H fragments a primitive."""
    batch.flush()
    tested = batch.work()["fragments"]
    assert tested <= primitives * W * H, (tested, primitives)


def new_batch(double=False, mode="span"):
    fb = kernel_framebuffer(W, H, double=double, zbits=24, stencil=8)
    return fb, kernel_batch(fb, mode)


# ------------------------------------------------------------ window-space path


def test_window_nonfinite_triangles_are_dropped():
    rng = np.random.default_rng(1)
    states = [
        full_state(W, H, zbuffer=True, zfunc=CMP_LEQUAL, stencil=True, szpass=OP_INCR),
        full_state(W, H, blend_sf=BF_SA, blend_df=BF_MSA, shademodel=0),
        full_state(W, H, zbuffer=True, zfunc=CMP_ALWAYS, zwritemask=0, stencil=True,
                   szpass=OP_INCR, wmpack=0),
    ]
    for trial in range(12):
        rs = states[trial % len(states)]
        n = 40
        xw = rng.uniform(-5, W + 5, n)
        yw = rng.uniform(-5, H + 5, n)
        zw = rng.uniform(-1e6, 1e6, n)
        col = rng.uniform(0, 1, (n, 4))
        bad = rng.choice(n, 8, replace=False)
        for k, i in enumerate(bad):
            (xw, yw, zw)[k % 3][i] = NONFINITE[k % len(NONFINITE)]
        tris = rng.integers(0, n, (30, 3))
        flat = col[tris[:, 2]]
        for mode in ("span", "general", "edge"):
            fb, batch = new_batch(mode=mode)
            batch.add_window_triangles(xw, yw, zw, col, tris, rs, flat_col=flat)
            flush_within_window(batch, len(tris))
            good = [t for t in tris if not np.isin(t, bad).any()]
            assert len(good) < len(tris)
            cmds = [("triangle", tuple((xw[i], yw[i], zw[i], tuple(col[i])) for i in t), rs)
                    for t in good]
            want = render_naive(cmds, W, H, double=False, zbits=24, stencil=8)
            assert_planes_equal(planes_of(fb), want, f"trial {trial} {mode}")


@pytest.mark.parametrize("big", ENORMOUS)
@pytest.mark.parametrize("subpixel", [False, True])
def test_window_enormous_coordinates_are_clamped(big, subpixel):
    tris = [
        [(2.0, 3.0), (30.0, 5.0), (big, 20.0)],
        [(10.0, 2.0), (20.0, big), (40.0, 30.0)],
        [(big, big), (5.0, 30.0), (44.0, 36.0)],
        [(-big, 7.0), (big, 9.5), (24.0, 1.0)],
    ]
    for tri in tris:
        fb, batch = new_batch()
        rs = full_state(W, H, subpixel=subpixel, **COUNT)
        v = np.array(tri)
        batch.add_window_triangles(v[:, 0], v[:, 1], np.zeros(3), None,
                                   np.array([[0, 1, 2]]), rs)
        flush_within_window(batch, 1)
        clamped = [snap_point(min(max(x, -LIMIT), LIMIT), min(max(y, -LIMIT), LIMIT),
                              subpixel) for x, y in tri]
        expected = winding_numbers(clamped, 0, W - 1, 0, H - 1) != 0
        np.testing.assert_array_equal(fb.stencil, expected.astype(np.uint8), err_msg=str(tri))


@pytest.mark.parametrize("big", ENORMOUS)
def test_window_enormous_depth_keeps_coverage(big):
    """Depth beyond the 24-bit range: coverage unchanged, z stays a 24-bit value."""
    tri = [(2.0, 3.0, 0.0), (45.0, 5.0, big), (20.0, 37.0, -5.0)]
    v = np.array(tri)
    fb, batch = new_batch()
    rs = full_state(W, H, zbuffer=True, zfunc=CMP_ALWAYS, stencil=True, szpass=OP_INCR)
    batch.add_window_triangles(v[:, 0], v[:, 1], v[:, 2],
                               np.ones((3, 4)), np.array([[0, 1, 2]]), rs)
    flush_within_window(batch, 1)
    expected = winding_numbers([snap_point(x, y, False) for x, y, _ in tri],
                               0, W - 1, 0, H - 1) != 0
    np.testing.assert_array_equal(fb.stencil, expected.astype(np.uint8))
    assert fb.z.min() >= -(1 << 23) and fb.z.max() < (1 << 23)


# --------------------------------------------------------------- clip-space path


def clip_draw(clip, tris, subpixel=True, mode="span"):
    fb, batch = new_batch(mode=mode)
    rs = full_state(W, H, subpixel=subpixel, **COUNT)
    view = Viewing(np.eye(4), VIEWPORT, DEPTH)
    # Clipping may cut a triangle into a polygon of up to 9 triangles (3 + 6 planes).
    draw_triangles(batch, rs, view, None, None, np.asarray(tris, np.int64),
                   clip_coords=np.asarray(clip, np.float64))
    flush_within_window(batch, 9 * len(tris))
    return fb.stencil.astype(np.int64)


def test_clip_nonfinite_triangles_are_dropped():
    rng = np.random.default_rng(2)
    for _ in range(20):
        n = 12
        clip = np.column_stack([rng.uniform(-1.5, 1.5, (n, 3)), rng.uniform(0.5, 2, n)])
        clip[:, :2] *= clip[:, 3:4]
        tris = rng.integers(0, n, (8, 3))
        bad = rng.choice(n, 3, replace=False)
        dirty = clip.copy()
        for k, i in enumerate(bad):
            dirty[i, int(rng.integers(4))] = NONFINITE[k]
        good = [t for t in tris if not np.isin(t, bad).any()]
        got = clip_draw(dirty, tris)
        want = clip_draw(clip, good) if good else np.zeros((H, W), np.int64)
        np.testing.assert_array_equal(got, want)


# Triangles with one enormous vertex, the lexicographically smaller endpoint of
# every clipped edge being the vertex inside the view volume.
POSITIVE_CASES = [
    ([1.0, 0.3, 0.0, 1.0], "x"),
    ([0.2, 0.3, 0.0, 1.0], "w"),
    ([1.0, 1.0, 1.0, 1.0], "all"),
    ([0.3, 0.2, 1.0, 1.0], "z"),
    ([1.0, -1.0, 0.0, 0.0], "xy at w=1e-300"),
]


def _big_vertex(template, kind, big):
    v = np.array(template)
    if kind == "x":
        v[0] = big
    elif kind == "w":
        v[3] = big
    elif kind == "all":
        v[:] = big
    elif kind == "z":
        v[2] = big
    else:
        v[0], v[1], v[3] = big, -big, 1e-300
    return v


def _check_clip_case(vertex, subpixel=True):
    tri = np.array([[-0.5, -0.5, 0.0, 1.0], [0.5, -0.4, 0.0, 1.0], vertex])
    for mode in ("span", "edge"):
        count = clip_draw(tri, [[0, 1, 2]], subpixel, mode)
        inside, dist, poly = clip_reference(tri, VIEWPORT, W, H)
        robust = dist > (0.01 if subpixel else 1.0)
        bad = robust & (count != inside)
        assert not bad.any(), f"{int(bad.sum())} pixels differ; vertex {vertex}, {poly}"
        assert count.max() <= 1


@pytest.mark.parametrize("big", [1e30, 1e300, 1.7e308])
@pytest.mark.parametrize("case", POSITIVE_CASES, ids=[c[1] for c in POSITIVE_CASES])
def test_clip_enormous_positive_coordinates(case, big):
    _check_clip_case(_big_vertex(case[0], case[1], big))


@pytest.mark.parametrize("big", [-1e30, -1e300, -1.7e308])
def test_clip_enormous_w_negative(big):
    # w < 0 everywhere near the vertex: behind the eye, cut by the near plane.
    _check_clip_case(np.array([0.2, 0.3, 0.0, big]))


@pytest.mark.parametrize("big", [-1e20, -1e30, -1e300, -1.7e308])
def test_clip_enormous_negative_coordinates(big):
    _check_clip_case(np.array([big, 0.3, 0.0, 1.0]))


# ------------------------------------------------------------ lines and points


def reference_line(a, b, subpixel):
    """In-window pixels of a clip-space segment: clipped plane by plane from its
    inside end, projected, snapped, and stepped by the naive oracle's line_pixels."""
    gx, gy = guard(VIEWPORT)
    poly = _clip_segment(np.asarray(a, np.float64), np.asarray(b, np.float64), gx, gy)
    if poly is None:
        return set()
    ends = []
    for v in poly:
        x = -0.5 + (v[0] / v[3] + 1) * W / 2
        y = -0.5 + (v[1] / v[3] + 1) * H / 2
        ends.append(snap_point(x, y, subpixel))
    return {(X, Y) for X, Y, *_ in line_pixels(ends[0], ends[1], not subpixel)
            if 0 <= X < W and 0 <= Y < H}


def _clip_segment(a, b, gx, gy):
    with np.errstate(over="ignore", invalid="ignore"):
        for dist in clip_planes(gx, gy):
            da, db = dist(a), dist(b)
            if da < 0 and db < 0:
                return None
            if da < 0:
                a = b + (db / (db - da)) * (a - b)
            elif db < 0:
                b = a + (da / (da - db)) * (b - a)
    if not (a[3] > 0 and b[3] > 0):
        return None
    return a, b


def line_draw(seg, subpixel):
    fb, batch = new_batch()
    rs = full_state(W, H, subpixel=subpixel, **COUNT)
    view = Viewing(np.eye(4), VIEWPORT, DEPTH)
    n = draw_lines(batch, rs, view, np.asarray(seg, np.float64), None,
                   np.array([[0, 1]]), np.array([0]))
    flush_within_window(batch, 1)
    ys, xs = np.nonzero(fb.stencil)
    assert fb.stencil.max(initial=0) <= 1
    return n, {(int(x), int(y)) for x, y in zip(xs, ys, strict=True)}


INSIDE = [-0.5, -0.5, 0.0, 1.0]


@pytest.mark.parametrize("value", NONFINITE)
def test_lines_and_points_with_nonfinite_vertices_are_dropped(value):
    for k in range(4):
        v = list(INSIDE)
        v[k] = value
        for seg in ([INSIDE, v], [v, INSIDE]):
            n, pix = line_draw(seg, True)
            assert n == 0 and not pix
        fb, batch = new_batch()
        rs = full_state(W, H, **COUNT)
        view = Viewing(np.eye(4), VIEWPORT, DEPTH)
        pts = np.array([INSIDE, v, [0.5, 0.5, 0.0, 1.0]])
        assert draw_points(batch, rs, view, pts, None) == 2
        batch.flush()
        assert fb.stencil.sum() == 2


@pytest.mark.parametrize("big", [1e30, 1e300, 1.7e308])
@pytest.mark.parametrize("subpixel", [False, True])
def test_lines_to_enormous_positive_coordinates(big, subpixel):
    for far in ([big, 0.3, 0.0, 1.0], [0.2, big, 0.0, 1.0], [0.2, 0.3, 0.0, big]):
        n, pix = line_draw([INSIDE, far], subpixel)
        assert pix == reference_line(INSIDE, far, subpixel), far
        assert n > 0


@pytest.mark.parametrize("big", [1e30, 1e300])
@pytest.mark.parametrize("subpixel", [False, True])
def test_lines_to_enormous_negative_w(big, subpixel):
    # Behind the eye: cut by the near plane, then the line runs to the guard band.
    far = [0.2, 0.3, 0.0, -big]
    n, pix = line_draw([INSIDE, far], subpixel)
    assert pix == reference_line(INSIDE, far, subpixel) and len(pix) > 5


@pytest.mark.parametrize("subpixel", [False, True])
def test_lines_to_w_near_minus_dbl_max(subpixel):
    # Near float overflow the pipeline rescales the vertex (the same homogeneous point,
    # vgxsim/geometry/pipeline.py _tame) so the clipper's plane distances stay finite.
    # The clipped end, far out in the guard band, may then round differently from
    # the unscaled float64 reference, and with snapping a tie pixel may move by one
    # row: every pixel must still lie within one pixel of the reference line.
    far = [0.2, 0.3, 0.0, -1.7e308]
    n, pix = line_draw([INSIDE, far], subpixel)
    ref = reference_line(INSIDE, far, subpixel)
    assert len(pix) > 5 and abs(len(pix) - len(ref)) <= 1
    for x, y in pix ^ ref:
        other = ref if (x, y) in pix else pix
        assert any(abs(x - u) <= 1 and abs(y - v) <= 1 for u, v in other)


@pytest.mark.parametrize("big", [1e20, -1e30, 1e300])
def test_lines_from_enormous_first_endpoint(big):
    far = [big, 0.3, 0.0, 1.0]
    n, pix = line_draw([far, INSIDE], False)
    assert pix == reference_line(far, INSIDE, False) and pix
