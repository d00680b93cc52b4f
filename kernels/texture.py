"""The texture stage: texture-coordinate planes and the per-fragment texture look-up.

docs/numeric_model.md section 14.  Per vertex the geometry stage hands over s/w,
t/w and 1/w (w the clip-space w); they are interpolated linearly in the window like
colour (section 4: the same canonical vertex order and plane origin), and each
fragment divides by the interpolated 1/w, so texture coordinates are
perspective-correct.  The look-up addresses texels with centres at half-integers,
wraps (repeat or clamp to the edge texel), filters (point or bilinear, and the
mipmap filters; minification or magnification and the level of detail decided per
fragment from the coordinates' exact screen derivatives) and applies the
environment (modulate, decal, blend) to the fragment colour.
"""

from __future__ import annotations

import numpy as np

from vgxsim.state.codes import (
    TEV_BLEND,
    TEV_DECAL,
    TEXF_BILINEAR,
    TEXF_MIPMAP_BILINEAR,
    TEXF_MIPMAP_POINT,
    TEXF_MIPMAP_TRILINEAR,
    TEXW_CLAMP,
    X_ENV,
    X_HEIGHT,
    X_LEVELS,
    X_MAGFILTER,
    X_MINFILTER,
    X_OFFSET,
    X_WIDTH,
    X_WRAP_S,
    X_WRAP_T,
)
from vgxsim.stream.opcodes import CM, CRAW, CSKIP, SYNC, C, N, T, V

from .decode import _int_payload
from .options import callee, inline, jit
from .setup import canonical_order, plane_frame


@jit
def setup_texture_planes(xf, yf, stq, tris, t_tex, offset):
    """Planes of s/w, t/w, 1/w of triangles set up at slots ``offset ..``.

    Parameters
    ----------
    xf, yf : ndarray, shape (Nv,), int64
        Fixed-point window coordinates (as given to setup_triangles).
    stq : ndarray, shape (Nv, 3), float64
        s/w, t/w, 1/w per vertex.
    tris : ndarray, shape (Nt, 3), int64
    t_tex : ndarray, shape (C, 3, 3), float64
        Out: per slot and quantity, (value at the plane origin, d/dx, d/dy); the
        origin is the canonical first vertex, as for depth and colour.
    offset : int
    """
    for t in range(tris.shape[0]):
        n = offset + t
        a, b, c = canonical_order(xf, yf, tris[t, 0], tris[t, 1], tris[t, 2])
        ax, ay, bx, by, cx, cy = xf[a], yf[a], xf[b], yf[b], xf[c], yf[c]
        det2 = (bx - ax) * (cy - ay) - (cx - ax) * (by - ay)
        if det2 == 0:
            for k in range(3):
                t_tex[n, k, 0] = 0.0
                t_tex[n, k, 1] = 0.0
                t_tex[n, k, 2] = 0.0
            continue
        fx0, fy0, dxb, dyb, dxc, dyc, det = plane_frame(ax, ay, bx, by, cx, cy, det2)
        for k in range(3):
            va = stq[a, k]
            vb = stq[b, k]
            vc = stq[c, k]
            t_tex[n, k, 0] = va
            t_tex[n, k, 1] = ((vb - va) * dyc - (vc - va) * dyb) / det
            t_tex[n, k, 2] = (dxb * (vc - va) - dxc * (vb - va)) / det
    return offset + tris.shape[0]


@inline
def _wrap(i, n, mode):
    if mode == TEXW_CLAMP:
        return min(max(i, 0), n - 1)
    return i % n  # floor modulo: repeat


@inline
def _texel(texels, base, w, i, j, ch):
    return np.float64((np.int64(texels[base + j * w + i]) >> (8 * ch)) & 0xFF)


@inline
def _filtered(texels, base, w, i0, i1, j0, j1, al, be, ch):
    """Bilinear sum of one component, in the order docs/numeric_model.md s. 14 writes."""
    return ((((1.0 - al) * (1.0 - be)) * _texel(texels, base, w, i0, j0, ch)
             + (al * (1.0 - be)) * _texel(texels, base, w, i1, j0, ch))
            + ((1.0 - al) * be) * _texel(texels, base, w, i0, j1, ch)) \
        + (al * be) * _texel(texels, base, w, i1, j1, ch)


