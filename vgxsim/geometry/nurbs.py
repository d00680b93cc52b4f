"""NURBS evaluation and trimming, pure functions for vgxsim.gl._nurbs.

B-spline basis functions by the Cox-de Boor recursion (de Boor, "A Practical Guide
to Splines", ch. IX): for knots ``t`` and order ``k`` (degree ``k - 1``) there are
``len(t) - k`` basis functions, nonzero on ``[t[i], t[i + k])``; the curve's domain
is ``[t[k - 1], t[n]]`` with ``n`` control points.  Control points are homogeneous
(IRIS N_XYZW / N_STW give ``(w x, w y, w z, w)``), so a rational curve is
``sum N_i P_i`` followed by the divide.

Trimming (bgntrim(3G)): each trim loop is a closed polyline in the (s, t) parameter
plane; the part of the surface "on the left" of a loop as it is traversed is kept,
so an outer loop runs counter-clockwise and a hole clockwise.  The kept region is
where the loops' total winding number is positive (:func:`winding_numbers`).
"""

from __future__ import annotations

import numpy as np


def domain(knots: np.ndarray, order: int, ncontrol: int) -> tuple[float, float]:
    """The parameter interval ``[t[k - 1], t[n]]`` on which the basis sums to one."""
    return float(knots[order - 1]), float(knots[ncontrol])


def basis_matrix(knots: np.ndarray, order: int, ts: np.ndarray) -> np.ndarray:
    """Values of every B-spline basis function at each parameter.

    Parameters
    ----------
    knots : ndarray, shape (m,), float64, nondecreasing
    order : int
        k >= 1.
    ts : ndarray, shape (p,), float64
        Parameters inside the domain; the domain's right end belongs to the last
        non-empty span (so the basis still sums to one there).

    Returns
    -------
    ndarray, shape (p, m - order), float64
    """
    t = np.asarray(knots, dtype=np.float64)
    x = np.asarray(ts, dtype=np.float64)
    m = t.shape[0]
    # Order 1: the indicator of the span holding x; a right end goes to the last
    # non-empty span that ends there.
    n = np.zeros((x.shape[0], m - 1))
    for i in range(m - 1):
        if t[i] < t[i + 1]:
            n[:, i] = (t[i] <= x) & (x < t[i + 1])
    nonempty = np.nonzero(t[1:] > t[:-1])[0]
    if nonempty.size:
        last = nonempty[-1]
        n[x == t[last + 1], :] = 0.0
        n[x == t[last + 1], last] = 1.0
    for k in range(2, order + 1):
        nk = np.zeros((x.shape[0], m - k))
        for i in range(m - k):
            d1 = t[i + k - 1] - t[i]
            d2 = t[i + k] - t[i + 1]
            if d1 > 0:
                nk[:, i] += (x - t[i]) / d1 * n[:, i]
            if d2 > 0:
                nk[:, i] += (t[i + k] - x) / d2 * n[:, i + 1]
        n = nk
    return n


def basis_derivative_matrix(knots: np.ndarray, order: int, ts: np.ndarray) -> np.ndarray:
    """First derivatives of the basis functions, shape (p, m - order):
    ``N'_{i,k} = (k-1) [N_{i,k-1} / (t_{i+k-1} - t_i) - N_{i+1,k-1} / (t_{i+k} - t_{i+1})]``.
    """
    t = np.asarray(knots, dtype=np.float64)
    if order < 2:
        return np.zeros((len(ts), t.shape[0] - order))
    low = basis_matrix(t, order - 1, ts)  # (p, m - k + 1)
    k = order
    out = np.zeros((low.shape[0], t.shape[0] - k))
    for i in range(t.shape[0] - k):
        d1 = t[i + k - 1] - t[i]
        d2 = t[i + k] - t[i + 1]
        if d1 > 0:
            out[:, i] += (k - 1) / d1 * low[:, i]
        if d2 > 0:
            out[:, i] -= (k - 1) / d2 * low[:, i + 1]
    return out


