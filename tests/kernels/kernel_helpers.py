"""Test-only helpers shared by tests/kernels: run naive-style command lists through
the Numba pipeline, and an exact, independent coverage oracle.

The command format is the one of :func:`vgxsim.reference.naive.render`, so one list
feeds both the oracle and the kernels:

* ``("triangle", verts, state)`` -> ``CommandBatch.add_window_triangles``;
* ``("line", verts, state[, pattern_start])`` -> ``kernels.lines.line_fragments``
  then ``CommandBatch.add_fragments``;
* ``("point", vert, state)`` -> ``kernels.lines.point_fragments`` then
  ``add_fragments``;
* ``("clear", planes, values, state)`` -> ``CommandBatch.add_clear``;
* ``("flush",)`` (kernels only, ignored by :func:`naive_commands`) flushes the batch.
"""

from __future__ import annotations

import math

import numpy as np

from vgxsim.batch import CLEAR_COLOUR, CLEAR_STENCIL, CLEAR_Z, CommandBatch
from vgxsim.geometry.pipeline import NO_BACKUP
from vgxsim.kernels.clip import snap_window
from vgxsim.kernels.lines import count_line_fragments, line_fragments, point_fragments
from vgxsim.reference import naive
from vgxsim.state.planes import Framebuffer, PlaneConfig
from vgxsim.state.raster import FLAT, RasterState

ONE = 256
PLANE_BITS = {"color": CLEAR_COLOUR, "z": CLEAR_Z, "stencil": CLEAR_STENCIL}


def full_state(w, h, **kw):
    """RasterState whose raster rectangle is the whole ``w`` x ``h`` window."""
    kw.setdefault("scissor", (0, w - 1, 0, h - 1))
    return RasterState(**kw)


# ------------------------------------------------------------------ framebuffers


def random_planes(rng, w, h, *, double, zbits, stencil):
    """Random initial plane contents (a dict of arrays, None for absent planes)."""
    smax = (1 << stencil) - 1
    return {
        "front": rng.integers(0, 1 << 32, size=(h, w), dtype=np.uint64).astype(np.uint32),
        "back": (rng.integers(0, 1 << 32, size=(h, w), dtype=np.uint64).astype(np.uint32)
                 if double else None),
        "z": (rng.integers(naive.GD_ZMIN, naive.GD_ZMAX + 1, size=(h, w)).astype(np.int32)
              if zbits else None),
        "stencil": (rng.integers(0, smax + 1, size=(h, w)).astype(np.uint8)
                    if stencil else None),
    }


def kernel_framebuffer(w, h, *, double, zbits, stencil, init=None):
    fb = Framebuffer(PlaneConfig(w, h, double=double, zbits=zbits, stencil=stencil))
    if init is not None:
        _load(fb, init)
    return fb


def naive_framebuffer(w, h, *, double, zbits, stencil, init=None):
    fb = naive.NaiveFramebuffer(w, h, stencil_planes=stencil, zbits=zbits, double=double)
    if init is not None:
        _load(fb, init)
    return fb


def _load(fb, init):
    for name in ("front", "back", "z", "stencil"):
        src = init.get(name)
        dst = getattr(fb, name)
        assert (src is None) == (dst is None), name
        if src is not None:
            dst[...] = src


def planes_of(fb):
    """Copies of the colour, z and stencil planes (None for absent planes)."""
    return {name: (None if getattr(fb, name) is None else getattr(fb, name).copy())
            for name in ("front", "back", "z", "stencil")}


def assert_planes_equal(got, want, context=""):
    for name in ("front", "back", "z", "stencil"):
        g, w = got[name], want[name]
        assert (g is None) == (w is None), f"{context}: plane {name} presence"
        if g is None:
            continue
        if not np.array_equal(g, w):
            ys, xs = np.nonzero(g != w)
            bad = [(int(x), int(y), int(g[y, x]), int(w[y, x]))
                   for x, y in zip(xs[:8], ys[:8], strict=True)]
            raise AssertionError(
                f"{context}: plane {name} differs at {len(xs)} pixels; "
                f"(x, y, kernel, expected) = {bad}")


# ------------------------------------------------------------------ kernel runner


