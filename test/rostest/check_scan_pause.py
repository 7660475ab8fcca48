#!/usr/bin/env python3
"""rostest: scans stop mid-lap, or come stamped far ahead of the clock; the robot stands still
within 0.5 s and drives on when good scans return.

Judged from ground truth: no pose stamped from 0.5 s after the last good
scan the gate passed on (plus the step its stop takes to act, and the steps
the scan may take to reach the follower) differs from the next, and the
robot moves again once the gate passes good scans again. Scans stamped
2100-01-01, or with the largest stamp a header holds (2**32 - 1 s), are
stale: the follower says so, stops, its last command a stop, and does not
die of them.
"""
import math
import sys
import threading
import unittest

import rospy
import rostest
from drive_guard import DriveGuard
from geometry_msgs.msg import Twist
from rosgraph_msgs.msg import Log
from rosout_log import RosoutLog
from sim_probe import SimProbe, pose_of
from std_srvs.srv import SetBool

from waiting import wait_until

STEP = 0.1          # the world's interval_sim [s]
STOP_WITHIN = 0.5   # [simulated s]
# The gate's scan reaches the follower on another connection: on a busy machine the
# world may step (on the follower's keepalive commands) before it is heard.
DELIVERY = 2 * STEP
PAUSE = 3.0         # [simulated s]
NODE = '/wall_following'
# Stamps no clock of a working robot reads: 2100-01-01, and the largest a header holds.
FAR_AHEAD = (4102444800.0, 4294967295.0)
WARNING = "years ahead of this node's clock; stopped"
WAIT_LIMIT = 20.0   # wall s


def moved(truths):
    """Largest distance between consecutive poses of a list of ground truth messages."""
    poses = [pose_of(msg) for msg in truths]
    return max([math.hypot(b[0] - a[0], b[1] - a[1]) for a, b in zip(poses, poses[1:])] or [0.0])


class Commands(object):
    """The last cmd_vel heard, as (linear, angular)."""

    def __init__(self):
        self.lock = threading.Lock()
        self.last = None
        rospy.Subscriber('cmd_vel', Twist, self._on_cmd, queue_size=100)

    def _on_cmd(self, msg):
        with self.lock:
            self.last = (msg.linear.x, msg.angular.z)


class ScanPause(unittest.TestCase):

    def setUp(self):
        self.guard = DriveGuard()
        self.commands = Commands()
        self.probe = SimProbe()
        self.gate = rospy.ServiceProxy('scan_gate/set_open', SetBool)
        self.gate.wait_for_service(30.0)
        self.probe.wait_ready()
        self.probe.wait_for(lambda: len(self.probe.truths) > 30, 'the lap to start')

    def wait_driving(self, what):
        since = rospy.get_time()
        self.probe.wait_for(lambda: moved(self.probe.truths_since(since)) > 0.01, what)

    def assert_still_after(self, last_good, what):
        """Wait PAUSE; the robot must not have moved from STOP_WITHIN after the last good
        scan on (with a step to act and DELIVERY)."""
        rospy.sleep(PAUSE)
        still = self.probe.truths_since(last_good + STOP_WITHIN + STEP + DELIVERY)
        self.assertGreater(len(still), 10)
        self.assertLess(moved(still), 1e-4, 'moved while %s' % what)

    def test_stops_without_scans_and_resumes(self):
        self.wait_driving('the robot to drive')
        last_scan = float(self.gate(False).message)
        self.assert_still_after(last_scan, 'blind')
        self.gate(True)
        self.wait_driving('the robot to drive again')
        self.guard.assert_safe(self)

    def test_stops_on_scans_stamped_far_ahead_and_resumes(self):
        log = RosoutLog(NODE)
        for stamp in FAR_AHEAD:
            self.wait_driving('the robot to drive')
            warnings = len(log.lines(NODE, WARNING, Log.WARN))
            last_good = float(self.gate(False).message)
            rospy.set_param('scan_gate/stamp', stamp)
            self.gate(True)
            try:
                self.assert_still_after(last_good, 'its scans were stamped %.0f s' % stamp)
                self.assertTrue(wait_until(lambda: len(log.lines(NODE, WARNING, Log.WARN))
                                           > warnings, WAIT_LIMIT),
                                'no warning saying "%s" of scans stamped %.0f s' % (WARNING, stamp))
                with self.commands.lock:
                    self.assertEqual(self.commands.last, (0.0, 0.0),
                                     'the last command on scans stamped %.0f s' % stamp)
            finally:
                self.gate(False)
                rospy.set_param('scan_gate/stamp', 0.0)
                self.gate(True)
            self.wait_driving('the robot to drive again on good scans')
        self.assertFalse(log.lines(NODE, 'Traceback'))
        self.guard.assert_safe(self)


if __name__ == '__main__':
    rospy.init_node('check_scan_pause')
    rostest.rosrun('wall_follower', 'check_scan_pause', ScanPause, sys.argv)
