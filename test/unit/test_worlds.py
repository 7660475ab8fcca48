"""The shipped worlds keep the promises their headers make: bitmaps that match
their generator, a Burger that can reach its top speeds, and a start pose
beside a straight wall on the right, 0.25 m from the laser, with at least
1 m of it ahead (what the follower tests and the course start from).
"""
import math
import os

import numpy as np
import pytest
from PIL import Image

from cell_geometry import exact_ranges
from bitmap_generator import generator
from wall_follower.sim.grid import OccupancyGrid
from wall_follower.sim.worldfile import load_world

REPO = os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, os.pardir)
WORLDS = ('room', 'arena', 'obstacles')
CELL = 0.02


def world(name):
    return load_world(os.path.join(REPO, 'worlds', name + '.world'))


@pytest.mark.parametrize('name', WORLDS)
def test_bitmap_matches_its_generator_and_the_world_file(name):
    image, size, centre = generator().render(generator().OUTLINES[name])
    committed = Image.open(os.path.join(REPO, 'worlds', name + '.png')).convert('L')
    assert np.array_equal(np.asarray(committed), np.asarray(image))
    floorplan = [o for o in world(name).obstacles if o.name == name][0]
    assert floorplan.pose[:2] == pytest.approx(centre)


@pytest.mark.parametrize('name', WORLDS)
def test_one_burger_able_to_reach_the_turtlebot3_limits(name):
    robots = world(name).robots
    assert len(robots) == 1
    robot = robots[0]
    assert robot.size == pytest.approx((0.138, 0.178, 0.192))
    assert robot.ranger.samples == 360
    xmin, xmax = robot.velocity_bounds[:2]
    amin, amax = robot.velocity_bounds[6:]
    assert xmax >= 0.22 and xmin <= -0.22
    assert amax >= 2.84 and amin <= -2.84


@pytest.mark.parametrize('name', WORLDS)
def test_start_beside_a_straight_wall_on_the_right(name):
    loaded = world(name)
    robot = loaded.robots[0]
    x, y, yaw = robot.pose
    mount = robot.ranger.pose[0]
    laser = (x + mount * math.cos(yaw), y + mount * math.sin(yaw))
    grid = OccupancyGrid.from_world(loaded)
    ahead = np.linspace(0.0, 1.0, 11)   # points of the wall from abeam to 1 m ahead
    bearings = np.arctan2(-0.25, ahead)
    ranges = exact_ranges(grid, laser[0], laser[1], yaw + bearings, 3.5)
    # every hit lies on one straight line 0.25 m to the right, to within the
    # cell that Stage's rasterisation may add to a wall face
    lateral = ranges * np.abs(np.sin(bearings))
    assert np.abs(lateral - 0.25).max() <= CELL + 1e-9
    clear_ahead = exact_ranges(grid, laser[0], laser[1], [yaw], 3.5)[0]
    assert clear_ahead > 1.0
