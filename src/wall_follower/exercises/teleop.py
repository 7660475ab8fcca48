"""Keyboard teleoperation with the keys and ramp of ROBOTIS's turtlebot3_teleop_key.

w/x raise/lower the target speed by `linear_step`, a/d the target turn
rate by `angular_step`, s or space stop at once, Ctrl-C (or its byte, 0x03,
read from a pipe) quits. The command sent moves toward the target by half a
step per tick, as ROBOTIS's does, so that a key held down accelerates
smoothly. Targets are clamped to `max_linear` and `max_angular`, the
package's limits; ROBOTIS's own (BURGER_MAX_*) are the hardware's, which
the course's real robot does not allow.
"""
from wall_follower.control.motion import Command
from wall_follower.params import checked
from wall_follower.params.exercises.teleop_key import TELEOP

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
    """The target set by keys and the command ramping toward it, one tick at a time.

    Its parameters (keyword arguments; their defaults, ranges and meanings
    are the TELEOP table) are the defaults overridden by those given.
    """

    def __init__(self, **params):
        self.target = Command(0.0, 0.0)
        self.command = Command(0.0, 0.0)
        self.quit = False
        self.reconfigure(**params)

    def reconfigure(self, **params):
        """Go on under these parameters (the defaults, overridden) from the next key and tick
        on; a target beyond new limits is brought within them."""
        p = checked(TELEOP, params)
        self.max_linear, self.max_angular = p['max_linear'], p['max_angular']
        self.linear_step, self.angular_step = p['linear_step'], p['angular_step']
        self.target = Command(limit(self.target.linear, self.max_linear),
                              limit(self.target.angular, self.max_angular))

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
