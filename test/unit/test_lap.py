"""Odometry recording on synthetic trajectories: path length, sampling, lap end."""
import math

import pytest

from wall_follower.control.course.lap import LapDetector, LapRecorder, PathLength, PeriodicSampler
from wall_follower.control.course.odom_check import JumpDetector, odometry_problem

RATE = 10.0  # odometry messages per second
SPEED = 0.19


def walk(waypoints, speed=SPEED, rate=RATE, start_time=0.0):
    """(t, x, y, yaw) poses at `rate` along a polyline driven at constant speed."""
    poses = []
    t = start_time
    step = speed / rate
    x, y = waypoints[0]
    yaw = math.atan2(waypoints[1][1] - y, waypoints[1][0] - x)
    poses.append((t, x, y, yaw))
    for (ax, ay), (bx, by) in zip(waypoints, waypoints[1:]):
        yaw = math.atan2(by - ay, bx - ax)
        length = math.hypot(bx - ax, by - ay)
        count = int(round(length / step))
        for i in range(1, count + 1):
            t += 1.0 / rate
            share = i / float(count)
            poses.append((t, ax + share * (bx - ax), ay + share * (by - ay), yaw))
    return poses


def feed(recorder, poses):
    """Feed poses until the lap closes; returns the pose that closed it (or None)."""
    for pose in poses:
        recorder.add(*pose)
        if recorder.closed:
            return pose
    return None


def lemniscate(size=1.5, count=1200):
    """Figure of eight through the origin: leaves at +45 deg, crosses back at 135 deg."""
    poses = []
    for i in range(count + 1):
        u = 2.0 * math.pi * i / count
        x, y = size * math.sin(u), size * math.sin(u) * math.cos(u)
        dx, dy = math.cos(u), math.cos(2.0 * u)
        poses.append((i * 0.1, x, y, math.atan2(dy, dx)))
    return poses


def test_lap_passing_the_start_10_cm_to_the_side_still_closes():
    path = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.5), (-1.0, 1.5), (-1.0, 0.1), (1.0, 0.1)]
    recorder = LapRecorder()
    closing = feed(recorder, walk(path))
    assert closing is not None
    _, x, y, _ = closing
    assert x == pytest.approx(0.0, abs=SPEED / RATE)
    assert y == pytest.approx(0.1)
    # The course's rule (within 5 cm of the first pose) never fires on this lap.
    assert min(math.hypot(px, py) for _, px, py, _ in walk(path)[50:]) > 0.05


def test_lap_passing_beyond_the_tolerance_does_not_close():
    path = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.5), (-1.0, 1.5), (-1.0, 0.4), (1.0, 0.4)]
    assert feed(LapRecorder(close_tolerance=0.3), walk(path)) is None


def test_nothing_closes_at_the_start():
    recorder = LapRecorder()
    standing = [(t * 0.1, 0.0, 0.0, 0.0) for t in range(100)]
    # Rocking back and forth across the start line, as a robot settling might.
    rocking = [(10.0 + t * 0.1, 0.02 * math.sin(t), 0.0, 0.0) for t in range(300)]
    assert feed(recorder, standing + rocking) is None
    assert not recorder.lap.left_start


def test_short_loop_near_the_start_does_not_close():
    """Crossing the start line again after a small circle is not a lap."""
    loop = [(0.0, 0.0), (0.3, 0.0), (0.3, 0.3), (-0.2, 0.3), (-0.2, 0.0), (0.5, 0.0)]
    assert feed(LapRecorder(), walk(loop)) is None


