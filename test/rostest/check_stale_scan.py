#!/usr/bin/env python3
"""rostest: the follower drives on fresh scans and stops when they go stale.

Runs in wall time against wall_following alone (no find_wall, no
record_odom), fed synthetic Stage-convention scans of a wall on the right.
"""
import sys
import threading
import time
import unittest

import rospy
import rostest
from geometry_msgs.msg import Twist
from sensor_msgs.msg import LaserScan
from synthetic_scans import wall_on_the_right
from waiting import assert_soon

SCAN_PERIOD = 0.1
FEED_TIME = 1.5
WAIT_LIMIT = 10.0


class StaleScan(unittest.TestCase):

    def setUp(self):
        self.commands = []
        self.lock = threading.Lock()
        rospy.Subscriber('cmd_vel', Twist, self._on_cmd, queue_size=100)
        self.scans = rospy.Publisher('scan', LaserScan, queue_size=1)

    def _on_cmd(self, msg):
        with self.lock:
            self.commands.append((time.monotonic(), msg.linear.x, msg.angular.z))

    def test_drives_on_fresh_scans_and_stops_after_the_timeout(self):
        assert_soon(self, WAIT_LIMIT, lambda: self.scans.get_num_connections() > 0,
                    'the follower to subscribe')
        scan = wall_on_the_right()
        end = time.monotonic() + FEED_TIME
        while True:
            scan.header.stamp = rospy.Time.now()
            self.scans.publish(scan)
            last_scan = time.monotonic()
            if last_scan >= end:
                break
            time.sleep(SCAN_PERIOD)
        with self.lock:
            self.assertTrue(any(v > 0.1 for _, v, _ in self.commands), 'never drove')

        def stopped():
            with self.lock:
                return any(t > last_scan and v == 0.0 and w == 0.0 for t, v, w in self.commands)
        assert_soon(self, WAIT_LIMIT, stopped,
                    'a zero command')
        timeout = rospy.get_param('/wall_following/scan_timeout')
        with self.lock:
            first_zero = next(t for t, v, w in self.commands
                              if t > last_scan and v == 0.0 and w == 0.0)
        self.assertGreaterEqual(first_zero - last_scan, timeout - SCAN_PERIOD)
        count = len(self.commands)
        assert_soon(self, WAIT_LIMIT, lambda: len(self.commands) >= count + 5,
                    'more commands')
        with self.lock:
            self.assertTrue(all(v == 0.0 and w == 0.0 for t, v, w in self.commands
                                if t > first_zero), 'moved again without scans')


if __name__ == '__main__':
    rospy.init_node('check_stale_scan')
    rostest.rosrun('wall_follower', 'check_stale_scan', StaleScan, sys.argv)
