"""Exact float64 ray casting over a BVH: the shadow oracle's kernels.

Ray/triangle test (watertight, Woop, Benthin and Wald 2013, "Watertight
Ray/Triangle Intersection", JCGT 2(1)): the ray is mapped to a space where it runs
along +z from the origin (translate by the origin, permute so the largest direction
component is z, shear x and y), and each vertex gets 2-D coordinates ``(X, Y)`` in
that space.  The three 2-D edge functions are then

    U = Cx*By - Cy*Bx  (edge B->C),  V = Ax*Cy - Ay*Cx  (C->A),  W = Bx*Ay - By*Ax  (A->B),

and the ray meets the triangle iff they have one sign.  A shared edge gives the two
triangles edge functions that are exact negatives of each other (the vertex
coordinates are the same floats and ``a*b - c*d`` is antisymmetric under the swap),
so no ray passes between them.

Tie rule (a ray exactly on an edge or through a vertex): an edge function that is
exactly 0 takes the sign it would have if the ray were shifted by
``(epsilon, epsilon**2)`` in the sheared x, y plane -- the sign of
``Qy*Pw - Py*Qw``, or if that is 0 the sign of ``Px*Qw - Qx*Pw``, for the edge
P->Q.  This is a symbolic perturbation of the ray (the same one for every triangle
the ray is tested against), so a ray through a shared edge or vertex of a surface
crosses it exactly once, and a ray through a fold (a silhouette edge seen along the
ray) crosses it 0 or 2 times, never once: counts of crossings stay exact.  It is the
rasterizer's rule (docs/numeric_model.md section 3: inclusive bottom and left
edges) transplanted to ray space.  A triangle whose projection has no area (the ray
lies in its plane, or the triangle is degenerate) is never hit.

Homogeneous vertices: ``w`` is exactly 1 (a point) or 0 (a point at infinity in the
direction ``(x, y, z)``, as infinite shadow-volume extrusions).  Translation by the
origin moves only points (``P - o*w``); the edge functions and the tie rule hold for
both, and the hit parameter is ``t = (U*Az + V*Bz + W*Cz) / (U*Aw + V*Bw + W*Cw)``
(a zero denominator is a hit at infinity: none).

All ray parameter intervals are closed: ``t0 <= t <= t1``.
"""

from __future__ import annotations

from collections import namedtuple

import numpy as np

from .bvh import COUNT, FIRST, HI, LO, STACK_SIZE
from .options import inline, inline_ir, jit


@inline
def _ray_space(dx, dy, dz):
    """Axis permutation and shear taking the direction to +z (Woop et al. 2013)."""
    ax, ay, az = abs(dx), abs(dy), abs(dz)
    kz = 0
    if ay > ax and ay >= az:
        kz = 1
    elif az > ax and az > ay:
        kz = 2
    kx = (kz + 1) % 3
    ky = (kz + 2) % 3
    dkz = dz if kz == 2 else (dy if kz == 1 else dx)
    if dkz < 0.0:  # keep the handedness, so the sign of U, V, W is the facing
        kx, ky = ky, kx
    dkx = dz if kx == 2 else (dy if kx == 1 else dx)
    dky = dz if ky == 2 else (dy if ky == 1 else dx)
    return kx, ky, kz, dkx / dkz, dky / dkz, 1.0 / dkz


@inline
def _edge_sign(e, px, py, pw, qx, qy, qw):
    """Sign of edge function ``e`` of the edge P->Q, ties by the perturbation rule."""
    if e > 0.0:
        return 1
    if e < 0.0:
        return -1
    g = qy * pw - py * qw
    if g > 0.0:
        return 1
    if g < 0.0:
        return -1
    h = px * qw - qx * pw
    if h > 0.0:
        return 1
    if h < 0.0:
        return -1
    return 0


@inline_ir
def _vertex(tris, k, j, kx, ky, kz, okx, oky, okz, sx, sy, sz):
    w = tris[k, j, 3]
    x = tris[k, j, kx] - okx * w
    y = tris[k, j, ky] - oky * w
    z = tris[k, j, kz] - okz * w
    return x - sx * z, y - sy * z, sz * z, w


