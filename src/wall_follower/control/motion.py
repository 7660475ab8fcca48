"""Velocity commands as plain values, and the safety clamp every node applies.

The course's real TurtleBot3 kills a node that exceeds MAX_LINEAR or
MAX_ANGULAR, so no command leaves a node without passing through clamp().
"""
import math
from collections import namedtuple

import numpy as np

from wall_follower.params.driving import MAX_ANGULAR, MAX_LINEAR

Command = namedtuple('Command', ['linear', 'angular'])
STOP = Command(0.0, 0.0)

Answer = namedtuple('Answer', ['command', 'ahead_known'])
"""A controller's Command with whether it knows the way ahead well enough to drive into it
(a camera's controller says so; a laser's command is judged by its scan's beams)."""


def clamp(command, max_linear=MAX_LINEAR, max_angular=MAX_ANGULAR):
    """Limit a Command to +-max_linear and +-max_angular (NaN becomes 0)."""
    def limit(value, bound):
        if value != value:  # NaN
            return 0.0
        return max(-bound, min(bound, float(value)))
    return Command(limit(command.linear, max_linear), limit(command.angular, max_angular))


def along_curvature(curvature, max_linear, max_angular):
    """The fastest Command along a path of curvature [1/m] (> 0 to the left) within the limits.

    Where max_linear would turn faster than max_angular, the turn is held at
    max_angular and the speed lowered to fit the curvature: a controller
    that steers by curvature keeps its turn at the limit round a curve and
    still corrects its path, by its speed.
    """
    if abs(curvature) * max_linear > max_angular:
        return Command(max_angular / abs(curvature), math.copysign(max_angular, curvature))
    return Command(max_linear, curvature * max_linear)


def seen_after_move(points, advance, turn, laser_x=0.0):
    """(N, 2) laser-frame points as the laser sees them after the robot's move.

    The robot drives advance metres ahead and then turns turn rad left
    about its rotation centre; the laser sits laser_x ahead of that centre.
    A laser off the centre (the Burger's sits 32 mm behind it) is
    carried sideways by every turn, which a controller circling a point
    at full turn rate has to know about.
    """
    c, s = math.cos(turn), math.sin(turn)
    x, y = points[:, 0] + laser_x - advance, points[:, 1]
    return np.column_stack((c * x + s * y - laser_x, -s * x + c * y))
