#!/usr/bin/env python3
"""rostest: the record_odom goal is not stamped by a clock that lags the world.

This node is the world: it publishes /clock at CLOCK_BEHIND and scans taken
at SCAN_TAKEN, later, as a follower whose /clock is slow to come up (or
starved of CPU) sees them, and serves a record_odom stub that keeps each
goal it is sent. The follower must not send its goal, from which the lap is
counted, until its ROS time has reached the newest scan: it says it waits,
then this node lets the clock reach the scans, and the goal must carry a
stamp no earlier than theirs.
"""
import sys
import threading
import time
import unittest

import actionlib
import rospy
import rostest
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import LaserScan

from rosout_log import RosoutLog
from synthetic_scans import wall_on_the_right
from waiting import wait_until
from wall_follower.msg import OdomRecordAction

NODE = '/wall_following'
CLOCK_BEHIND = 10.0
SCAN_TAKEN = 50.0
# Wall seconds between two publications of the world's clock and scan.
PERIOD = 0.05
WAIT_LIMIT = 20.0


class World(object):
    """Publishes /clock and a scan every PERIOD wall seconds, and keeps the goals sent."""

    def __init__(self):
        self.clock = rospy.Time.from_sec(CLOCK_BEHIND)
        self.scan = wall_on_the_right()
        self.scan.header.stamp = rospy.Time.from_sec(SCAN_TAKEN)
        self.goals = []
        self._clock_pub = rospy.Publisher('/clock', Clock, queue_size=1)
        self._scan_pub = rospy.Publisher('scan', LaserScan, queue_size=1)
        self._server = actionlib.ActionServer('record_odom', OdomRecordAction, self._on_goal,
                                              auto_start=False)
        self._server.start()
        thread = threading.Thread(target=self._publish)
        thread.daemon = True
        thread.start()

    def _on_goal(self, goal):
        goal.set_accepted()
        self.goals.append(goal.get_goal_id().stamp.to_sec())

    def _publish(self):
        while not rospy.is_shutdown():
            self._clock_pub.publish(Clock(clock=self.clock))
            self._scan_pub.publish(self.scan)
            time.sleep(PERIOD)


class ClockLag(unittest.TestCase):

    def test_goal_waits_for_the_clock_to_reach_the_scans(self):
        log = RosoutLog()
        world = World()
        waiting = 'waiting for ROS time'
        self.assertTrue(wait_until(lambda: world.goals or log.said(NODE, waiting), WAIT_LIMIT),
                        'neither a goal nor a wait for the clock')
        self.assertEqual(world.goals, [], 'goal sent while the clock lagged the scans, '
                         'stamped %s s; scans taken at %.1f s' % (world.goals, SCAN_TAKEN))
        world.clock = rospy.Time.from_sec(SCAN_TAKEN)
        self.assertTrue(wait_until(lambda: world.goals, WAIT_LIMIT), 'no goal once caught up')
        self.assertGreaterEqual(world.goals[0], SCAN_TAKEN)


if __name__ == '__main__':
    rospy.init_node('check_follower_clock_lag')
    rostest.rosrun('wall_follower', 'check_follower_clock_lag', ClockLag, sys.argv)
