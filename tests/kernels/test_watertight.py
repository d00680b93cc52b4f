"""Watertight coverage: every pixel centre inside a tiled region is covered exactly
once, counted with stencil INCR, against an exact independent oracle.

The oracle (kernel_helpers.winding_numbers) computes, with int64 arithmetic and the
crossing rule, the winding number of a fixed-point polygon around each pixel centre
moved by the infinitesimal offset (eps, eps**2); that offset is exactly the model's
tie rule (docs/numeric_model.md section 3).  Two checks per scene:

* per triangle: the stencil count equals the number of snapped triangles whose
  oracle coverage contains the pixel (the kernels cover exactly the right pixels);
* per region: when every snapped triangle keeps its counter-clockwise orientation,
  the count equals the winding number of the region's snapped boundary, which is 1
  inside and 0 outside (no pixel twice, none missed along shared edges or at shared
  vertices).
"""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from kernel_helpers import (
    area2,
    full_state,
    kernel_batch,
    kernel_framebuffer,
    snap_point,
    winding_numbers,
)

from vgxsim.kernels.raster import coverage_mask_edge, coverage_mask_scanline
from vgxsim.kernels.setup import setup_triangles
from vgxsim.state.raster import CMP_ALWAYS, OP_INCR

W, H = 48, 40
MODES = ("span", "general", "edge")
# Stencil counting with the z-buffer off (IRIS applies `pass`) and with it on
# (ZF_ALWAYS, `zpass`; no colour, no z write: the shadow-volume fast path).
COUNT_STATES = {
    "pass": dict(stencil=True, sfunc=CMP_ALWAYS, spass=OP_INCR, zbuffer=False, wmpack=0),
    "zpass": dict(stencil=True, sfunc=CMP_ALWAYS, szpass=OP_INCR, zbuffer=True,
                  zfunc=CMP_ALWAYS, zwritemask=0, wmpack=0),
}


def count_coverage(verts, tris, subpixel, how="pass", mode="span", w=W, h=H):
    """Stencil INCR count of triangles given in float window coordinates."""
    fb = kernel_framebuffer(w, h, double=False, zbits=24, stencil=8)
    batch = kernel_batch(fb, mode)
    rs = full_state(w, h, subpixel=subpixel, **COUNT_STATES[how])
    v = np.asarray(verts, np.float64)
    batch.add_window_triangles(v[:, 0], v[:, 1], np.zeros(len(v)), None,
                               np.asarray(tris, np.int64), rs)
    batch.flush()
    return fb.stencil.astype(np.int64)


def expected_counts(snapped, tris, w=W, h=H):
    """Sum over triangles of the oracle's coverage (any orientation)."""
    total = np.zeros((h, w), np.int64)
    for t in tris:
        total += winding_numbers([snapped[i] for i in t], 0, w - 1, 0, h - 1) != 0
    return total


def check_tiling(verts, tris, boundary, subpixel, modes=MODES, hows=("pass", "zpass")):
    """Run every counting variant; return the count (for extra assertions)."""
    snapped = [snap_point(x, y, subpixel) for x, y in verts]
    per_tri = expected_counts(snapped, tris)
    oriented = all(area2(*(snapped[i] for i in t)) >= 0 for t in tris)
    region = winding_numbers([snapped[i] for i in boundary], 0, W - 1, 0, H - 1)
    if oriented:
        # The oracle itself: a positively oriented tiling covers its region once.
        np.testing.assert_array_equal(per_tri, region)
        assert set(np.unique(region)) <= {0, 1}
    count = None
    for how in hows:
        for mode in modes:
            count = count_coverage(verts, tris, subpixel, how, mode)
            np.testing.assert_array_equal(count, per_tri, err_msg=f"{how} {mode}")
            if oriented:
                np.testing.assert_array_equal(count, region, err_msg=f"{how} {mode}")
    return count, oriented


# ---------------------------------------------------------------------- fans


def fan(cx, cy, n, radius, phase=0.0, closed=True, jitter=None):
    ring = []
    for k in range(n):
        a = phase + 2 * math.pi * k / n
        if jitter is not None:
            a += jitter[k]
        ring.append((cx + radius * math.cos(a), cy + radius * math.sin(a)))
    verts = [(cx, cy)] + ring
    m = n if closed else n - 1
    tris = [(0, 1 + k, 1 + (k + 1) % n) for k in range(m)]
    boundary = list(range(1, n + 1)) if closed else [0] + list(range(1, n + 1))
    return verts, tris, boundary


