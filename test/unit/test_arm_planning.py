"""Planned moves: to named states and points, the wrist kept, and every goal that cannot
be planned refused with the reason."""
import numpy as np
import pytest

from arm_files import limits, model, semantics
from wall_follower.arm.collision import CollisionChecker
from wall_follower.arm.kinematics import tool_position
from wall_follower.arm.planning import (MIN_VELOCITY_SCALING, Planner, PlanningError,
                                        velocity_factor)
from wall_follower.arm.timing import TimedMove


def planner(**options):
    arm = model()
    velocity, acceleration = limits(arm)
    return Planner(arm, semantics(arm), acceleration, velocity, **options)


def test_a_named_state_is_planned_to_its_joints():
    plan = planner().to_state('ready', np.zeros(4))
    assert np.allclose(plan.goal, [0.0, 0.6, 1.2, 0.8])
    assert np.allclose(plan.move.sample(plan.move.duration)[0], plan.goal)


def test_a_point_is_planned_keeping_the_wrist_and_a_clear_line():
    arm = model()
    current = np.array([0.3, 0.2, 0.4, -0.6])
    plan = planner().to_point((0.4, -0.3, 0.6), current)
    assert np.allclose(tool_position(arm, plan.goal), (0.4, -0.3, 0.6))
    assert plan.goal[3] == current[3]
    checker = CollisionChecker(arm, semantics(arm).disabled)
    assert checker.path_contacts(current, plan.goal, 0.005) is None


def test_velocity_scaling_slows_the_move():
    fast = planner().to_state('ready', np.zeros(4), 1.0).move.duration
    slow = planner().to_state('ready', np.zeros(4), 0.25).move.duration
    assert slow > 2.0 * fast
    assert planner().to_state('ready', np.zeros(4), 0.0).move.duration == fast


def test_another_wrist_angle_is_tried_when_keeping_it_collides():
    """A hand held straight along the lower arm, lowered to 0.1 m above the floor, would
    pass through it; turned back a little, it does not."""
    arm = model()
    current = np.zeros(4)
    point = (0.5, 0.0, 0.1)
    plan = planner().to_point(point, current)
    assert plan.goal[3] != current[3]
    assert np.allclose(tool_position(arm, plan.goal), point)


@pytest.mark.parametrize('call, words', [
    (lambda p: p.to_state('dance', np.zeros(4)), "no named target 'dance'"),
    (lambda p: p.to_point((0.3, 0.0, -0.05), np.zeros(4)), 'below the floor'),
    (lambda p: p.to_point((1.5, 0.0, 0.5), np.zeros(4)), 'unreachable: out of reach'),
    (lambda p: p.to_point((0.5, 0.0, 0.01), np.zeros(4)),
     'reachable only in collision: in collision .* \\(hand .* below the floor\\)'),
    # a NaN once ended in "cannot convert float NaN to integer" deep in the kinematics
    (lambda p: p.to_point((float('nan'), 0.0, 0.5), np.zeros(4)),
     'point \\(nan, 0.0, 0.5\\) is not finite'),
    (lambda p: p.to_point((0.3, float('inf'), 0.5), np.zeros(4)), 'inf, 0.5\\) is not finite'),
    (lambda p: p.to_point((0.3, 0.0, float('-inf')), np.zeros(4)), 'is not finite'),
    (lambda p: p.to_state('ready', np.zeros(4), 1e-9),
     'velocity_scaling 1e-09 is below the least allowed, 0.01'),
    (lambda p: p.to_point((0.4, -0.3, 0.6), np.zeros(4), 1e-9), 'below the least allowed'),
    (lambda p: p.to_state('ready', np.zeros(4), 1.5), 'velocity_scaling 1.5 is not within 0 to 1'),
    (lambda p: p.to_state('ready', np.zeros(4), -0.5), 'velocity_scaling -0.5 is not within'),
    (lambda p: p.to_state('ready', np.zeros(4), float('nan')), 'velocity_scaling nan is not'),
])
def test_a_goal_that_cannot_be_planned_says_why(call, words):
    with pytest.raises(PlanningError, match=words):
        call(planner())


def test_a_line_through_a_collision_is_refused():
    """From the hand held low and forward, the wrist cannot turn back through the floor."""
    arm = model()
    current = np.array([0.0, 2.0, 0.4, -1.2])
    semantic = semantics(arm)
    semantic.states['back'] = dict(zip(arm.names, (0.0, 2.0, 0.4, 1.7)))
    velocity, acceleration = limits(arm)
    with pytest.raises(PlanningError, match='named target back: in collision .*% of the way'):
        Planner(arm, semantic, acceleration, velocity).to_state('back', current)


def test_the_least_velocity_scaling_is_allowed_and_zero_means_full_speed():
    assert velocity_factor(0.0) == 1.0
    assert velocity_factor(MIN_VELOCITY_SCALING) == MIN_VELOCITY_SCALING
    assert velocity_factor(1.0) == 1.0
    arm = model()
    velocity, acceleration = limits(arm)
    longest = TimedMove(arm.lower, arm.upper, velocity * MIN_VELOCITY_SCALING, acceleration)
    assert 5 * 60.0 < longest.duration < 15 * 60.0     # about ten minutes, as documented


def test_a_move_s_time_share_is_exactly_one_from_its_end_on():
    """move_arm's feedback: a move judged at its end (started + duration) is reported done,
    not a rounding short of it ((0.1 + 4.0) - 0.1 is a shade under 4.0)."""
    move = TimedMove([0.0], [1.0], [0.25], [1e9])
    assert move.duration == pytest.approx(4.0)
    move.duration = 4.0
    assert move.time_share(0.1, 0.1 + 4.0) == 1.0
    assert move.time_share(0.1, 9.0) == 1.0
    assert move.time_share(0.1, 2.1) == pytest.approx(0.5)
    assert move.time_share(0.1, 0.0) == 0.0
