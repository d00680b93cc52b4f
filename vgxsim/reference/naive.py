"""Naive, obviously-correct reference pipeline (the test oracle).

Everything here follows docs/numeric_model.md literally, one pixel at a time, with
Python ints for every fixed-point and integer quantity and Python floats (IEEE
float64, never fused) for the interpolation expressions, evaluated in exactly the
order the model writes them.  NumPy is used only to hold the planes.  It is slow by
design: it exists so that the Numba kernels can be checked for bit-identical output.

Section numbers in comments (``§n``) refer to docs/numeric_model.md.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence

import numpy as np

from vgxsim.state.codes import (
    AC_ACCUMULATE,
    AC_ADD,
    AC_CLEAR,
    AC_CLEAR_ACCUMULATE,
    AC_MULT,
    AC_RETURN,
    BF_DA,
    BF_DC,
    BF_MDA,
    BF_MDC,
    BF_MIN_SA_MDA,
    BF_MSA,
    BF_ONE,
    BF_SA,
    BF_ZERO,
    CULL_BACK,
    CULL_FRONT,
    FLAT,
    LO_SRC,
    OP_DECR,
    OP_INCR,
    OP_INVERT,
    OP_KEEP,
    OP_REPLACE,
    OP_ZERO,
    TEV_BLEND,
    TEV_DECAL,
    TEXF_BILINEAR,
    TEXF_MIPMAP_BILINEAR,
    TEXF_MIPMAP_POINT,
    TEXF_MIPMAP_TRILINEAR,
    TEXW_CLAMP,
)
from vgxsim.state.raster import RasterState
from vgxsim.state.textures import binding

__all__ = [
    "AC_ACCUMULATE",
    "AC_ADD",
    "AC_CLEAR",
    "AC_CLEAR_ACCUMULATE",
    "AC_MULT",
    "AC_RETURN",
    "GD_ZMAX",
    "GD_ZMIN",
    "ONE",
    "SUBPIXEL_BITS",
    "NaiveFramebuffer",
    "accum",
    "area2",
    "compare",
    "covered_pixels",
    "line_pixels",
    "render",
    "snap",
]

SUBPIXEL_BITS = 8
ONE = 1 << SUBPIXEL_BITS  # 256
GD_ZMIN = -0x800000
GD_ZMAX = 0x7FFFFF
Z_BITS = 24
Z_MASK = (1 << Z_BITS) - 1
COLOR_MASK = 0xFFFFFFFF

ACC_MIN, ACC_MAX = -32768, 32767


# --------------------------------------------------------------------------- planes


class NaiveFramebuffer:
    """The planes of one window (§7), stored as NumPy arrays indexed ``[y, x]``.

    Parameters
    ----------
    width, height : int
        Size in pixels.
    stencil_planes : int, optional
        Number of stencil bit planes (0..8); 0 means no stencil plane.
    zbits : int, optional
        Depth-buffer size; 0 means no z plane.  Any other value gives the 24-bit
        signed z plane of the model (§7).
    double : bool, optional
        Whether a back buffer exists (doublebuffer).

    Attributes
    ----------
    width, height, stencil_planes, zbits : int
        As given.
    front : numpy.ndarray
        ``(H, W)`` uint32 packed 0xAABBGGRR colour, all zero.
    back : numpy.ndarray or None
        Same as ``front``; None when single-buffered.
    z : numpy.ndarray or None
        ``(H, W)`` int32, initialised to ``GD_ZMAX`` (0x7FFFFF); None when
        ``zbits == 0``.
    stencil : numpy.ndarray or None
        ``(H, W)`` uint8, all zero; None when ``stencil_planes == 0``.
    """

    def __init__(self, width, height, stencil_planes=8, zbits=24, double=True):
        if not 0 <= stencil_planes <= 8:
            raise ValueError("stencil_planes must be in 0..8")
        self.width = int(width)
        self.height = int(height)
        self.stencil_planes = int(stencil_planes)
        self.zbits = int(zbits)
        shape = (self.height, self.width)
        self.front = np.zeros(shape, dtype=np.uint32)
        self.back = np.zeros(shape, dtype=np.uint32) if double else None
        self.z = np.full(shape, GD_ZMAX, dtype=np.int32) if self.zbits > 0 else None
        self.stencil = np.zeros(shape, dtype=np.uint8) if self.stencil_planes > 0 else None

    @property
    def smax(self):
        """int: Largest stencil value, ``2**stencil_planes - 1``."""
        return (1 << self.stencil_planes) - 1


# --------------------------------------------------------------------- small helpers


def compare(func, lhs, rhs):
    """Evaluate an SF_/ZF_/AF_ comparison code (§6).

    Parameters
    ----------
    func : int
        Comparison code 0..7, a bit mask of less (1), equal (2), greater (4).
    lhs, rhs : int
        Operands; the test is ``lhs FUNC rhs``.

    Returns
    -------
    bool
        True when the test passes.
    """
    if lhs < rhs:
        cmp = 0
    elif lhs == rhs:
        cmp = 1
    else:
        cmp = 2
    return bool((func >> cmp) & 1)


def _round(x):
    """``floor(x + 0.5)`` as a Python int (the model's rounding everywhere)."""
    return math.floor(x + 0.5)


def _clamp(v, lo, hi):
    return lo if v < lo else hi if v > hi else v


def _pack(r, g, b, a):
    return (a << 24) | (b << 16) | (g << 8) | r


def _unpack(c):
    return c & 0xFF, (c >> 8) & 0xFF, (c >> 16) & 0xFF, (c >> 24) & 0xFF


def _rect(fb, scissor):
    """Raster rectangle ``scissor ∩ window`` as inclusive ``(x0, x1, y0, y1)``."""
    x0, x1, y0, y1 = (int(v) for v in scissor)
    return max(x0, 0), min(x1, fb.width - 1), max(y0, 0), min(y1, fb.height - 1)


def _in_rect(rect, x, y):
    x0, x1, y0, y1 = rect
    return x0 <= x <= x1 and y0 <= y <= y1


def _draw_targets(fb, draw_front, draw_back):
    """Colour planes a primitive or clear writes.

    A single-buffered framebuffer has only its front buffer, which is then the
    target of both ``frontbuffer`` and ``backbuffer`` drawing.
    """
    if fb.back is None:
        return [fb.front] if (draw_front or draw_back) else []
    targets = []
    if draw_front:
        targets.append(fb.front)
    if draw_back:
        targets.append(fb.back)
    return targets


def _z_masked(old, new, zwm):
    """24-bit two's-complement masked z write, then sign extension (§6)."""
    m = zwm & Z_MASK
    v = ((old & Z_MASK) & ~m) | ((new & Z_MASK) & m)
    if v & 0x800000:
        v -= 1 << Z_BITS
    return v


def _color_masked(old, new, wm):
    """``(old & ~wm) | (new & wm)`` on the 32-bit packed word (§6)."""
    m = wm & COLOR_MASK
    return ((old & ~m) | (new & m)) & COLOR_MASK


# ------------------------------------------------------------------- §2 snapping


def snap(xw, yw, subpixel):
    """Snap float window coordinates to fixed point (§2).

    Parameters
    ----------
    xw, yw : float
        Window coordinates (integers are pixel centres).
    subpixel : bool
        ``subpixel(TRUE)`` keeps 8 fractional bits; FALSE snaps to the nearest pixel
        centre, ties upward.

    Returns
    -------
    tuple of int
        ``(xf, yf)`` in units of 1/256 pixel.
    """
    xw = float(xw)
    yw = float(yw)
    if subpixel:
        return math.floor(xw * ONE + 0.5), math.floor(yw * ONE + 0.5)
    return math.floor(xw + 0.5) * ONE, math.floor(yw + 0.5) * ONE


# -------------------------------------------------------------- §3 triangle coverage


def area2(p0, p1, p2):
    """Twice the signed area of three fixed-point points (§3), exact int.

    Parameters
    ----------
    p0, p1, p2 : tuple of int
        ``(xf, yf)`` fixed-point vertices.

    Returns
    -------
    int
        Positive for counter-clockwise (front-facing) order.
    """
    (x0, y0), (x1, y1), (x2, y2) = p0, p1, p2
    return (x1 - x0) * (y2 - y0) - (x2 - x0) * (y1 - y0)


def _edge(pi, pj, X, Y):
    """Edge function ``E_ij`` at the centre of pixel ``(X, Y)`` (§3)."""
    (xi, yi), (xj, yj) = pi, pj
    return (xj - xi) * (Y * ONE - yi) - (yj - yi) * (X * ONE - xi)


def _inclusive(pi, pj):
    """Whether directed edge i -> j owns the pixel centres lying on it (§3)."""
    (xi, yi), (xj, yj) = pi, pj
    return (yj - yi) < 0 or (yj == yi and xj > xi)


def covered_pixels(tri_fixed):
    """Pixels whose centres a triangle covers under the tie rule (§3), no scissor.

    Parameters
    ----------
    tri_fixed : sequence of three (int, int)
        Fixed-point vertices ``(xf, yf)`` in any winding.

    Returns
    -------
    list of tuple of int
        ``(X, Y)`` pixels in row-major order (Y ascending, then X ascending).
        Empty for a zero-area triangle.
    """
    v0, v1, v2 = (tuple(int(c) for c in v) for v in tri_fixed)
    a = area2(v0, v1, v2)
    if a == 0:
        return []
    if a < 0:
        v1, v2 = v2, v1
    edges = [(v0, v1), (v1, v2), (v2, v0)]
    xs = [v[0] for v in (v0, v1, v2)]
    ys = [v[1] for v in (v0, v1, v2)]
    # Pixel centres X*256 within [min, max]; floor/ceil give a safe superset.
    x_lo, x_hi = min(xs) // ONE, -(-max(xs) // ONE)
    y_lo, y_hi = min(ys) // ONE, -(-max(ys) // ONE)
    out = []
    for Y in range(y_lo, y_hi + 1):
        for X in range(x_lo, x_hi + 1):
            inside = True
            for pi, pj in edges:
                e = _edge(pi, pj, X, Y)
                if e < 0 or (e == 0 and not _inclusive(pi, pj)):
                    inside = False
                    break
            if inside:
                out.append((X, Y))
    return out


# ------------------------------------------------------------ §4 interpolation


class _Plane:
    """One linear interpolant set up from canonically ordered vertices (§4)."""

    __slots__ = ("a0", "X0", "Y0", "dadx", "dady")

    def __init__(self, canon, values):
        (x0, y0), (x1, y1), (x2, y2) = canon
        X0, Y0 = x0 / ONE, y0 / ONE
        X1, Y1 = x1 / ONE, y1 / ONE
        X2, Y2 = x2 / ONE, y2 / ONE
        det = float(area2(*canon)) / 65536
        a0, a1, a2 = (float(v) for v in values)
        self.a0, self.X0, self.Y0 = a0, X0, Y0
        self.dadx = ((a1 - a0) * (Y2 - Y0) - (a2 - a0) * (Y1 - Y0)) / det
        self.dady = ((X1 - X0) * (a2 - a0) - (X2 - X0) * (a1 - a0)) / det

    def at(self, X, Y):
        """Value at the centre of pixel ``(X, Y)``, in the model's exact order."""
        return (self.a0 + self.dady * (float(Y) - self.Y0)) + self.dadx * (float(X) - self.X0)


def _flat_color(rgba):
    """Flat colour of a vertex: ``floor(c*255 + 0.5)`` clamped, per component."""
    return tuple(_clamp(_round(float(c) * 255.0), 0, 255) for c in rgba)


# ------------------------------------------------------------- §6 fragment stage


def _stencil_op(fb, state, X, Y, op):
    """Apply stencil operation ``op`` at ``(X, Y)`` through ``swritemask`` (§6)."""
    smax = fb.smax
    s = int(fb.stencil[Y, X])
    if op == OP_KEEP:
        new = s
    elif op == OP_ZERO:
        new = 0
    elif op == OP_REPLACE:
        new = state.sref & smax
    elif op == OP_INCR:
        new = min(s + 1, smax)
    elif op == OP_DECR:
        new = max(s - 1, 0)
    elif op == OP_INVERT:
        new = ~s & smax
    else:
        raise ValueError(f"unknown stencil op {op}")
    swm = state.swritemask & smax
    fb.stencil[Y, X] = (s & ~swm) | (new & swm)


def _src_factor(f, k, s, d, sa, da):
    """Source blend factor for component ``k`` (0..3 = r, g, b, a)."""
    if f == BF_ZERO:
        return 0
    if f == BF_ONE:
        return 255
    if f == BF_DC:
        return d[k]
    if f == BF_MDC:
        return 255 - d[k]
    if f == BF_SA:
        return sa
    if f == BF_MSA:
        return 255 - sa
    if f == BF_DA:
        return da
    if f == BF_MDA:
        return 255 - da
    if f == BF_MIN_SA_MDA:
        return 255 if k == 3 else min(sa, 255 - da)
    raise ValueError(f"unknown source blend factor {f}")


def _dst_factor(f, k, s, d, sa, da):
    """Destination blend factor for component ``k`` (0..3 = r, g, b, a)."""
    if f == BF_ZERO:
        return 0
    if f == BF_ONE:
        return 255
    if f == BF_DC:  # BF_SC as a destination factor
        return s[k]
    if f == BF_MDC:  # BF_MSC as a destination factor
        return 255 - s[k]
    if f == BF_SA:
        return sa
    if f == BF_MSA:
        return 255 - sa
    if f == BF_DA:
        return da
    if f == BF_MDA:
        return 255 - da
    raise ValueError(f"blend factor {f} is not valid as a destination factor")


def _blend(sf, df, src, dst):
    """Integer blend of two packed colours (§6)."""
    s = _unpack(src)
    d = _unpack(dst)
    sa, da = s[3], d[3]
    out = []
    for k in range(4):
        fs = _src_factor(sf, k, s, d, sa, da)
        fd = _dst_factor(df, k, s, d, sa, da)
        out.append(min(255, (s[k] * fs + d[k] * fd + 127) // 255))
    return _pack(*out)


def _logicop(op, src, dst):
    """Bitwise logic operation ``op(src, dst)`` on packed words (§6).

    Bits of the 4-bit code are read most significant first, as in gl.h: the result
    for source bit ``s`` and destination bit ``d`` is bit ``3 - (2*s + d)`` of
    ``op`` counted from the least significant bit (so LO_AND = 1 is ``s & d`` and
    LO_SRC = 3 is ``s``).
    """
    out = 0
    for bit in range(32):
        s = (src >> bit) & 1
        d = (dst >> bit) & 1
        out |= ((op >> (3 - (2 * s + d))) & 1) << bit
    return out


def _fragment(fb, state, X, Y, zf, rgba):
    """Run one fragment through alpha, stencil and z tests and the writes (§6)."""
    r, g, b, a = rgba
    # 1. alpha test
    if not compare(state.afunc, a, state.aref):
        return
    use_stencil = bool(state.stencil) and fb.stencil is not None
    use_z = bool(state.zbuffer) and fb.z is not None
    # 2. stencil test
    if use_stencil:
        s = int(fb.stencil[Y, X])
        if not compare(state.sfunc, state.sref & state.smask, s & state.smask):
            _stencil_op(fb, state, X, Y, state.sfail)
            return
    # 3. z test
    if use_z:
        zb = int(fb.z[Y, X])
        if not compare(state.zfunc, zf, zb):
            if use_stencil:
                _stencil_op(fb, state, X, Y, state.spass)
            return
    # 4. both passed
    if use_stencil:
        _stencil_op(fb, state, X, Y, state.szpass if use_z else state.spass)
    if use_z:
        fb.z[Y, X] = _z_masked(int(fb.z[Y, X]), zf, state.zwritemask)
    src = _pack(r, g, b, a)
    for buf in _draw_targets(fb, state.draw_front, state.draw_back):
        dst = int(buf[Y, X])
        if state.logicop != LO_SRC:
            new = _logicop(state.logicop, src, dst)
        else:
            new = _blend(state.blend_sf, state.blend_df, src, dst)
        buf[Y, X] = _color_masked(dst, new, state.wmpack)


# ------------------------------------------------------------------- primitives


def _triangle(fb, verts, state):
    """Rasterize one triangle command (§2, §3, §4, §6)."""
    snapped = [snap(v[0], v[1], state.subpixel) for v in verts]
    a = area2(*snapped)
    if a == 0:
        return
    if (state.cull & CULL_BACK and a < 0) or (state.cull & CULL_FRONT and a > 0):
        return
    pixels = covered_pixels(snapped)
    rect = _rect(fb, state.scissor)
    pixels = [(X, Y) for X, Y in pixels if _in_rect(rect, X, Y)]
    if not pixels:
        return
    # Canonical order: ascending (yf, xf); stable, ties only when degenerate.
    order = sorted(range(3), key=lambda i: (snapped[i][1], snapped[i][0]))
    canon = [snapped[i] for i in order]
    zs = [float(verts[i][2]) for i in order]
    z_plane = _Plane(canon, zs)
    zr = [_round(z) for z in zs]
    z_lo, z_hi = min(zr), max(zr)
    if state.shademodel == FLAT:
        flat = _flat_color(verts[2][3])
        c_planes = None
    else:
        flat = None
        c_planes = [_Plane(canon, [float(verts[i][3][k]) * 255.0 for i in order]) for k in range(4)]
    tex = None
    if state.texture != 0 and len(verts[0]) > 4:
        tex = (binding(state.texture),
               [_Plane(canon, [float(verts[i][4][k]) for i in order]) for k in range(3)])
    for X, Y in pixels:
        zf = _clamp(_round(z_plane.at(X, Y)), z_lo, z_hi)
        if c_planes is None:
            rgba = flat
        else:
            rgba = tuple(_clamp(_round(p.at(X, Y)), 0, 255) for p in c_planes)
        if tex is not None:
            rgba = tuple(_clamp(_round(c), 0, 255) for c in _textured(tex, X, Y, rgba))
        _fragment(fb, state, X, Y, zf, rgba)


# ------------------------------------------------------------------ §14 texture


def _texel_index(i, n, wrap):
    return _clamp(i, 0, n - 1) if wrap == TEXW_CLAMP else i % n


_LEVELS: dict[int, list] = {}


def _pyramid(texture) -> list:
    """Levels 0.. of a mipmapped texture as lists of rows of RGBA int lists (§14 box
    filter: the mean of the 2 x 2 texels under each, indices past the edge clamped,
    rounded half up), down to 1 x 1."""
    got = _LEVELS.get(id(texture))
    if got is not None and got[0] is texture:
        return got[1]
    cur = [[[int(c) for c in px] for px in row] for row in texture.texels.tolist()]
    levels = [cur]
    while len(cur) > 1 or len(cur[0]) > 1:
        h, w = len(cur), len(cur[0])
        nxt = []
        for j in range(max(h // 2, 1)):
            ja, jb = min(2 * j, h - 1), min(2 * j + 1, h - 1)
            row = []
            for i in range(max(w // 2, 1)):
                ia, ib = min(2 * i, w - 1), min(2 * i + 1, w - 1)
                row.append([(cur[ja][ia][k] + cur[ja][ib][k] + cur[jb][ia][k]
                             + cur[jb][ib][k] + 2) // 4 for k in range(4)])
            nxt.append(row)
        cur = nxt
        levels.append(cur)
    _LEVELS[id(texture)] = (texture, levels)
    return levels


def _sample(img, wrap_s, wrap_t, s, t, bilinear):
    """Point or bilinear sample (§14) of a level ``img`` (rows of RGBA, lists or the
    (H, W, 4) texel array) at (s, t)."""
    h, w = len(img), len(img[0])
    u = min(max(s * w, -1e15), 1e15)
    v = min(max(t * h, -1e15), 1e15)
    if bilinear:
        u -= 0.5
        v -= 0.5
        i0, j0 = math.floor(u), math.floor(v)
        al, be = u - i0, v - j0
        ia, ib = (_texel_index(i, w, wrap_s) for i in (i0, i0 + 1))
        ja, jb = (_texel_index(j, h, wrap_t) for j in (j0, j0 + 1))
        return [((((1.0 - al) * (1.0 - be)) * float(img[ja][ia][k])
                  + (al * (1.0 - be)) * float(img[ja][ib][k]))
                 + ((1.0 - al) * be) * float(img[jb][ia][k]))
                + (al * be) * float(img[jb][ib][k]) for k in range(4)]
    i = _texel_index(math.floor(u), w, wrap_s)
    j = _texel_index(math.floor(v), h, wrap_t)
    return [float(img[j][i][k]) for k in range(4)]


def _mipmap_sample(texture, fil, s, t, rho2):
    """The MIPMAP filters (§14): level of detail log2(rho2) / 2, nearest level or the
    two around it, each sampled by point or bilinear, mixed (1 - f) a + f b."""
    levels = _pyramid(texture)
    top = len(levels) - 1
    lam = min(0.5 * math.log2(rho2), 64.0)
    bilinear = fil in (TEXF_MIPMAP_BILINEAR, TEXF_MIPMAP_TRILINEAR)
    ws, wt = texture.wrap_s, texture.wrap_t
    if fil in (TEXF_MIPMAP_POINT, TEXF_MIPMAP_BILINEAR):
        d = 0 if lam <= 0.5 else math.ceil(lam + 0.5) - 1
        return _sample(levels[min(d, top)], ws, wt, s, t, bilinear)
    d = math.floor(lam)
    if d >= top:
        return _sample(levels[top], ws, wt, s, t, bilinear)
    f = lam - d
    a = _sample(levels[d], ws, wt, s, t, bilinear)
    b = _sample(levels[d + 1], ws, wt, s, t, bilinear)
    return [(1.0 - f) * a[k] + f * b[k] for k in range(4)]


def _textured(tex, X, Y, rgba):
    """The texture stage of one fragment (§14): perspective-correct s, t from the
    s/w, t/w, 1/w planes, the filter chosen by the screen derivatives, the texel
    look-up and the environment.  Returns float components (rounded by the caller)."""
    b, (ps, pt, pq) = tex
    texture = b.texture
    h, w = texture.texels.shape[:2]
    q = pq.at(X, Y)
    if q == 0.0:
        q = 1e-300
    s = ps.at(X, Y) / q
    t = pt.at(X, Y) / q
    fil = texture.magfilter
    rho2 = 0.0
    if texture.minfilter != texture.magfilter:
        dudx = w * (ps.dadx - s * pq.dadx) / q
        dvdx = h * (pt.dadx - t * pq.dadx) / q
        dudy = w * (ps.dady - s * pq.dady) / q
        dvdy = h * (pt.dady - t * pq.dady) / q
        rho2 = max(dudx * dudx + dvdx * dvdx, dudy * dudy + dvdy * dvdy)
        if rho2 > 1.0:
            fil = texture.minfilter
    if fil >= TEXF_MIPMAP_POINT:
        c = _mipmap_sample(texture, fil, s, t, rho2)
    else:
        c = _sample(texture.texels, texture.wrap_s, texture.wrap_t, s, t,
                    fil == TEXF_BILINEAR)
    f = [float(x) for x in rgba]
    mode = b.env.mode
    if mode == TEV_DECAL:
        return tuple((f[k] * (255.0 - c[3]) + c[k] * c[3]) / 255.0 for k in range(3)) + (f[3],)
    if mode == TEV_BLEND:
        cc = [float(x) * 255.0 for x in b.env.colour]
        return tuple((f[k] * (255.0 - c[k]) + cc[k] * c[k]) / 255.0
                     for k in range(3)) + ((f[3] * c[3]) / 255.0,)
    return tuple((f[k] * c[k]) / 255.0 for k in range(4))


def _ydiv_round(num, den):
    """``floor(num / den + 1/2)`` exactly, for ints with ``den != 0``."""
    if den < 0:
        num, den = -num, -den
    return (2 * num + den) // (2 * den)


def line_pixels(p0, p1, closed):
    """Pixels of a one-pixel-wide line between fixed-point endpoints (§5).

    Parameters
    ----------
    p0, p1 : tuple of int
        Fixed-point endpoints ``(xf, yf)``.
    closed : bool
        Draw the last pixel (``subpixel(FALSE)``) or not (``subpixel(TRUE)``).

    Returns
    -------
    list of tuple
        ``(X, Y, i, t, xmajor)`` in drawing order: the pixel, its step index ``i``
        from the first end (the line-style position), the interpolation parameter
        ``t`` and whether the line is x-major.  The minor coordinate is
        ``floor(minor(M) + 0.5)`` on the exact line through the endpoints, computed
        with exact integer arithmetic.  ``t`` is the position of the pixel centre
        along the major axis between the endpoints, ``t = (M - P0) / (P1 - P0)``
        in float64 with ``P = major fixed coordinate / 256`` (0 when the endpoints
        share the major coordinate).
    """
    (x0, y0), (x1, y1) = p0, p1
    dx, dy = x1 - x0, y1 - y0
    xmajor = abs(dx) >= abs(dy)
    if not xmajor:
        # y-major: swap the roles of x and y.
        x0, y0, x1, y1, dx, dy = y0, x0, y1, x1, dy, dx
    M0 = (x0 + ONE // 2) // ONE  # floor(x0/256 + 0.5)
    M1 = (x1 + ONE // 2) // ONE
    n = abs(M1 - M0)
    step = 1 if M1 >= M0 else -1
    count = n + 1 if closed else n
    major0 = x0 / ONE
    span = dx / ONE
    out = []
    for i in range(count):
        M = M0 + step * i
        if dx == 0:
            m = (y0 + ONE // 2) // ONE
        else:
            # minor(M) = (y0 + (M*256 - x0) * dy / dx) / 256, rounded exactly.
            m = _ydiv_round(y0 * dx + (M * ONE - x0) * dy, dx * ONE)
        t = 0.0 if span == 0.0 else (float(M) - major0) / span
        out.append((M, m, i, t, xmajor) if xmajor else (m, M, i, t, xmajor))
    return out


def _lerp(v0, v1, t):
    """Linear interpolation between end values: ``v0 + (v1 - v0) * t``."""
    return v0 + (v1 - v0) * t


def _line(fb, verts, state, pattern_start=0):
    """Rasterize one line command (§5, §6)."""
    (xa, ya, za, ca), (xb, yb, zb, cb) = verts[0], verts[1]
    p0 = snap(xa, ya, state.subpixel)
    p1 = snap(xb, yb, state.subpixel)
    closed = not state.subpixel
    width = int(state.linewidth)
    repeat = int(state.lsrepeat)
    if width < 1 or repeat < 1:
        raise ValueError("linewidth and lsrepeat must be >= 1")
    offsets = range(-((width - 1) // 2), width // 2 + 1)
    rect = _rect(fb, state.scissor)
    za, zb = float(za), float(zb)
    z_lo, z_hi = sorted((_round(za), _round(zb)))
    flat = _flat_color(cb) if state.shademodel == FLAT else None
    ca255 = [float(c) * 255.0 for c in ca]
    cb255 = [float(c) * 255.0 for c in cb]
    for X, Y, i, t, xmajor in line_pixels(p0, p1, closed):
        pos = int(pattern_start) + i
        if not (state.linestyle >> ((pos // repeat) % 16)) & 1:
            continue
        zf = _clamp(_round(_lerp(za, zb, t)), z_lo, z_hi)
        if flat is not None:
            rgba = flat
        else:
            rgba = tuple(_clamp(_round(_lerp(ca255[k], cb255[k], t)), 0, 255) for k in range(4))
        for off in offsets:
            px, py = (X, Y + off) if xmajor else (X + off, Y)
            if _in_rect(rect, px, py):
                _fragment(fb, state, px, py, zf, rgba)


def _point(fb, vert, state):
    """Rasterize one point command (§5, §6)."""
    xw, yw, zw, rgba = vert
    xf, yf = snap(xw, yw, state.subpixel)
    X = (xf + ONE // 2) // ONE
    Y = (yf + ONE // 2) // ONE
    size = int(state.pntsize)
    if size < 1:
        raise ValueError("pntsize must be >= 1")
    zf = _round(float(zw))
    color = _flat_color(rgba)
    rect = _rect(fb, state.scissor)
    x_ll = X - (size - 1) // 2
    y_ll = Y - (size - 1) // 2
    for py in range(y_ll, y_ll + size):
        for px in range(x_ll, x_ll + size):
            if _in_rect(rect, px, py):
                _fragment(fb, state, px, py, zf, color)


def _clear(fb, planes, values, state):
    """Clear the raster rectangle through the write masks (§8)."""
    planes = set(planes)
    unknown = planes - {"color", "z", "stencil"}
    if unknown:
        raise ValueError(f"unknown planes {sorted(unknown)}")
    x0, x1, y0, y1 = _rect(fb, state.scissor)
    targets = _draw_targets(fb, state.draw_front, state.draw_back) if "color" in planes else []
    do_z = "z" in planes and fb.z is not None
    do_s = "stencil" in planes and fb.stencil is not None
    for Y in range(y0, y1 + 1):
        for X in range(x0, x1 + 1):
            for buf in targets:
                buf[Y, X] = _color_masked(int(buf[Y, X]), int(values["color"]), state.wmpack)
            if do_z:
                fb.z[Y, X] = _z_masked(int(fb.z[Y, X]), int(values["z"]), state.zwritemask)
            if do_s:
                smax = fb.smax
                swm = state.swritemask & smax
                s = int(fb.stencil[Y, X])
                fb.stencil[Y, X] = (s & ~swm) | (int(values["stencil"]) & swm)


def render(fb, commands: Iterable[Sequence]):
    """Execute a list of commands in order on a framebuffer.

    Parameters
    ----------
    fb : NaiveFramebuffer
        Target planes, modified in place.
    commands : iterable of tuple
        ``("triangle", verts, state)`` with three ``(xw, yw, zw, (r, g, b, a))``
        (and, when ``state.texture`` is set, a fifth item ``(s/w, t/w, 1/w)``);
        ``("line", verts, state[, pattern_start])`` with two vertices;
        ``("point", vert, state)``; ``("clear", planes, values, state)`` with
        ``planes`` a subset of {"color", "z", "stencil"} and ``values`` a dict of
        packed colour, z and stencil ints.  ``state`` is a
        :class:`~vgxsim.state.raster.RasterState`.
    """
    for cmd in commands:
        kind = cmd[0]
        if kind == "triangle":
            _, verts, state = cmd
            _check_state(state)
            _triangle(fb, verts, state)
        elif kind == "line":
            verts, state = cmd[1], cmd[2]
            _check_state(state)
            start = cmd[3] if len(cmd) > 3 else 0
            _line(fb, verts, state, start)
        elif kind == "point":
            _, vert, state = cmd
            _check_state(state)
            _point(fb, vert, state)
        elif kind == "clear":
            _, planes, values, state = cmd
            _check_state(state)
            _clear(fb, planes, values, state)
        else:
            raise ValueError(f"unknown command {kind!r}")


def _check_state(state):
    if not isinstance(state, RasterState):
        raise TypeError("state must be a RasterState")


# --------------------------------------------------------------- §9 accumulation


def accum(fb, acc, op, value, scissor, wmpack, source):
    """Accumulation-buffer operation ``acbuf(op, value)`` (§9).

    Parameters
    ----------
    fb : NaiveFramebuffer
        Framebuffer whose colour is read (and written by AC_RETURN).
    acc : numpy.ndarray
        ``(H, W, 4)`` int16 RGBA accumulation plane, modified in place.
    op : int
        One of AC_CLEAR, AC_ACCUMULATE, AC_CLEAR_ACCUMULATE, AC_RETURN, AC_MULT,
        AC_ADD.
    value : float
        The ``value`` argument of acbuf.
    scissor : tuple of int
        Raster rectangle ``(x0, x1, y0, y1)``, inclusive.
    wmpack : int
        Colour write mask used by AC_RETURN.
    source : {'front', 'back'}
        Colour buffer read by the accumulate operations and written by AC_RETURN;
        'back' on a single-buffered framebuffer means the front buffer.
    """
    if source not in ("front", "back"):
        raise ValueError("source must be 'front' or 'back'")
    buf = fb.back if (source == "back" and fb.back is not None) else fb.front
    v = float(value)
    x0, x1, y0, y1 = _rect(fb, scissor)
    for Y in range(y0, y1 + 1):
        for X in range(x0, x1 + 1):
            c = _unpack(int(buf[Y, X]))
            old = [int(acc[Y, X, k]) for k in range(4)]
            if op == AC_RETURN:
                new = _pack(*(_clamp(_round(v * old[k]), 0, 255) for k in range(4)))
                buf[Y, X] = _color_masked(int(buf[Y, X]), new, wmpack)
                continue
            if op == AC_CLEAR:
                res = [_round(v)] * 4
            elif op == AC_ACCUMULATE:
                res = [old[k] + _round(v * c[k]) for k in range(4)]
            elif op == AC_CLEAR_ACCUMULATE:
                res = [_round(v * c[k]) for k in range(4)]
            elif op == AC_MULT:
                res = [_round(v * old[k]) for k in range(4)]
            elif op == AC_ADD:
                res = [old[k] + _round(v) for k in range(4)]
            else:
                raise ValueError(f"unknown accumulation op {op}")
            for k in range(4):
                acc[Y, X, k] = _clamp(res[k], ACC_MIN, ACC_MAX)