@pytest.mark.parametrize("subpixel", [False, True])
@pytest.mark.parametrize("centre", [(20.0, 17.0), (20.5, 17.5), (20.37, 17.81),
                                    (19.999, 17.0 + 1 / 256)])
@pytest.mark.parametrize("n", [3, 5, 8, 16, 40])
def test_fan_around_shared_vertex(centre, n, subpixel):
    verts, tris, boundary = fan(*centre, n, 14.3, phase=0.1)
    count, oriented = check_tiling(verts, tris, boundary, subpixel)
    assert count.max() == 1
    # The shared vertex's own pixel is covered exactly once.
    x, y = (math.floor(c + 0.5) for c in centre)
    assert count[y, x] == 1


@pytest.mark.parametrize("subpixel", [False, True])
def test_fan_with_rim_on_pixel_centres(subpixel):
    # Rim vertices on pixel centres, axis-aligned and diagonal spokes: many pixel
    # centres lie exactly on shared edges and on the shared vertex.
    c = (24, 20)
    rim = [(34, 20), (34, 30), (24, 30), (14, 30), (14, 20), (14, 10), (24, 10), (34, 10)]
    verts = [c] + rim
    tris = [(0, 1 + k, 1 + (k + 1) % 8) for k in range(8)]
    count, oriented = check_tiling(verts, tris, list(range(1, 9)), subpixel)
    assert oriented
    # The square [14, 34) x [10, 30) under the tie rule: 20 x 20 pixels.
    expected = np.zeros((H, W), np.int64)
    expected[10:30, 14:34] = 1
    np.testing.assert_array_equal(count, expected)


@settings(max_examples=60, deadline=None)
@given(
    cx=st.floats(8, 40), cy=st.floats(8, 32), n=st.integers(3, 24),
    radius=st.floats(2, 30), phase=st.floats(0, 7), closed=st.booleans(),
    subpixel=st.booleans(), data=st.data(),
)
def test_random_fans(cx, cy, n, radius, phase, closed, subpixel, data):
    jitter = data.draw(st.lists(st.floats(-0.4, 0.4), min_size=n, max_size=n))
    jitter = [j * math.pi / n for j in jitter]  # keeps the rim angles increasing
    verts, tris, boundary = fan(cx, cy, n, radius, phase, closed, jitter)
    count, oriented = check_tiling(verts, tris, boundary, subpixel, modes=("span", "edge"))
    if oriented:
        assert count.max() <= 1


# ----------------------------------------------------------------------- grids


@pytest.mark.parametrize("subpixel", [False, True])
@pytest.mark.parametrize("origin, step", [((2.0, 3.0), (4.0, 3.0)), ((1.5, 0.5), (3.5, 2.5)),
                                          ((-3.3, -2.7), (5.1, 4.7)), ((0.0, 0.0), (1.0, 1.0))])
def test_grid_of_quads(origin, step, subpixel):
    rng = np.random.default_rng(3)
    nx = min(int((W + 6 - origin[0]) / step[0]), 40)
    ny = min(int((H + 6 - origin[1]) / step[1]), 40)
    verts = [(origin[0] + i * step[0], origin[1] + j * step[1])
             for j in range(ny + 1) for i in range(nx + 1)]

    def vid(i, j):
        return j * (nx + 1) + i

    tris = []
    for j in range(ny):
        for i in range(nx):
            a, b, c, d = vid(i, j), vid(i + 1, j), vid(i + 1, j + 1), vid(i, j + 1)
            if rng.random() < 0.5:
                tris += [(a, b, c), (a, c, d)]
            else:
                tris += [(a, b, d), (b, c, d)]
    # Half of the triangles drawn clockwise: the tie rule does not depend on winding.
    tris = [t if k % 2 else (t[0], t[2], t[1]) for k, t in enumerate(tris)]
    boundary = ([vid(i, 0) for i in range(nx)] + [vid(nx, j) for j in range(ny)]
                + [vid(i, ny) for i in range(nx, 0, -1)] + [vid(0, j) for j in range(ny, 0, -1)])
    snapped = [snap_point(x, y, subpixel) for x, y in verts]
    region = winding_numbers([snapped[i] for i in boundary], 0, W - 1, 0, H - 1)
    for how in ("pass", "zpass"):
        for mode in MODES:
            count = count_coverage(verts, tris, subpixel, how, mode)
            np.testing.assert_array_equal(count, region, err_msg=f"{how} {mode}")
    assert region.sum() > 0


