"""A Stage 4.3 camera, rendered without OpenGL: colour and depth images of a world.

What real Stage draws (model_camera.cc, camera.cc, canvas.cc, blockgroup.cc;
measured under xvfb-run, see DESIGN.md "Stage's camera"):

- a pinhole camera with the world file's horizontal and vertical fields of
  view (a frustum, not a fixed aspect), clipped at `range [near far]` along
  its optical axis; each pixel is sampled at one point, SAMPLE_POINT from its
  top-left corner (not its centre): where Mesa's software rasteriser under
  xvfb-run samples Stage's window, which asks for a multisample visual (the
  first of the four standard sample positions; a calibration world of
  floating boxes pins every edge to within 0.05 px of it);
- the eye sits on the robot's centre (the camera model's own x, y and yaw are
  not used) at height = body height + camera pose z, looking along the
  robot's heading turned by pan (pan > 0 turns right) and down by tilt;
- the floor is white over the world's extent (whole superregions of its
  raster: 20.48 m squares at the default resolution), the background
  beyond it Stage's clear colour; every model is drawn as its blocks extruded from
  zmin to zmax in the model's colour, sides and top, however low it is (the
  sides of a 1 mm line on the floor thicken its near edge by about a pixel),
  with no face culled; the robots' own bodies, rangers and cameras included:
  a camera placed ahead of the robot's centre sees its own box (from behind
  and below, just above the horizon) when it looks up far enough.
- depth is the distance along the optical axis (stageros: -inf nearer than
  `near`, +inf where nothing was drawn).

The per-pixel loop is C (src/stage_camera.c, through compiled_camera):
each ray meets the floor, each model's top (a raster lookup, or a crossing
test for a few edges) and each model's side faces: one segment test per
edge, or, for a flat model with a raster (a line painted on the floor), a
walk along the raster's cells over the few millimetres where the ray is
within the model's height. So a world of a room and a line costs a few
dozen edge tests and a few cell steps per pixel. This module prepares what
the loop needs: the pixel rays, the models as solids, the eye.
"""
import math
from collections import namedtuple

import numpy as np

from . import compiled_camera

__all__ = ['Solid', 'CameraScene', 'CameraRenderer', 'CameraFrame', 'CameraMount', 'BACKGROUND',
           'FLOOR', 'body_solids', 'camera_intrinsics', 'optical_frame_rpy', 'camera_mount']

# Where in a pixel (right, down from its top-left corner, in pixels) real Stage's frame
# samples the scene.
SAMPLE_POINT = (0.375, 0.125)
# Stage's glClearColor (canvas.cc) where no floor or model is drawn, and its floor.
BACKGROUND = (0.7, 0.7, 0.8)
FLOOR = (1.0, 1.0, 1.0)
# Up to this height a model with a raster finds its side faces by walking the raster's
# cells (few steps: a ray is within so low a model for a few millimetres); taller ones
# test their edges.
FLAT_HEIGHT = 0.005
# Stage's world extent grows by superregions of this many cells a side (region.hh: 2^10).
SUPERREGION_CELLS = 1024
# Models with more edges than this test their top against a filled raster of this cell.
RASTER_EDGES = 32
RASTER_CELL = 0.0025

# base_link -> camera as stageros publishes it: translation and quaternion (x, y, z, w).
CameraMount = namedtuple('CameraMount', ['x', 'y', 'z', 'rotation'])

CameraFrame = namedtuple('CameraFrame', [
    'rgba',    # (height, width, 4) uint8, rows top-down
    'depth',   # (height, width) float32 [m] along the optical axis; +inf where nothing is
               # drawn (nothing nearer than `near` is drawn, so stageros' -inf never occurs)
])


class Solid(object):
    """A model's blocks in the world frame: outline edges extruded over z in [zmin, zmax].

    edges: (M, 2, 2) outline segments; their even-odd interior is the top face, looked
    up in `raster` ((mask, origin) of cells of RASTER_CELL) when there are many edges.
    walk_sides: the side faces are found on that raster (a flat solid's) rather than
    by testing every edge. convex: the edges are one convex polygon, in order (a box).
    """

    def __init__(self, edges, zmin, zmax, color):
        self.edges = np.asarray(edges, dtype=float).reshape(-1, 2, 2)
        self.zmin = float(zmin)
        self.zmax = float(zmax)
        self.color = tuple(float(c) for c in color)
        flat = self.edges.reshape(-1, 2)
        self.lower = flat.min(axis=0)
        self.upper = flat.max(axis=0)
        self.raster = _fill_raster(self.edges, self.lower, self.upper) \
            if len(self.edges) > RASTER_EDGES else None
        self.walk_sides = self.raster is not None and self.zmax - self.zmin < FLAT_HEIGHT
        self.convex = _is_convex(self.edges)


