"""Splines, timing within the limits, JointTrajectoryController's rules (each rejection,
the stamp, dropped points, the smooth takeover) and the joints that follow them."""
import math

import numpy as np
import pytest

from arm_files import limits, model
from wall_follower.arm.spline import CUBIC, LINEAR, QUINTIC, Segment
from wall_follower.arm.timing import (MAX_WAYPOINTS, TimedMove, fastest_duration, stopping,
                                      trapezoid_duration)
from wall_follower.arm.trajectory import (Command, Rejected, Trajectory, TrajectoryPoint,
                                          accept, stop)
from wall_follower.sim.arm_joints import ArmJoints

NAMES = ['hip', 'shoulder', 'elbow', 'wrist']


def point(time, positions, velocities=(), accelerations=()):
    return TrajectoryPoint(time, list(positions), list(velocities), list(accelerations))


# --- splines ---------------------------------------------------------------------------

@pytest.mark.parametrize('given, kind', [((True, True), QUINTIC), ((True, False), CUBIC),
                                         ((False, False), LINEAR)])
def test_a_segment_meets_its_end_points_as_far_as_they_are_given(given, kind):
    p0, p1 = np.array([0.1, -0.2]), np.array([0.7, 0.4])
    v0, v1 = np.array([0.3, 0.0]), np.array([-0.2, 0.5])
    a0, a1 = np.array([1.0, -1.0]), np.array([0.0, 2.0])
    with_velocity, with_acceleration = given
    segment = Segment(2.0, 3.5, (p0, v0 if with_velocity else None,
                                 a0 if with_acceleration else None),
                      (p1, v1 if with_velocity else None, a1 if with_acceleration else None))
    assert segment.kind == kind
    start, end = segment.sample(2.0), segment.sample(3.5)
    assert np.allclose(start[0], p0) and np.allclose(end[0], p1)
    if with_velocity:
        assert np.allclose(start[1], v0) and np.allclose(end[1], v1)
    else:
        assert np.allclose(start[1], (p1 - p0) / 1.5) and np.allclose(start[2], 0.0)
    if with_acceleration:
        assert np.allclose(start[2], a0) and np.allclose(end[2], a1)
    # the derivatives are those of the positions
    t, h = 2.6, 1e-6
    assert np.allclose((segment.sample(t + h)[0] - segment.sample(t - h)[0]) / (2 * h),
                       segment.sample(t)[1], atol=1e-6)
    assert np.allclose((segment.sample(t + h)[1] - segment.sample(t - h)[1]) / (2 * h),
                       segment.sample(t)[2], atol=1e-5)


def test_a_segment_holds_its_ends_outside_its_time():
    segment = Segment(1.0, 2.0, ([0.0], None, None), ([1.0], None, None))
    assert segment.sample(0.0)[0] == [0.0] and segment.sample(5.0)[0] == [1.0]


def test_a_segment_given_only_one_end_velocity_is_linear():
    segment = Segment(0.0, 1.0, ([0.0], [1.0], None), ([1.0], None, None))
    assert segment.kind == LINEAR


# --- timing ----------------------------------------------------------------------------

def test_trapezoid_durations():
    assert trapezoid_duration(0.0, 1.0, 2.0) == 0.0
    assert math.isclose(trapezoid_duration(2.0, 1.0, 2.0), 2.5)      # reaches 1 rad/s
    assert math.isclose(trapezoid_duration(0.5, 1.0, 2.0), 1.0)      # a triangle


@pytest.mark.parametrize('seed', range(20))
def test_a_timed_move_stays_within_the_limits_and_ends_at_rest_on_the_goal(seed):
    arm = model()
    velocity, acceleration = limits(arm)
    rng = np.random.RandomState(seed)
    start, goal = rng.uniform(arm.lower, arm.upper), rng.uniform(arm.lower, arm.upper)
    scale = rng.uniform(0.1, 1.0)
    move = TimedMove(start, goal, velocity * scale, acceleration)
    times = np.linspace(0.0, move.duration, 400)
    samples = [move.sample(t) for t in times]
    for positions, speeds, accelerations in samples:
        assert (np.abs(speeds) <= velocity * scale + 1e-9).all()
        assert (np.abs(accelerations) <= acceleration + 1e-9).all()
        # on the straight line from start to goal
        s = np.dot(positions - start, goal - start) / np.dot(goal - start, goal - start)
        assert np.allclose(positions, start + s * (goal - start))
    assert np.allclose(samples[0][0], start) and np.allclose(samples[-1][0], goal)
    assert np.allclose(samples[0][1], 0.0) and np.allclose(samples[-1][1], 0.0)
    # as fast as the limits allow on that line: some joint at its speed or acceleration limit
    peak_speed = max(np.max(np.abs(s[1]) / (velocity * scale)) for s in samples)
    peak_gain = max(np.max(np.abs(s[2]) / acceleration) for s in samples)
    assert max(peak_speed, peak_gain) > 1.0 - 1e-6
    assert move.duration >= fastest_duration(start, goal, velocity * scale, acceleration) - 1e-9


