"""stage_sim's interface rules that need no ROS: how several robots are named
(as stageros names them) and how a start pose is written as a parameter.
"""
import math


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