@inline_ir
def _hit(tris, k, kx, ky, kz, okx, oky, okz, sx, sy, sz):
    """(hit, t, side) of the ray with triangle ``k``; side +1/-1 is its facing."""
    ax, ay, az, aw = _vertex(tris, k, 0, kx, ky, kz, okx, oky, okz, sx, sy, sz)
    bx, by, bz, bw = _vertex(tris, k, 1, kx, ky, kz, okx, oky, okz, sx, sy, sz)
    cx, cy, cz, cw = _vertex(tris, k, 2, kx, ky, kz, okx, oky, okz, sx, sy, sz)
    u = cx * by - cy * bx
    v = ax * cy - ay * cx
    if (u < 0.0 and v > 0.0) or (u > 0.0 and v < 0.0):
        return False, 0.0, 0  # the common miss, decided before W
    w = bx * ay - by * ax
    if u > 0.0 and v > 0.0 and w > 0.0:
        su = 1
    elif u < 0.0 and v < 0.0 and w < 0.0:
        su = -1
    elif u != 0.0 and v != 0.0 and w != 0.0:
        return False, 0.0, 0
    else:  # some edge function is exactly 0: the tie rule decides
        su = _edge_sign(u, bx, by, bw, cx, cy, cw)
        sv = _edge_sign(v, cx, cy, cw, ax, ay, aw)
        sw = _edge_sign(w, ax, ay, aw, bx, by, bw)
        if su == 0 or su != sv or su != sw:
            return False, 0.0, 0
    den = u * aw + v * bw + w * cw
    if den == 0.0:
        return False, 0.0, 0
    return True, (u * az + v * bz + w * cz) / den, su


#: Eye rays through pixel centres tested in window space, as the rasterizer does
#: (docs/numeric_model.md section 3), for the triangles it draws (clipped, snapped).
#: ``width``: the image width (ray r is pixel ``(r % width, r // width)``), 0 for
#: none; ``fx, fy``: (T, 3) int64 fixed-point window coordinates (1/256 px) by caller
#: index; ``exact``: (T,) bool, which triangles are tested so (others in 3-D).
Window = namedtuple("Window", ["width", "fx", "fy", "exact"])


@inline
def _edge_covers(xi, yi, xj, yj, px, py):
    """Rasterizer edge test: E > 0, or E == 0 on an inclusive (left/bottom) edge."""
    e = (xj - xi) * (py - yi) - (yj - yi) * (px - xi)
    if e > 0:
        return True
    if e < 0:
        return False
    return (yj - yi) < 0 or ((yj == yi) and (xj > xi))