def test_grid_with_jittered_vertices():
    rng = np.random.default_rng(11)
    nx, ny = 12, 10
    verts = []
    for j in range(ny + 1):
        for i in range(nx + 1):
            jx = rng.uniform(-1.2, 1.2) if 0 < i < nx else 0.0
            jy = rng.uniform(-1.2, 1.2) if 0 < j < ny else 0.0
            verts.append((1.0 + 3.7 * i + jx, 0.5 + 3.9 * j + jy))
    tris = []
    for j in range(ny):
        for i in range(nx):
            a, b = j * (nx + 1) + i, j * (nx + 1) + i + 1
            c, d = b + nx + 1, a + nx + 1
            tris += [(a, b, c), (a, c, d)] if (i + j) % 2 else [(a, b, d), (b, c, d)]
    boundary = ([i for i in range(nx)] + [j * (nx + 1) + nx for j in range(ny)]
                + [ny * (nx + 1) + i for i in range(nx, 0, -1)]
                + [j * (nx + 1) for j in range(ny, 0, -1)])
    for subpixel in (False, True):
        count, oriented = check_tiling(verts, tris, boundary, subpixel)
        if oriented:
            assert count.max() == 1


# --------------------------------------------------- random polygons, triangulated


def convex_hull(points):
    """Exact monotone chain on int points, counter-clockwise, no collinear points."""
    pts = sorted(set(points))
    if len(pts) < 3:
        return pts

    def half(seq):
        out = []
        for p in seq:
            while len(out) >= 2 and area2(out[-2], out[-1], p) <= 0:
                out.pop()
            out.append(p)
        return out

    lower = half(pts)
    upper = half(reversed(pts))
    return lower[:-1] + upper[:-1]


def ear_clip(poly):
    """Exact ear clipping of a simple counter-clockwise int polygon (index triples)."""
    idx = list(range(len(poly)))
    tris = []
    while len(idx) > 3:
        for k in range(len(idx)):
            a, b, c = idx[k - 1], idx[k], idx[(k + 1) % len(idx)]
            if area2(poly[a], poly[b], poly[c]) <= 0:
                continue
            inside = False
            for o in idx:
                if o in (a, b, c):
                    continue
                p = poly[o]
                if (area2(poly[a], poly[b], p) >= 0 and area2(poly[b], poly[c], p) >= 0
                        and area2(poly[c], poly[a], p) >= 0):
                    inside = True
                    break
            if not inside:
                tris.append((a, b, c))
                idx.pop(k)
                break
        else:
            raise AssertionError("no ear found: polygon not simple")
    tris.append(tuple(idx))
    return tris


def star_polygon(rng, subpixel):
    """Random star-shaped polygon, snapped, with its kernel point (all as floats that
    snap exactly to the int fixed-point values returned)."""
    while True:
        n = int(rng.integers(5, 30))
        angles = np.sort(rng.uniform(0, 2 * np.pi, n))
        radii = rng.uniform(3, 22, n)
        c = (rng.uniform(16, 32), rng.uniform(14, 26))
        pts = [(c[0] + r * math.cos(a), c[1] + r * math.sin(a))
               for a, r in zip(angles, radii, strict=True)]
        sp = [snap_point(x, y, subpixel) for x, y in pts]
        sc = snap_point(*c, subpixel)
        if all(area2(sc, sp[i], sp[(i + 1) % n]) > 0 for i in range(n)):
            return sp, sc


def fixed_to_window(p):
    return (p[0] / 256, p[1] / 256)


