"""Pixels onto the floor and back, for a pinhole camera of any size, field of view and pose.

The camera is described by what ROS says of it and nothing else: its
camera_info (the K matrix: fx, fy, cx, cy, and the image's size) and the tf
of its frame in a floor frame whose z = 0 plane is the floor (the robot's
base_footprint). Two conventions of that frame are met:

- OPTICAL, REP 103's camera optical frame (x right, y down, z along the
  optical axis), as the real TurtleBot3's raspicam publishes it;
- STAGEROS, the frame stageros publishes: rotated by roll = Stage's camera
  pitch - 180 deg (pitch = 90 deg - tilt) and by a yaw that mixes in the
  robot's own heading, placed at the body's height + the camera's z. Real
  Stage draws the image from the robot's centre, looking straight ahead, so
  only the height and the tilt of that tf are used.
"""
import math
from collections import namedtuple

import numpy as np

from wall_follower.params.camera.line_follower import CONVENTIONS
from wall_follower.rotation import matrix_of_quaternion, wrap_angle

# The frame conventions a camera's tf may follow: the choices of line_follower's
# ~frame_convention, named once in its parameter table.
AUTO, OPTICAL, STAGEROS = CONVENTIONS


class Intrinsics(namedtuple('Intrinsics', ['fx', 'fy', 'cx', 'cy', 'width', 'height'])):
    """A pinhole camera's focal lengths and principal point [px] and its image size [px]."""

    __slots__ = ()

    @classmethod
    def from_camera_info(cls, k, width, height):
        """From camera_info's K (9 numbers, row-major) and size; ValueError if unusable."""
        k = [float(value) for value in k]
        if len(k) != 9:
            raise ValueError('K holds %d numbers, not 9' % len(k))
        if width <= 0 or height <= 0:
            raise ValueError('an image size of %d x %d' % (width, height))
        if not (k[0] > 0.0 and k[4] > 0.0) or not all(math.isfinite(value) for value in k):
            raise ValueError('K has no positive, finite focal lengths: %s' % (k,))
        return cls(k[0], k[4], k[2], k[5], int(width), int(height))


def convention_of(frame_id, convention):
    """The frame convention to use: convention itself unless AUTO, which takes a frame
    named *optical* (REP 103's habit) as OPTICAL and any other as STAGEROS."""
    if convention != AUTO:
        return convention
    return OPTICAL if 'optical' in frame_id else STAGEROS


def level_camera_axes(tilt):
    """Columns: the optical x (right), y (down), z (ahead) axes, in the floor frame, of a
    camera looking straight ahead, tilted down by tilt [rad]."""
    c, s = math.cos(tilt), math.sin(tilt)
    return np.array([[0.0, -s, c], [-1.0, 0.0, 0.0], [0.0, -c, -s]])


def camera_pose(translation, quaternion, convention):
    """(optical axes as columns, optical centre) in the floor frame, from the tf of the
    camera's frame in the floor frame (translation x, y, z; quaternion x, y, z, w) read
    in the given convention (OPTICAL or STAGEROS)."""
    rotation = matrix_of_quaternion(quaternion)
    if convention == OPTICAL:
        return rotation, np.asarray(translation, float)
    # STAGEROS: the frame's y axis is Stage's "down" in the image plane; its roll is
    # -90 deg - tilt whatever its yaw, i.e. the angle of y below the floor plane.
    roll = math.atan2(rotation[2, 1], rotation[2, 2])
    tilt = -roll - math.pi / 2.0
    tilt = wrap_angle(tilt)
    return level_camera_axes(tilt), np.array([0.0, 0.0, float(translation[2])])


class FloorProjection(object):
    """Maps pixels to points of the floor (z = 0 of the floor frame) and back.

    intrinsics: an Intrinsics; axes, centre: camera_pose's; max_distance:
    floor points farther than this from the camera's foot [m] are not
    returned (near the horizon a pixel spans metres of floor).
    """

    def __init__(self, intrinsics, axes, centre, max_distance):
        self.intrinsics = intrinsics
        self.axes = np.asarray(axes, float)
        self.centre = np.asarray(centre, float)
        self.max_distance = max_distance
        if self.centre[2] <= 0.0:
            raise ValueError('the camera is %.3f m above the floor: it cannot see it'
                             % self.centre[2])

    def key(self):
        """A value equal for two projections that map every pixel alike (for caches)."""
        return (tuple(self.intrinsics), self.axes.tobytes(), self.centre.tobytes(),
                self.max_distance)

    def to_floor(self, pixels):
        """(M, 2) floor points (x, y) of the (N, 2) pixels (column, row) whose rays meet the
        floor within max_distance; the others are left out."""
        points, on_floor = self.floor_points(pixels)
        return points[on_floor]

    def floor_view(self):
        """(height, width) bool image: which pixels see the floor within max_distance."""
        k = self.intrinsics
        columns, rows = np.meshgrid(np.arange(k.width), np.arange(k.height))
        _, on_floor = self.floor_points(np.column_stack((columns.ravel(), rows.ravel())))
        return on_floor.reshape(k.height, k.width)

    def homography(self):
        """3x3 matrix taking floor points (x, y, 1) to pixels (column, row, 1), up to scale
        (valid for points in front of the camera)."""
        k = self.intrinsics
        camera = np.array([[k.fx, 0.0, k.cx], [0.0, k.fy, k.cy], [0.0, 0.0, 1.0]])
        local = self.axes.T
        return camera.dot(np.column_stack((local[:, 0], local[:, 1], -local.dot(self.centre))))

    def floor_points(self, pixels):
        """(N, 2) floor points of the (N, 2) pixels, and (N,) whether each ray meets the floor
        within max_distance (the point is meaningless where not)."""
        k = self.intrinsics
        pixels = np.asarray(pixels, float).reshape(-1, 2)
        rays = np.column_stack(((pixels[:, 0] - k.cx) / k.fx, (pixels[:, 1] - k.cy) / k.fy,
                                np.ones(len(pixels))))
        directions = rays.dot(self.axes.T)
        down = -directions[:, 2]
        hits = down > 1e-9
        scale = self.centre[2] / np.where(hits, down, 1.0)
        points = self.centre[:2] + directions[:, :2] * scale[:, None]
        near = np.hypot(*(points - self.centre[:2]).T) <= self.max_distance
        return points, hits & near

    def to_pixels(self, points):
        """(N, 2) pixels (column, row) of (N, 2) floor points, and (N,) whether each lies in
        front of the camera."""
        k = self.intrinsics
        points = np.asarray(points, float).reshape(-1, 2)
        offsets = np.column_stack((points, np.zeros(len(points)))) - self.centre
        local = offsets.dot(self.axes)
        ahead = local[:, 2] > 1e-9
        depth = np.where(ahead, local[:, 2], 1.0)
        pixels = np.column_stack((k.fx * local[:, 0] / depth + k.cx,
                                  k.fy * local[:, 1] / depth + k.cy))
        return pixels, ahead

    def sees(self, points, margin):
        """(N,) whether each floor point is in view: in front, inside the image by margin
        pixels, and within max_distance."""
        k = self.intrinsics
        pixels, ahead = self.to_pixels(points)
        inside = ((pixels[:, 0] >= margin) & (pixels[:, 0] <= k.width - 1 - margin)
                  & (pixels[:, 1] >= margin) & (pixels[:, 1] <= k.height - 1 - margin))
        near = np.hypot(*(np.asarray(points, float).reshape(-1, 2)
                          - self.centre[:2]).T) <= self.max_distance
        return ahead & inside & near