def _is_convex(edges):
    """Whether `edges` are the sides of one convex polygon, each starting where the one
    before ends, turning one way (or not at all) at every corner."""
    if len(edges) < 3 or not np.array_equal(edges[:, 0], np.roll(edges[:, 1], 1, axis=0)):
        return False
    along = edges[:, 1] - edges[:, 0]
    following = np.roll(along, -1, axis=0)
    turns = along[:, 0] * following[:, 1] - along[:, 1] * following[:, 0]
    return bool((turns >= 0).all() or (turns <= 0).all())


def _fill_raster(edges, lower, upper):
    """The even-odd interior of `edges` on cells of RASTER_CELL from `lower` (one scanline
    per row of cells, sampled at the cell centres)."""
    cols = int(math.ceil((upper[0] - lower[0]) / RASTER_CELL)) + 1
    rows = int(math.ceil((upper[1] - lower[1]) / RASTER_CELL)) + 1
    ys = lower[1] + (np.arange(rows) + 0.5) * RASTER_CELL
    slanted = edges[edges[:, 0, 1] != edges[:, 1, 1]]
    y1, y2 = slanted[:, 0, 1], slanted[:, 1, 1]
    x1, x2 = slanted[:, 0, 0], slanted[:, 1, 0]
    spans = (y1[None, :] <= ys[:, None]) != (y2[None, :] <= ys[:, None])
    row, edge = np.nonzero(spans)
    cross = x1[edge] + (ys[row] - y1[edge]) * (x2[edge] - x1[edge]) / (y2[edge] - y1[edge])
    # A crossing flips every cell whose centre lies at or beyond it.
    first = np.clip(np.ceil((cross - lower[0]) / RASTER_CELL - 0.5), 0, cols).astype(np.int64)
    flips = np.zeros((rows, cols + 1), dtype=np.int64)
    np.add.at(flips, (row, first), 1)
    mask = (np.cumsum(flips, axis=1)[:, :cols] % 2).astype(bool)
    return mask, (float(lower[0]), float(lower[1]))


def _box_edges(center_x, center_y, yaw, length, width):
    half = np.array([[-0.5, -0.5], [0.5, -0.5], [0.5, 0.5], [-0.5, 0.5]]) * [length, width]
    cosa, sina = math.cos(yaw), math.sin(yaw)
    points = np.stack([center_x + half[:, 0] * cosa - half[:, 1] * sina,
                       center_y + half[:, 0] * sina + half[:, 1] * cosa], axis=1)
    return np.stack([points, np.roll(points, -1, axis=0)], axis=1)


def body_solids(spec, pose):
    """A robot's body box, its ranger's box and its camera's box at world pose (x, y, yaw),
    as Stage draws them (each child model stacked on top of the body). The eye sits on
    the robot's centre level with the camera box's base, so only rays that look up meet
    that box: from inside it (a camera at the centre) all nearer than a sensible near
    clip; from behind it (a camera ahead of the centre) as a dark band just above the
    horizon."""
    x, y, yaw = pose
    cosa, sina = math.cos(yaw), math.sin(yaw)

    def placed(local_x, local_y, local_yaw, size, zmin, color):
        return Solid(_box_edges(x + local_x * cosa - local_y * sina,
                                y + local_x * sina + local_y * cosa,
                                yaw + local_yaw, size[0], size[1]),
                     zmin, zmin + size[2], color)
    origin = spec.origin
    solids = [placed(origin[0], origin[1], origin[2], spec.size, 0.0, spec.color)]
    ranger = spec.ranger
    if ranger is not None:
        solids.append(placed(ranger.pose[0], ranger.pose[1], ranger.pose[3], ranger.size,
                             spec.size[2] + ranger.pose[2], ranger.color))
    camera = spec.camera
    if camera is not None:
        solids.append(placed(camera.pose[0], camera.pose[1], camera.pose[3], camera.size,
                             camera.height, camera.color))
    return solids


def _obstacle_solid(obstacle):
    """An Obstacle's edges moved from its geometry frame into the world."""
    px, py, _, pyaw = obstacle.pose
    ox, oy, _, oyaw = obstacle.origin
    cosa, sina = math.cos(pyaw), math.sin(pyaw)
    gx, gy = px + ox * cosa - oy * sina, py + ox * sina + oy * cosa
    yaw = pyaw + oyaw
    cosg, sing = math.cos(yaw), math.sin(yaw)
    local = obstacle.edges
    world = np.empty_like(local)
    world[..., 0] = gx + local[..., 0] * cosg - local[..., 1] * sing
    world[..., 1] = gy + local[..., 0] * sing + local[..., 1] * cosg
    return Solid(world, obstacle.z_range[0], obstacle.z_range[1], obstacle.color)


