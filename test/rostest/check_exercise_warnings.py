#!/usr/bin/env python3
"""rostest: the exercises say what is wrong with their scans, and no more often than asked.

range_ahead fed unusable scans at 10 Hz warns at its ~period (1 s here),
not at every scan; wander facing a cone with no valid reading warns while
it pivots; forward_stop warns when the scans' stamps go back. In wall
time, with synthetic scans.
"""
import math
import sys
import threading
import time
import unittest

import rospy
import rostest
from rosout_log import RosoutLog
from sensor_msgs.msg import LaserScan
from synthetic_scans import one_valid_beam

from waiting import assert_soon

PERIOD = 0.1
WAIT_LIMIT = 10.0
WATCH = 3.0              # wall s of range_ahead's warnings to count
RANGE_AHEAD_PERIOD = 1.0  # as exercise_warnings.test sets it
NODES = ('/range_ahead/range_ahead', '/wander/wander', '/forward_stop/forward_stop')


def blind_ahead():
    """Walls 1.0 m away all round, but nothing valid within 60 deg of straight ahead."""
    scan = one_valid_beam([math.nan if min(i, 360 - i) <= 60 else 1.0 for i in range(360)])
    scan.ranges[29] = math.nan
    return scan


class Feed(object):
    """Publishes a scan to one namespace at PERIOD, stamped now minus `behind` seconds."""

    def __init__(self, namespace, scan):
        self.scan, self.behind = scan, 0.0
        self.publisher = rospy.Publisher(namespace + '/scan', LaserScan, queue_size=1)
        threading.Thread(target=self._run, daemon=True).start()

    def _run(self):
        while not rospy.is_shutdown():
            scan = self.scan
            scan.header.stamp = rospy.Time.now() - rospy.Duration(self.behind)
            self.publisher.publish(scan)
            time.sleep(PERIOD)


class ExerciseWarnings(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        cls.log = RosoutLog(*NODES)

    def test_range_ahead_warns_at_its_period(self):
        Feed('range_ahead', one_valid_beam())
        words = 'only 1 of its 360 readings is usable'
        assert_soon(self, WAIT_LIMIT, lambda: self.log.said(NODES[0], words),
                    'range_ahead to warn of the scan')
        first = len(self.log.lines(NODES[0], words))
        time.sleep(WATCH)
        warnings = len(self.log.lines(NODES[0], words)) - first
        self.assertLessEqual(warnings, WATCH / RANGE_AHEAD_PERIOD + 1,
                             '%d warnings in %.0f s' % (warnings, WATCH))
        self.assertGreaterEqual(warnings, 1, 'no warning repeated while it lasts')

    def test_wander_warns_while_it_pivots_with_nothing_valid_ahead(self):
        Feed('wander', blind_ahead())
        assert_soon(self, WAIT_LIMIT, lambda: self.log.said(
            NODES[1], 'deg ahead; turning'),
            'wander to warn that it turns for want of a valid reading ahead')

    def test_forward_stop_warns_when_scan_stamps_go_back(self):
        feed = Feed('forward_stop', one_valid_beam([3.0] * 360))
        assert_soon(self, WAIT_LIMIT, lambda: self.log.said(NODES[2], 'forward at'),
                    'forward_stop to start')
        feed.behind = 20.0
        assert_soon(self, WAIT_LIMIT, lambda: self.log.said(NODES[2], 'scan stamps went back'),
                    'forward_stop to warn that the stamps went back')


if __name__ == '__main__':
    rospy.init_node('check_exercise_warnings')
    rostest.rosrun('wall_follower', 'check_exercise_warnings', ExerciseWarnings, sys.argv)
