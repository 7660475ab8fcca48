"""OdomCheck: odometry that cannot be trusted is named, each problem once."""
import math

import pytest

from wall_follower.control.course.odom_check import OdomCheck

UNIT = (0.0, 0.0, 0.0, 1.0)


def test_odometry_of_a_robot_driving_at_its_speed_is_trusted():
    check = OdomCheck(max_speed=0.5, allowance=0.1)
    assert all(check.problem(0.1 * i, 0.019 * i, 0.0, *UNIT) is None for i in range(50))
    assert check.broken is None


@pytest.mark.parametrize('pose, words', [
    ((math.nan, 0.0) + UNIT, 'position (nan, 0.0) is not finite'),
    ((0.0, math.inf) + UNIT, 'position (0.0, inf) is not finite'),
    ((0.0, 0.0, 0.0, 0.0, math.nan, 1.0), 'is not a unit quaternion'),
    ((0.0, 0.0, 0.0, 0.0, 0.0, 0.0), 'orientation (0.0, 0.0, 0.0, 0.0) is not a unit quaternion'),
])
def test_a_pose_that_is_not_finite_or_has_no_heading_is_named(pose, words):
    check = OdomCheck()
    assert check.problem(0.0, 0.0, 0.0, *UNIT) is None
    assert words in check.problem(0.1, *pose)
    # It is not the reference: the next good pose is checked against the last good one.
    assert check.problem(0.2, 0.01, 0.0, *UNIT) is None
    assert check.broken is None


def test_a_jump_is_named_once_and_breaks_the_frame():
    check = OdomCheck(max_speed=0.5, allowance=0.1)
    assert check.problem(0.0, 0.0, 0.0, *UNIT) is None
    problem = check.problem(0.1, 5.0, 0.0, *UNIT)
    assert problem.startswith('it jumped 5.00 m, further than the robot can drive at 0.50 m/s')
    assert check.problem(0.2, 5.01, 0.0, *UNIT) is None
    assert check.broken == problem
    check.reset()
    assert check.broken is None


def test_time_going_back_is_named_as_such():
    check = OdomCheck()
    assert check.problem(10.0, 0.0, 0.0, *UNIT) is None
    problem = check.problem(4.0, 0.0, 0.0, *UNIT)
    assert problem == 'its time went back 6.00 s (from 10.00 s to 4.00 s)'
    assert check.problem(4.1, 0.01, 0.0, *UNIT) is None
    assert check.broken == problem


def test_a_stamp_that_is_not_finite_is_named():
    assert 'stamp nan is not finite' in OdomCheck().problem(math.nan, 0.0, 0.0, *UNIT)