def surface_points(control: np.ndarray, sknots: np.ndarray, tknots: np.ndarray,
                   sorder: int, torder: int, ss: np.ndarray, ts: np.ndarray
                   ) -> tuple[np.ndarray, np.ndarray]:
    """Homogeneous surface points and unit normals on the grid ``ss`` x ``ts``.

    Parameters
    ----------
    control : ndarray, shape (ns, nt, 4)
        Homogeneous control points, ``control[a, b]`` at s index a, t index b.

    Returns
    -------
    points : ndarray, shape (len(ss), len(ts), 4)
    normals : ndarray, shape (len(ss), len(ts), 3)
        ``dS/ds x dS/dt`` of the projected (divided) surface, normalised (zero where
        the surface is degenerate).
    """
    ns_ = basis_matrix(sknots, sorder, ss)
    nt_ = basis_matrix(tknots, torder, ts)
    ds_ = basis_derivative_matrix(sknots, sorder, ss)
    dt_ = basis_derivative_matrix(tknots, torder, ts)
    p = np.einsum("ia,abc,jb->ijc", ns_, control, nt_)
    ps = np.einsum("ia,abc,jb->ijc", ds_, control, nt_)
    pt = np.einsum("ia,abc,jb->ijc", ns_, control, dt_)
    w = p[..., 3:4]
    safe = np.where(w == 0, 1.0, w)
    # Quotient rule: d(X / w) = (dX w - X dw) / w^2 (the 1 / w^2 does not change the
    # normal's direction, only its length, so it is left out).
    du = ps[..., :3] * safe - p[..., :3] * ps[..., 3:4]
    dv = pt[..., :3] * safe - p[..., :3] * pt[..., 3:4]
    nrm = np.cross(du, dv)
    length = np.linalg.norm(nrm, axis=-1, keepdims=True)
    nrm = np.where(length > 0, nrm / np.where(length > 0, length, 1.0), 0.0)
    return p, nrm


def curve_points(control: np.ndarray, knots: np.ndarray, order: int, ts: np.ndarray
                 ) -> np.ndarray:
    """Homogeneous curve points ``sum N_i(t) P_i``: shape (len(ts), control.shape[1])."""
    return basis_matrix(knots, order, ts) @ np.asarray(control, dtype=np.float64)


def winding_numbers(points: np.ndarray, loops: list[np.ndarray]) -> np.ndarray:
    """Total winding number of the closed polylines ``loops`` around each point.

    Parameters
    ----------
    points : ndarray, shape (P, 2)
    loops : list of ndarray, shape (L_i, 2)
        Each loop's vertices in order; the last joins the first.

    Returns
    -------
    ndarray, shape (P,), int64
        Counter-clockwise loops count +1 inside, clockwise loops -1 (the crossing
        rule: an upward edge with the point on its left adds one, a downward edge with
        the point on its right subtracts one).
    """
    pts = np.asarray(points, dtype=np.float64)
    wn = np.zeros(pts.shape[0], np.int64)
    px, py = pts[:, 0], pts[:, 1]
    for loop in loops:
        a = np.asarray(loop, dtype=np.float64)
        b = np.roll(a, -1, axis=0)
        for (ax, ay), (bx, by) in zip(a, b, strict=True):
            side = (bx - ax) * (py - ay) - (px - ax) * (by - ay)
            up = (ay <= py) & (by > py) & (side > 0)
            down = (ay > py) & (by <= py) & (side < 0)
            wn += up.astype(np.int64) - down.astype(np.int64)
    return wn


def surface_at(control: np.ndarray, sknots: np.ndarray, tknots: np.ndarray, sorder: int,
               torder: int, ss: np.ndarray, ts: np.ndarray) -> np.ndarray:
    """Homogeneous surface points at the parameter pairs ``(ss[i], ts[i])``:
    shape (len(ss), 4)."""
    ns_ = basis_matrix(sknots, sorder, ss)
    nt_ = basis_matrix(tknots, torder, ts)
    return np.einsum("ia,abc,ib->ic", ns_, control, nt_)
