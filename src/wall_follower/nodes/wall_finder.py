"""The find_wall service node: on each call, drive to the nearest wall and put it on the right.

The handler steps the WallFinder state machine once for each new scan, which
the scan subscriber keeps delivering in its own thread. Whatever happens
(success, failure, time-out, shutdown), the robot is left standing still.
Only one search runs at a time: a call that arrives while another is in
progress is refused at once with wallfound false.
"""
import math
import threading

import rospy

from wall_follower.control.finder import DEFAULTS as FINDER_DEFAULTS
from wall_follower.control.finder import WallFinder
from wall_follower.nodes.common import LatestScan, VelocityCommander, init_node, private_params
from wall_follower.nodes.drive_loop import DriveLoop
from wall_follower.srv import FindWall, FindWallResponse

NODE_DEFAULTS = {
    'rate': 20.0,
    'keepalive': 0.15,
    'timeout': 60.0,
    'scan_timeout': 1.0,
    'ahead_half_width': 0.5236,
}
"""Parameters of the node itself (the finder's own are finder.DEFAULTS).

rate: how often (Hz) the loop looks at the clock while it waits for scans.
    Each new scan is answered at once with a new command.
keepalive: when no new scan has come for this long (ROS s), the last
    command is sent again, so that a velocity watchdog (stageros stops the
    robot after 0.2 s without one) does not stop the robot mid-turn. Longer
    than a scan period, so that a repeat never stands in for an answer.
timeout: a call that has not succeeded after this long (ROS s) answers false.
scan_timeout: a call answers false when no usable scan younger than this
    (ROS s) is available this long after it started, or at any point later on.
ahead_half_width: never drive forward while no beam within this angle (rad)
    either side of straight ahead reads a hit or a proven no-return.
"""

# The TurtleBot3 Burger (and every world of this package) has its laser
# 32 mm behind the wheel axle; the finder's own default assumes none.
ROBOT_DEFAULTS = {'laser_x': -0.032}


class WallFinderNode(object):
    """Offers find_wall; each call runs one search with a fresh WallFinder."""

    def __init__(self):
        defaults = dict(FINDER_DEFAULTS)
        defaults.update(ROBOT_DEFAULTS)
        defaults.update(NODE_DEFAULTS)
        params = private_params(defaults)
        self.rate = params.pop('rate')
        self.keepalive = params.pop('keepalive')
        self.timeout = params.pop('timeout')
        self.scan_timeout = params.pop('scan_timeout')
        self.ahead_half_width = params.pop('ahead_half_width')
        self.finder_params = params
        self.commander = VelocityCommander('cmd_vel')
        # The behaviour never asks for more than the node will send.
        self.finder_params['max_linear'] = min(params['max_linear'], self.commander.max_linear)
        self.finder_params['max_angular'] = min(params['max_angular'], self.commander.max_angular)
        self.loop = DriveLoop('find_wall', LatestScan('scan'), self.commander, self.rate,
                              self.keepalive, self.scan_timeout, self.ahead_half_width)
        self._busy = threading.Lock()
        self.service = rospy.Service('find_wall', FindWall, self.handle)
        rospy.loginfo('find_wall: ready (timeout %.0f s)', self.timeout)

    def handle(self, _request):
        """One call, one search. rospy serves each caller in its own thread,
        so a second caller is turned away at once rather than queued behind
        (or worse, steering against) the search that is running."""
        if not self._busy.acquire(False):
            rospy.logwarn('find_wall: refused: a search is already running; '
                          'call again when it has ended')
            return FindWallResponse(wallfound=False)
        try:
            return FindWallResponse(wallfound=self._search())
        finally:
            self.commander.stop()
            self._busy.release()

    def _search(self):
        """Run one search to its end; True when the wall is on the right."""
        search = Search(WallFinder(**self.finder_params), self.timeout)
        rospy.loginfo('find_wall: searching for the nearest wall')
        return self.loop.run(search.answer, search.outcome, patience=self.scan_timeout,
                             on_clock_reset=search.restart) is True


class Search(object):
    """One find_wall call: the WallFinder it steps, timed from the call on ROS time."""

    def __init__(self, finder, timeout):
        self.finder = finder
        self.timeout = timeout
        self.restart()

    def restart(self):
        """Start from the beginning, e.g. when ROS time has moved back."""
        self.finder.start()
        self.started = rospy.get_time()
        self.state = self.finder.state

    def answer(self, view, _taken):
        command = self.finder.update(view)
        if self.finder.state != self.state:
            rospy.loginfo('find_wall: %s -> %s%s', self.state, self.finder.state,
                          _describe(self.finder))
            self.state = self.finder.state
        return command

    def outcome(self):
        """True or False once the search has ended, else None."""
        elapsed = rospy.get_time() - self.started
        finder = self.finder
        if finder.done:
            if finder.success:
                rospy.loginfo('find_wall: wall found: %.3f m on the right after %.1f s',
                              finder.wall.distance, elapsed)
            else:
                rospy.logwarn('find_wall: no wall found: %s', finder.failure_reason)
            return finder.success
        if elapsed > self.timeout:
            rospy.logwarn('find_wall: gave up after %.1f s (~timeout) in state %s',
                          elapsed, finder.state)
            return False
        return None


def _describe(finder):
    if finder.wall is None:
        return ''
    return ' (wall %.2f m away at %.0f deg)' % (
        finder.wall.distance, math.degrees(finder.wall.angle))


def main():
    init_node('wall_finder')
    WallFinderNode()
    rospy.spin()
