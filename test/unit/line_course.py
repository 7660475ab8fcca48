"""A synthetic line course and camera for closed-loop tests of the line follower's step.

The course is a centreline, painted on the floor as a band of the line's
width; the camera renders it (the floor's pixels through the camera's
projection, yellow on the band, white elsewhere), and the frame goes through
the line follower's own step (vision.line_step), as the node runs it. The
robot moves as a unicycle in steps of STEP, one frame a step, as the
built-in simulator in lockstep does, and never forward unless the step says
the line is known ahead (as the node's drive loop holds it).
"""
import math

import cv2
import numpy as np

from wall_follower.control.motion import Command, clamp
from wall_follower.params import defaults
from wall_follower.params.camera.line_follower import TABLE
from wall_follower.vision.floor import FloorProjection, Intrinsics, level_camera_axes
from wall_follower.vision.line_step import LineStep

STEP = 0.1
LINE_WIDTH = 0.045
PAINT_CELL = 0.0025    # m: the painted floor's raster
YELLOW, WHITE = (0, 255, 255), (255, 255, 255)


def arc(centre, radius, start, sweep, spacing=0.002):
    count = max(2, int(abs(sweep) * radius / spacing))
    angles = start + np.linspace(0.0, sweep, count)
    return np.column_stack((centre[0] + radius * np.cos(angles),
                            centre[1] + radius * np.sin(angles)))


def segment(a, b, spacing=0.002):
    count = max(2, int(np.hypot(b[0] - a[0], b[1] - a[1]) / spacing))
    t = np.linspace(0.0, 1.0, count)[:, None]
    return np.asarray(a) * (1 - t) + np.asarray(b) * t


class PaintedFloor(object):
    """The centreline painted width [m] wide on a raster of the floor, and frames of it."""

    def __init__(self, centreline, width=LINE_WIDTH, margin=3.0):
        self.origin = centreline.min(axis=0) - margin
        size = np.ceil((centreline.max(axis=0) + margin - self.origin) / PAINT_CELL).astype(int)
        self.raster = np.zeros((size[1], size[0]), np.uint8)
        cells = np.round((centreline - self.origin) / PAINT_CELL).astype(np.int32)
        cv2.polylines(self.raster, [cells.reshape(-1, 1, 2)], False, 255,
                      thickness=int(round(width / PAINT_CELL)))
        self._floor_view = (None, None)    # (projection key, pixels that see the floor)

    def frame(self, projection, base):
        """The BGR image the camera of projection sees from the base at (x, y, yaw)."""
        k = projection.intrinsics
        x, y, yaw = base
        c, s = math.cos(yaw), math.sin(yaw)
        to_raster = np.array([[1.0 / PAINT_CELL, 0.0, -self.origin[0] / PAINT_CELL],
                              [0.0, 1.0 / PAINT_CELL, -self.origin[1] / PAINT_CELL],
                              [0.0, 0.0, 1.0]])
        to_world = np.array([[c, -s, x], [s, c, y], [0.0, 0.0, 1.0]])
        to_floor = np.linalg.inv(projection.homography())
        painted = cv2.warpPerspective(self.raster, to_raster.dot(to_world).dot(to_floor),
                                      (k.width, k.height),
                                      flags=cv2.INTER_NEAREST | cv2.WARP_INVERSE_MAP)
        if self._floor_view[0] != projection.key():
            self._floor_view = (projection.key(), FloorProjection(
                k, projection.axes, projection.centre, 1e3).floor_view())
        floor = self._floor_view[1]
        image = np.empty((k.height, k.width, 3), np.uint8)
        image[:] = WHITE
        image[(painted > 0) & floor] = YELLOW
        return image


def distance_to(centreline, point):
    return float(np.min(np.hypot(*(centreline - point).T)))


def camera(height=0.25, tilt_deg=40.0, width=320, image_height=240, hfov=62.2, vfov=48.8):
    fx = width / (2.0 * math.tan(math.radians(hfov) / 2.0))
    fy = image_height / (2.0 * math.tan(math.radians(vfov) / 2.0))
    k = [fx, 0, width / 2.0, 0, fy, image_height / 2.0, 0, 0, 1]
    return FloorProjection(Intrinsics.from_camera_info(k, width, image_height),
                           level_camera_axes(math.radians(tilt_deg)), (0.0, 0.0, height), 1.5)


def run(centreline, start, steps, projection=None, values=None, lose_after=None, spoil=None):
    """Drive the follower on the course; returns (poses, commands, states).

    lose_after: from this step on the camera sees nothing (a covered lens). spoil(step,
    image): the image to show instead at that step (None: the course's)."""
    projection = projection or camera()
    values = dict(defaults(TABLE), **(values or {}))
    line_step = LineStep(values)
    floor = PaintedFloor(centreline)
    pose = np.array(start, float)
    poses, commands, states = [], [], []
    for step in range(steps):
        base = tuple(pose)
        image = floor.frame(projection, base)
        if lose_after is not None and step >= lose_after:
            image[:] = WHITE
        if spoil is not None and spoil(step, image) is not None:
            image = spoil(step, image)
        answer = line_step.update(image, projection, base, values['ahead_half_width']).answer
        command = clamp(answer.command)
        if command.linear > 0.0 and not answer.ahead_known:
            command = Command(0.0, command.angular)
        poses.append(base)
        commands.append(command)
        states.append(line_step.pursuit.state)
        x, y, yaw = pose
        pose = np.array([x + command.linear * STEP * math.cos(yaw),
                         y + command.linear * STEP * math.sin(yaw),
                         yaw + command.angular * STEP])
    return np.array(poses), commands, states
