"""wall_fit: how far a wall on the right runs on past its fitted line's hits (wall_runs_to),
how far the hits ahead stand out of it toward the robot (proud_of), which right_wall
tells with the wall."""
import math

import numpy as np
import pytest

from laser_conventions import COURSE_720, scan_view
from wall_follower.control.following.follower import FollowerParams
from wall_follower.control.sensing.lines import Line
from wall_follower.control.sensing.scan import RIGHT
from wall_follower.control.sensing.wall_fit import (
    NOTHING_STANDS_OUT, proud_of, right_wall, wall_beyond, wall_runs_to)

PARAMS = FollowerParams()
# A wall parallel on the right, 0.25 m from the laser.
WALL = Line(0.25, RIGHT)
END = np.array((0.2, -0.25))


def runs_to(points):
    """Where WALL runs on to from END over points."""
    return wall_runs_to(WALL, WALL.offsets(points), END, points, PARAMS)


def hits(start, heading_deg, length, step=0.01):
    """Hits every step metres along a straight run from start, heading_deg from ahead."""
    heading = math.radians(heading_deg)
    steps = np.arange(step, length + step / 2, step)[:, None]
    return np.asarray(start) + steps * np.array((math.cos(heading), math.sin(heading)))


def test_a_wall_that_runs_on_at_a_slight_slant_runs_to_its_last_hit():
    # The saw-tooth of a wall slanted to Stage's grid: the line fitted through
    # a few teeth is tilted some 12 deg off the hits farther on.
    ahead = hits(END, -12.0, 0.4)
    assert runs_to(ahead) == pytest.approx(ahead[-1])


def test_the_teeth_of_a_saw_tooth_do_not_stop_it():
    ahead = hits(END, 0.0, 0.4, step=0.02)
    ahead[::2, 1] += 0.02   # every other hit a cell farther
    assert runs_to(ahead) == pytest.approx(ahead[-1])


def test_a_wall_that_ends_runs_to_its_end_however_near_the_next_one_lies():
    farther = hits(END + np.array((0.02, -0.3)), 0.0, 0.4)
    assert runs_to(farther) == pytest.approx(END)


def test_a_bend_away_sharper_than_the_continue_angle_ends_it():
    away = hits(END, -40.0, 0.4)
    reached = runs_to(away)
    assert reached[0] < END[0] + 0.1


def test_a_gap_wider_than_the_continue_gap_ends_it():
    beyond = hits(END + np.array((PARAMS.wall_continue_gap + 0.02, 0.0)), 0.0, 0.3)
    assert runs_to(beyond) == pytest.approx(END)


def standing(points, wall=WALL):
    """What of points stands out of wall toward the robot."""
    return proud_of(wall.offsets(points), points, wall.distance, PARAMS)


def proud(points, wall=WALL):
    """How far points stand out of wall toward the robot."""
    return standing(points, wall).depth


def along_the_wall():
    """WALL's hits from 0.3 m behind the laser to END."""
    return hits((-0.3, -0.25), 0.0, 0.5)


def test_the_face_of_a_wall_met_at_the_end_stands_out_by_its_depth_past_the_inliers():
    # The wall the followed one meets sticks 6 cm out of its line at its end;
    # its second farthest hit, 5 mm short of that, counts.
    face = hits(END, 90.0, 0.06, step=0.005)
    assert proud(np.vstack((along_the_wall(), face))) == pytest.approx(
        0.055 - PARAMS.wall_inlier_distance)


def test_a_step_ups_top_stands_out_as_far_ahead_as_it_is_seen_a_corners_lip_only_at_the_corner():
    # A step 0.1 m up at END: its face, then its top for 0.3 m. The top of
    # the next wall at a corner stands out 6 cm, and that wall falls away.
    face = hits(END, 90.0, 0.1, step=0.01)
    top = hits(END + np.array((0.0, 0.1)), 0.0, 0.3)
    step_up = standing(np.vstack((along_the_wall(), face, top)))
    assert step_up.depth == pytest.approx(0.1 - PARAMS.wall_inlier_distance)
    assert step_up.reach == pytest.approx(top[-2, 0])
    lip = hits(END + np.array((-0.02, 0.06)), 0.0, 0.02, step=0.005)
    falls_away = hits(END + np.array((0.0, 0.06)), -90.0, 0.5)
    lipped = standing(np.vstack((along_the_wall(), lip, falls_away)))
    assert lipped.depth > 0.0 and lipped.reach <= END[0] + 0.001


