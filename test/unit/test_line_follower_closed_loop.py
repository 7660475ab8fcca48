"""The line follower's path memory and pursuit, closed round a synthetic camera on synthetic
courses: a circle, an S bend, a tight bend, an open line's end, a lost line."""
import math

import numpy as np
import pytest

from line_course import STEP, arc, camera, distance_to, run, segment
from wall_follower.params.camera.line_follower import CONVENTIONS as DECLARED_CONVENTIONS
from wall_follower.vision.floor import CONVENTIONS
from wall_follower.vision.line_pursuit import FINISHED, FOLLOW, LOST, SEARCH


def cross_track(centreline, poses):
    errors = np.array([distance_to(centreline, pose[:2]) for pose in poses])
    return float(np.sqrt(np.mean(errors ** 2))), float(errors.max())


def mean_speed(poses):
    return float(np.hypot(*np.diff(poses[:, :2], axis=0).T).sum()) / ((len(poses) - 1) * STEP)


@pytest.mark.parametrize('radius', [0.6, 0.35])
def test_a_circle_is_followed_on_the_line_at_speed(radius):
    circle = arc((0.0, radius), radius, -math.pi / 2, 2.2 * math.pi)
    poses, commands, states = run(circle, (0.0, 0.0, 0.0), 160)
    rms, worst = cross_track(circle, poses)
    assert rms <= 0.015 and worst <= 0.05, (rms, worst)
    assert set(states) == {FOLLOW}
    assert mean_speed(poses) >= min(0.15, 0.8 * 0.85 * 0.49 * radius)


def s_bend():
    return np.vstack((segment((-0.2, 0.0), (0.5, 0.0)),
                      arc((0.5, 0.4), 0.4, -math.pi / 2, math.pi / 2),
                      arc((1.3, 0.4), 0.4, math.pi, -math.pi / 2)[1:],
                      segment((1.3, 0.8), (2.6, 0.8))[1:]))


@pytest.mark.parametrize('height,tilt,width,height_px', [
    (0.25, 40.0, 320, 240), (0.4, 55.0, 640, 480), (0.18, 30.0, 160, 120)])
def test_an_s_bend_is_followed_to_its_end_with_any_camera(height, tilt, width, height_px):
    line = s_bend()
    poses, commands, states = run(line, (-0.2, 0.0, 0.0), 250,
                                  projection=camera(height, tilt, width, height_px))
    assert states[-1] == FINISHED
    finished = states.index(FINISHED)
    rms, worst = cross_track(line, poses[:finished])
    assert rms <= 0.015 and worst <= 0.05, (rms, worst)
    end = line[-1]
    assert np.hypot(*(poses[finished][:2] - end)) <= 0.35
    assert all(c.linear == 0.0 and c.angular == 0.0 for c in commands[finished:])


def test_a_tight_bend_is_taken_slowly_and_on_the_line():
    line = np.vstack((segment((0.0, 0.0), (0.6, 0.0)),
                      arc((0.6, 0.2), 0.2, -math.pi / 2, math.pi)[1:],
                      segment((0.6, 0.4), (-0.4, 0.4))[1:]))
    poses, commands, states = run(line, (0.0, 0.0, 0.0), 220)
    rms, worst = cross_track(line, poses[:states.index(FINISHED)])
    assert worst <= 0.05 and rms <= 0.015, (rms, worst)
    turning = [c for c, p in zip(commands, poses) if p[0] > 0.65]
    assert max(c.linear for c in turning) < 0.19 * 0.8


def test_a_lost_line_only_turns_in_place_then_stops():
    line = segment((0.0, 0.0), (5.0, 0.0))
    poses, commands, states = run(line, (0.0, 0.0, 0.0), 300, lose_after=10)
    lost_at = states.index(SEARCH)
    # What was seen before the lens was covered is driven on (at most its length), no more.
    assert poses[lost_at][0] < 1.6
    assert all(c.linear == 0.0 for c in commands[lost_at:])
    assert any(c.angular != 0.0 for c in commands[lost_at:])
    assert states[-1] == LOST and commands[-1] == (0.0, 0.0)
    turned = poses[-1][2] - poses[lost_at][2]
    assert 2 * math.pi - 0.1 <= abs(turned) <= 2 * math.pi + 0.1