def line_to_fragments(verts, rs, pattern_start=0):
    """Fragments of one naive-style line command, via kernels.lines."""
    (xa, ya, za, ca), (xb, yb, zb, cb) = verts
    xf, yf = snap_window(np.array([xa, xb], np.float64), np.array([ya, yb], np.float64),
                         rs.subpixel)
    seg_xf = xf.reshape(1, 2)
    seg_yf = yf.reshape(1, 2)
    seg_z = np.array([[za, zb]], np.float64)
    ca = np.asarray(ca, np.float64) * 255.0
    cb = np.asarray(cb, np.float64) * 255.0
    if rs.shademodel == FLAT:
        ca = cb
    seg_c = np.stack([ca, cb])[None, :, :].copy()
    closed = not rs.subpixel
    total = count_line_fragments(seg_xf, seg_yf, closed, rs.linewidth)
    out_xy = np.empty((total, 2), np.int64)
    out_z = np.empty(total, np.int64)
    out_c = np.empty(total, np.int64)
    nf = line_fragments(seg_xf, seg_yf, seg_z, seg_c, np.array([pattern_start], np.int64),
                        closed, rs.linewidth, rs.linestyle, rs.lsrepeat, NO_BACKUP,
                        out_xy, out_z, out_c, 0)
    return out_xy[:nf], out_z[:nf], out_c[:nf]


def point_to_fragments(vert, rs):
    """Fragments of one naive-style point command, via kernels.lines."""
    xw, yw, zw, rgba = vert
    xf, yf = snap_window(np.array([xw], np.float64), np.array([yw], np.float64), rs.subpixel)
    size = rs.pntsize
    out_xy = np.empty((size * size, 2), np.int64)
    out_z = np.empty(size * size, np.int64)
    out_c = np.empty(size * size, np.int64)
    c = np.asarray(rgba, np.float64).reshape(1, 4) * 255.0
    nf = point_fragments(xf, yf, np.array([zw], np.float64), c, size, out_xy, out_z, out_c, 0)
    return out_xy[:nf], out_z[:nf], out_c[:nf]


def _queue_triangles(batch, group, rs):
    """One add_window_triangles call for consecutive triangles sharing ``rs``."""
    verts = [v for tri in group for v in tri]
    xw = np.array([v[0] for v in verts], np.float64)
    yw = np.array([v[1] for v in verts], np.float64)
    zw = np.array([v[2] for v in verts], np.float64)
    col = np.array([v[3] for v in verts], np.float64).reshape(-1, 4)
    tris = np.arange(len(verts), dtype=np.int64).reshape(-1, 3)
    flat_col = col[tris[:, 2]].copy()  # flat shading: each triangle's last vertex
    if rs.texture and len(verts[0]) > 4:  # textured: (s/w, t/w, 1/w) per vertex
        tex = np.array([v[4] for v in verts], np.float64).reshape(-1, 3)
        batch.add_window_triangles(xw, yw, zw, col, tris, rs, flat_col=flat_col, tex=tex)
        return
    batch.add_window_triangles(xw, yw, zw, col, tris, rs, flat_col=flat_col)


def queue_commands(batch, commands, group_triangles=True):
    """Queue naive-style commands on a CommandBatch (does not flush at the end)."""
    pending, pending_rs = [], None

    def drain():
        nonlocal pending, pending_rs
        if pending:
            _queue_triangles(batch, pending, pending_rs)
        pending, pending_rs = [], None

    for cmd in commands:
        kind = cmd[0]
        if kind == "triangle":
            _, verts, rs = cmd
            if pending and (rs is not pending_rs or not group_triangles):
                drain()
            pending.append(verts)
            pending_rs = rs
            continue
        drain()
        if kind == "line":
            verts, rs = cmd[1], cmd[2]
            start = cmd[3] if len(cmd) > 3 else 0
            batch.add_fragments(*line_to_fragments(verts, rs, start), rs)
        elif kind == "point":
            _, vert, rs = cmd
            batch.add_fragments(*point_to_fragments(vert, rs), rs)
        elif kind == "clear":
            _, planes, values, rs = cmd
            bits = 0
            for p in planes:
                bits |= PLANE_BITS[p]
            batch.add_clear(bits, values.get("color", 0), values.get("z", 0),
                            values.get("stencil", 0), rs)
        elif kind == "flush":
            batch.flush()
        else:
            raise ValueError(kind)
    drain()