@pytest.mark.parametrize("subpixel", [False, True])
def test_star_polygons_fan_and_ear_triangulations(subpixel):
    rng = np.random.default_rng(5 + subpixel)
    for _ in range(12):
        sp, sc = star_polygon(rng, subpixel)
        n = len(sp)
        # Fan from the kernel point.
        verts = [fixed_to_window(p) for p in sp] + [fixed_to_window(sc)]
        tris = [(n, i, (i + 1) % n) for i in range(n)]
        count, oriented = check_tiling(verts, tris, list(range(n)), subpixel,
                                       modes=("span", "edge"))
        assert oriented and count.max() == 1
        # Ear clipping: the internal edges join polygon vertices.
        tris = ear_clip(sp)
        count, oriented = check_tiling(verts[:n], tris, list(range(n)), subpixel,
                                       modes=("span", "edge"))
        assert oriented and count.max() == 1


@pytest.mark.parametrize("subpixel", [False, True])
def test_random_convex_polygons(subpixel):
    rng = np.random.default_rng(17 + subpixel)
    for _ in range(15):
        pts = [snap_point(*rng.uniform([-3, -3], [W + 3, H + 3]), subpixel)
               for _ in range(int(rng.integers(3, 25)))]
        hull = convex_hull(pts)
        if len(hull) < 3:
            continue
        verts = [fixed_to_window(p) for p in hull]
        start = int(rng.integers(len(hull)))  # fan from an arbitrary hull vertex
        order = hull[start:] + hull[:start]
        verts = [fixed_to_window(p) for p in order]
        tris = [(0, i, i + 1) for i in range(1, len(order) - 1)]
        count, oriented = check_tiling(verts, tris, list(range(len(order))), subpixel,
                                       modes=("span", "edge"))
        assert oriented and count.max() <= 1


@pytest.mark.parametrize("subpixel", [False, True])
def test_delaunay_triangulations(subpixel):
    spatial = pytest.importorskip("scipy.spatial")
    rng = np.random.default_rng(23 + subpixel)
    checked = 0
    for _ in range(12):
        k = int(rng.integers(4, 60))
        pts = sorted({snap_point(*rng.uniform([-2, -2], [W + 2, H + 2]), subpixel)
                      for _ in range(k)})
        hull = convex_hull(pts)
        if len(hull) < 3:
            continue
        tri = spatial.Delaunay(np.array(pts, np.float64) / 256)
        tris = []
        for a, b, c in tri.simplices:
            a, b, c = int(a), int(b), int(c)
            s = area2(pts[a], pts[b], pts[c])
            if s == 0:
                continue
            tris.append((a, b, c) if s > 0 else (a, c, b))
        # Use only triangulations verified exactly: areas add up to the hull's.
        hull_area = sum(area2(hull[0], hull[i], hull[i + 1]) for i in range(1, len(hull) - 1))
        if sum(area2(*(pts[i] for i in t)) for t in tris) != hull_area:
            continue
        verts = [fixed_to_window(p) for p in pts]
        index = {p: i for i, p in enumerate(pts)}
        count, oriented = check_tiling(verts, tris, [index[p] for p in hull], subpixel,
                                       modes=("span", "edge"))
        assert oriented and count.max() <= 1
        checked += 1
    assert checked >= 8


# ------------------------------------------------ scanline == edge-function coverage


def setup_edges(tri_fixed):
    """Edge arrays of fixed-point triangles (N, 3, 2) from kernels.setup.

    Returns a dict {triangle index: (edge, box)} for the triangles setup keeps.
    """
    tri_fixed = np.asarray(tri_fixed, np.int64)
    n = tri_fixed.shape[0]
    xf = np.ascontiguousarray(tri_fixed[:, :, 0].reshape(-1))
    yf = np.ascontiguousarray(tri_fixed[:, :, 1].reshape(-1))
    zw = np.repeat(np.arange(n, dtype=np.float64), 3)  # t_z[k, 0] names the triangle
    tris = np.arange(3 * n, dtype=np.int64).reshape(n, 3)
    t_edge = np.zeros((n, 3, 3), np.int64)
    t_box = np.zeros((n, 4), np.int64)
    t_z = np.zeros((n, 5))
    t_zlim = np.zeros((n, 2), np.int64)
    t_col = np.zeros((n, 4, 3))
    t_state = np.zeros(n, np.int32)
    m = setup_triangles(xf, yf, zw, np.zeros((1, 4)), tris, np.zeros(n, np.int64),
                        np.zeros((1, 4)), 0, 0, True, False,
                        t_edge, t_box, t_z, t_zlim, t_col, t_state, 0)
    # Culled and pixel-less triangles keep their slot as a dead record (first row
    # beyond last row); only live records carry set-up data.
    return {int(t_z[k, 0]): (t_edge[k].copy(), t_box[k].copy()) for k in range(m)
            if t_box[k, 2] <= t_box[k, 3]}