@inline
def _sample(texels, base, w, h, ws, wt, s, tt, bilinear):
    """One filtered texel (four components) of the w x h image at ``base``, point
    or bilinear, at texture coordinates (s, t) (docs/numeric_model.md s. 14)."""
    # Far outside the texture (or a degenerate 1/w): keep the texel index an int64.
    u = min(max(s * w, -1e15), 1e15)
    v = min(max(tt * h, -1e15), 1e15)
    if bilinear:
        u = u - 0.5
        v = v - 0.5
        fu = np.floor(u)
        fv = np.floor(v)
        al = u - fu
        be = v - fv
        i0 = _wrap(np.int64(fu), w, ws)
        i1 = _wrap(np.int64(fu) + 1, w, ws)
        j0 = _wrap(np.int64(fv), h, wt)
        j1 = _wrap(np.int64(fv) + 1, h, wt)
    else:
        # Point sampling is the bilinear sum with zero weights off the texel: the
        # same expression, exactly the texel (0 * T adds exact zeros).
        al = 0.0
        be = 0.0
        i0 = i1 = _wrap(np.int64(np.floor(u)), w, ws)
        j0 = j1 = _wrap(np.int64(np.floor(v)), h, wt)
    return (_filtered(texels, base, w, i0, i1, j0, j1, al, be, 0),
            _filtered(texels, base, w, i0, i1, j0, j1, al, be, 1),
            _filtered(texels, base, w, i0, i1, j0, j1, al, be, 2),
            _filtered(texels, base, w, i0, i1, j0, j1, al, be, 3))


@inline
def _level_sample(texels, base, w, h, ws, wt, s, tt, bilinear, level):
    """:func:`_sample` in mipmap level ``level``: max(w >> k, 1) x max(h >> k, 1)
    texels, stored after levels 0 .. k - 1."""
    for k in range(level):
        base += max(w >> k, 1) * max(h >> k, 1)
    return _sample(texels, base, max(w >> level, 1), max(h >> level, 1), ws, wt, s, tt,
                   bilinear)


@inline
def _level_of_detail(fil, levels, rho2):
    """The MIPMAP filters' level and mix (docs/numeric_model.md s. 14): ``lambda =
    log2(rho2) / 2`` (rho2 > 1); the nearest level ``ceil(lambda + 1/2) - 1`` (0 for
    lambda <= 1/2), or level ``floor(lambda)`` mixed with the next by the fraction
    ``f``; levels past the last are the last.  Returns (level, f, bilinear)."""
    lam = 0.5 * np.log2(rho2)
    if lam > 64.0:  # an infinite derivative: the last level
        lam = 64.0
    bilinear = fil == TEXF_MIPMAP_BILINEAR or fil == TEXF_MIPMAP_TRILINEAR
    top = levels - 1
    f = 0.0
    if fil == TEXF_MIPMAP_POINT or fil == TEXF_MIPMAP_BILINEAR:
        d = np.int64(0)
        if lam > 0.5:
            d = np.int64(np.ceil(lam + 0.5)) - 1
        d = min(d, top)
    else:
        d = np.int64(np.floor(lam))
        if d >= top:
            d = top
        else:
            f = lam - np.floor(lam)
    return d, f, bilinear


@callee
def _mipmapped(texels, base, w, h, ws, wt, s, tt, fil, levels, rho2):
    """A MIPMAP-filtered texel: level ``d`` of :func:`_level_of_detail` with weight
    1 - f, then, for the linear filters below the last level, level d + 1 with weight
    f (``(1 - f) a + f b``; with f = 0 exactly a).  Out of line and with one sampling
    call site, so that the rare path adds little to the fragment code's compile and
    nothing to the non-mipmap path."""
    d, f, bilinear = _level_of_detail(fil, levels, rho2)
    c0 = c1 = c2 = c3 = 0.0
    for k in range(2):
        if k == 1 and f == 0.0:
            break
        x0, x1, x2, x3 = _level_sample(texels, base, w, h, ws, wt, s, tt, bilinear, d + k)
        wk = 1.0 - f if k == 0 else f
        c0 = c0 + wk * x0
        c1 = c1 + wk * x1
        c2 = c2 + wk * x2
        c3 = c3 + wk * x3
    return c0, c1, c2, c3