def kernel_batch(fb, mode="span"):
    """A CommandBatch on ``fb`` taking one rasterizer path: ``mode`` is 'span' (the
    default paths), 'general' (``general_only``) or 'edge' (``edge_mode``)."""
    batch = CommandBatch(fb)
    batch.general_only = mode == "general"
    batch.edge_mode = mode == "edge"
    return batch


def render_kernels(commands, w, h, *, double, zbits, stencil, init=None, mode="span",
                   group_triangles=True):
    """Render through CommandBatch; ``mode`` is 'span', 'general' or 'edge'."""
    fb = kernel_framebuffer(w, h, double=double, zbits=zbits, stencil=stencil, init=init)
    batch = kernel_batch(fb, mode)
    queue_commands(batch, commands, group_triangles=group_triangles)
    batch.flush()
    return planes_of(fb)


def naive_commands(commands):
    return [c for c in commands if c[0] != "flush"]


def render_naive(commands, w, h, *, double, zbits, stencil, init=None):
    fb = naive_framebuffer(w, h, double=double, zbits=zbits, stencil=stencil, init=init)
    naive.render(fb, naive_commands(commands))
    return planes_of(fb)


# ------------------------------------------------------- exact coverage oracle


def winding_numbers(poly, x0, x1, y0, y1):
    """Winding number of a closed fixed-point polygon around every pixel centre.

    The tie rule of docs/numeric_model.md section 3 (inclusive left and bottom edges
    of a counter-clockwise triangle) is the same as moving the sample point by the
    infinitesimal offset ``(eps, eps**2)``: for an edge function
    ``E = dx*(Y - yi) - dy*(X - xi)`` the offset adds ``dx*eps**2 - dy*eps``, which is
    positive exactly for the inclusive edges.  The moved point lies on no edge and
    on no vertex's horizontal line, so its winding number is unambiguous; it is
    computed here by the crossing rule with exact int64 arithmetic, which shares no
    code or formulation with the kernels' edge equations.

    Parameters
    ----------
    poly : sequence of (int, int)
        Vertices ``(xf, yf)`` in units of 1/256 pixel (any orientation; the result
        is positive inside a counter-clockwise polygon).
    x0, x1, y0, y1 : int
        Inclusive pixel window.

    Returns
    -------
    ndarray, shape (y1 - y0 + 1, x1 - x0 + 1), int64
    """
    X = np.arange(x0, x1 + 1, dtype=np.int64) * ONE
    Y = np.arange(y0, y1 + 1, dtype=np.int64) * ONE
    Xc, Yc = np.meshgrid(X, Y)
    wn = np.zeros(Xc.shape, np.int64)
    n = len(poly)
    for i in range(n):
        xi, yi = (int(c) for c in poly[i])
        xj, yj = (int(c) for c in poly[(i + 1) % n])
        if yi == yj:
            continue  # a horizontal edge never crosses the line y = Y + eps**2
        # The moved point's y is Y + eps**2: a vertex is below it iff yv <= Y.
        below_i = yi <= Yc
        below_j = yj <= Yc
        crosses = below_i != below_j
        # Crossing x at y = Y is right of X (strictly; at equality the crossing is
        # left of X + eps) iff (xi - X)*(yj - yi) + (Y - yi)*(xj - xi) has the sign
        # of (yj - yi).
        num = (xi - Xc) * (yj - yi) + (Yc - yi) * (xj - xi)
        right = num > 0 if yj > yi else num < 0
        hit = crosses & right
        wn += np.where(hit, 1 if yj > yi else -1, 0)
    return wn


def area2(p0, p1, p2):
    (x0, y0), (x1, y1), (x2, y2) = p0, p1, p2
    return (x1 - x0) * (y2 - y0) - (x2 - x0) * (y1 - y0)


def snap_point(x, y, subpixel):
    """Model section 2 snapping in Python (independent of the kernels)."""
    if subpixel:
        return math.floor(x * ONE + 0.5), math.floor(y * ONE + 0.5)
    return math.floor(x + 0.5) * ONE, math.floor(y + 0.5) * ONE


# ------------------------------------------------------ float64 clipping reference


def guard(viewport):
    """Guard band half-extents in NDC: 16384 pixels from the viewport centre."""
    l, r, b, t = viewport
    return max(1.0, 16384.0 / ((r - l + 1) / 2)), max(1.0, 16384.0 / ((t - b + 1) / 2))


