"""stage_sim's start check: a world with no robot, a robot inside a wall, outside the map or on
top of another are refused with the world file and the robot named; every shipped world and
the starts the tests use pass. Inside a wall is measured exactly: the body's polygon against
the obstacles' true edges, so a body a centimetre clear of a wall starts (as in real Stage)
however coarse Stage's cells."""
import glob
import math
import os
import textwrap

import pytest

from wall_follower.sim.grid import OccupancyGrid
from wall_follower.sim.start_check import start_problems
from wall_follower.sim.worldfile import load_world

REPO = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..')
ROOM = os.path.join(REPO, 'worlds', 'room.world')
# Real Stage's 4 m room (test/data/stage_reference): its wall faces at x, y = +-1.9.
REF_ROOM = os.path.join(REPO, 'test', 'data', 'stage_reference', 'ref_room.world')
# Two boxes, one whose top face is y = -1 and one whose bottom face is y = 1, and a square
# robot 0.5 m a side between them: every number exact in binary.
SQUARE_BY_A_BOX = """\
    resolution 0.02
    model ( name "box" pose [ 0 -1.5 0 0 ] size [ 2 1 0.5 ] )
    model ( name "far" pose [ 0 1.5 0 0 ] size [ 2 1 0.5 ] )
    position ( name "square" pose [ 0 0 0 0 ] size [ 0.5 0.5 0.2 ] )
    """
SHIPPED = sorted(glob.glob(os.path.join(REPO, 'worlds', '*.world')) +
                 glob.glob(os.path.join(REPO, 'test', 'rostest', '*.world')))


def problems(path, starts=None):
    """start_problems for the world at path, its robots at starts (default: the file's)."""
    world = load_world(path)
    starts = list(starts) if starts is not None else [robot.pose for robot in world.robots]
    return start_problems(world, OccupancyGrid.from_world(world), starts)


def world_file(tmp_path, body):
    path = os.path.join(str(tmp_path), 'test.world')
    with open(path, 'w') as stream:
        stream.write(textwrap.dedent(body))
    return path


@pytest.mark.parametrize('path', SHIPPED)
def test_every_shipped_world_starts(path):
    assert problems(path) == []


@pytest.mark.parametrize('start', [(-1.0, -0.3, 0.0), (-1.2, 0.3, 0.0), (0.8, 0.0, 0.0),
                                   (0.2, 0.1, math.radians(135)), (0.1, -0.2, math.radians(137))])
def test_the_room_starts_the_tests_use_are_accepted(start):
    assert problems(ROOM, [start]) == []


def test_a_robot_across_a_wall_is_refused_naming_the_world_and_the_robot():
    # The room's west wall is at x = -1.6: the body, 0.138 m long, centred 0.05 m from it.
    assert problems(ROOM, [(-1.55, 0.0, 0.0)]) == [
        '%s: robot "turtlebot3" at (-1.550, 0.000) starts inside a wall (its body overlaps '
        'an obstacle)' % ROOM]


def test_a_burger_a_centimetre_clear_of_a_wall_starts():
    # Its body reaches y = -1.889, 1.1 cm from the wall face at -1.9, though it shares a
    # Stage cell with the wall (both in [-1.90, -1.88)); real Stage starts it.
    assert problems(REF_ROOM, [(0.30, -1.80, 0.0)]) == []


# Burger starts 0.5 mm into a wall of REF_ROOM, each with its twin 0.5 mm clear: its side
# across y = -1.9, its front corners across x = 1.9, a corner of the turned body below -1.9.
INTO_A_WALL = [(0.30, -1.8115, 0.0), (1.8635, 0.3, 0.0), (0.3, -1.824, math.radians(-60.0))]
CLEAR_OF_A_WALL = [(0.30, -1.8105, 0.0), (1.8625, 0.3, 0.0), (0.3, -1.823, math.radians(-60.0))]


@pytest.mark.parametrize('start', INTO_A_WALL)
def test_a_burger_half_a_millimetre_into_a_wall_is_refused(start):
    assert problems(REF_ROOM, [start]) == [
        '%s: robot "robot" at (%.3f, %.3f) starts inside a wall (its body overlaps an '
        'obstacle)' % (REF_ROOM, start[0], start[1])]


@pytest.mark.parametrize('start', CLEAR_OF_A_WALL)
def test_a_burger_half_a_millimetre_clear_of_a_wall_starts(start):
    assert problems(REF_ROOM, [start]) == []


@pytest.mark.parametrize('y, refused', [(-0.75, False), (-0.7499, False), (-0.7501, True),
                                        (-0.9, True)])
def test_touching_a_wall_is_not_overlapping_it(tmp_path, y, refused):
    # y = -0.75: the body's lower side lies on the box's top face.
    path = world_file(tmp_path, SQUARE_BY_A_BOX)
    assert bool(problems(path, [(0.0, y, 0.0)])) == refused


def test_an_obstacle_inside_the_body_is_an_overlap(tmp_path):
    path = world_file(tmp_path, """\
        resolution 0.02
        model ( name "room" pose [ 0 0 0 0 ] size [ 4 4 0.5 ] )
        model ( name "peg" pose [ 1.0 1.0 0 0 ] size [ 0.04 0.04 0.5 ] )
        position ( name "square" pose [ 0 0 0 0 ] size [ 0.5 0.5 0.2 ] )
        """)
    assert problems(path, [(1.05, 0.95, 0.3)]) != []
    assert problems(path, [(0.6, 0.6, 0.0)]) == []


@pytest.mark.parametrize('start', [(5.0, 0.0, 0.0), (0.0, -9.0, 1.0), (-30.0, 40.0, 0.0)])
def test_a_robot_outside_the_map_is_refused(start):
    (problem,) = problems(ROOM, [start])
    assert problem.startswith('%s: robot "turtlebot3" at (%.3f, %.3f) is outside the map '
                              '(its walls span x ' % (ROOM, start[0], start[1]))


def test_a_world_with_no_robot_is_refused(tmp_path):
    path = world_file(tmp_path, """\
        resolution 0.02
        model ( name "box" pose [ 0 0 0 0 ] size [ 1 1 0.5 ] )
        """)
    assert problems(path) == ['%s: no robot to simulate (the world has no position model)'
                              % path]


def test_a_world_with_no_walls_has_no_outside(tmp_path):
    path = world_file(tmp_path, """\
        resolution 0.02
        position ( name "alone" pose [ 40 -3 0 0 ] size [ 0.2 0.2 0.2 ] )
        """)
    assert problems(path) == []


def test_robots_on_top_of_each_other_are_refused():
    path = os.path.join(REPO, 'test', 'rostest', 'two_robots.world')
    assert problems(path, [(0.0, 0.0, 0.0), (0.05, 0.0, 1.0)]) == [
        '%s: robots "first" and "second" start on top of each other' % path]
