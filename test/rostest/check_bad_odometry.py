#!/usr/bin/env python3
"""rostest: simple_move_square stands, and says why, on odometry it cannot trust.

Three squares, fed a room's scan and the odometry of a robot standing at
the origin: one whose odometry has a NaN position from the start, one with
a NaN orientation from the start, and one with good odometry until it
drives, then a NaN position, a NaN orientation, an all-zero quaternion,
odometry stamped 2100-01-01 and with the largest stamp a header holds
(2**32 - 1 s), and a jump of 5 m. While odometry is bad no command may
move the robot, and the node must warn naming what is wrong (once it has,
it may send nothing but stops); it drives on once good odometry returns,
but after the jump it stands for good. In wall time, with synthetic
messages.
"""
import math
import sys
import threading
import time
import unittest

import rospy
import rostest
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry
from rosout_log import RosoutLog
from sensor_msgs.msg import LaserScan

from synthetic_scans import square_room
from waiting import assert_soon

PERIOD = 0.1        # wall s between two scans and two odometry messages
WATCH = 2.0         # wall s of commands to look at while odometry is bad
WAIT_LIMIT = 10.0
STANDING = (0.0, 0.0)


def odometry(x=0.0, y=0.0, orientation=(0.0, 0.0, 0.0, 1.0)):
    msg = Odometry()
    msg.header.frame_id, msg.child_frame_id = 'odom', 'base_footprint'
    msg.pose.pose.position.x, msg.pose.pose.position.y = x, y
    q = msg.pose.pose.orientation
    q.x, q.y, q.z, q.w = orientation
    return msg


NAN_POSITION = odometry(x=math.nan)
NAN_ORIENTATION = odometry(orientation=(0.0, 0.0, math.nan, 1.0))
ZERO_QUATERNION = odometry(orientation=(0.0, 0.0, 0.0, 0.0))
YEAR_2100 = rospy.Time(4102444800)
LARGEST_STAMP = rospy.Time(2 ** 32 - 1, 999999999)
FAR_AHEAD = "years ahead of this node's clock"


class Square(object):
    """One simple_move_square node: what it is fed, and what it commands."""

    def __init__(self, namespace, odom):
        self.node = '/%s/simple_move_square' % namespace
        self.odom = odom
        self.stamp = None   # the odometry's stamp: None for this clock's
        self.lock = threading.Lock()
        self.commands = []
        self.scans = rospy.Publisher(namespace + '/scan', LaserScan, queue_size=1)
        self.odometry = rospy.Publisher(namespace + '/odom', Odometry, queue_size=1)
        rospy.Subscriber(namespace + '/cmd_vel', Twist, self._on_cmd, queue_size=1000)

    def _on_cmd(self, msg):
        with self.lock:
            self.commands.append((msg.linear.x, msg.angular.z))

    def count(self):
        with self.lock:
            return len(self.commands)

    def since(self, index):
        with self.lock:
            return list(self.commands[index:])

    def connected(self):
        return self.scans.get_num_connections() > 0 and self.odometry.get_num_connections() > 0


class BadOdometry(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        cls.squares = dict((name, Square(name, odom)) for name, odom in (
            ('nan_position', NAN_POSITION), ('nan_orientation', NAN_ORIENTATION),
            ('mid_run', odometry())))
        cls.log = RosoutLog(*(square.node for square in cls.squares.values()))
        threading.Thread(target=cls._feed, daemon=True).start()

    def setUp(self):
        for square in self.squares.values():
            assert_soon(self, WAIT_LIMIT, square.connected, '%s to subscribe' % square.node)

    @classmethod
    def _feed(cls):
        scan = square_room()
        while not rospy.is_shutdown():
            now = rospy.Time.now()
            scan.header.stamp = now
            for square in cls.squares.values():
                odom = square.odom
                odom.header.stamp = square.stamp or now
                square.scans.publish(scan)
                square.odometry.publish(odom)
            time.sleep(PERIOD)

    def assert_stands_and_warns(self, square, words, warned=0):
        """The node warns naming the problem (more than the `warned` times it had), and from
        then on sends only stops."""
        assert_soon(self, WAIT_LIMIT, lambda: len(self.log.lines(square.node, words)) > warned,
                    '%s to warn of odometry with %s' % (square.node, words))
        start = square.count()
        assert_soon(self, WAIT_LIMIT, lambda: square.count() >= start + int(WATCH / PERIOD),
                    'commands from %s' % square.node)
        moving = [c for c in square.since(start) if c != STANDING]
        self.assertEqual(moving, [], '%s moved on odometry with %s' % (square.node, words))

    def test_bad_odometry_from_the_start_keeps_the_robot_standing(self):
        self.assert_stands_and_warns(self.squares['nan_position'],
                                     'position (nan, 0.0) is not finite')
        self.assert_stands_and_warns(self.squares['nan_orientation'],
                                     'orientation (0.0, 0.0, nan, 1.0) is not a unit quaternion')

    def test_odometry_going_bad_mid_run_stops_the_robot(self):
        square = self.squares['mid_run']
        for odom, stamp, words in (
                (NAN_POSITION, None, 'position (nan, 0.0) is not finite'),
                (NAN_ORIENTATION, None, 'is not a unit quaternion (norm nan)'),
                (ZERO_QUATERNION, None, 'is not a unit quaternion (norm 0.0)'),
                (odometry(), YEAR_2100, FAR_AHEAD),
                (odometry(), LARGEST_STAMP, FAR_AHEAD),
                (odometry(x=5.0), None, 'it jumped 5.00 m')):
            square.odom, square.stamp = odometry(), None
            start = square.count()
            assert_soon(self, WAIT_LIMIT, lambda: any(
                c != STANDING for c in square.since(start)), 'driving on good odometry')
            warned = len(self.log.lines(square.node, words))
            square.odom, square.stamp = odom, stamp
            self.assert_stands_and_warns(square, words, warned)
        square.odom = odometry(x=5.0)
        self.assert_stands_and_warns(square, 'the square is given up')


if __name__ == '__main__':
    rospy.init_node('check_bad_odometry')
    rostest.rosrun('wall_follower', 'check_bad_odometry', BadOdometry, sys.argv)
