"""The rules stageros applies around each world step, kept free of ROS so that
they can be tested alone: how several robots are named, when the cmd_vel
watchdog stops a robot, and how a start pose is written on the command line.
"""
import math

# Simulated times are sums of 0.1 s steps; compare them with this slack so
# that 0.7 - 0.5 counts as the 0.2 s it means (stageros uses integer ns).
_TIME_EPSILON = 1e-9


def robot_prefix(index, robot_count):
    """Name prefix of robot `index`: none for a lone robot, 'robot_<i>/' for
    several, as stageros names topics (robot_0/base_scan) and frames
    (robot_0/base_link). Relative, so that a launch namespace still applies.
    """
    if robot_count <= 1:
        return ''
    return 'robot_%d/' % index


class CommandWatchdog(object):
    """Stops a robot whose velocity commands have stopped coming.

    stageros stamps each cmd_vel with the simulated time of the last world
    update before it arrived and, after every update, stops the robot once
    `now - stamp >= timeout`. One single message therefore drives the robot
    for two 0.1 s updates with the default 0.2 s. A timeout <= 0 disables
    the watchdog; a robot that never received a command counts as stopped.
    """

    def __init__(self, timeout):
        self.timeout = timeout
        self.last_command = None

    def command_received(self, sim_time):
        self.last_command = sim_time

    def reset(self):
        self.last_command = None

    def expired(self, sim_time):
        if self.last_command is None:
            return True
        if self.timeout <= 0.0:
            return False
        return sim_time - self.last_command >= self.timeout - _TIME_EPSILON


def parse_pose(text):
    """(x, y, yaw [rad]) from 'x y yaw_deg' (commas also accepted); None for ''.

    Raises ValueError with a message that quotes the text.
    """
    fields = text.replace(',', ' ').split()
    if not fields:
        return None
    if len(fields) != 3:
        raise ValueError("pose %r: expected 'x y yaw_deg'" % text)
    try:
        x, y, yaw_deg = (float(field) for field in fields)
    except ValueError:
        raise ValueError("pose %r: expected three numbers 'x y yaw_deg'" % text) from None
    if not all(math.isfinite(value) for value in (x, y, yaw_deg)):
        raise ValueError('pose %r: values must be finite' % text)
    return x, y, math.radians(yaw_deg)
