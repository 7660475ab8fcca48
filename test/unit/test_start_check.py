"""stage_sim's start check: a world with no robot, a robot inside a wall, outside the map or on
top of another are refused with the world file and the robot named; every shipped world and
the starts the tests use pass."""
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
