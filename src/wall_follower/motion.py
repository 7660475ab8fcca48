"""Velocity commands as plain values, and the safety clamp every node applies.

The course's real TurtleBot3 kills a node that exceeds 0.19 m/s or
0.49 rad/s, so no command leaves a node without passing through clamp().
"""
from collections import namedtuple

MAX_LINEAR = 0.19
MAX_ANGULAR = 0.49

Command = namedtuple('Command', ['linear', 'angular'])
STOP = Command(0.0, 0.0)


def clamp(command, max_linear=MAX_LINEAR, max_angular=MAX_ANGULAR):
    """Limit a Command to +-max_linear and +-max_angular (NaN becomes 0)."""
    def limit(value, bound):
        if value != value:  # NaN
            return 0.0
        return max(-bound, min(bound, float(value)))
    return Command(limit(command.linear, max_linear), limit(command.angular, max_angular))