@callee
def texture_fragment(t_tex, t, x, y, x0, y0, info, env_colour, texels, slot, r, g, b, a):
    """Textured colour of one fragment.

    ``t_tex[t]`` are the triangle's planes, (x0, y0) their origin; ``slot`` the row
    of the texture table (``info``, ``env_colour``, ``texels``: see
    vgxsim.state.textures.pack_bindings); r, g, b, a the fragment's rounded colour
    (ints 0..255).  Returns the four components as floats (rounded by pack_rgba).
    """
    dy = y - y0
    dx = x - x0
    sw = (t_tex[t, 0, 0] + t_tex[t, 0, 2] * dy) + t_tex[t, 0, 1] * dx
    tw = (t_tex[t, 1, 0] + t_tex[t, 1, 2] * dy) + t_tex[t, 1, 1] * dx
    q = (t_tex[t, 2, 0] + t_tex[t, 2, 2] * dy) + t_tex[t, 2, 1] * dx
    if q == 0.0:
        q = 1e-300
    s = sw / q
    tt = tw / q
    w = info[slot, X_WIDTH]
    h = info[slot, X_HEIGHT]
    fil = info[slot, X_MAGFILTER]
    rho2 = 0.0
    if info[slot, X_MINFILTER] != fil:
        dudx = w * (t_tex[t, 0, 1] - s * t_tex[t, 2, 1]) / q
        dvdx = h * (t_tex[t, 1, 1] - tt * t_tex[t, 2, 1]) / q
        dudy = w * (t_tex[t, 0, 2] - s * t_tex[t, 2, 2]) / q
        dvdy = h * (t_tex[t, 1, 2] - tt * t_tex[t, 2, 2]) / q
        rho2 = max(dudx * dudx + dvdx * dvdx, dudy * dudy + dvdy * dvdy)
        if rho2 > 1.0:
            fil = info[slot, X_MINFILTER]
    base = info[slot, X_OFFSET]
    ws = info[slot, X_WRAP_S]
    wt = info[slot, X_WRAP_T]
    if fil >= TEXF_MIPMAP_POINT:
        t0, t1, t2, t3 = _mipmapped(texels, base, w, h, ws, wt, s, tt, fil,
                                    info[slot, X_LEVELS], rho2)
    else:
        t0, t1, t2, t3 = _sample(texels, base, w, h, ws, wt, s, tt, fil == TEXF_BILINEAR)
    fr, fg, fb, fa = np.float64(r), np.float64(g), np.float64(b), np.float64(a)
    mode = info[slot, X_ENV]
    if mode == TEV_DECAL:
        ta = t3
        return ((fr * (255.0 - ta) + t0 * ta) / 255.0,
                (fg * (255.0 - ta) + t1 * ta) / 255.0,
                (fb * (255.0 - ta) + t2 * ta) / 255.0, fa)
    if mode == TEV_BLEND:
        return ((fr * (255.0 - t0) + env_colour[slot, 0] * t0) / 255.0,
                (fg * (255.0 - t1) + env_colour[slot, 1] * t1) / 255.0,
                (fb * (255.0 - t2) + env_colour[slot, 2] * t2) / 255.0,
                (fa * t3) / 255.0)
    return ((fr * t0) / 255.0, (fg * t1) / 255.0, (fb * t2) / 255.0,
            (fa * t3) / 255.0)


@jit
def decode_texcoords(ops, nops, fl, st0):
    """The texture coordinate (t2*) of every vertex of a command stream.

    Walks the stream as :func:`vgxsim.kernels.decode.decode_stream` does (same
    payload sizes), for streams that hold T ops only.

    Parameters
    ----------
    ops, nops, fl
        As for decode_stream.
    st0 : ndarray, shape (2,), float64
        In: s, t current at the start of the stream; out: at its end.

    Returns
    -------
    ndarray, shape (V, 2), float64
    """
    nv = 0
    i = 0
    while i < nops:
        op = ops[i]
        if op == V:
            nv += 1
        i += 1 + _int_payload(op)
    out = np.empty((nv, 2))
    s = st0[0]
    t = st0[1]
    iv = 0
    f = 0
    i = 0
    while i < nops:
        op = ops[i]
        if op == V:
            out[iv, 0] = s
            out[iv, 1] = t
            iv += 1
            f += 4
        elif op == T:
            s = fl[f]
            t = fl[f + 1]
            f += 2
        elif op == SYNC:
            f += 7
        elif op == C or op == CM or op == CSKIP or op == CRAW:
            f += 4
        elif op == N:
            f += 3
        i += 1 + _int_payload(op)
    st0[0] = s
    st0[1] = t
    return out
