"""wall_follower.rotation: the package's one wrap of angles and its rotations agree."""
import math

import numpy as np
import pytest

from wall_follower.rotation import (axis_angle_matrix, matrix_of_quaternion, quaternion_of_yaw,
                                    rpy_matrix, wrap_angle, yaw_of_quaternion)


@pytest.mark.parametrize('angle, wrapped', [
    (0.0, 0.0), (math.pi, -math.pi), (-math.pi, -math.pi), (3 * math.pi / 2, -math.pi / 2),
    (-7 * math.pi / 2, math.pi / 2), (20.0, 20.0 - 6 * math.pi)])
def test_wrap_takes_an_angle_into_minus_pi_to_pi(angle, wrapped):
    assert wrap_angle(angle) == pytest.approx(wrapped, abs=1e-12)
    assert isinstance(wrap_angle(angle), float)


def test_wrap_takes_arrays_alike():
    angles = np.array([0.0, 4.0, -4.0])
    assert wrap_angle(angles) == pytest.approx([0.0, 4.0 - 2 * math.pi, 2 * math.pi - 4.0])


@pytest.mark.parametrize('yaw', [0.0, 0.3, -2.5, math.pi - 1e-9])
def test_a_yaw_survives_a_quaternion(yaw):
    z, w = quaternion_of_yaw(yaw)
    assert yaw_of_quaternion(0.0, 0.0, z, w) == pytest.approx(yaw)
    assert matrix_of_quaternion((0.0, 0.0, z, w)) == pytest.approx(
        axis_angle_matrix((0.0, 0.0, 1.0), yaw))


def test_roll_pitch_yaw_turn_about_fixed_axes_in_that_order():
    roll, pitch, yaw = 0.2, -0.4, 1.1
    expected = (axis_angle_matrix((0, 0, 1), yaw).dot(axis_angle_matrix((0, 1, 0), pitch))
                .dot(axis_angle_matrix((1, 0, 0), roll)))
    assert rpy_matrix(roll, pitch, yaw) == pytest.approx(expected)


def test_a_quaternion_is_normalised_first():
    assert matrix_of_quaternion((0.0, 0.0, 2.0, 0.0)) == pytest.approx(
        np.diag([-1.0, -1.0, 1.0]))
