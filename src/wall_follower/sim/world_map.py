"""A Stage world as map_server would serve it: the walls as an occupancy grid.

rviz shows walls only from a map; a simulated robot has none until it maps.
So the simulation launch publishes the world's own obstacles, rasterised on
Stage's grid (the cells the simulator's lasers hit), in map_server's
convention: row 0 at the bottom, 100 occupied, 0 free, `origin` the pose of
cell (0, 0)'s outer corner.

The grid is given in the robot's odometry frame, so that it lines up with
the robot in rviz without any extra transform: with `localization "gps"`
Stage's odom frame is the world frame; with `localization "odom"` it is the
robot's start pose (odometry starts at zero there).
"""
import math
from collections import namedtuple

import numpy as np

from .grid import OccupancyGrid

OCCUPIED = 100
FREE = 0

# values: int8 (rows, cols), row 0 at the bottom; origin: (x, y, yaw) of cell (0, 0)'s
# corner in the odometry frame; resolution: m per cell.
WorldMap = namedtuple('WorldMap', ['values', 'resolution', 'origin'])


def odom_frame_pose(robot, start=None):
    """Pose (x, y, yaw) of a robot's odometry frame in the world.

    robot: a worldfile.RobotSpec; start: its start pose (x, y, yaw) when
    not the world file's (stage_sim's ~pose).
    """
    if robot.localization == 'odom':
        return tuple(start if start is not None else robot.pose)
    return (0.0, 0.0, 0.0)


def in_frame(pose, frame):
    """pose (x, y, yaw), given in the world, expressed in `frame` (a pose in the world)."""
    dx, dy = pose[0] - frame[0], pose[1] - frame[1]
    cos, sin = math.cos(frame[2]), math.sin(frame[2])
    return (cos * dx + sin * dy, -sin * dx + cos * dy, pose[2] - frame[2])


def world_map(world, start=None):
    """The WorldMap of a worldfile.World, in its first robot's odometry frame
    (the world frame when it has no robot)."""
    grid = OccupancyGrid.from_world(world)
    values = np.where(grid.occupied, OCCUPIED, FREE).astype(np.int8)
    corner = (grid.origin[0], grid.origin[1], 0.0)
    frame = odom_frame_pose(world.robots[0], start) if world.robots else (0.0, 0.0, 0.0)
    return WorldMap(values, grid.resolution, in_frame(corner, frame))
