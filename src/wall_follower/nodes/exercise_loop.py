"""What the lab exercises' driving nodes share: their DriveLoop's parameters and set-up."""
import rospy

from wall_follower.nodes.common import LatestScan, VelocityCommander
from wall_follower.nodes.drive_loop import DriveLoop

LOOP_DEFAULTS = {
    'rate': 20.0,
    'keepalive': 0.15,
    'scan_timeout': 0.5,
    'ahead_half_width': 0.5236,
}
"""rate: how often (Hz) the loop looks at the clock while it waits for scans.
keepalive: with no new scan for this long (ROS s), send the last command
    again, so that Stage's 0.2 s cmd_vel watchdog does not stop the robot.
scan_timeout: stop the robot while the newest scan is older than this (ROS s).
ahead_half_width: never drive forward while no beam within this angle (rad)
    either side of straight ahead reads a hit or a proven no-return.
"""


def split_params(params, names):
    """Take the entries named out of params (in place) into a dict of their own."""
    return dict((name, params.pop(name)) for name in names)


def drive_loop(name, loop_params, tick=None):
    """A DriveLoop on scan and cmd_vel (clamped to ~max_linear, ~max_angular), from
    LOOP_DEFAULTS' names."""
    return DriveLoop(name, LatestScan('scan'), VelocityCommander('cmd_vel'),
                     loop_params['rate'], loop_params['keepalive'], loop_params['scan_timeout'],
                     loop_params['ahead_half_width'], tick=tick)


def behaviour_or_exit(name, make, params):
    """make(**params), or None after a clear error when a parameter is refused."""
    try:
        return make(**params)
    except ValueError as error:
        rospy.logfatal('%s: bad parameters: %s', name, error)
        return None
