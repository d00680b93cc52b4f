"""Points and lines expanded to fragments (docs/numeric_model.md section 5).

IRIS GL draws lines closed without subpixel and half-open with it (subpixel(3G));
the pixel chosen in each column (x-major) or row (y-major) is found with exact
integer arithmetic on the fixed-point endpoints, so ties go the same way everywhere.
"""

from __future__ import annotations

import numpy as np

from .clip import ONE
from .fragment import round_c, round_z
from .options import inline, jit


@inline
def _floor_div(n, d):
    if d < 0:
        n = -n
        d = -d
    return n // d


@inline
def _line_count(xa, ya, xb, yb, closed, width):
    dx = xb - xa
    dy = yb - ya
    if abs(dx) >= abs(dy):
        s = (xa + ONE // 2) // ONE
        e = (xb + ONE // 2) // ONE
    else:
        s = (ya + ONE // 2) // ONE
        e = (yb + ONE // 2) // ONE
    n = abs(e - s) + (1 if closed else 0)
    return n * width


@jit
def count_line_fragments(seg_xf, seg_yf, closed, width):
    """Upper bound of fragments for segments (N, 2) of fixed endpoints."""
    total = 0
    for i in range(seg_xf.shape[0]):
        total += _line_count(seg_xf[i, 0], seg_yf[i, 0], seg_xf[i, 1], seg_yf[i, 1],
                             closed, width)
    return total


@jit
def line_steps(seg_xf, seg_yf):
    """Major-axis steps of each segment (N, 2) of fixed endpoints: the pixels a
    line-style pattern advances over it (deflinestyle(3G): one bit per pixel drawn;
    the shared vertex of two segments of a polyline is one pixel), the same count
    :func:`line_fragments` steps through.

    Returns
    -------
    ndarray, shape (N,), int64
    """
    out = np.empty(seg_xf.shape[0], np.int64)
    for i in range(seg_xf.shape[0]):
        out[i] = _line_count(seg_xf[i, 0], seg_yf[i, 0], seg_xf[i, 1], seg_yf[i, 1],
                             False, 1)
    return out


@jit
def line_fragments(seg_xf, seg_yf, seg_z, seg_c, pattern_start, closed, width, pattern,
                   repeat, always_from, out_xy, out_z, out_c, offset):
    """Expand line segments into fragments.

    Parameters
    ----------
    seg_xf, seg_yf : ndarray, shape (N, 2), int64
        Fixed-point endpoints of each segment.
    seg_z : ndarray, shape (N, 2), float64
        Window depth at the endpoints.
    seg_c : ndarray, shape (N, 2, 4), float64
        RGBA at the endpoints, already scaled to 0..255 (flat: both ends equal).
    pattern_start : ndarray, shape (N,), int64
        Line-style position of each segment's first pixel.
    closed : bool
        Draw the last pixel (subpixel off) or not (subpixel on).
    width : int
        Line width in pixels, replicated across the minor axis.
    pattern, repeat : int
        16-bit line style (bit 0 first) and lsrepeat factor.
    always_from : int
        Pixels at line-style positions from this one on are drawn whatever their
        pattern bit (lsbackup(3G): the last two pixels of a line); a position no line
        reaches to leave the pattern alone.
    out_xy, out_z, out_c : ndarray
        Output arrays, shapes (F, 2) int64, (F,) int64, (F,) int64 packed RGBA.
    offset : int
        First free output slot.

    Returns
    -------
    int
        New number of used output slots.
    """
    n = offset
    lo_off = -((width - 1) // 2)
    for i in range(seg_xf.shape[0]):
        xa, ya, xb, yb = seg_xf[i, 0], seg_yf[i, 0], seg_xf[i, 1], seg_yf[i, 1]
        dx = xb - xa
        dy = yb - ya
        xmajor = abs(dx) >= abs(dy)
        if xmajor:
            s = (xa + ONE // 2) // ONE
            e = (xb + ONE // 2) // ONE
        else:
            s = (ya + ONE // 2) // ONE
            e = (yb + ONE // 2) // ONE
        step = 1 if e >= s else -1
        count = abs(e - s) + (1 if closed else 0)
        za, zb = seg_z[i, 0], seg_z[i, 1]
        zlo = min(np.int64(np.floor(za + 0.5)), np.int64(np.floor(zb + 0.5)))
        zhi = max(np.int64(np.floor(za + 0.5)), np.int64(np.floor(zb + 0.5)))
        major0 = (xa if xmajor else ya) / ONE
        span = (dx if xmajor else dy) / ONE
        for k in range(count):
            m = s + k * step
            pos = pattern_start[i] + k
            if pos < always_from and ((pattern >> ((pos // repeat) % 16)) & 1) == 0:
                continue
            # Minor coordinate: floor(minor(m) + 0.5), exactly, in fixed point.
            if xmajor:
                if dx == 0:
                    minor = (ya + ONE // 2) // ONE
                else:
                    minor = _floor_div(ya * dx + (m * ONE - xa) * dy + (ONE // 2) * dx, ONE * dx)
            else:
                minor = _floor_div(xa * dy + (m * ONE - ya) * dx + (ONE // 2) * dy, ONE * dy)
            f = 0.0 if span == 0.0 else (m - major0) / span
            zi = round_z(za + (zb - za) * f, zlo, zhi)
            rgba = 0
            for ch in range(4):
                ca = seg_c[i, 0, ch]
                rgba |= round_c(ca + (seg_c[i, 1, ch] - ca) * f) << (8 * ch)
            for w in range(width):
                if xmajor:
                    out_xy[n, 0] = m
                    out_xy[n, 1] = minor + lo_off + w
                else:
                    out_xy[n, 0] = minor + lo_off + w
                    out_xy[n, 1] = m
                out_z[n] = zi
                out_c[n] = rgba
                n += 1
    return n


@jit
def point_fragments(xf, yf, z, c, size, out_xy, out_z, out_c, offset):
    """Expand points (size x size blocks) into fragments.

    Parameters
    ----------
    xf, yf : ndarray, shape (N,), int64
        Fixed-point positions.
    z : ndarray, shape (N,), float64
    c : ndarray, shape (N, 4), float64
        RGBA scaled to 0..255.
    size : int
    out_xy, out_z, out_c, offset
        As for :func:`line_fragments`.
    """
    n = offset
    lo = -((size - 1) // 2)
    for i in range(xf.shape[0]):
        x = (xf[i] + ONE // 2) // ONE
        y = (yf[i] + ONE // 2) // ONE
        zr = np.int64(np.floor(z[i] + 0.5))
        rgba = 0
        for ch in range(4):
            rgba |= round_c(c[i, ch]) << (8 * ch)
        for dy in range(size):
            for dx in range(size):
                out_xy[n, 0] = x + lo + dx
                out_xy[n, 1] = y + lo + dy
                out_z[n] = zr
                out_c[n] = rgba
                n += 1
    return n
