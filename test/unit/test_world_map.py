"""The world's walls as a map: map_server's layout, in the robot's odometry frame."""
import math
import os

import numpy as np
import pytest

from wall_follower.sim.grid import OccupancyGrid
from wall_follower.sim.world_map import FREE, OCCUPIED, in_frame, odom_frame_pose, world_map
from wall_follower.sim.worldfile import load_world

WORLDS = os.path.join(os.path.dirname(__file__), '..', '..', 'worlds')


def load(name):
    return load_world(os.path.join(WORLDS, name + '.world'))


def cell_corner_in_world(grid_map, row, col):
    """World (x, y) of cell (row, col)'s lower-left corner, through the map's origin pose."""
    x, y, yaw = grid_map.origin
    u, v = col * grid_map.resolution, row * grid_map.resolution
    return x + math.cos(yaw) * u - math.sin(yaw) * v, y + math.sin(yaw) * u + math.cos(yaw) * v


def test_gps_world_map_is_the_grid_with_row_zero_at_the_bottom():
    world = load('arena')
    grid = OccupancyGrid.from_world(world)
    walls = world_map(world)
    assert walls.values.dtype == np.int8
    assert set(np.unique(walls.values)) == {FREE, OCCUPIED}
    assert np.array_equal(walls.values == OCCUPIED, grid.occupied)
    assert walls.resolution == grid.resolution
    assert walls.origin == pytest.approx((grid.origin[0], grid.origin[1], 0.0))
    # A cell's centre, placed through the origin, is in the grid's cell of that row and column.
    row, col = np.argwhere(walls.values == OCCUPIED)[0]
    x, y = cell_corner_in_world(walls, row + 0.5, col + 0.5)
    assert tuple(int(i) for i in grid.world_to_cell(x, y)) == (row, col)


@pytest.mark.parametrize('start', [None, (0.4, -0.3, math.radians(70.0))])
def test_odom_world_map_lines_up_in_the_frame_odometry_starts_in(start):
    world = load('arena_odom')
    walls = world_map(world, start)
    frame = start if start is not None else world.robots[0].pose
    assert odom_frame_pose(world.robots[0], start) == tuple(frame)
    row, col = np.argwhere(walls.values == OCCUPIED)[0]
    in_odom = cell_corner_in_world(walls, row + 0.5, col + 0.5)
    # The same point of the world, expressed in the odom frame by the robot's start pose.
    grid = OccupancyGrid.from_world(world)
    world_x = (grid.ix0 + col + 0.5) * grid.resolution
    world_y = (grid.iy0 + row + 0.5) * grid.resolution
    assert in_odom == pytest.approx(in_frame((world_x, world_y, 0.0), frame)[:2], abs=1e-9)


def test_gps_odom_frame_is_the_world_whatever_the_start():
    world = load('arena')
    assert odom_frame_pose(world.robots[0], (1.0, 2.0, 0.5)) == (0.0, 0.0, 0.0)


def test_in_frame_expresses_a_pose_in_another():
    assert in_frame((1.0, 1.0, 0.5), (1.0, 0.0, math.pi / 2)) == pytest.approx(
        (1.0, 0.0, 0.5 - math.pi / 2))
