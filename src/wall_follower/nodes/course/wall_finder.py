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

from wall_follower.cfg import WallFinderConfig
from wall_follower.control.course.finder import WallFinder
from wall_follower.nodes.shared.drive_loop import drive_loop, take_retuned, tune_drive_loop
from wall_follower.nodes.shared.laser_mount import laser_x
from wall_follower.nodes.shared.latest_scan import LatestScan
from wall_follower.nodes.shared.parameters import NodeParameters
from wall_follower.nodes.shared.startup import init_node
from wall_follower.params import pick
from wall_follower.params.course.wall_finder import FINDER, TABLE
from wall_follower.srv import FindWall, FindWallResponse


class WallFinderNode(object):
    """Offers find_wall; each call runs one search with a fresh WallFinder."""

    def __init__(self):
        # ~laser_x if set, else read from tf, once the given values have passed.
        self.params = NodeParameters(TABLE, WallFinderConfig, found={'laser_x': laser_x})
        values = self.params.snapshot()
        # max_linear and max_angular are the behaviour's limits and the clamp
        # alike, so the behaviour never asks for more than the node will send.
        self.loop = drive_loop('find_wall', values, LatestScan('scan'))
        self.commander = self.loop.commander
        self._busy = threading.Lock()
        self.service = rospy.Service('find_wall', FindWall, self.handle)
        rospy.loginfo('find_wall: ready (timeout %.0f s)', values['timeout'])

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
        values = self.params.snapshot()
        search = Search(WallFinder(**pick(values, FINDER)), values['timeout'])
        tune_drive_loop(self.loop, values)
        rospy.loginfo('find_wall: searching for the nearest wall')
        return self.loop.run(lambda view, taken: self._answer(search, view, taken),
                             search.outcome, patience=self.loop.input_timeout,
                             on_clock_reset=search.restart) is True

    def _answer(self, search, view, taken):
        """The search's answer to a scan, under any parameters changed since the last."""
        values = take_retuned(self.params, self.loop)
        if values is not None:
            search.timeout = values['timeout']
            search.finder.reconfigure(**pick(values, FINDER))
        return search.answer(view, taken)


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
