"""Synthetic laser scans of straight-segment worlds, in each real laser's conventions.

Shared by the unit tests (not itself a test module). A world is a list of
segments ((x0, y0), (x1, y1)); a scan is cast exactly from a laser pose and
written the way each laser writes it: where beam 0 points, how many beams,
and what "no return" looks like.
"""
import math
from collections import namedtuple

import numpy as np

from wall_follower.control.sensing.scan import ScanView

Convention = namedtuple('Convention', ['name', 'angle_min', 'count', 'increment',
                                       'range_min', 'range_max', 'no_return'])

STAGE = Convention('stage', -math.pi, 360, 2.0 * math.pi / 359, 0.12, 3.5, 'range_max')
LDS01 = Convention('lds01', 0.0, 360, 2.0 * math.pi / 360, 0.12, 3.5, 0.0)
GAZEBO = Convention('gazebo', 0.0, 360, 2.0 * math.pi / 360, 0.12, 3.5, math.inf)
COURSE_720 = Convention('course720', -math.pi, 720, 2.0 * math.pi / 720, 0.12, 30.0, math.inf)
CONVENTIONS = [STAGE, LDS01, GAZEBO, COURSE_720]


def box(x0, y0, x1, y1):
    """The four sides of an axis-aligned rectangle."""
    return [((x0, y0), (x1, y0)), ((x1, y0), (x1, y1)),
            ((x1, y1), (x0, y1)), ((x0, y1), (x0, y0))]


def cast(segments, pose, convention):
    """Ranges of a scan taken at pose (x, y, yaw), as the convention writes them."""
    x, y, yaw = pose
    angles = yaw + convention.angle_min + convention.increment * np.arange(convention.count)
    dx, dy = np.cos(angles), np.sin(angles)
    ranges = np.full(convention.count, np.inf)
    for (ax, ay), (bx, by) in segments:
        ex, ey = bx - ax, by - ay
        denom = dx * ey - dy * ex
        with np.errstate(divide='ignore', invalid='ignore'):
            t = ((ax - x) * ey - (ay - y) * ex) / denom
            s = ((ax - x) * dy - (ay - y) * dx) / denom
        hit = (np.abs(denom) > 1e-12) & (t > 0.0) & (s >= 0.0) & (s <= 1.0)
        ranges = np.where(hit & (t < ranges), t, ranges)
    missing = ~(ranges < convention.range_max)
    if convention.no_return == 'range_max':
        ranges[missing] = convention.range_max
    else:
        ranges[missing] = convention.no_return
    return ranges


def scan_view(segments, pose, convention):
    return ScanView(cast(segments, pose, convention), convention.angle_min,
                    convention.increment, convention.range_min, convention.range_max)


# Beam 0 backwards and the sweep clockwise (a negative increment): no laser
# of the table does this, but nothing may depend on the sweep's direction.
REVERSED = Convention('reversed', math.pi, 360, -2.0 * math.pi / 360, 0.12, 3.5, math.inf)