def random_triangles(rng, n):
    """Fixed-point triangles of many kinds: small, large, slivers, degenerate,
    axis-aligned edges, vertices on pixel centres, far from the origin."""
    out = []
    for _ in range(n):
        kind = rng.integers(7)
        scale = float(rng.choice([4, 40, 400, 65536]))
        base = rng.uniform(-scale, scale, 2)
        if kind == 0:  # generic
            p = base + rng.uniform(-scale, scale, (3, 2))
        elif kind == 1:  # on pixel centres
            p = np.round(base + rng.uniform(-scale, scale, (3, 2)))
        elif kind == 2:  # sliver: third vertex close to the first edge
            a, b = base, base + rng.uniform(-scale, scale, 2)
            t = rng.uniform(0, 1)
            n_ = np.array([-(b - a)[1], (b - a)[0]])
            n_ /= max(np.linalg.norm(n_), 1e-9)
            p = np.array([a, b, a + t * (b - a) + n_ * rng.uniform(-0.01, 0.01)])
        elif kind == 3:  # degenerate: collinear or repeated vertices
            a, b = base, base + rng.uniform(-scale, scale, 2)
            p = np.array([a, b, a + rng.integers(-2, 3) * (b - a)])
        elif kind == 4:  # axis-aligned right triangle
            d = rng.uniform(-scale, scale, 2)
            p = np.array([base, base + [d[0], 0], base + [0, d[1]]])
        elif kind == 5:  # tiny, sub-pixel
            p = base + rng.uniform(-1.5, 1.5, (3, 2))
        else:  # horizontal / vertical edge on a pixel row
            y = np.round(base[1])
            p = np.array([[base[0], y], [base[0] + rng.uniform(-scale, scale), y],
                          base + rng.uniform(-scale, scale, 2)])
        p = np.clip(p, -65536, 65536)
        if rng.random() < 0.5:
            f = np.floor(p * 256 + 0.5)
        else:
            f = np.floor(p + 0.5) * 256
        out.append(f.astype(np.int64))
    return np.array(out)


def _window(rng, tri, box):
    """At most 64 x 64 pixels around a random part of the triangle's box."""
    x0, x1, y0, y1 = (int(v) for v in box)
    if x1 - x0 > 60:
        x0 = int(rng.integers(x0 - 4, x1 - 56))
        x1 = x0 + 63
    else:
        x0, x1 = x0 - 2, x1 + 2
    if y1 - y0 > 60:
        y0 = int(rng.integers(y0 - 4, y1 - 56))
        y1 = y0 + 63
    else:
        y0, y1 = y0 - 2, y1 + 2
    return x0, x1, y0, y1


def test_scanline_equals_edge_function_coverage():
    rng = np.random.default_rng(99)
    tri = random_triangles(rng, 4000)
    kept = setup_edges(tri)
    nonempty = degenerate = 0
    for i in range(tri.shape[0]):
        pts = [tuple(int(c) for c in v) for v in tri[i]]
        a = area2(*pts)
        if i not in kept:
            # Dropped by setup: zero area, or no pixel centre in the bounding box.
            xs = [v[0] for v in pts]
            ys = [v[1] for v in pts]
            no_centre = (-(-min(xs) // 256) > max(xs) // 256
                         or -(-min(ys) // 256) > max(ys) // 256)
            assert a == 0 or no_centre, pts
            degenerate += a == 0
            continue
        assert a != 0
        edge, box = kept[i]
        x0, x1, y0, y1 = _window(rng, tri[i], box)
        span = coverage_mask_scanline(edge, x0, x1, y0, y1)
        full = coverage_mask_edge(edge, x0, x1, y0, y1)
        np.testing.assert_array_equal(span, full, err_msg=str(pts))
        oracle = winding_numbers(pts, x0, x1, y0, y1) != 0
        np.testing.assert_array_equal(full, oracle, err_msg=str(pts))
        nonempty += bool(full.any())
    assert nonempty > 1500 and degenerate > 100