def clip_planes(gx, gy):
    """Signed distances of a homogeneous vertex to the six clip planes (near, far,
    then the x and y guard band ``gx``, ``gy``): inside where all are >= 0."""
    return [
        lambda v: v[3] + v[2], lambda v: v[3] - v[2],
        lambda v: gx * v[3] - v[0], lambda v: gx * v[3] + v[0],
        lambda v: gy * v[3] - v[1], lambda v: gy * v[3] + v[1],
    ]


def clip_polygon(poly, gx, gy):
    """Sutherland-Hodgman in homogeneous coordinates, float64.

    Each intersection is interpolated from the edge's inside endpoint, so the
    parameter is small and exact enough even when the outside endpoint is enormous
    (1e300): interpolating from the far end would cancel catastrophically.
    """
    with np.errstate(over="ignore", invalid="ignore"):
        return _sutherland_hodgman(poly, clip_planes(gx, gy))


def _sutherland_hodgman(poly, planes):
    for dist in planes:
        out = []
        n = len(poly)
        for i in range(n):
            p, q = poly[i], poly[(i + 1) % n]
            dp, dq = dist(p), dist(q)
            if dp >= 0:
                out.append(p)
            if (dp >= 0) != (dq >= 0):
                a, b, da, db = (p, q, dp, dq) if dp >= 0 else (q, p, dq, dp)
                t = da / (da - db)
                out.append(a + t * (b - a))
        poly = out
        if len(poly) < 3:
            return []
    return poly


def clip_reference(clip_tri, viewport, w, h):
    """Pixel-centre coverage of a clip-space triangle by exact float64 geometry.

    Returns
    -------
    inside : ndarray, shape (h, w), bool
        Pixel centres inside the projected clipped polygon (crossing rule).
    dist : ndarray, shape (h, w), float64
        Distance of each centre to the polygon's boundary (inf when nothing
        survives clipping).
    poly : list
        The projected polygon (window coordinates).
    """
    gx, gy = guard(viewport)
    poly = clip_polygon([np.asarray(v, np.float64) for v in clip_tri], gx, gy)
    inside = np.zeros((h, w), bool)
    dist = np.full((h, w), np.inf)
    if len(poly) < 3 or any(not v[3] > 0 for v in poly):
        return inside, dist, poly
    l, r, b, t = viewport
    pts = [((l - 0.5) + (v[0] / v[3] + 1) * (r - l + 1) / 2,
            (b - 0.5) + (v[1] / v[3] + 1) * (t - b + 1) / 2) for v in poly]
    n = len(pts)
    X, Y = np.meshgrid(np.arange(w, dtype=np.float64), np.arange(h, dtype=np.float64))
    # Crossing-number inside test and distance to the edge segments: both stay
    # meaningful when clipping leaves two nearly coincident vertices (a tiny edge
    # whose direction is rounding noise).
    odd = np.zeros((h, w), bool)
    for i in range(n):
        (ax, ay), (bx, by) = pts[i], pts[(i + 1) % n]
        ex, ey = bx - ax, by - ay
        length2 = ex * ex + ey * ey
        if length2 > 0:
            u = np.clip(((X - ax) * ex + (Y - ay) * ey) / length2, 0.0, 1.0)
            dist = np.minimum(dist, np.hypot(X - (ax + u * ex), Y - (ay + u * ey)))
        else:
            dist = np.minimum(dist, np.hypot(X - ax, Y - ay))
        if ey != 0:
            straddle = (ay > Y) != (by > Y)
            odd ^= straddle & (X < ax + (Y - ay) * ex / ey)
    return odd, dist, pts


# ------------------------------------------------------------------ switch checks


def band_states(w, h, cull, ops, funcs, blend):
    """The states of :func:`band_scene`: z only, z LESS with colour writes off, z +
    stencil INCR/DECR, a stencil test with ONE+ONE blending, back-face culling and a
    scissor (``cull``, ``ops``, ``funcs`` and ``blend``: the raster codes used)."""
    incr, decr = ops
    less, notequal = funcs
    return [
        full_state(w, h, zbuffer=True),
        full_state(w, h, zbuffer=True, zfunc=less, wmpack=0),
        full_state(w, h, zbuffer=True, zwritemask=0, wmpack=0, stencil=True,
                   szpass=incr, spass=decr),
        full_state(w, h, zbuffer=True, stencil=True, sfunc=notequal, sref=1,
                   blend_sf=blend, blend_df=blend),
        full_state(w, h, zbuffer=True, cull=cull),
        full_state(w, h, zbuffer=True, scissor=(10, 70, 40, 250)),
    ]


