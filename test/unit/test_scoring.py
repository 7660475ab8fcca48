"""Scoring from ground truth: distances, alignment, clearance and lap figures."""
import math
import os

import numpy as np
import pytest

from wall_follower.evaluation.scoring.geometry import polygon_clearance
from wall_follower.evaluation.scoring.course import (CourseMap, RunScore, stretches_on_trail,
                                                     taken_every, true_lap_length)

WORLDS = os.path.join(os.path.dirname(__file__), '..', '..', 'worlds')
# room.world: free space x in [-1.5, 1.5], y in [-1.2, 1.2]; laser 32 mm behind the axle.
LASER_BACK = 0.032
HALF_WIDTH = 0.089


@pytest.fixture(scope='module')
def room():
    return CourseMap(os.path.join(WORLDS, 'room.world'))


def test_right_wall_distance_is_the_perpendicular_distance(room):
    assert room.right_wall_distance((-0.8, -0.95, 0.0)) == pytest.approx(0.25, abs=1e-6)


def test_right_wall_distance_takes_the_nearest_within_30_degrees(room):
    # Heading +x beside the bottom wall but turned 20 deg toward it: the
    # nearest point within +-30 deg of the right is still the perpendicular foot.
    yaw = math.radians(-20.0)
    laser_y = -0.95 + LASER_BACK * math.sin(-yaw)
    assert room.right_wall_distance((-0.8, -0.95, yaw)) == pytest.approx(laser_y + 1.2, abs=1e-6)


def test_alignment_reports_distance_and_heading_error(room):
    distance, error = room.right_wall_alignment((-0.8, -0.95, 0.0))
    assert distance == pytest.approx(0.25, abs=1e-6)
    assert error == pytest.approx(0.0, abs=1e-9)
    _, error = room.right_wall_alignment((-0.8, -0.95, math.radians(5.0)))
    assert math.degrees(error) == pytest.approx(5.0, abs=0.01)


def test_right_wall_distance_from_the_middle_of_the_room(room):
    # Facing -x, the right is +y: the top wall, 1.2 m away.
    assert room.right_wall_distance((0.0, 0.0, math.pi)) == pytest.approx(1.2, abs=1e-6)


@pytest.mark.parametrize('yaw, x', [(math.pi / 2, 1.25), (-math.pi / 2, -1.25)])
def test_the_grid_reading_puts_a_wall_off_its_edge_as_stage_does(room, yaw, x):
    # The laser 0.25 m from the east (west) wall, beside it: a beam along an
    # axis reads a whole number of Stage's 0.02 m cells (stage-reference), so
    # the grid puts the wall at the next one out, while the judge has 0.25.
    pose = (x, 0.0, yaw)
    assert room.right_wall_distance(pose) == pytest.approx(0.25, abs=1e-6)
    assert room.grid_right_wall_distance(pose) == pytest.approx(0.26, abs=1e-6)


def test_the_worst_of_a_stretch_out_of_band_is_where_it_was(room):
    score = RunScore(room)
    # Along the bottom wall (y = -1.2), edging out to 0.32 m and back into the band.
    offsets = [0.25, 0.28, 0.31, 0.32, 0.31, 0.28, 0.25, 0.25]
    for step, off in enumerate(offsets):
        score.add_pose(step * 0.1, (-0.8 + step * 0.019, -1.2 + off, 0.0))
    score.summary()
    (stretch,) = score.stretches_out_of_band()
    after, seconds, began, distance, worst = stretch
    assert began[1] == pytest.approx(-1.2 + 0.31)
    assert distance == pytest.approx(0.32, abs=1e-6)
    assert worst[1] == pytest.approx(-1.2 + 0.32)
    assert seconds == pytest.approx(0.3)


