"""Keyboard teleoperation with the keys and ramp of ROBOTIS's turtlebot3_teleop_key.

w/x raise/lower the target speed by LINEAR_STEP, a/d the target turn rate
by ANGULAR_STEP, s or space stop at once, Ctrl-C (or its byte, 0x03, read
from a pipe) quits. The command sent moves toward the target by half a step
per tick, as ROBOTIS's does, so that a key held down accelerates smoothly.
Targets are clamped to the limits given, the package's 0.19 m/s and
0.49 rad/s by default; ROBOTIS's own limits (BURGER_MAX_*) are the
hardware's, which the course's real robot does not allow.
"""
from wall_follower.control.motion import Command

LINEAR_STEP = 0.01    # m/s per key press
ANGULAR_STEP = 0.1    # rad/s per key press
BURGER_MAX_LINEAR = 0.22    # the Burger's hardware limits [m/s, rad/s], for reference
BURGER_MAX_ANGULAR = 2.84

QUIT = '\x03'
STOP_KEYS = ('s', ' ')
# key -> (steps of linear, steps of angular)
STEPS = {'w': (1, 0), 'x': (-1, 0), 'a': (0, 1), 'd': (0, -1)}

USAGE = """Control your TurtleBot3!
---------------------------
Moving around:
        w
   a    s    d
        x

w/x : increase/decrease linear velocity (limit %.2f m/s)
a/d : increase/decrease angular velocity (limit %.2f rad/s)
space key, s : force stop

CTRL-C to quit"""


def ramp(current, target, slop):
    """current moved toward target by at most slop."""
    if target > current:
        return min(target, current + slop)
    if target < current:
        return max(target, current - slop)
    return target


def limit(value, bound):
    return max(-bound, min(bound, value))


class Teleop(object):
    """The target set by keys and the command ramping toward it, one tick at a time."""

    def __init__(self, max_linear, max_angular, linear_step=LINEAR_STEP,
                 angular_step=ANGULAR_STEP):
        self.max_linear = abs(max_linear)
        self.max_angular = abs(max_angular)
        self.linear_step = linear_step
        self.angular_step = angular_step
        self.target = Command(0.0, 0.0)
        self.command = Command(0.0, 0.0)
        self.quit = False

    def press(self, key):
        """Apply one key; True when it changed the target (or stopped the robot)."""
        if key == QUIT:
            self.quit = True
            self.target = self.command = Command(0.0, 0.0)
            return False
        if key in STOP_KEYS:
            self.target = self.command = Command(0.0, 0.0)
            return True
        if key not in STEPS:
            return False
        linear, angular = STEPS[key]
        self.target = Command(
            limit(self.target.linear + linear * self.linear_step, self.max_linear),
            limit(self.target.angular + angular * self.angular_step, self.max_angular))
        return True

    def tick(self):
        """The next command: half a step nearer the target on each axis."""
        self.command = Command(
            ramp(self.command.linear, self.target.linear, self.linear_step / 2.0),
            ramp(self.command.angular, self.target.angular, self.angular_step / 2.0))
        return self.command

    def describe(self):
        return 'target: linear %.2f m/s, angular %.2f rad/s' % self.target