def test_figure_of_eight_does_not_close_at_its_middle_crossing():
    poses = lemniscate()
    total = sum(math.hypot(b[1] - a[1], b[2] - a[2]) for a, b in zip(poses, poses[1:]))
    recorder = LapRecorder()
    # The eight passes through the start after half its length, obliquely.
    assert feed(recorder, poses[:len(poses) // 2 + 50]) is None
    # Going on, it closes when it comes back through the start the first way.
    extra = [(poses[-1][0] + 0.1 * (i + 1),) + p[1:] for i, p in enumerate(poses[1:50])]
    closing = feed(recorder, poses[len(poses) // 2 + 50:] + extra)
    assert closing is not None
    assert recorder.total_distance >= 0.99 * total


def arc(center, radius, start, end, count=12):
    """Waypoints on a circle round center, from angle start to end [rad]."""
    return [(center[0] + radius * math.cos(start + (end - start) * i / count),
             center[1] + radius * math.sin(start + (end - start) * i / count))
            for i in range(count + 1)]


def test_a_lap_from_a_corner_closes_where_it_cuts_the_corner_past_the_start():
    """find_wall left the robot in a corner, heading north into it; the lap comes
    back north, turns west short of the start line and passes 8 cm from the start,
    heading 135 deg: 45 deg off the start heading, 90 deg off the way it crossed
    the start line, had it crossed it."""
    leaving = arc((-0.2, 0.0), 0.2, 0.0, math.pi / 2)
    around = [(-2.0, 0.2), (-2.0, -2.0), (0.0, -2.0)]
    returning = arc((-0.2, -0.2), 0.2, 0.0, math.pi / 2) + [(-1.0, 0.0)]
    poses = walk(leaving + around + returning)
    assert all(pose[2] < 0.0 or abs(pose[3] - math.pi / 2) > math.radians(60.0)
               for pose in poses[40:] if abs(pose[1]) < 0.3)
    recorder = LapRecorder()
    closing = feed(recorder, poses)
    assert closing is not None
    # Just past the point nearest the start, (-0.06, -0.06).
    assert math.hypot(closing[1] + 0.059, closing[2] + 0.059) < 2.0 * SPEED / RATE
    assert recorder.total_distance == pytest.approx(path_length(poses[:poses.index(closing) + 1]))


def test_a_lap_that_turns_on_the_spot_short_of_the_start_closes_at_the_start_line():
    """The last left turn before the start pivots 15 cm short of it, within
    close_tolerance and heading nearly the start's way: standing there, the
    robot comes no nearer, but it has not passed the start point."""
    path = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.5), (-1.0, 1.5), (-1.0, 0.0), (-0.15, 0.0)]
    poses = walk(path)
    t = poses[-1][0]
    pivot = [(t + 0.1 * (i + 1), -0.15, 0.0, math.radians(-30.0 + 5.0 * i)) for i in range(7)]
    on = [(t + 0.8 + pose[0], pose[1], pose[2], pose[3])
          for pose in walk([(-0.15, 0.0), (1.0, 0.0)])[1:]]
    recorder = LapRecorder()
    closing = feed(recorder, poses + pivot + on)
    assert closing is not None
    assert closing[1] == pytest.approx(0.0, abs=SPEED / RATE)


def test_passing_the_start_point_the_other_way_closes_nothing():
    path = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (1.5, 1.0), (1.5, 0.05), (-1.0, 0.05)]
    poses = walk(path)
    assert feed(LapRecorder(), poses) is None


def test_path_length_of_a_known_polygon():
    rectangle = [(0.0, 0.0), (2.0, 0.0), (2.0, 3.0), (0.0, 3.0), (0.0, 0.0)]
    length = PathLength()
    for _, x, y, _ in walk(rectangle, speed=0.13):
        length.add(x, y)
    assert length.total == pytest.approx(10.0, rel=1e-9)


def test_samples_once_per_second_of_the_given_clock():
    recorder = LapRecorder(sample_period=1.0)
    # 12.5 s of odometry at 30 Hz, standing still: 13 samples at t = 0, 1, ... 12.
    for i in range(376):
        recorder.add(i / 30.0, 0.0, 0.0, 0.5)
    assert len(recorder.points) == 13
    assert recorder.points[0] == (0.0, 0.0, 0.5)


def test_poses_stamped_before_the_start_are_not_recorded():
    recorder = LapRecorder(sample_period=1.0, start=2.0)
    # A recorder that fell behind still reads poses from before the goal's stamp.
    poses = walk([(0.0, 0.0), (1.0, 0.0)])
    for pose in poses:
        recorder.add(*pose)
    at_start = next(pose for pose in poses if pose[0] >= 2.0)
    assert recorder.points[0] == at_start[1:]
    assert recorder.total_distance == pytest.approx(1.0 - at_start[1], abs=1e-9)
    assert [recorder.takes(t) for t in (1.99, 2.0, 2.1)] == [False, True, True]


def test_sampler_keeps_to_its_grid_and_skips_gaps():
    sampler = PeriodicSampler(1.0)
    stamps = [0.0, 0.5, 0.98, 1.0, 1.5, 2.04, 5.3, 5.9, 6.02]
    # Due at 0, 1, 2, then (after the gap) at 5.3 and at 6, not at 6.3.
    assert [s for s in stamps if sampler.due(s)] == [0.0, 1.0, 2.04, 5.3, 6.02]


def test_points_hold_x_y_and_yaw_and_end_with_the_closing_pose():
    path = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (-1.0, 1.0), (-1.0, 0.0), (0.5, 0.0)]
    recorder = LapRecorder()
    closing = feed(recorder, walk(path))
    assert recorder.points[0] == (0.0, 0.0, 0.0)
    assert recorder.points[-1] == closing[1:]
    count = len(recorder.points)
    # Once closed, the recording takes nothing more.
    assert not recorder.add(closing[0] + 1.0, 0.3, 0.0, 0.0)
    assert len(recorder.points) == count
    duration = closing[0]
    assert count in (int(duration) + 1, int(duration) + 2)


def test_lap_must_be_armed_by_distance_and_by_leaving():
    detector = LapDetector((0.0, 0.0, 0.0), min_travel=2.0, leave_radius=0.5)
    assert not detector.update(-0.1, 0.0, 0.0, travelled=5.0)
    assert not detector.update(0.1, 0.0, 0.0, travelled=5.0)  # never left
    detector.update(1.0, 0.0, 0.0, travelled=5.0)
    detector.update(-0.1, 0.0, 0.0, travelled=1.0)
    assert not detector.update(0.1, 0.0, 0.0, travelled=1.9)  # too short a path
    detector.update(-0.1, 0.0, 0.0, travelled=3.0)
    assert detector.update(0.1, 0.0, 0.0, travelled=3.2)