def test_clearance_of_the_footprint(room):
    assert room.clearance((-0.8, -0.95, 0.0)) == pytest.approx(1.2 - 0.95 - HALF_WIDTH, abs=1e-6)
    assert room.clearance((-0.8, -1.2 + HALF_WIDTH, 0.0)) == pytest.approx(0.0, abs=1e-6)


def drive_square(score, side, speed=0.19, dt=0.1, start=(-0.8, -0.95)):
    """Feed a square lap, counter-clockwise, starting along +x."""
    x, y = start
    t = 0.0
    for heading in (0.0, math.pi / 2, math.pi, -math.pi / 2):
        steps = int(round(side / (speed * dt)))
        for _ in range(steps):
            score.add_pose(t, (x, y, heading))
            score.add_command(speed, 0.0)
            x += speed * dt * math.cos(heading)
            y += speed * dt * math.sin(heading)
            t += dt
    for _ in range(5):
        score.add_pose(t, (x, y, 0.0))
        x += speed * dt
        t += dt
    return score


def test_run_score_of_a_lap_along_the_bottom_wall(room):
    score = drive_square(RunScore(room), side=1.9)
    figures = score.summary()
    assert figures['lap_closed']
    assert figures['path_length'] == pytest.approx(4 * 1.9, abs=0.05)
    assert figures['lap_time_ratio'] == pytest.approx(1.0, abs=0.03)
    assert figures['max_linear'] == pytest.approx(0.19)
    assert not figures['contact']
    # The bottom and top sides run 0.25 m from a wall, the other two 0.4 m
    # and 0.7 m: about half the lap in band.
    assert 0.45 < figures['time_in_band'] < 0.55


@pytest.mark.parametrize('standing', [1, 3])
def test_a_lap_is_timed_from_when_the_robot_leaves_where_it_was_first_heard(room, standing):
    # A controller that comes up a few steps after the simulator leaves the
    # robot standing meanwhile, for more steps on a busy machine: the same
    # lap must read the same.
    moving = drive_square(RunScore(room), side=1.9).summary()
    score = RunScore(room)
    for step in range(standing):
        score.add_pose(-0.1 * (standing - step), (-0.8, -0.95, 0.0))
    stood = drive_square(score, side=1.9).summary()
    for name in ('lap_time', 'time_in_band', 'rms_error', 'path_length'):
        assert stood[name] == pytest.approx(moving[name], abs=1e-9), name


def test_a_summary_taken_while_a_pose_is_half_added_counts_the_complete_ones(room):
    # A monitor's subscriber thread adds a pose's weight before the pose;
    # a summary taken in between must not pair the weights with the poses
    # one off.
    score = RunScore(room)
    for step in range(20):
        score.add_pose(0.1 * step, (-0.8 + 0.019 * step, -0.95, 0.0))
    whole = score.summary()
    score.weights.append(0.1)
    half_added = score.summary()
    assert half_added['time_in_band'] == whole['time_in_band'] == 1.0
    assert half_added['rms_error'] == pytest.approx(whole['rms_error'])


def test_true_lap_length_of_a_square_trail():
    side, step = 1.0, 0.01
    trail = []
    for k in range(int(4 * side / step) + 30):
        s = (k * step) % (4 * side)
        if s < side:
            trail.append((s, 0.0))
        elif s < 2 * side:
            trail.append((side, s - side))
        elif s < 3 * side:
            trail.append((3 * side - s, side))
        else:
            trail.append((0.0, 4 * side - s))
    assert true_lap_length(trail, (0.0, 0.0)) == pytest.approx(4.0, abs=0.02)
    assert true_lap_length(trail[:300], (0.0, 0.0)) is None


def test_clearance_is_zero_when_the_footprint_overlaps_or_encloses():
    square = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])
    inside = np.array([[[0.4, 0.4], [0.6, 0.6]]])
    crossing = np.array([[[0.5, 0.5], [2.0, 0.5]]])
    apart = np.array([[[1.5, -1.0], [1.5, 2.0]]])
    assert polygon_clearance(square, inside) == 0.0
    assert polygon_clearance(square, crossing) == 0.0
    assert polygon_clearance(square, apart) == pytest.approx(0.5)