@pytest.mark.parametrize('beside', [
    hits(END, 0.0, 0.3, step=0.02) + np.array((0.0, 0.02)),   # a saw-tooth a cell deep
    np.array(((0.3, -0.15),)),                                  # one stray beam
    hits((-0.2, -0.25), 90.0, 0.1),                             # a stub already passed
    hits((-PARAMS.laser_x / 2, -0.25), 90.0, 0.1),              # one level with the robot
], ids=['saw-tooth', 'stray beam', 'behind', 'level'])
def test_hits_within_a_cell_of_the_line_one_stray_beam_or_a_stub_not_ahead_stand_out_by_nothing(
        beside):
    # Level: ahead of the laser, but behind the rotation centre it sits behind.
    assert proud(np.vstack((along_the_wall(), beside))) == 0.0


def test_the_next_wall_beyond_a_wall_turned_away_does_not_stand_out():
    # A wall turned 40 deg away behind the right: its line runs far out to
    # the right ahead, and the next wall, 0.35 m to the right (across the
    # end of an obtuse inner corner), lies up to 0.24 m inside that line,
    # but no nearer than the wall: nothing to keep clear of. A face nearer
    # than the wall still stands out.
    away = Line(0.25, RIGHT - math.radians(40.0))
    next_wall = hits((0.1, -0.35), 0.0, 0.3)
    assert np.max(-away.offsets(next_wall)) > 0.2
    assert proud(next_wall, away) == 0.0
    assert proud(hits((0.1, -0.19), 0.0, 0.1), away) > 0.1


def test_without_a_wall_nothing_stands_out():
    # A wall farther than wall_lost_distance is none to follow.
    far = hits((-0.5, -PARAMS.wall_lost_distance - 0.1), 0.0, 1.0)
    wall, _, _, nothing = right_wall(far, PARAMS)
    assert wall is None and nothing == NOTHING_STANDS_OUT


@pytest.mark.parametrize('turn_deg', [30.0, 45.0, 62.0])
def test_the_next_wall_beyond_a_walls_end_is_fitted_from_its_tip_on(turn_deg):
    # A wall 0.25 m to the right ends 5 cm ahead; the next wall leaves its
    # tip turn_deg to the right. Fitted as the follower fits the wall on the
    # right, the robot heads away from it by that angle.
    tip = np.array((0.05, -0.25))
    turn = math.radians(turn_deg)
    points = np.vstack((hits((-0.3, -0.25), 0.0, 0.35), hits(tip, -turn_deg, 0.5)))
    wall = wall_beyond(points, tip, (1.0, 0.0), PARAMS)
    assert wall.angle == pytest.approx(-turn, abs=math.radians(2.0))
    assert wall.distance == pytest.approx(math.cos(turn) * 0.25 - math.sin(turn) * 0.05,
                                          abs=0.01)


def test_a_wall_beyond_that_does_not_meet_the_tip_is_no_next_wall():
    # A wall 0.3 m beyond WALL's line, past a gap: not the one that ends
    # at the tip (a room's far wall seen past a pillar's side, say).
    farther = hits(END + np.array((0.0, -0.3)), 0.0, 0.5)
    assert wall_beyond(np.vstack((along_the_wall(), farther)), END, (1.0, 0.0), PARAMS) is None


@pytest.mark.parametrize('bend_deg', [25.0, 35.0, 45.0])
@pytest.mark.parametrize('vertex_ahead', [-0.04, 0.0, 0.04])
def test_past_a_bend_away_the_wall_on_the_right_is_the_next_one(bend_deg, vertex_ahead):
    # The robot has turned round a wall that bends away by bend_deg and heads
    # along the next wall, 0.25 m from it, beside the bend: the wall it
    # left comes from behind the right. The wall to follow is the next one,
    # not a line half way between the two (a few hits of the one left,
    # beside the bend, may still tilt it by a degree or two).
    bend = math.radians(bend_deg)
    vertex = np.array((vertex_ahead, -0.25))
    left_behind = vertex - 1.0 * np.array((math.cos(bend), math.sin(bend)))
    world = [(tuple(left_behind), tuple(vertex)), (tuple(vertex), tuple(vertex + (1.5, 0.0)))]
    points = scan_view(world, (0.0, 0.0, 0.0), COURSE_720).points()
    wall, _, _, _ = right_wall(points[np.hypot(*points.T) < PARAMS.wall_fit_range], PARAMS)
    assert abs(wall.angle) < math.radians(5.0)
    assert wall.distance == pytest.approx(0.25, abs=0.015)
