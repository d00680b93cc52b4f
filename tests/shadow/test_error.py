"""Shadow error metrics on hand-made masks (counts worked out by hand below)."""

from __future__ import annotations

import numpy as np
import pytest

from vgxsim.shadow.error import count_error, mask_error, near_boundary


def test_boundary_is_the_8_neighbourhood_of_a_class_change():
    c = np.zeros((5, 6), int)
    c[:, 3:] = 1  # a vertical change between columns 2 and 3
    b = near_boundary(c)
    assert b[:, 2:4].all() and not b[:, [0, 1, 4, 5]].any()
    # a single odd pixel marks its whole 3 x 3 neighbourhood, diagonals included
    d = np.zeros((5, 5), int)
    d[2, 2] = 7
    assert near_boundary(d).sum() == 9 and near_boundary(d)[1:4, 1:4].all()
    assert not near_boundary(np.zeros((3, 3), int)).any()


def test_mask_error_splits_interior_boundary_false_lit_and_false_shadow():
    # reference: 6 x 8, columns 0-3 lit, 4-7 in shadow, top row background
    ref = np.zeros((6, 8), bool)
    ref[:, :4] = True
    vis = np.ones((6, 8), bool)
    vis[5, :] = False
    got = ref.copy()
    got[1, 0] = False   # interior, false shadow
    got[2, 6] = True    # interior, false lit
    got[0, 3] = False   # boundary (next to column 4), false shadow
    got[3, 4] = True    # boundary, false lit
    got[4, 7] = True    # boundary: next to the background row; false lit
    got[5, 6] = True    # background: not compared
    e = mask_error(got, ref, vis)
    assert e.compared == 40
    # boundary pixels: columns 3-4 of the 5 visible rows (10) plus row 4 next to the
    # background row (8 pixels, 2 of them already counted) = 16
    assert e.boundary_pixels == 16
    assert (e.misclassified, e.interior, e.boundary) == (5, 2, 3)
    assert (e.false_lit, e.false_shadow) == (3, 2)
    assert (e.false_lit_interior, e.false_shadow_interior) == (1, 1)
    assert e.rate == pytest.approx(5 / 40)
    assert mask_error(ref, ref, vis).misclassified == 0


def test_count_error_histogram():
    ref = np.zeros((4, 6), int)
    ref[:, 3:] = 1
    got = ref.copy()
    got[0, 0] = -1      # interior, -1
    got[3, 5] = 3       # interior, +2
    got[1, 2] = 2       # boundary, +2
    e = count_error(got, ref)
    assert (e.compared, e.boundary_pixels) == (24, 8)
    assert (e.mismatched, e.interior, e.boundary) == (3, 2, 1)
    assert e.histogram == {-1: 1, 0: 21, 2: 2}
    assert e.interior_histogram == {-1: 1, 0: 14, 2: 1}  # 16 interior pixels, 2 wrong
    where = np.ones((4, 6), bool)
    where[0, 0] = False
    e2 = count_error(got, ref, where)
    assert e2.compared == 23 and e2.histogram == {0: 21, 2: 2}


def test_shapes_are_checked():
    with pytest.raises(ValueError, match="rendered_lit has shape"):
        mask_error(np.zeros((2, 3), bool), np.zeros((3, 2), bool), np.ones((3, 2), bool))
    with pytest.raises(ValueError, match="must be"):
        count_error(np.zeros(3), np.zeros(3))