def band_scene(rng, n, w, h, states, *, switch_below, point_above, line_above,
               wide_below, dead_below, wide, small):
    """A flush of mostly small triangles for the band-layout tests: ``n`` primitives,
    each drawn by one uniform ``u``: the state switches among ``states`` where
    ``u < switch_below``; a point where ``u > point_above``, else a line where
    ``u > line_above``; else a triangle of half-size ``wide`` (crossing bands) where
    ``u < wide_below``, zero-size where ``u < dead_below``, else of half-size
    uniform in [1, ``small``).  A stencil clear half way."""
    cmds = [("clear", {"color", "z", "stencil"},
             {"color": 0x40302010, "z": 0x7FFFFF, "stencil": 1}, full_state(w, h))]
    rs = states[0]
    for k in range(n):
        u = rng.random()
        if u < switch_below:
            rs = states[int(rng.integers(len(states)))]
        if k == n // 2:
            cmds.append(("clear", {"stencil"}, {"stencil": 2}, full_state(w, h)))
        if u > point_above:
            x, y = (float(v) for v in rng.uniform([0, 0], [w, h]))
            cmds.append(("point", (x, y, 0.0, (1.0, 0.5, 0.0, 1.0)), rs))
            continue
        if u > line_above:
            a = tuple(float(v) for v in rng.uniform([0, 0], [w, h]))
            b = tuple(float(v) for v in rng.uniform([0, 0], [w, h]))
            cmds.append(("line", [(a[0], a[1], 0.0, (0.0, 1.0, 0.0, 1.0)),
                                  (b[0], b[1], 0.0, (0.0, 1.0, 0.0, 1.0))], rs))
            continue
        side = wide if u < wide_below else (0.0 if u < dead_below else
                                            float(rng.uniform(1.0, small)))
        c = rng.uniform([0, 0], [w, h])
        z = float(rng.uniform(-4000, 4000))
        tri = tuple((float(x), float(y), z + float(rng.uniform(-500, 500)),
                     tuple(float(v) for v in rng.uniform(0, 1, 4)))
                    for x, y in c + rng.uniform(-side, side, (3, 2)))
        cmds.append(("triangle", tri, rs))
    return cmds


def render_switched(commands, w, h, *, cfg=None, init=None, nthreads=1, mode="span",
                    **switches):
    """Render ``commands`` through one CommandBatch on ``nthreads`` threads with the
    batch's switches set as given (``tall_bands=False``, ...): ``(planes, work)``,
    the planes of :func:`planes_of` and the batch's work counters.  ``cfg``: the
    framebuffer's double/zbits/stencil (default double buffered, 24-bit z, 8-bit
    stencil); ``mode`` as in :func:`kernel_batch`."""
    from vgxsim import threads

    keep = threads._override  # None: follow numba.set_num_threads
    threads.set_threads(nthreads)
    try:
        fb = kernel_framebuffer(w, h, init=init,
                                **(cfg or dict(double=True, zbits=24, stencil=8)))
        batch = kernel_batch(fb, mode)
        for name, value in switches.items():
            setattr(batch, name, value)
        queue_commands(batch, commands)
        batch.flush()
        return planes_of(fb), batch.work()
    finally:
        threads.set_threads(keep)


def heidmann_images(monkeypatch, switch, nthreads, width=640, height=512):
    """The Heidmann 1991 example's frame (vgxsim.examples.heidmann1991) rendered with
    ``CommandBatch.<switch>`` off and on under ``nthreads`` threads: ``{False: img,
    True: img}``, each an (H, W, 4) uint8 array."""
    from vgxsim import threads
    from vgxsim.examples import heidmann1991 as h91
    from vgxsim.gl._core import session

    images = {}
    for on in (False, True):
        monkeypatch.setattr(CommandBatch, switch, on)
        keep = threads._override
        threads.set_threads(nthreads)
        session.reset()
        try:
            images[on] = h91.render(width, height)
        finally:
            session.reset()
            threads.set_threads(keep)
    return images
