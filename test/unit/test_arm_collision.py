"""Collision checks: the exact lowest point of each shape, the distance between segments,
the arm against the floor and itself (minus the SRDF's pairs), and along a joint-space line."""
import math

import numpy as np
import pytest

from arm_files import model, semantics
from wall_follower.arm.collision import CollisionChecker, lowest_point, segment_distance
from wall_follower.arm.kinematics import link_frames, rotation
from wall_follower.arm.model import Shape, transform


def checker(**margins):
    arm = model()
    return CollisionChecker(arm, semantics(arm).disabled, **margins)


def test_lowest_points_of_turned_shapes():
    cylinder = Shape('cylinder', (0.1, 0.4), np.eye(4))
    assert math.isclose(lowest_point(cylinder, transform((0, 0, 1))), 0.8)
    lying = rotation((0, 1, 0), math.pi / 2).dot(np.eye(4))
    lying[:3, 3] = (0, 0, 1)
    assert math.isclose(lowest_point(cylinder, lying), 0.9)
    box = Shape('box', (0.2, 0.2, 0.2), np.eye(4))
    tilted = rotation((1, 0, 0), math.pi / 4)
    assert math.isclose(lowest_point(box, tilted), -0.1 * math.sqrt(2))
    assert math.isclose(lowest_point(Shape('sphere', (0.3,), transform((0, 0, 0.5))),
                                     np.eye(4)), 0.2)


@pytest.mark.parametrize('a, b, distance', [
    (((0, 0, 0), (1, 0, 0)), ((0, 1, 0), (1, 1, 0)), 1.0),          # parallel
    (((0, 0, 0), (1, 0, 0)), ((0.5, -1, 1), (0.5, 1, 1)), 1.0),     # crossing above
    (((0, 0, 0), (1, 0, 0)), ((2, 0, 0), (3, 0, 0)), 1.0),          # end to end
    (((0, 0, 0), (0, 0, 0)), ((0, 3, 4), (0, 3, 4)), 5.0),          # two points
    (((0, 0, 0), (1, 0, 0)), ((0.5, 0, 0), (0.5, 1, 0)), 0.0),      # touching
])
def test_segment_distance(a, b, distance):
    a, b = [np.array(p, float) for p in a], [np.array(p, float) for p in b]
    assert math.isclose(segment_distance(a[0], a[1], b[0], b[1]), distance, abs_tol=1e-12)
    assert math.isclose(segment_distance(b[1], b[0], a[1], a[0]), distance, abs_tol=1e-12)


def test_the_named_states_are_clear():
    arm = model()
    check = checker()
    for state in semantics(arm).states.values():
        assert check.contacts([state[n] for n in arm.names]) == []


def test_a_hand_pushed_into_the_floor_is_seen():
    found = checker().contacts((0.0, 2.0, 0.8, 0.0))
    assert 'hand 0.096 m below the floor' in found
    assert any(sentence.startswith('lower_arm') for sentence in found)


def test_the_floor_margin_counts_a_hand_close_above_the_floor():
    arm = model()
    positions = (0.0, 2.0, 0.2, 0.0)
    low = lowest_point(arm.shapes['hand'][0], link_frames(arm, positions)['hand'])
    assert 0.0 < low < 0.1
    assert checker().contacts(positions) == []
    assert checker(floor_margin=low - 0.001).contacts(positions) == []
    assert checker(floor_margin=low + 0.001).contacts(positions) == [
        'hand %.3f m above the floor' % low]


def test_the_lower_arm_folded_onto_the_torso_is_a_self_collision():
    found = checker().contacts((0.0, 1.7, 2.5, 0.0))
    assert 'torso touches lower_arm' in found and 'torso touches hand' in found
    assert not any('floor' in sentence for sentence in found)


def test_adjacent_links_are_not_checked():
    # the elbow fully bent puts the lower arm against the upper arm: disabled, and clear of
    # everything else when the shoulder points it up and away
    assert checker().contacts((0.0, -1.2, 2.5, 0.0)) == []


def test_a_line_through_a_collision_is_caught_midway():
    """The wrist turning a low hand from forward to backward sweeps it through the floor."""
    start, goal = (0.0, 2.0, 0.4, -1.2), (0.0, 2.0, 0.4, 1.7)
    assert checker().contacts(start) == [] and checker().contacts(goal) == []
    found = checker().path_contacts(start, goal, 0.02)
    assert found is not None and 0.0 < found[0] < 1.0
    assert found[1][0].startswith('hand')
    assert checker().path_contacts((0.0, 0.0, 0.0, 0.0), (1.0, 0.6, 1.2, 0.8), 0.02) is None


def test_skipping_along_the_clearance_misses_no_contact_a_dense_walk_finds():
    """Lines between random clear poses with the hand low: the check that steps by what the
    clearance proves finds a contact wherever one every 0.01 rad does, and finds the line
    clear where it is."""
    arm = model()
    check = checker()
    rng = np.random.RandomState(6)
    low = np.array([arm.lower[0], 1.5, 0.3, arm.lower[3]])
    poses = []
    while len(poses) < 30:
        positions = rng.uniform(low, arm.upper)
        if not check.contacts(positions):
            poses.append(positions)
    blocked = 0
    for start, goal in zip(poses[::2], poses[1::2]):
        count = int(np.ceil(np.max(np.abs(goal - start)) / 0.01))
        dense = [f for f in np.linspace(0.0, 1.0, count + 1)
                 if check.contacts(start + (goal - start) * f)]
        found = check.path_contacts(start, goal, 0.01)
        assert (found is None) == (not dense)
        if dense:
            blocked += 1
            assert found[0] <= dense[0] + 1.0 / count
    assert 3 <= blocked <= 12
