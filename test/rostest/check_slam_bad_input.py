#!/usr/bin/env python3
"""rostest: slam says what it cannot trust in scans and odometry, by name.

Fed a room's scan and a standing robot's odometry (with the laser's mount
on tf), then in turn: odometry with a NaN position (it must say the
odometry cannot be trusted, not wait for ever for the robot to stand
still), scans of nothing but NaN (unusable, not "match not trusted"),
odometry whose time goes back (told as such, not as "no odometry") and
odometry that jumps 5 m (warned of). In wall time, with synthetic messages.
"""
import math
import sys
import threading
import time
import unittest

import rospy
import rostest
import tf2_ros
from geometry_msgs.msg import TransformStamped
from nav_msgs.msg import Odometry
from rosout_log import RosoutLog
from sensor_msgs.msg import LaserScan

from waiting import assert_soon

PERIOD = 0.1
WAIT_LIMIT = 15.0
NODE = '/slam'


def room_scan(value=None):
    """A 360-beam scan (beam 0 ahead) of walls 1.2 m away on every side, or every
    reading value."""
    scan = LaserScan()
    scan.header.frame_id = 'base_scan'
    scan.angle_min, scan.angle_increment = 0.0, 2.0 * math.pi / 360
    scan.angle_max = scan.angle_increment * 359
    scan.range_min, scan.range_max = 0.12, 3.5
    scan.ranges = [value if value is not None else 1.2 / max(abs(math.cos(a)), abs(math.sin(a)))
                   for a in (scan.angle_increment * i for i in range(360))]
    return scan


class SlamBadInput(unittest.TestCase):

    def setUp(self):
        self.log = RosoutLog(NODE)
        self.scan, self.x, self.delay = room_scan(), 0.0, 0.0
        mount = TransformStamped()
        mount.header.stamp = rospy.Time.now()
        mount.header.frame_id, mount.child_frame_id = 'base_footprint', 'base_scan'
        mount.transform.rotation.w = 1.0
        self.static = tf2_ros.StaticTransformBroadcaster()
        self.static.sendTransform(mount)
        self.scans = rospy.Publisher('scan', LaserScan, queue_size=10)
        self.odom = rospy.Publisher('odom', Odometry, queue_size=10)
        threading.Thread(target=self._feed, daemon=True).start()

    def _feed(self):
        while not rospy.is_shutdown():
            stamp = rospy.Time.now() - rospy.Duration(self.delay)
            odom = Odometry()
            odom.header.stamp, odom.header.frame_id = stamp, 'odom'
            odom.child_frame_id = 'base_footprint'
            odom.pose.pose.position.x = self.x
            odom.pose.pose.orientation.w = 1.0
            self.odom.publish(odom)
            scan = self.scan
            scan.header.stamp = stamp
            self.scans.publish(scan)
            time.sleep(PERIOD)

    def said(self, words):
        assert_soon(self, WAIT_LIMIT, lambda: self.log.said(NODE, words),
                    'slam to say "%s"' % words)

    def test_each_problem_is_named(self):
        self.x = math.nan
        self.said('odometry on /odom cannot be trusted: position (nan, 0.0) is not finite')
        self.said('(the odometry cannot be trusted: position (nan, 0.0) is not finite)')
        self.x = 0.0
        self.scan = room_scan(math.nan)
        self.said('the scan on /scan is unusable: none of its 360 readings is usable (360 NaN)')
        self.assertFalse(self.log.said(NODE, 'match not trusted'))
        self.scan = room_scan()
        self.delay = 30.0
        self.said('its time went back')
        self.delay = 0.0
        time.sleep(1.0)
        self.x = 5.0
        self.said('it jumped 5.00 m')


if __name__ == '__main__':
    rospy.init_node('check_slam_bad_input')
    rostest.rosrun('wall_follower', 'check_slam_bad_input', SlamBadInput, sys.argv)