def test_finish_ends_the_lap_where_the_recorder_said(room):
    score = RunScore(room)
    for k in range(11):
        score.add_pose(k * 0.1, (-0.8 + 0.019 * k, -0.95, 0.0))
    score.finish(1.2)
    score.add_pose(1.1, (-0.8 + 0.019 * 11, -0.95, 0.0))   # late, but before the end
    score.add_pose(1.2, (-0.8 + 0.019 * 12, -0.95, 0.0))
    score.add_pose(1.3, (-0.8 + 0.019 * 13, -0.95, 0.0))   # after the end: ignored
    figures = score.summary()
    assert figures['lap_closed']
    assert figures['lap_time'] == pytest.approx(1.2)
    assert figures['path_length'] == pytest.approx(12 * 0.019)
    assert figures['time_in_band'] == pytest.approx(1.0)


def places_on_trail(trail, points):
    """The first index of each point's stretch (a moving robot's stretch is one pose)."""
    return [first for first, _ in stretches_on_trail(trail, points)]


def test_a_recorded_point_on_a_stretch_driven_twice_is_placed_on_its_own_pass():
    """Out along x and back: the third point lies where the first was, on the way back."""
    trail = [(0.1 * min(step, 20 - step), 0.0) for step in range(21)]
    points = [(0.2, 0.0), (1.0, 0.0), (0.2, 0.0)]
    assert places_on_trail(trail, points) == [2, 10, 18]


def test_places_on_trail_takes_the_nearest_pose_to_an_inexact_point():
    trail = [(0.1 * step, 0.0) for step in range(10)]
    assert places_on_trail(trail, [(0.32, 0.01), (0.68, -0.01)]) == [3, 7]
    assert places_on_trail([], [(0.0, 0.0)]) == []


def test_a_point_taken_while_standing_still_may_have_been_taken_any_time_then():
    """Three poses at the origin (standing still), then along x."""
    trail = [(0.0, 0.0)] * 3 + [(0.1 * step, 0.0) for step in range(1, 10)]
    points = [(0.0, 0.0), (0.5, 0.0)]
    assert stretches_on_trail(trail, points) == [(0, 2), (7, 7)]
    assert places_on_trail(trail, points) == [0, 7]
    assert stretches_on_trail([], points) == []


def test_points_are_taken_every_period_if_their_time_spans_allow_it():
    # The first one taken while standing still, some time from 0.2 to 0.4 s.
    assert taken_every([(0.2, 0.4), (1.3, 1.3), (2.3, 2.3)], 1.0, 1e-3)
    assert taken_every([(0.0, 0.0), (1.0005, 1.0005)], 1.0, 1e-3)
    assert not taken_every([(0.0, 0.2), (1.3, 1.3)], 1.0, 1e-3)
    assert not taken_every([(0.0, 0.0), (1.0, 1.0), (2.2, 2.2)], 1.0, 1e-3)


def test_points_on_a_trail_that_goes_round_twice_are_placed_on_their_own_pass():
    # Round a pillar twice, 100 poses a turn; the second turn runs 1 cm
    # inside the first, so its poses lie nearer some points of the first
    # turn than the first turn's own poses do (the recorder's odometry lags).
    angles = np.linspace(0.0, 2 * math.pi, 100, endpoint=False)
    first = np.column_stack((np.cos(angles), np.sin(angles)))
    second = 0.99 * first
    trail = np.concatenate((first, second))
    # Points taken every 10 poses of the first turn, each a hair toward the centre.
    points = [tuple(0.995 * first[i]) + (0.0,) for i in range(0, 100, 10)]
    stretches = stretches_on_trail(trail, points)
    assert [s[0] for s in stretches] == list(range(0, 100, 10))