def test_waypoints_fall_on_the_phase_changes_and_the_end():
    move = TimedMove([0.0], [2.0], [1.0], [2.0])     # 0.5 s up, 1.5 s cruise, 0.5 s down
    times = move.waypoint_times(0.2)
    assert 0.5 in times and any(math.isclose(t, 2.0) for t in times)
    assert math.isclose(times[-1], 2.5) and times[0] > 0.0
    assert all(b - a <= 0.2 + 1e-9 for a, b in zip([0.0] + times, times))


def test_a_crawling_move_is_sampled_by_a_bounded_number_of_points():
    """velocity_scaling 1e-9 once made move_arm list a point every 0.1 s of a move lasting
    years, and grow by 70 MB/s; the points are bounded whatever the move's length, and the
    move is still met at each of them."""
    arm = model()
    velocity, acceleration = limits(arm)
    move = TimedMove(arm.lower, arm.upper, velocity * 1e-4, acceleration)
    assert move.duration > 1e4
    times = move.waypoint_times(0.1)
    assert len(times) <= MAX_WAYPOINTS
    assert math.isclose(times[-1], move.duration) and times == sorted(times)
    assert {move.ramp, move.ramp + move.cruise} <= set(times)


def test_a_move_to_where_the_arm_is_takes_no_time():
    move = TimedMove([0.1, 0.2], [0.1, 0.2], [1.0, 1.0], [1.0, 1.0])
    assert move.duration == 0.0 and np.allclose(move.sample(0.0)[0], [0.1, 0.2])


def test_a_stop_spanned_as_one_point_brakes_within_the_acceleration_limits():
    positions, velocities = np.array([0.2, -0.4, 1.0, 0.0]), np.array([0.9, -0.5, 1.1, 0.0])
    acceleration = np.array([2.0, 2.0, 2.5, 3.0])
    place, duration = stopping(positions, velocities, acceleration)
    zero = np.zeros(4)
    segment = Segment(0.0, duration, (positions, velocities, zero), (place, zero, zero))
    samples = [segment.sample(t) for t in np.linspace(0.0, duration, 201)]
    peak = np.max([np.abs(s[2]) for s in samples], axis=0)
    assert (peak <= acceleration + 1e-9).all()
    assert np.isclose(peak / acceleration, 1.0).any()       # as short as the limits allow
    for (p, v, _), (q, _, _) in zip(samples, samples[1:]):
        assert (np.sign(q - p) * np.sign(velocities) >= 0).all()   # no turning back
    assert np.allclose(samples[-1][0], place) and np.allclose(samples[-1][1], 0.0)


# --- the controller's rules ------------------------------------------------------------

REST = Trajectory.hold([0.0, 0.0, 0.0, 0.0], 0.0)


@pytest.mark.parametrize('command, words', [
    (Command(['hip', 'shoulder', 'elbow', 'thumb'], 0.0, [point(1.0, [0, 0, 0, 0])]),
     'unknown joint\\(s\\) thumb'),
    (Command(['hip', 'shoulder', 'elbow'], 0.0, [point(1.0, [0, 0, 0])]),
     'joint\\(s\\) wrist missing'),
    (Command(['hip', 'hip', 'elbow', 'wrist'], 0.0, [point(1.0, [0, 0, 0, 0])]),
     'hip named more than once'),
    (Command(NAMES, 0.0, [point(1.0, [0, 0, 0, 0]), point(1.0, [0.1, 0, 0, 0])]),
     'time_from_start must increase: point 1 at 1.000 s'),
    (Command(NAMES, 0.0, [point(2.0, [0, 0, 0, 0]), point(1.0, [0.1, 0, 0, 0])]),
     'must increase'),
    (Command(NAMES, 0.0, [point(1.0, [0, 0, 2.6, 0])]), 'elbow at 2.6000 rad is outside'),
    (Command(NAMES, 0.0, [point(1.0, [0, 0, 0])]), 'point 0 has 3 positions for 4 joints'),
    (Command(NAMES, 0.0, [point(1.0, [0, 0, 0, 0], [0, 0])]), '2 velocities for 4'),
    (Command(NAMES, 0.0, [point(1.0, [0, float('nan'), 0, 0])]), 'not finite'),
    (Command(NAMES, 0.0, [point(1.0, [0, 0, 0, 0], (), [0, 0, 0, 0])]),
     'accelerations without velocities'),
    (Command(NAMES, 0.0, [point(-1.0, [0, 0, 0, 0])]), 'not negative'),
    (Command(NAMES, 5.0, [point(1.0, [0, 0, 0, 0]), point(2.0, [0.1, 0, 0, 0])]),
     'every point is in the past \\(the last was due 3.000 s ago\\)'),
])
def test_a_bad_command_is_rejected_saying_why(command, words):
    with pytest.raises(Rejected, match=words):
        accept(model(), command, 10.0, REST)


