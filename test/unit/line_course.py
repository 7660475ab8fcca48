"""A synthetic line course and camera for closed-loop tests of the line follower's logic.

The course is a centreline; the camera "sees" the points of a painted
band of the line's width that fall in its view (FloorProjection.sees), as
the vision pipeline would hand them over after projecting the mask. The
robot moves as a unicycle in steps of STEP, one frame a step, as the
built-in simulator in lockstep does.
"""
import math

import numpy as np

from wall_follower.control.motion import clamp
from wall_follower.vision.floor import FloorProjection, Intrinsics, level_camera_axes
from wall_follower.vision.line_path import LinePath
from wall_follower.vision.line_pursuit import LinePursuit, in_base_frame
from wall_follower.params import defaults, pick
from wall_follower.params.line_follower import NODE, PATH, PURSUIT

STEP = 0.1
LINE_WIDTH = 0.045


def arc(centre, radius, start, sweep, spacing=0.002):
    count = max(2, int(abs(sweep) * radius / spacing))
    angles = start + np.linspace(0.0, sweep, count)
    return np.column_stack((centre[0] + radius * np.cos(angles),
                            centre[1] + radius * np.sin(angles)))


def segment(a, b, spacing=0.002):
    count = max(2, int(np.hypot(b[0] - a[0], b[1] - a[1]) / spacing))
    t = np.linspace(0.0, 1.0, count)[:, None]
    return np.asarray(a) * (1 - t) + np.asarray(b) * t


def band(centreline, width, spacing=0.005):
    """Points painted over a band of width about the centreline."""
    tangent = np.gradient(centreline, axis=0)
    normal = np.column_stack((-tangent[:, 1], tangent[:, 0]))
    normal /= np.hypot(*normal.T)[:, None]
    offsets = np.arange(-width / 2.0, width / 2.0 + 1e-9, spacing)
    points = np.vstack([centreline + o * normal for o in offsets])
    keys = np.unique(np.round(points / spacing).astype(int), axis=0)
    return keys * spacing


def distance_to(centreline, point):
    return float(np.min(np.hypot(*(centreline - point).T)))


def camera(height=0.25, tilt_deg=40.0, width=320, image_height=240, hfov=62.2, vfov=48.8):
    fx = width / (2.0 * math.tan(math.radians(hfov) / 2.0))
    fy = image_height / (2.0 * math.tan(math.radians(vfov) / 2.0))
    k = [fx, 0, width / 2.0, 0, fy, image_height / 2.0, 0, 0, 1]
    return FloorProjection(Intrinsics.from_camera_info(k, width, image_height),
                           level_camera_axes(math.radians(tilt_deg)), (0.0, 0.0, height), 1.5)


def run(centreline, start, steps, projection=None, values=None, lose_after=None):
    """Drive the follower on the course; returns (poses, commands, states).

    lose_after: from this step on the camera sees nothing (a covered lens)."""
    projection = projection or camera()
    values = dict(defaults(PATH + PURSUIT), **(values or {}))
    margin = defaults(NODE)['view_margin']
    memory = LinePath(**pick(values, PATH))
    pursuit = LinePursuit(**pick(values, PURSUIT))
    painted = band(centreline, LINE_WIDTH)
    pose = np.array(start, float)
    poses, commands, states = [], [], []
    for step in range(steps):
        base = tuple(pose)
        local = in_base_frame(painted, base)
        seen = painted[projection.sees(local, 0.0)]
        if lose_after is not None and step >= lose_after:
            seen = seen[:0]
        memory.update(seen, lambda p, b=base: projection.sees(in_base_frame(p, b), margin),
                      base, lambda p, b=base: projection.sees(in_base_frame(p, b), margin)[0])
        command = clamp(pursuit.update(memory.path, memory.end_seen, base))
        poses.append(base)
        commands.append(command)
        states.append(pursuit.state)
        x, y, yaw = pose
        pose = np.array([x + command.linear * STEP * math.cos(yaw),
                         y + command.linear * STEP * math.sin(yaw),
                         yaw + command.angular * STEP])
    return np.array(poses), commands, states
