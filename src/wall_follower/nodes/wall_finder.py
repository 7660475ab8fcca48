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
from wall_follower.control.finder import WallFinder
from wall_follower.nodes.common import LatestScan, VelocityCommander
from wall_follower.nodes.parameters import NodeParameters
from wall_follower.params import pick
from wall_follower.params.wall_finder import FINDER, TABLE
from wall_follower.srv import FindWall, FindWallResponse


class WallFinderNode(object):
    """Offers find_wall; each call runs one search with a fresh WallFinder."""

    def __init__(self):
        self.params = NodeParameters(TABLE, WallFinderConfig)
        self.commander = VelocityCommander('cmd_vel')
        self.scan = LatestScan('scan')
        self._busy = threading.Lock()
        self.service = rospy.Service('find_wall', FindWall, self.handle)
        rospy.loginfo('find_wall: ready (timeout %.0f s)', self.params.snapshot()['timeout'])

    def _apply(self, values, finder):
        """Put the node's parameters (name -> value) in force for this search.

        max_linear and max_angular are both the behaviour's limits and the
        commander's clamp, so the behaviour never asks for more than is sent.
        """
        self.rate, self.keepalive = values['rate'], values['keepalive']
        self.timeout, self.scan_timeout = values['timeout'], values['scan_timeout']
        self.commander.max_linear = values['max_linear']
        self.commander.max_angular = values['max_angular']
        finder.reconfigure(**pick(values, FINDER))

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
        finder = WallFinder()
        self._apply(self.params.snapshot(), finder)
        finder.start()
        rospy.loginfo('find_wall: searching for the nearest wall')
        started = sent = rospy.get_time()
        state = finder.state
        last_view = None
        while not rospy.is_shutdown():
            now = rospy.get_time()
            elapsed = now - started
            if elapsed > self.timeout:
                rospy.logwarn('find_wall: gave up after %.1f s (~timeout) in state %s',
                              elapsed, finder.state)
                return False
            view = self.scan.fresh(self.scan_timeout)
            if view is None:
                if elapsed > self.scan_timeout:
                    rospy.logwarn('find_wall: no scan on %s for %.1f s; stopping',
                                  rospy.resolve_name('scan'), self.scan_timeout)
                    return False
                self.commander.stop()
            elif view is not last_view:
                last_view = view
                update = self.params.take_update()
                if update is not None:
                    self._apply(update, finder)
                self.commander.send(finder.update(view))
                sent = now
                if finder.state != state:
                    rospy.loginfo('find_wall: %s -> %s%s', state, finder.state, _describe(finder))
                    state = finder.state
                if finder.done:
                    return self._report(finder, rospy.get_time() - started)
            elif now - sent >= self.keepalive:
                self.commander.send(self.commander.last)
                sent = now
            self.scan.wait_for_newer(last_view, 1.0 / self.rate)
        return False

    @staticmethod
    def _report(finder, elapsed):
        if finder.success:
            rospy.loginfo('find_wall: wall found: %.3f m on the right after %.1f s',
                          finder.wall.distance, elapsed)
        else:
            rospy.logwarn('find_wall: no wall found: %s', finder.failure_reason)
        return finder.success


def _describe(finder):
    if finder.wall is None:
        return ''
    return ' (wall %.2f m away at %.0f deg)' % (
        finder.wall.distance, math.degrees(finder.wall.angle))


def main():
    rospy.init_node('wall_finder')
    WallFinderNode()
    rospy.spin()
