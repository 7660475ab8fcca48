"""stage_sim's interface rules that need no ROS master: which file a `world`
argument names, how several robots are named (as stageros names them), how
a start pose is written as a parameter, and the line it logs at quit_time
(which the sim benchmark reads back).
"""
import math
import re

import rospkg

_QUIT_REPORT = re.compile(r'quit_time [0-9.]+ s of simulated time reached after [0-9.]+ wall s '
                          r'\(([0-9.]+)x real time\)')


def robot_prefix(index, robot_count):
    """Name prefix of robot `index`: none for a lone robot, 'robot_<i>/' for
    several, as stageros names topics (robot_0/base_scan) and frames
    (robot_0/base_link). Relative, so that a launch namespace still applies.
    """
    if robot_count <= 1:
        return ''
    return 'robot_%d/' % index


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


def quit_report(quit_time, wall_seconds):
    """What stage_sim logs when it reaches quit_time, wall_seconds after its first step.

    The real-time multiple in it is the only way to see how fast the
    simulator runs with nobody subscribed to anything.
    """
    return 'quit_time %.1f s of simulated time reached after %.2f wall s (%.0fx real time)' % (
        quit_time, wall_seconds, quit_time / max(wall_seconds, 1e-9))


def rate_in_quit_report(text):
    """The real-time multiple of the first quit_report line in `text`, or None."""
    found = _QUIT_REPORT.search(text)
    return float(found.group(1)) if found else None


def world_path(world):
    """The .world file meant by a launch file's `world` argument.

    A bare name (`arena`) is a world shipped in this package's worlds/; an
    absolute path is taken as it is, as simulation.launch does.
    """
    if world.startswith('/'):
        return world
    name = world if world.endswith('.world') else world + '.world'
    return '%s/worlds/%s' % (rospkg.RosPack().get_path('wall_follower'), name)