@inline
def _window_covers(win, idx, r):
    """The rasterizer's coverage of pixel r by triangle idx (exact integers)."""
    px = (r % win.width) * 256
    py = (r // win.width) * 256
    x0, y0 = win.fx[idx, 0], win.fy[idx, 0]
    x1, y1 = win.fx[idx, 1], win.fy[idx, 1]
    x2, y2 = win.fx[idx, 2], win.fy[idx, 2]
    area2 = (x1 - x0) * (y2 - y0) - (x2 - x0) * (y1 - y0)
    if area2 == 0:
        return False
    if area2 < 0:
        x1, y1, x2, y2 = x2, y2, x1, y1
    return (_edge_covers(x0, y0, x1, y1, px, py) and _edge_covers(x1, y1, x2, y2, px, py)
            and _edge_covers(x2, y2, x0, y0, px, py))


@inline
def _plane_t(tris, k, kx, ky, kz, okx, oky, okz, sx, sy, sz):
    """(ok, t) where the ray meets triangle k's plane (ok False if parallel)."""
    ax, ay, az, aw = _vertex(tris, k, 0, kx, ky, kz, okx, oky, okz, sx, sy, sz)
    bx, by, bz, bw = _vertex(tris, k, 1, kx, ky, kz, okx, oky, okz, sx, sy, sz)
    cx, cy, cz, cw = _vertex(tris, k, 2, kx, ky, kz, okx, oky, okz, sx, sy, sz)
    u = cx * by - cy * bx
    v = ax * cy - ay * cx
    w = bx * ay - by * ax
    den = u * aw + v * bw + w * cw
    if den == 0.0:
        return False, 0.0
    return True, (u * az + v * bz + w * cz) / den


@inline
def _test(tris, k, idx, win, r, kx, ky, kz, okx, oky, okz, sx, sy, sz):
    """(hit, t): window-space coverage when ``win`` covers triangle idx, else 3-D."""
    if win.width > 0 and win.exact[idx]:
        if not _window_covers(win, idx, r):
            return False, 0.0
        return _plane_t(tris, k, kx, ky, kz, okx, oky, okz, sx, sy, sz)
    hit, t, _ = _hit(tris, k, kx, ky, kz, okx, oky, okz, sx, sy, sz)
    return hit, t


@inline_ir
def _box(nodes, node, ox, oy, oz, dx, dy, dz, ix, iy, iz, t0, t1):
    """(hit, t_enter): the ray meets the node's box within [t0, t1] (conservative).

    Each slab's interval is widened by a relative 1e-15 (more than the rounding of
    ``(lo - o) * (1/d)``) and a zero direction component is a containment test, so
    the test never culls a ray that meets the box; infinite bounds are fine.  The
    general case, for rays with a zero component; :func:`_box_signed` is the same
    test for the others.
    """
    tn = -np.inf
    tf = np.inf
    for c in range(3):
        if c == 0:
            o, d, inv = ox, dx, ix
        elif c == 1:
            o, d, inv = oy, dy, iy
        else:
            o, d, inv = oz, dz, iz
        lo = nodes[node, LO + c]
        hi = nodes[node, HI + c]
        if d == 0.0:
            if o < lo or o > hi:
                return False, tn
            continue
        a = (lo - o) * inv
        b = (hi - o) * inv
        if a > b:
            a, b = b, a
        if a > tn:
            tn = a
        if b < tf:
            tf = b
    # widening the max of the entries equals the max of the widened entries
    # (x - |x| c is increasing), so once per box is enough
    tn -= abs(tn) * 1e-15
    tf += abs(tf) * 1e-15
    if t0 > tn:
        tn = t0
    if t1 < tf:
        tf = t1
    return tn <= tf, tn


@inline_ir
def _box_signed(nodes, node, ox, oy, oz, ix, iy, iz, nx, ny, nz, t0, t1):
    """:func:`_box` for a ray with every direction component non-zero and finite
    inverses: the entry plane of each slab is chosen once per ray by the sign of the
    component (column ``nx`` is ``lo x`` for dx > 0, ``hi x`` for dx < 0; the exit
    plane is the other), which gives the same ``a, b`` as _box's swap, so the same
    answer, without its branches (Williams et al. 2005, "An efficient and robust
    ray-box intersection algorithm")."""
    tn = (nodes[node, nx] - ox) * ix
    a = (nodes[node, ny] - oy) * iy
    if a > tn:
        tn = a
    a = (nodes[node, nz] - oz) * iz
    if a > tn:
        tn = a
    tf = (nodes[node, 3 - nx] - ox) * ix
    a = (nodes[node, 5 - ny] - oy) * iy
    if a < tf:
        tf = a
    a = (nodes[node, 7 - nz] - oz) * iz
    if a < tf:
        tf = a
    tn -= abs(tn) * 1e-15
    tf += abs(tf) * 1e-15
    if t0 > tn:
        tn = t0
    if t1 < tf:
        tf = t1
    return tn <= tf, tn


@inline
def _ray_boxes(dx, dy, dz):
    """Per-ray constants of the box tests: inverses, entry columns, and whether the
    signed test applies (every component non-zero with a finite inverse)."""
    ix = 1.0 / dx if dx != 0.0 else 0.0
    iy = 1.0 / dy if dy != 0.0 else 0.0
    iz = 1.0 / dz if dz != 0.0 else 0.0
    signed = (dx != 0.0 and dy != 0.0 and dz != 0.0 and np.isfinite(ix) and np.isfinite(iy)
              and np.isfinite(iz))
    nx = LO if dx > 0.0 else HI
    ny = LO + 1 if dy > 0.0 else HI + 1
    nz = LO + 2 if dz > 0.0 else HI + 2
    return ix, iy, iz, nx, ny, nz, signed


@inline_ir
def _either_box(nodes, node, signed, ox, oy, oz, dx, dy, dz, ix, iy, iz, nx, ny, nz, t0, t1):
    if signed:
        return _box_signed(nodes, node, ox, oy, oz, ix, iy, iz, nx, ny, nz, t0, t1)
    return _box(nodes, node, ox, oy, oz, dx, dy, dz, ix, iy, iz, t0, t1)


@inline_ir
def _closest(bvh, win, r, stack, stack_t, ox, oy, oz, dx, dy, dz, t0, t1):
    """Nearest hit with t0 <= t <= t1: (caller's triangle index or -1, t).

    Ties in t go to the lowest caller index, whatever the tree's order.  The
    traversal descends into the nearer child and leaves the other on the stack with
    its entry parameter; a node is dropped when a hit found since is nearer."""
    best = -1
    bt = t1
    nodes, tris, index = bvh.nodes, bvh.tris, bvh.index
    if nodes.shape[0] == 0:
        return best, np.inf
    kx, ky, kz, sx, sy, sz = _ray_space(dx, dy, dz)
    okx = oz if kx == 2 else (oy if kx == 1 else ox)
    oky = oz if ky == 2 else (oy if ky == 1 else ox)
    okz = oz if kz == 2 else (oy if kz == 1 else ox)
    ix, iy, iz, nx, ny, nz, signed = _ray_boxes(dx, dy, dz)
    # the root's box is not tested, only its children's (a ray missing it misses
    # them): two inlined box tests per traversal instead of three
    windowed = win.width > 0
    node = 0
    sp = 0
    while node >= 0:
        cnt = int(nodes[node, COUNT])
        first = int(nodes[node, FIRST])
        if cnt > 0:
            for k in range(first, first + cnt):
                idx = index[k]
                if windowed:
                    hit, t = _test(tris, k, idx, win, r, kx, ky, kz, okx, oky, okz, sx, sy, sz)
                else:
                    hit, t, _ = _hit(tris, k, kx, ky, kz, okx, oky, okz, sx, sy, sz)
                if hit and t >= t0 and t <= bt:
                    if t < bt or best < 0 or idx < best:
                        bt = t
                        best = idx
            node = -1
        else:
            hl, tl = _either_box(nodes, first, signed, ox, oy, oz, dx, dy, dz, ix, iy, iz,
                                 nx, ny, nz, t0, bt)
            hr, tr = _either_box(nodes, first + 1, signed, ox, oy, oz, dx, dy, dz, ix, iy,
                                 iz, nx, ny, nz, t0, bt)
            if hl and hr:
                if tl <= tr:  # nearer child first, the other waits
                    node = first
                    stack[sp] = first + 1
                    stack_t[sp] = tr
                else:
                    node = first + 1
                    stack[sp] = first
                    stack_t[sp] = tl
                sp += 1
            elif hl:
                node = first
            elif hr:
                node = first + 1
            else:
                node = -1
        while node < 0 and sp > 0:
            sp -= 1
            if stack_t[sp] <= bt:
                node = stack[sp]
    if best < 0:
        return best, np.inf
    return best, bt


@inline_ir
def _all_hits(bvh, win, r, stack, hits, mark, stamp, ox, oy, oz, dx, dy, dz, t0, t1,
              exclude, any_hit):
    """Caller indices of every triangle hit with t0 <= t <= t1 (``exclude`` left out),
    written to ``hits``; returns how many (at most 1 when ``any_hit``: the search
    stops at the first hit, nearer children first).

    A triangle cut into several pieces (kernels/bvh.py) is counted once: ``mark``
    (indexed by caller index) holds the ``stamp`` of the query that last tested it.
    The first-hit search needs no mark (a piece tested again misses again).
    """
    nodes, tris, index = bvh.nodes, bvh.tris, bvh.index
    if nodes.shape[0] == 0:
        return 0
    kx, ky, kz, sx, sy, sz = _ray_space(dx, dy, dz)
    okx = oz if kx == 2 else (oy if kx == 1 else ox)
    oky = oz if ky == 2 else (oy if ky == 1 else ox)
    okz = oz if kz == 2 else (oy if kz == 1 else ox)
    ix, iy, iz, nx, ny, nz, signed = _ray_boxes(dx, dy, dz)
    windowed = win.width > 0
    n = 0
    node = 0
    sp = 0
    while node >= 0:
        cnt = int(nodes[node, COUNT])
        first = int(nodes[node, FIRST])
        if cnt > 0:
            for k in range(first, first + cnt):
                idx = index[k]
                if idx == exclude:
                    continue
                if not any_hit:
                    if mark[idx] == stamp:
                        continue
                    mark[idx] = stamp
                if windowed:
                    hit, t = _test(tris, k, idx, win, r, kx, ky, kz, okx, oky, okz, sx, sy, sz)
                else:
                    hit, t, _ = _hit(tris, k, kx, ky, kz, okx, oky, okz, sx, sy, sz)
                if hit and t >= t0 and t <= t1:
                    hits[n] = idx
                    n += 1
                    if any_hit:
                        return n
            node = -1
        else:
            hl, tl = _either_box(nodes, first, signed, ox, oy, oz, dx, dy, dz, ix, iy, iz,
                                 nx, ny, nz, t0, t1)
            hr, tr = _either_box(nodes, first + 1, signed, ox, oy, oz, dx, dy, dz, ix, iy,
                                 iz, nx, ny, nz, t0, t1)
            if hl and hr:
                if tl <= tr:
                    node = first
                    stack[sp] = first + 1
                else:
                    node = first + 1
                    stack[sp] = first
                sp += 1
            elif hl:
                node = first
            elif hr:
                node = first + 1
            else:
                node = -1
        if node < 0 and sp > 0:
            sp -= 1
            node = stack[sp]
    return n


@inline
def _n_items(bvh):
    """1 + the largest caller index in the tree (the size of a per-triangle mark)."""
    m = 0
    for q in range(bvh.index.shape[0]):
        m = max(m, bvh.index[q] + 1)
    return max(1, m)


@jit
def closest_hits(bvh, win, origin, direction, t0, t1, order, r0, r1, out_tri, out_t):
    """Nearest triangle along rays ``order[r0:r1]``.

    Parameters
    ----------
    bvh : BVH
    win : Window
        Window-space coverage for eye rays (width 0: none).
    origin, direction : ndarray, shape (R, 3), float64
        Ray ``origin + t * direction``.
    t0, t1 : float
        Closed parameter interval.
    order : ndarray, shape (R,), int64
        The rays in the order they are cast (a permutation of 0 .. R-1; square
        tiles of pixels, :func:`vgxsim.shadow.raycast.tile_order`, keep successive
        rays in the same nodes); outputs stay indexed by ray.
    r0, r1 : int
        The slice of ``order`` this call handles (a worker thread's band).
    out_tri : ndarray, shape (R,), int64
        Caller's triangle index, -1 for none (ties in t: lowest index).
    out_t : ndarray, shape (R,), float64
        Its parameter, inf for none.
    """
    stack = np.empty(STACK_SIZE, dtype=np.int64)
    stack_t = np.empty(STACK_SIZE)
    for q in range(r0, r1):
        r = order[q]
        k, t = _closest(bvh, win, r, stack, stack_t, origin[r, 0], origin[r, 1], origin[r, 2],
                        direction[r, 0], direction[r, 1], direction[r, 2], t0, t1)
        out_tri[r] = k
        out_t[r] = t


@jit
def shadow_segments(bvh, tri_object, n_objects, layer_weight, points, exclude, active,
                    lights, far, offset, counts, order, r0, r1, out_blocked, out_objects,
                    out_layers):
    """Per point and light: is the segment to the light blocked, and by how much.

    The segment from point P to light l is ``P + s * (L - P)`` with ``L`` the light
    position (w != 0) or, for a directional light (w = 0), ``P + far * unit(x, y, z)``
    -- beyond every caster when ``far`` exceeds the scene's diameter.  It is cut
    short by ``offset`` (world units) at both ends: ``s0 <= s <= 1 - s0`` with
    ``s0 = offset / |L - P|``.  Triangle ``exclude[r]`` (the one P was found on) is
    skipped: with the offset this keeps a surface from shadowing itself.

    Parameters
    ----------
    bvh : BVH
        Caster triangles, numbered by the caller's (scene) index.
    tri_object : ndarray, shape (T,), int64
        Object of each scene triangle (0 .. n_objects-1).
    n_objects : int
    layer_weight : ndarray, shape (L, T), int64
        Per light, the weight each caster triangle adds to ``out_layers`` when the
        segment crosses it (the caller passes 1 for light-facing triangles).
    points : ndarray, shape (R, 3), float64
    exclude : ndarray, shape (R,), int64
        Scene triangle to skip per point (-1: none).
    active : ndarray, shape (R,), bool
        Points to test (others are left untouched).
    lights : ndarray, shape (L, 4), float64
        Homogeneous light positions (w = 1 point or spot light, w = 0 directional).
    far : float
    offset : float
    counts : bool
        False: only ``out_blocked``, each segment stopping at its first hit (the fast
        path); True: also the counts, from every hit.
    order : ndarray, shape (R,), int64
        The rays in the order they are cast (a permutation of 0 .. R-1; square
        tiles of pixels, :func:`vgxsim.shadow.raycast.tile_order`, keep successive
        rays in the same nodes); outputs stay indexed by ray.
    r0, r1 : int
        The slice of ``order`` this call handles (a worker thread's band).
    out_blocked : ndarray, shape (R, L), bool
    out_objects : ndarray, shape (R, L), int64
        Distinct objects crossed.
    out_layers : ndarray, shape (R, L), int64
        Sum of ``layer_weight`` over the triangles crossed.
    """
    stack = np.empty(STACK_SIZE, dtype=np.int64)
    hits = np.empty(max(1, bvh.index.shape[0]), dtype=np.int64)
    seen = np.full(_n_items(bvh), -1, dtype=np.int64)
    mark = np.full(max(1, n_objects), -1, dtype=np.int64)
    win = Window(0, np.zeros((0, 3), np.int64), np.zeros((0, 3), np.int64),
                 np.zeros(0, np.bool_))
    nl = lights.shape[0]
    for q in range(r0, r1):
        r = order[q]
        if not active[r]:
            continue
        px, py, pz = points[r, 0], points[r, 1], points[r, 2]
        for li in range(nl):
            lw = lights[li, 3]
            if lw != 0.0:
                dx = lights[li, 0] / lw - px
                dy = lights[li, 1] / lw - py
                dz = lights[li, 2] / lw - pz
            else:
                nrm = np.sqrt(lights[li, 0] ** 2 + lights[li, 1] ** 2 + lights[li, 2] ** 2)
                dx = far * lights[li, 0] / nrm
                dy = far * lights[li, 1] / nrm
                dz = far * lights[li, 2] / nrm
            s0 = offset / np.sqrt(dx * dx + dy * dy + dz * dz)
            n = 0
            if s0 < 0.5:
                n = _all_hits(bvh, win, r, stack, hits, seen, r * nl + li, px, py, pz,
                              dx, dy, dz,
                              s0, 1.0 - s0, exclude[r], not counts)
            out_blocked[r, li] = n > 0
            if counts:
                objs = 0
                layers = 0
                key = r * nl + li
                for q in range(n):
                    idx = hits[q]
                    layers += layer_weight[li, idx]
                    ob = tri_object[idx]
                    if mark[ob] != key:
                        mark[ob] = key
                        objs += 1
                out_objects[r, li] = objs
                out_layers[r, li] = layers


@jit
def count_crossings(bvh, win, face_light, face_weight, origin, direction, t_end, order, r0,
                    r1, out_count):
    """Signed count of shadow-volume faces crossed by each ray, per light.

    Parameters
    ----------
    bvh : BVH
        Faces of every light, numbered by the caller's face index.
    win : Window
        Window-space coverage for eye rays (width 0: none).
    face_light : ndarray, shape (F,), int64
        The light each face belongs to.
    face_weight : ndarray, shape (F,), int64
        +1 for a face going into shadow (ST_INCR), -1 out of it (ST_DECR).
    origin, direction : ndarray, shape (R, 3), float64
    t_end : ndarray, shape (R,), float64
        Faces with ``0 <= t <= t_end[r]`` count.
    order : ndarray, shape (R,), int64
        The rays in the order they are cast (a permutation of 0 .. R-1; square
        tiles of pixels, :func:`vgxsim.shadow.raycast.tile_order`, keep successive
        rays in the same nodes); outputs stay indexed by ray.
    r0, r1 : int
        The slice of ``order`` this call handles (a worker thread's band).
    out_count : ndarray, shape (R, L), int64
    """
    stack = np.empty(STACK_SIZE, dtype=np.int64)
    hits = np.empty(max(1, bvh.index.shape[0]), dtype=np.int64)
    seen = np.full(_n_items(bvh), -1, dtype=np.int64)
    nl = out_count.shape[1]
    for q in range(r0, r1):
        r = order[q]
        for li in range(nl):
            out_count[r, li] = 0
        n = _all_hits(bvh, win, r, stack, hits, seen, r, origin[r, 0], origin[r, 1],
                      origin[r, 2],
                      direction[r, 0], direction[r, 1], direction[r, 2], 0.0, t_end[r],
                      -1, False)
        for q in range(n):
            f = hits[q]
            out_count[r, face_light[f]] += face_weight[f]