def test_no_line_in_sight_never_drives():
    line = segment((0.0, 2.0), (1.0, 2.0))
    poses, commands, states = run(line, (0.0, 0.0, -math.pi / 2), 30)
    assert all(c.linear == 0.0 for c in commands)


def test_the_table_offers_the_projections_conventions():
    assert set(DECLARED_CONVENTIONS) == set(CONVENTIONS)


def test_frames_of_the_base_and_the_odometry_invert_each_other():
    from wall_follower.vision.line_pursuit import from_base_frame, in_base_frame, known_ahead
    base = (1.0, -2.0, 2.5)
    points = np.array([(0.3, 0.1), (-0.2, 0.5)])
    assert in_base_frame(from_base_frame(points, base), base) == pytest.approx(points)
    assert from_base_frame([(1.0, 0.0)], (0.0, 0.0, math.pi / 2))[0] == pytest.approx((0.0, 1.0))
    path = from_base_frame([(0.3, 0.25), (-0.5, 0.0)], base)
    assert not known_ahead(path, base, 0.5)
    assert known_ahead(path, base, 0.8)


def test_an_end_found_stays_while_the_floor_beyond_it_leaves_the_view():
    from wall_follower.params import defaults, pick
    from wall_follower.params.camera.line_follower import PATH
    from wall_follower.vision.line_path import LinePath
    memory = LinePath(**pick(defaults(PATH), PATH))
    x = np.arange(0.2, 0.5, 0.005)
    seen = np.array([(a, b) for a in x for b in (-0.01, 0.0, 0.01)])

    def in_view(points):
        return np.asarray(points).reshape(-1, 2)[:, 0] >= 0.15

    memory.update(seen, in_view, (0.0, 0.0, 0.0), lambda point: True)
    assert memory.end_seen and memory.path[-1][0] == pytest.approx(0.49, abs=0.03)
    # The end's last bit still traced, but the floor beyond it counts as out of view.
    memory.update(seen, in_view, (0.02, 0.0, 0.0), lambda point: False)
    assert memory.end_seen
    # A covered lens is no end: a path never seen to end does not become one.
    fresh = LinePath(**pick(defaults(PATH), PATH))
    fresh.update(seen, in_view, (0.0, 0.0, 0.0), lambda point: False)
    fresh.update(seen[:0], in_view, (0.02, 0.0, 0.0), lambda point: True)
    assert not fresh.end_seen


def test_an_end_found_stays_when_only_the_end_is_left_of_the_path():
    """The line's last bit, seen beyond the near floor that has left the view, is traced in
    one jump; once the base is past the middle of that jump with nothing in view, only the
    end is left of the path: still the line's end, not a lost line (line_camera.test's
    robot turned round there and drove the line back)."""
    from wall_follower.params import defaults, pick
    from wall_follower.params.camera.line_follower import PATH
    from wall_follower.vision.line_path import LinePath
    memory = LinePath(**pick(defaults(PATH), PATH))

    def dots(x0, x1):
        return np.array([(a, b) for a in np.arange(x0, x1, 0.005) for b in (-0.01, 0.0, 0.01)])

    def beyond(x):
        return lambda points: np.asarray(points).reshape(-1, 2)[:, 0] >= x

    memory.update(dots(0.0, 0.04), beyond(-1.0), (0.0, 0.0, 0.0), lambda point: False)
    memory.update(dots(0.17, 0.19), beyond(0.1), (0.0, 0.0, 0.0), lambda point: True)
    assert memory.end_seen and memory.path[-1][0] == pytest.approx(0.18, abs=0.01)
    path = memory.update(np.zeros((0, 2)), beyond(1.0), (0.13, 0.0, 0.0), lambda point: True)
    assert len(path) == 1 and memory.end_seen