def test_joints_are_matched_by_name_and_a_zero_stamp_means_now():
    command = Command(['wrist', 'elbow', 'hip', 'shoulder'], 0.0,
                      [point(2.0, [0.4, 0.3, 0.1, 0.2])])
    trajectory = accept(model(), command, 10.0, REST)
    assert np.allclose(trajectory.sample(10.0)[0], 0.0)
    assert np.allclose(trajectory.sample(11.0)[0], [0.05, 0.1, 0.15, 0.2])
    assert np.allclose(trajectory.sample(12.0)[0], [0.1, 0.2, 0.3, 0.4])
    assert np.allclose(trajectory.sample(20.0)[0], [0.1, 0.2, 0.3, 0.4])
    assert np.allclose(trajectory.sample(20.0)[1], 0.0)


def test_points_already_due_are_dropped_and_the_rest_joined_from_where_the_arm_is_meant_to_be():
    command = Command(NAMES, 8.0, [point(1.0, [1.0, 0, 0, 0]), point(3.0, [0.5, 0, 0, 0]),
                                   point(4.0, [0.0, 0, 0, 0])])
    trajectory = accept(model(), command, 10.0, REST)    # the first point was due at 9
    assert np.allclose(trajectory.sample(10.0)[0], 0.0)
    assert np.allclose(trajectory.sample(11.0)[0], [0.5, 0, 0, 0])
    assert np.allclose(trajectory.sample(11.5)[0], [0.25, 0, 0, 0])


def test_a_stamp_still_to_come_lets_the_current_trajectory_go_on_until_then():
    first = accept(model(), Command(NAMES, 0.0, [point(4.0, [0.4, 0, 0, 0])]), 0.0, REST)
    second = accept(model(), Command(NAMES, 2.0, [point(1.0, [0.4, 0.3, 0, 0])]), 1.0, first)
    assert np.allclose(second.sample(1.5)[0], first.sample(1.5)[0])
    assert np.allclose(second.sample(2.0)[0], [0.2, 0, 0, 0])
    assert np.allclose(second.sample(3.0)[0], [0.4, 0.3, 0, 0])


def test_a_replacing_trajectory_takes_over_smoothly():
    start = Command(NAMES, 0.0, [point(1.0, [0.5, 0, 0, 0], [0.5, 0, 0, 0], [0, 0, 0, 0]),
                                 point(2.0, [1.0, 0, 0, 0], [0, 0, 0, 0], [0, 0, 0, 0])])
    first = accept(model(), start, 0.0, REST)
    replacing = Command(NAMES, 0.0, [point(1.0, [0.0, 0.5, 0, 0], [0, 0, 0, 0], [0, 0, 0, 0])])
    second = accept(model(), replacing, 1.0, first)
    before, after = first.sample(1.0), second.sample(1.0 + 1e-9)
    for was, now in zip(before, after):
        assert np.allclose(was, now, atol=1e-6)       # position, velocity, acceleration
    assert np.allclose(second.sample(2.0)[0], [0.0, 0.5, 0, 0])


def test_a_rejected_command_leaves_the_current_trajectory_alone():
    first = accept(model(), Command(NAMES, 0.0, [point(4.0, [0.4, 0, 0, 0])]), 0.0, REST)
    segments = list(first.segments)
    with pytest.raises(Rejected):
        accept(model(), Command(NAMES, 0.0, [point(1.0, [9, 0, 0, 0])]), 1.0, first)
    assert first.segments == segments


