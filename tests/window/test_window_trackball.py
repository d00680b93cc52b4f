"""The trackball against geometry computed here: sphere points, angles, scipy's
quaternions."""

from __future__ import annotations

import math

import numpy as np
import pytest

from vgxsim.shadow.trackball import TRACKBALL_SIZE, add_quats, rotation_matrix, trackball

Rotation = pytest.importorskip("scipy.spatial.transform").Rotation


def _on_sphere(x, y, r=TRACKBALL_SIZE):
    return np.array([x, y, math.sqrt(r * r - x * x - y * y)])


@pytest.mark.parametrize("p1, p2", [((0.0, 0.0), (0.2, 0.0)), ((0.1, -0.2), (-0.15, 0.3)),
                                    ((0.3, 0.3), (0.31, 0.25))])
def test_the_point_under_the_mouse_follows_it(p1, p2):
    """Inside the sphere part the drag's rotation takes the sphere point under the first
    position to the one under the second, by the angle between them."""
    a, b = _on_sphere(*p1), _on_sphere(*p2)
    q = trackball(*p1, *p2)
    m = rotation_matrix(q)[:3, :3]
    np.testing.assert_allclose(a @ m, b, atol=1e-12)  # row vectors, as multmatrix
    angle = math.acos(np.dot(a, b) / (TRACKBALL_SIZE ** 2))
    assert 2 * math.acos(q[3]) == pytest.approx(angle, abs=1e-12)


def test_no_motion_is_no_rotation():
    assert trackball(0.3, 0.1, 0.3, 0.1) == (0.0, 0.0, 0.0, 1.0)


def test_far_drags_stay_finite_on_the_hyperbolic_sheet():
    q = trackball(-3.0, 0.0, 3.0, 0.5)
    assert math.isclose(sum(c * c for c in q), 1.0) and all(map(math.isfinite, q))


def test_matrix_and_composition_match_scipy():
    rng = np.random.default_rng(4)
    q1, q2 = (tuple(Rotation.random(random_state=rng).as_quat()) for _ in range(2))
    # scipy's matrices act on column vectors; IRIS GL's row vectors use the transpose
    np.testing.assert_allclose(rotation_matrix(q1)[:3, :3],
                               Rotation.from_quat(q1).as_matrix().T, atol=1e-12)
    both = Rotation.from_quat(q2) * Rotation.from_quat(q1)  # q1 first, then q2
    np.testing.assert_allclose(rotation_matrix(add_quats(q1, q2))[:3, :3],
                               both.as_matrix().T, atol=1e-12)
