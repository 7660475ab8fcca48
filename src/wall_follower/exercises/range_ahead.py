"""The distance straight ahead, read by angle: the lab's experiment 2 done right.

The lab reads ranges[len(ranges) / 2], which is straight ahead only for a
laser whose sweep starts straight behind (the course's 720-beam one); on
the TurtleBot3's LDS-01, in Gazebo and in Stage's 360-degree laser that
beam points behind or beside the robot, and an LDS-01 writes 0.0 for "no
return", which it would print as an obstacle at 0 m. Here the beams within
a small window of 0 rad are found from the scan's own angles, invalid
readings are dropped, and the median of the rest is the answer.
"""
import math
from collections import namedtuple

import numpy as np

Ahead = namedtuple('Ahead', ['distance', 'hits', 'free', 'unknown'])
"""distance: median valid range in the window [m], None without one; hits,
free, unknown: how many beams of the window were valid, proven no-returns
(nothing up to range_max), and readings that prove nothing."""


def range_ahead(view, half_width):
    """An Ahead for a ScanView: what lies within half_width [rad] of straight ahead."""
    window = view.in_sector(0.0, half_width)
    hits = view.ranges[window & view.valid]
    free = int((window & view.free).sum())
    unknown = int(window.sum()) - hits.size - free
    distance = float(np.median(hits)) if hits.size else None
    return Ahead(distance, int(hits.size), free, unknown)


def describe(ahead, half_width, range_max):
    """One line for a person: the distance, or plainly why there is none."""
    if ahead.distance is not None:
        return 'range ahead: %.3f m' % ahead.distance
    if ahead.free:
        why = 'nothing within the laser\'s %.1f m' % range_max
    else:
        why = '%d reading%s there prove%s nothing (0.0, NaN or out of range)' % (
            ahead.unknown, '' if ahead.unknown == 1 else 's', 's' if ahead.unknown == 1 else '')
    return 'range ahead: no valid reading within %.0f deg of straight ahead: %s' % (
        math.degrees(half_width), why)