def test_a_single_point_due_now_is_rejected_saying_why():
    """As ros_control's JointTrajectoryController: a point due now (time_from_start 0 of a
    zero stamp) is dropped with those already past, and a command of that point alone has
    nothing left to follow."""
    command = Command(NAMES, 0.0, [point(0.0, [0.3, 0, 0, 0])])
    with pytest.raises(Rejected, match='its last point is due now \\(time_from_start 0.000 s '
                       'from a zero stamp.*give it a time_from_start above 0'):
        accept(model(), command, 10.0, REST)


def test_a_first_point_due_now_is_dropped_and_the_rest_followed():
    command = Command(NAMES, 0.0, [point(0.0, [0.3, 0, 0, 0]), point(2.0, [0.4, 0, 0, 0])])
    trajectory = accept(model(), command, 10.0, REST)
    assert np.allclose(trajectory.sample(11.0)[0], [0.2, 0, 0, 0])   # from REST, not 0.3
    assert np.allclose(trajectory.sample(12.0)[0], [0.4, 0, 0, 0])


def test_an_empty_command_is_a_stop_not_a_trajectory():
    with pytest.raises(Rejected, match='an empty command is a stop'):
        accept(model(), Command([], 0.0, []), 2.0, REST)


def test_the_stop_brakes_from_the_actual_state_within_the_acceleration_limits():
    """JointTrajectoryController's way: from where the joints are and how fast they go (here
    behind what was desired of them), not from the desired state, to rest as soon as the
    acceleration limits allow, never turning back, and held there."""
    arm = model()
    _, acceleration = limits(arm)
    positions, velocities = np.array([0.4, -0.2, 1.0, 0.1]), np.array([0.8, -0.5, 0.0, 1.2])
    stopped = stop(positions, velocities, 5.0, acceleration)
    start = stopped.sample(5.0)
    assert np.allclose(start[0], positions) and np.allclose(start[1], velocities)
    place, duration = stopping(positions, velocities, acceleration)
    assert math.isclose(stopped.end, 5.0 + duration)
    times = np.linspace(5.0, stopped.end, 201)
    samples = [stopped.sample(t) for t in times]
    assert np.max([np.abs(s[2]) / acceleration for s in samples]) <= 1.0 + 1e-9
    for (p, _, _), (q, _, _) in zip(samples, samples[1:]):
        assert (np.sign(q - p) * np.sign(velocities) >= 0).all()
    for later in (stopped.end, stopped.end + 10.0):
        held = stopped.sample(later)
        assert np.allclose(held[0], place) and np.allclose(held[1], 0.0)


@pytest.mark.parametrize('velocities, acceleration', [
    ([0.0, 0.0, 0.0, 0.0], [2.0, 2.0, 2.5, 3.0]),      # at rest: nothing to brake
    ([0.8, -0.5, 0.0, 1.2], [np.inf] * 4),             # no limits: at once, JTC's hold
])
def test_a_stop_with_nothing_to_brake_holds_the_actual_position(velocities, acceleration):
    positions = np.array([0.4, -0.2, 1.0, 0.1])
    stopped = stop(positions, velocities, 5.0, np.array(acceleration))
    for time in (5.0, 6.0):
        assert np.allclose(stopped.sample(time)[0], positions)
        assert np.allclose(stopped.sample(time)[1], 0.0)


# --- the simulated joints --------------------------------------------------------------

def test_the_joints_follow_exactly_within_their_speed_limits_and_never_past_them():
    arm = model()
    joints = ArmJoints([0.0] * 4, arm.lower, arm.upper, arm.velocity)
    joints.step([0.01, 0.0, 0.0, 0.0], [0.5, 0, 0, 0], 0.02)
    assert np.allclose(joints.positions, [0.01, 0, 0, 0])
    assert np.allclose(joints.velocities, [0.5, 0, 0, 0])
    joints.step([1.0, -1.0, 0.0, 0.0], [0, 0, 0, 0], 0.02)     # far too fast: held back
    assert np.allclose(joints.positions, [0.01 + 0.02 * arm.velocity[0],
                                          -0.02 * arm.velocity[1], 0, 0])
    assert np.allclose(np.abs(joints.velocities[:2]), arm.velocity[:2])
    for _ in range(500):
        joints.step([9.0, -9.0, 9.0, 9.0], [0, 0, 0, 0], 0.02)
        assert (joints.positions <= arm.upper).all() and (joints.positions >= arm.lower).all()
    assert np.allclose(joints.positions, [arm.upper[0], arm.lower[1], arm.upper[2],
                                          arm.upper[3]])
    assert np.allclose(joints.velocities, 0.0)