class CameraScene(object):
    """The static part of what cameras see: the world's models and the floor's extent."""

    def __init__(self, world):
        self.solids = [_obstacle_solid(obstacle) for obstacle in world.obstacles]
        corners = [solid.lower for solid in self.solids] + [solid.upper for solid in self.solids]
        for robot in world.robots:
            reach = math.hypot(robot.size[0], robot.size[1])
            corners.append([robot.pose[0] - reach, robot.pose[1] - reach])
            corners.append([robot.pose[0] + reach, robot.pose[1] + reach])
        corners = np.array(corners, dtype=float).reshape(-1, 2) if corners else np.zeros((1, 2))
        self.floor_lower, self.floor_upper = floor_extent(corners, world.resolution)
        self.tables = compiled_camera.SceneTables(self.solids, RASTER_CELL)


def floor_extent(points, resolution):
    """(lower, upper) corners of the floor Stage draws round `points` (x, y): its world's
    extent, the box of every superregion (SUPERREGION_CELLS square cells of `resolution`,
    aligned on the origin) that a model's outline touches."""
    size = SUPERREGION_CELLS * resolution
    cells = np.floor(np.asarray(points, dtype=float) / resolution)
    regions = np.floor(cells / SUPERREGION_CELLS)
    return regions.min(axis=0) * size, (regions.max(axis=0) + 1.0) * size


def camera_intrinsics(camera):
    """(fx, fy, cx, cy) as stageros fills camera_info: w / (2 tan(hfov/2)), w/2, ..."""
    width, height = camera.resolution
    return (width / (2.0 * math.tan(camera.fov[0] / 2.0)),
            height / (2.0 * math.tan(camera.fov[1] / 2.0)), width / 2.0, height / 2.0)


def optical_frame_rpy(camera):
    """(roll, pitch, yaw) of base_link -> camera as stageros publishes it: an optical frame
    (z along the view, x right, y down) turned by the camera model's yaw, pan and tilt."""
    pan, tilt = camera.pantilt
    return (-(math.pi / 2.0 + tilt), 0.0, camera.pose[3] - math.pi / 2.0 - pan)


def camera_mount(robot):
    """base_link -> camera of a RobotSpec with a camera, as stageros publishes it: the camera
    model's x, y, body height + its z, and the optical frame of optical_frame_rpy."""
    camera = robot.camera
    roll, pitch, yaw = optical_frame_rpy(camera)
    cr, sr = math.cos(roll / 2.0), math.sin(roll / 2.0)
    cp, sp = math.cos(pitch / 2.0), math.sin(pitch / 2.0)
    cy, sy = math.cos(yaw / 2.0), math.sin(yaw / 2.0)
    rotation = (sr * cp * cy - cr * sp * sy, cr * sp * cy + sr * cp * sy,
                cr * cp * sy - sr * sp * cy, cr * cp * cy + sr * sp * sy)
    return CameraMount(camera.pose[0], camera.pose[1], robot.size[2] + camera.pose[2], rotation)


class CameraRenderer(object):
    """Renders one CameraSpec's frames in a CameraScene.

    The pixel rays pass through each pixel's SAMPLE_POINT, with a forward component of 1
    so that the ray parameter is the depth along the optical axis.
    """

    def __init__(self, scene, camera):
        self.scene = scene
        self.camera = camera
        width, height = camera.resolution
        fx, fy, cx, cy = camera_intrinsics(camera)
        self._u = (np.arange(width) + SAMPLE_POINT[0] - cx) / fx
        self._v = (np.arange(height) + SAMPLE_POINT[1] - cy) / fy
        self.shape = (height, width)

    def axes(self, yaw):
        """The camera's forward, right and down in the world for a robot heading `yaw`:
        pixel (row, column) looks along forward + u[column] right + v[row] down."""
        pan, tilt = self.camera.pantilt
        heading = yaw - pan
        ch, sh = math.cos(heading), math.sin(heading)
        ct, st = math.cos(tilt), math.sin(tilt)
        return ((ch * ct, sh * ct, -st), (sh, -ch, 0.0), (-ch * st, -sh * st, -ct))

    def render(self, pose, robots=()):
        """CameraFrame seen from a robot at world pose (x, y, yaw).

        robots: (RobotSpec, pose) of every robot to draw, this one included.
        """
        bodies = []
        for spec, robot_pose in robots:
            bodies.extend(body_solids(spec, robot_pose))
        scenes = [self.scene.tables, compiled_camera.SceneTables(bodies, RASTER_CELL)]
        floor = tuple(self.scene.floor_lower) + tuple(self.scene.floor_upper)
        rgba, depth = compiled_camera.render(
            scenes, self._u, self._v, self.axes(pose[2]), (pose[0], pose[1], self.camera.height),
            self.camera.range, floor, _bytes(FLOOR), _bytes(BACKGROUND))
        return CameraFrame(rgba.reshape(self.shape + (4,)), depth.reshape(self.shape))


def _bytes(color):
    return tuple(int(round(c * 255.0)) for c in color)
