"""Error of a rendered shadow against the exact ray-cast reference.

The metrics shared/reference/shadow_literature.md section 3.2 recommends:

* misclassified pixels, split into **false lit** (rendered lit, reference in shadow)
  and **false shadow** (the reverse), and into **boundary** pixels -- within one pixel
  (8-neighbourhood) of a place where the reference's class changes, where snapping
  and tie rules may legitimately decide the other way -- and **interior** pixels,
  which must be 0 for an exact technique (issue 9, item 3);
* a histogram of **count errors**, rendered stencil count minus the reference's
  crossing count, which shows a crack (a +-1 line, H6) even where the binary mask
  happens to be right.

Masks are compared only where the reference sees a surface (a stencil value over the
background shades nothing); the reference's classes for the boundary are
background / shadow / lit, so an object's outline against the background is a
boundary too.  Counts are compared on every pixel unless told otherwise, with the
boundary taken where the reference count changes.

All arrays are (H, W) with row 0 at the bottom, as the framebuffer planes and
:class:`vgxsim.shadow.raycast.RayCastResult`.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass

import numpy as np


def near_boundary(classes: np.ndarray) -> np.ndarray:
    """Pixels within one pixel (8-neighbourhood) of a change of class.

    Parameters
    ----------
    classes : ndarray, shape (H, W), int
        Any labelling (pixels outside the image count as equal to their neighbour).

    Returns
    -------
    ndarray, shape (H, W), bool
        True where some pixel of the 3 x 3 neighbourhood has another class.
    """
    c = np.asarray(classes)
    if c.ndim != 2:
        raise ValueError(f"classes must be (H, W), not shape {c.shape}")
    p = np.pad(c, 1, mode="edge")
    h, w = c.shape
    out = np.zeros(c.shape, dtype=bool)
    for dy in (-1, 0, 1):
        for dx in (-1, 0, 1):
            out |= p[1 + dy:1 + dy + h, 1 + dx:1 + dx + w] != c
    return out


@dataclass(frozen=True)
class MaskError:
    """Misclassified pixels of one light's lit/shadow mask.

    Attributes
    ----------
    compared : int
        Pixels compared (the reference sees a surface there).
    boundary_pixels : int
        Compared pixels within one pixel of a reference boundary.
    misclassified, interior, boundary : int
        Wrong pixels: all, away from boundaries, on boundaries.
    false_lit, false_shadow : int
        Wrong pixels rendered lit (reference: shadow), and rendered in shadow.
    false_lit_interior, false_shadow_interior : int
        The same, away from boundaries.
    """

    compared: int
    boundary_pixels: int
    misclassified: int
    interior: int
    boundary: int
    false_lit: int
    false_shadow: int
    false_lit_interior: int
    false_shadow_interior: int

    @property
    def rate(self) -> float:
        """Misclassified fraction of the compared pixels (0 when none compared)."""
        return self.misclassified / self.compared if self.compared else 0.0

    def as_dict(self) -> dict[str, int]:
        return asdict(self)


@dataclass(frozen=True)
class CountError:
    """Stencil count against the reference crossing count.

    Attributes
    ----------
    compared, boundary_pixels : int
        Pixels compared, and those within one pixel of a change of reference count.
    mismatched, interior, boundary : int
        Pixels whose count differs: all, away from boundaries, on boundaries.
    histogram : dict of int to int
        Rendered minus reference count -> number of pixels (0 included).
    interior_histogram : dict of int to int
        The same over interior pixels only.
    """

    compared: int
    boundary_pixels: int
    mismatched: int
    interior: int
    boundary: int
    histogram: dict[int, int]
    interior_histogram: dict[int, int]


def _check(name: str, a: np.ndarray, shape: tuple[int, ...]) -> np.ndarray:
    a = np.asarray(a)
    if a.shape != shape:
        raise ValueError(f"{name} has shape {a.shape}, expected {shape}")
    return a


def _histogram(values: np.ndarray) -> dict[int, int]:
    keys, n = np.unique(values.astype(np.int64), return_counts=True)
    return {int(k): int(c) for k, c in zip(keys, n, strict=True)}


def mask_error(rendered_lit: np.ndarray, reference_lit: np.ndarray,
               visible: np.ndarray) -> MaskError:
    """Compare a rendered lit mask with the reference's, for one light.

    Parameters
    ----------
    rendered_lit : ndarray, shape (H, W), bool
        True where the technique lights the pixel (for a stencil technique: the
        stencil equals its zero).
    reference_lit : ndarray, shape (H, W), bool
        ``RayCastResult.lit[..., light]``.
    visible : ndarray, shape (H, W), bool
        ``RayCastResult.hit``: pixels where the reference sees a surface.

    Returns
    -------
    MaskError
    """
    ref = np.asarray(reference_lit, dtype=bool)
    if ref.ndim != 2:
        raise ValueError(f"reference_lit must be (H, W), not shape {ref.shape}")
    got = _check("rendered_lit", rendered_lit, ref.shape).astype(bool)
    vis = _check("visible", visible, ref.shape).astype(bool)
    edge = near_boundary(np.where(vis, ref.astype(np.int8), np.int8(-1))) & vis
    wrong = vis & (got != ref)
    fl = wrong & got
    fs = wrong & ~got
    return MaskError(compared=int(vis.sum()), boundary_pixels=int(edge.sum()),
                     misclassified=int(wrong.sum()), interior=int((wrong & ~edge).sum()),
                     boundary=int((wrong & edge).sum()), false_lit=int(fl.sum()),
                     false_shadow=int(fs.sum()), false_lit_interior=int((fl & ~edge).sum()),
                     false_shadow_interior=int((fs & ~edge).sum()))


def count_error(rendered: np.ndarray, reference: np.ndarray,
                where: np.ndarray | None = None) -> CountError:
    """Compare rendered stencil counts with the reference's crossing counts.

    Parameters
    ----------
    rendered : ndarray, shape (H, W), int
        Stencil value minus the technique's zero (e.g. ``stencil - 128`` for the
        article's MYZERO).
    reference : ndarray, shape (H, W), int
        ``RayCastResult.crossings[..., light]`` (z-pass) or the count the technique
        should hold (``layers`` for z-fail).
    where : ndarray, shape (H, W), bool, optional
        Pixels to compare (default: all).

    Returns
    -------
    CountError
    """
    ref = np.asarray(reference)
    if ref.ndim != 2:
        raise ValueError(f"reference must be (H, W), not shape {ref.shape}")
    got = _check("rendered", rendered, ref.shape).astype(np.int64)
    ref = ref.astype(np.int64)
    sel = (np.ones(ref.shape, bool) if where is None
           else _check("where", where, ref.shape).astype(bool))
    edge = near_boundary(ref) & sel
    diff = got - ref
    bad = sel & (diff != 0)
    inner = sel & ~edge
    return CountError(compared=int(sel.sum()), boundary_pixels=int(edge.sum()),
                      mismatched=int(bad.sum()), interior=int((bad & ~edge).sum()),
                      boundary=int((bad & edge).sum()), histogram=_histogram(diff[sel]),
                      interior_histogram=_histogram(diff[inner]))


def shadow_error(rendered_lit: np.ndarray, result, light: int) -> MaskError:
    """:func:`mask_error` against a :class:`~vgxsim.shadow.raycast.RayCastResult`."""
    return mask_error(rendered_lit, result.lit[..., light], result.hit)
