"""What a world file is read into (World, its robots, rangers, cameras and obstacles), the
error a file that cannot be read raises, and the bounds a world must keep."""
import math
from collections import namedtuple


# Stage's ModelPosition default bounds: +-1 m/s on x, y, z and +-90 deg/s on yaw.
STAGE_VELOCITY_BOUNDS = (-1.0, 1.0, -1.0, 1.0, -1.0, 1.0, -math.pi / 2.0, math.pi / 2.0)


# Real Stage draws a camera's frame in its window's drawing area, below a menu bar of this
# height, and caps the camera's resolution at that area's width and height (worldgui.cc,
# model_camera.cc); stageros opens a window of STAGEROS_WINDOW unless `window size` says.
STAGE_MENU_BAR = 30


STAGEROS_WINDOW = (600, 400)


# The most pixels a camera may draw (1920 x 1080): the simulator draws a frame on the CPU
# at about 0.1 us a pixel, a quarter of a second at this size (two and a half world steps
# of 0.1 s), and the step, and the node's answer to Ctrl-C, wait for it.
MAX_CAMERA_PIXELS = 1920 * 1080


# The most cells of `resolution` the obstacles may span: the simulator's grid keeps some
# 30 bytes a cell (sim.grid), so this bounds it to about half a GB, where a resolution
# slipped by a few decimal places would otherwise ask for many GB.
MAX_GRID_CELLS = 20000000


# The most beams a ranger may have: far above any laser's, far below what exhausts memory.
MAX_SAMPLES = 100000


class WorldFileError(Exception):
    """A world file that cannot be read; str() is '<file>:<line>: <problem>'."""

    def __init__(self, path, line, problem):
        super(WorldFileError, self).__init__('%s:%d: %s' % (path, line, problem))
        self.path = path
        self.line = line
        self.problem = problem


RangerSpec = namedtuple('RangerSpec', [
    'pose',        # (x, y, z, yaw) of the ranger model in base_link (stageros' laser tf)
    'sensor_pose',  # (x, y, z, yaw) of the sensor inside the ranger model (usually zeros)
    'sensor_height',  # z of the beams above the robot's base, for Stage's obstacle height test
    'range_min', 'range_max',
    'fov',         # rad
    'samples',
    'noise',       # (constant sigma [m], proportional factor, angle [rad]) as Stage's `noise`
    'size',        # (length, width, height) of the ranger model's box
    'color',       # (r, g, b) in [0, 1] of that box
])


CameraSpec = namedtuple('CameraSpec', [
    'pose',        # (x, y, z, yaw) of the camera model in base_link
    'size',        # (length, width, height) of the camera model's box
    'color',       # (r, g, b) in [0, 1] of that box
    'resolution',  # (width, height) [px]
    'range',       # (near, far) clip distances [m] along the optical axis
    'fov',         # (horizontal, vertical) [rad]
    'pantilt',     # (pan, tilt) [rad]; pan > 0 turns right, tilt > 0 looks down (as Stage)
    'height',      # z of the eye above the floor: body height + pose z (as Stage draws it)
])


RobotSpec = namedtuple('RobotSpec', [
    'name',
    'pose',        # (x, y, yaw) start pose in the world
    'size',        # (length, width, height)
    'origin',      # (x, y, yaw) of the body box centre in base_link
    'drive',
    'localization',
    'velocity_bounds',  # (xmin, xmax, ymin, ymax, zmin, zmax, amin [rad/s], amax [rad/s])
    'ranger',      # RangerSpec or None
    'odom_error',  # (x, y, yaw) odometry scale errors for localization "odom", or None
    'color',       # (r, g, b) in [0, 1] of the body
    'camera',      # CameraSpec or None
])


Obstacle = namedtuple('Obstacle', [
    'name',
    'pose',        # (x, y, z, yaw) global pose of the model
    'origin',      # (x, y, z, yaw) geometry offset (Stage's `origin`)
    'edges',       # (M, 2, 2) directed outline edges [start, end] in the model's geometry
                   # frame, already scaled to `size` (Stage rasterises edge by edge)
    'z_range',     # (zmin, zmax) global heights of the model's blocks
    'ranger_return',
    'obstacle_return',
    'color',       # (r, g, b) in [0, 1], as the camera draws the model
])


World = namedtuple('World', [
    'path', 'resolution', 'interval_sim', 'speedup', 'quit_time', 'paused',
    'obstacles', 'robots', 'unknown_keywords',
    'warnings',    # '<file>:<line>: <what>' of what loads but likely not as meant
])
