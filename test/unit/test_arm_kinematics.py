"""Forward kinematics against the URDF's dimensions; inverse kinematics round trips (the
hand origin within 1 mm, every joint within its limits, the solution nearest the current
joints)."""
import math

import numpy as np
import pytest

from arm_files import model
from wall_follower.arm.kinematics import (arm_solutions, inverse, link_frames,
                                          planar_dimensions, tool_position)

# From the URDF: base 0.05 high, torso 0.5 (to the shoulder), upper and lower arm 0.4 each.
SHOULDER_HEIGHT = 0.55
UPPER = LOWER = 0.4


def planar_tool_position(dimensions, positions):
    """The hand origin by the planar arm's trigonometry, with no matrices (an oracle for
    tool_position and the triples of arm_solutions)."""
    hip, shoulder, elbow = positions[0], positions[1], positions[2]
    reach = dimensions.upper * math.sin(shoulder) + dimensions.lower * math.sin(shoulder + elbow)
    height = dimensions.height + dimensions.upper * math.cos(shoulder) + \
        dimensions.lower * math.cos(shoulder + elbow)
    return np.array([reach * math.cos(hip), reach * math.sin(hip), height])


@pytest.mark.parametrize('positions, hand', [
    ((0.0, 0.0, 0.0, 0.0), (0.0, 0.0, 1.35)),
    ((0.0, math.pi / 2, 0.0, 0.0), (0.8, 0.0, 0.55)),
    ((math.pi / 2, math.pi / 2, 0.0, 1.0), (0.0, 0.8, 0.55)),
    ((0.0, math.pi / 2, -math.pi / 2, 0.3), (0.4, 0.0, 0.95)),
    ((-math.pi / 2, 0.5, 1.0, -1.0), (0.0, -(0.4 * math.sin(0.5) + 0.4 * math.sin(1.5)),
                                      0.55 + 0.4 * math.cos(0.5) + 0.4 * math.cos(1.5))),
])
def test_forward_kinematics_puts_the_hand_where_the_urdf_says(positions, hand):
    arm = model()
    assert np.allclose(tool_position(arm, positions), hand, atol=1e-12)
    assert np.allclose(planar_tool_position(planar_dimensions(arm), positions), hand)


def test_each_link_frame_sits_on_its_joint():
    arm = model()
    frames = link_frames(arm, (0.3, 0.4, 0.5, 0.6))
    assert np.allclose(frames['base_link'], np.eye(4))
    assert np.allclose(frames['torso'][:3, 3], (0, 0, 0.05))
    assert np.allclose(frames['upper_arm'][:3, 3], (0, 0, SHOULDER_HEIGHT))
    elbow = frames['lower_arm'][:3, 3]
    assert math.isclose(np.linalg.norm(elbow - frames['upper_arm'][:3, 3]), UPPER)
    # the wrist turns the hand about the hand's origin, not moving it
    assert np.allclose(tool_position(arm, (0.3, 0.4, 0.5, -1.0)), frames['hand'][:3, 3])
    # a yaw of the hip and pitches after it: the hand's y axis stays horizontal
    assert math.isclose(frames['hand'][2, 1], 0.0, abs_tol=1e-12)


def test_the_closed_form_reads_its_dimensions_from_the_model():
    assert planar_dimensions(model()) == pytest.approx((SHOULDER_HEIGHT, UPPER, LOWER))


def test_inverse_kinematics_round_trips_on_a_thousand_random_reachable_points():
    arm = model()
    dimensions = planar_dimensions(arm)
    rng = np.random.RandomState(28)
    worst = 0.0
    for _ in range(1000):
        point = tool_position(arm, rng.uniform(arm.lower, arm.upper))
        current = rng.uniform(arm.lower, arm.upper)
        solutions, reason = inverse(arm, dimensions, point, current)
        assert solutions, reason
        for solution in solutions:
            assert not arm.outside_limits(solution)
            worst = max(worst, np.linalg.norm(tool_position(arm, solution) - point))
        assert solutions[0][3] == current[3]    # the wrist is kept
        cost = [np.max(np.abs(s - current) / arm.velocity) for s in solutions]
        assert cost[0] == min(cost)
    assert worst < 1e-3


def test_every_pose_reaching_a_point_is_found():
    """Reaching over the top and both elbow bends: four poses in front of the arm."""
    dimensions = planar_dimensions(model())
    point = (0.3, 0.2, 0.8)
    found = arm_solutions(dimensions, point, 0.0)
    assert len(found) == 4
    for hip, shoulder, elbow in found:
        assert np.allclose(planar_tool_position(dimensions, (hip, shoulder, elbow, 0.0)), point)


def test_the_nearest_solution_keeps_the_elbow_bent_the_way_it_is():
    arm = model()
    dimensions = planar_dimensions(arm)
    point = tool_position(arm, (0.2, 0.6, 1.0, 0.0))
    assert inverse(arm, dimensions, point, (0.0, 0.5, 0.9, 0.0))[0][0][2] > 0
    assert inverse(arm, dimensions, point, (0.0, 1.5, -0.9, 0.0))[0][0][2] < 0


def test_a_point_on_the_vertical_axis_keeps_the_hip_where_it_is():
    arm = model()
    solutions, _ = inverse(arm, planar_dimensions(arm), (0.0, 0.0, 1.0), (0.7, 0, 0, 0))
    assert solutions and all(s[0] == 0.7 for s in solutions)


@pytest.mark.parametrize('point, words', [
    ((2.0, 0.0, 0.5), 'out of reach'),
    ((0.0, 0.0, 1.36), 'out of reach'),
    ((0.0, 0.0, 0.56), 'joint limits'),     # needs the elbow folded flat
])
def test_an_unreachable_point_says_why(point, words):
    arm = model()
    solutions, reason = inverse(arm, planar_dimensions(arm), point, np.zeros(4))
    assert solutions == [] and words in reason
