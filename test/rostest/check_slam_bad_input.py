#!/usr/bin/env python3
"""rostest: slam says what it cannot trust in scans and odometry, by name.

Fed a room's scan and a standing robot's odometry (with the laser's mount
on tf), then in turn: odometry with a NaN position (it must say the
odometry cannot be trusted, not wait for ever for the robot to stand
still), scans of nothing but NaN (unusable, not "match not trusted"),
odometry whose time goes back (told as such, not as "no odometry") and
odometry that jumps 5 m (warned of). And scans and odometry (with the
robot's tf, as a robot sends it) stamped 2100-01-01, then with the largest
stamp a header holds (2**32 - 1 s): slam must say they are stamped far
ahead, broadcast no transform at such a stamp (every tf listener, its own
included, would abort), not die, and map on once good ones return. In wall
time, with synthetic messages.
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
from tf2_msgs.msg import TFMessage

from waiting import assert_soon

PERIOD = 0.1
WAIT_LIMIT = 15.0
NODE = '/slam'
FAR_AHEAD = (rospy.Time(4102444800), rospy.Time(2 ** 32 - 1, 999999999))
# What slam must say of scans and of odometry stamped far ahead.
STALE = ('the scan on /scan is stale: it is stamped over',
         'odometry on /odom cannot be trusted: it is stamped over')


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
        self.scan, self.x, self.delay, self.stamp = room_scan(), 0.0, 0.0, None
        mount = TransformStamped()
        mount.header.stamp = rospy.Time.now()
        mount.header.frame_id, mount.child_frame_id = 'base_footprint', 'base_scan'
        mount.transform.rotation.w = 1.0
        self.static = tf2_ros.StaticTransformBroadcaster()
        self.static.sendTransform(mount)
        self.robot_tf = tf2_ros.TransformBroadcaster()
        self.scans = rospy.Publisher('scan', LaserScan, queue_size=10)
        self.odom = rospy.Publisher('odom', Odometry, queue_size=10)
        self.map_to_odom = []   # the stamps of slam's map -> odom transforms
        self.tf = rospy.Subscriber('/tf', TFMessage, self._on_tf, queue_size=100)
        self.stopped = threading.Event()
        self.feed = threading.Thread(target=self._feed, daemon=True)
        self.feed.start()

    def tearDown(self):
        self.stopped.set()
        self.feed.join()
        self.tf.unregister()

    def _feed(self):
        while not self.stopped.is_set() and not rospy.is_shutdown():
            stamp = self.stamp or rospy.Time.now() - rospy.Duration(self.delay)
            odom = Odometry()
            odom.header.stamp, odom.header.frame_id = stamp, 'odom'
            odom.child_frame_id = 'base_footprint'
            odom.pose.pose.position.x = self.x
            odom.pose.pose.orientation.w = 1.0
            self.odom.publish(odom)
            robot = TransformStamped(header=odom.header, child_frame_id='base_footprint')
            robot.transform.translation.x = self.x
            robot.transform.rotation.w = 1.0
            self.robot_tf.sendTransform(robot)
            scan = self.scan
            scan.header.stamp = stamp
            self.scans.publish(scan)
            time.sleep(PERIOD)

    def _on_tf(self, msg):
        self.map_to_odom.extend(t.header.stamp for t in msg.transforms
                                if (t.header.frame_id, t.child_frame_id) == ('map', 'odom'))

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

    def mapping_since(self, start):
        """Wait for a map -> odom transform stamped from start on: slam mapped a scan."""
        assert_soon(self, WAIT_LIMIT, lambda: any(t >= start for t in list(self.map_to_odom)),
                    'slam to map a scan stamped from %.1f s on' % start.to_sec())

    def test_stamps_far_ahead_are_skipped_and_mapping_goes_on(self):
        self.mapping_since(rospy.Time.now())
        for stamp in FAR_AHEAD:
            said = [len(self.log.lines(NODE, words)) for words in STALE]
            self.stamp = stamp   # until slam has said so of both (its warnings are throttled)
            for words, before in zip(STALE, said):
                assert_soon(self, WAIT_LIMIT, lambda: len(self.log.lines(NODE, words)) > before,
                            'slam to say "%s" at the stamp %d s' % (words, stamp.secs))
            self.stamp = None
            self.mapping_since(rospy.Time.now())
        ahead = [t.to_sec() for t in self.map_to_odom if t >= FAR_AHEAD[0]]
        self.assertEqual(ahead, [], 'map -> odom broadcast at stamps far ahead')


if __name__ == '__main__':
    rospy.init_node('check_slam_bad_input')
    rostest.rosrun('wall_follower', 'check_slam_bad_input', SlamBadInput, sys.argv)