def test_crossing_backwards_does_not_close():
    detector = LapDetector((0.0, 0.0, 0.0))
    detector.update(1.0, 0.0, 0.0, travelled=3.0)
    assert not detector.update(-0.1, 0.0, math.pi, travelled=4.0)
    assert not detector.update(0.1, 0.0, math.pi, travelled=4.2)


# A lap of a 2 m x 1.5 m rectangle from the origin, heading +x: 7 m.
RECTANGLE = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.5), (-1.0, 1.5), (-1.0, 0.0), (0.5, 0.0)]


def path_length(poses):
    return sum(math.hypot(b[1] - a[1], b[2] - a[2]) for a, b in zip(poses, poses[1:]))


def test_a_reset_to_the_spawn_pose_is_not_travel_and_the_lap_ends_a_lap_later():
    """reset_positions mid-lap: the robot is back at its spawn pose, 0.19 m behind
    the start line (it drove 1 s before the goal came); the jump is left out."""
    spawned = walk(RECTANGLE)
    before = spawned[10:150]                   # 14 s from x = 0.19: round the first corner
    after = walk(RECTANGLE, start_time=before[-1][0] + 0.1)
    recorder = LapRecorder()
    closing = feed(recorder, before + after)
    assert len(recorder.jumps) == 1
    stamp, distance = recorder.jumps[0]
    assert stamp == after[0][0]
    assert distance == pytest.approx(math.hypot(before[-1][1], before[-1][2]))
    # Not as the robot drives off over the start line, but a whole lap after the reset.
    start_x = before[0][1]
    corner = after.index(next(p for p in after if p[1:3] == (-1.0, 0.0)))
    assert closing == next(p for p in after[corner:] if p[1] >= start_x)
    assert recorder.total_distance == pytest.approx(
        path_length(before) + path_length(after[:after.index(closing) + 1]), abs=1e-9)
    assert recorder.points[0] == before[0][1:]


def test_an_odometry_reset_across_the_start_line_closes_nothing():
    """A jump from just behind the start line to just ahead of it is not a crossing."""
    recorder = LapRecorder()
    lap = walk(RECTANGLE)
    behind = [pose for pose in lap if pose[1] < -0.05]
    feed(recorder, lap[:lap.index(behind[-1]) + 1])
    assert recorder.total_distance > recorder.lap.min_travel and recorder.lap.left_start
    t = behind[-1][0]
    # The odometry's origin moves to where the robot stands: it reads 0.1 m past the start.
    recorder.add(t + 0.1, 0.1, 0.0, 0.0)
    recorder.add(t + 0.2, 0.12, 0.0, 0.0)
    assert not recorder.closed
    assert len(recorder.jumps) == 1


def test_driving_at_the_speed_limit_is_never_a_jump():
    for speed, rate in ((0.19, 30.0), (0.26, 10.0), (0.19, 1.0)):
        recorder = LapRecorder(max_speed=0.5, jump_allowance=0.1)
        feed(recorder, walk(RECTANGLE, speed=speed, rate=rate))
        assert recorder.jumps == []
        assert recorder.closed


def test_jump_detector_allows_max_speed_times_the_time_plus_the_allowance():
    detector = JumpDetector(max_speed=0.5, allowance=0.1)
    assert detector.jump(0.0, 0.0, 0.0) is None
    assert detector.jump(1.0, 0.59, 0.0) is None          # 0.5 m/s over 1 s, + 0.09
    assert detector.jump(1.0, 0.68, 0.0) is None          # same stamp: the allowance only
    assert detector.jump(1.0, 0.80, 0.0) == pytest.approx(0.12)
    assert detector.jump(0.5, 0.85, 0.0) is None          # a stamp going back counts as 0 s
    assert detector.jump(0.6, 0.0, 0.0) == pytest.approx(0.85)
    with pytest.raises(ValueError):
        JumpDetector(max_speed=0.0)


@pytest.mark.parametrize('pose, words', [
    ((float('nan'), 0.0, 0.0, 0.0, 0.0, 1.0), 'not finite'),
    ((0.0, float('inf'), 0.0, 0.0, 0.0, 1.0), 'not finite'),
    ((0.0, 0.0, 0.0, 0.0, 0.0, 0.0), 'not a unit quaternion'),
    ((0.0, 0.0, 0.0, 0.0, 1.0, 1.0), 'not a unit quaternion'),
    ((0.0, 0.0, 0.0, 0.0, float('nan'), 1.0), 'not a unit quaternion'),
])
def test_malformed_odometry_is_named(pose, words):
    assert words in odometry_problem(*pose)


def test_unit_quaternions_are_accepted_with_float32_rounding():
    assert odometry_problem(1.0, -2.0, 0.0, 0.0, math.sin(0.3), math.cos(0.3)) is None
    assert odometry_problem(0.0, 0.0, 0.0, 0.0, 0.0, 0.9999) is None
