#!/usr/bin/env python3
"""rostest: the record_odom goal is stamped by a clock that has caught up with the laser.

On simulated time (follower_clock_lag.test) this node is the world: it
publishes /clock at CLOCK_BEHIND and scans taken at SCAN_TAKEN, later, as
a follower whose /clock is slow to come up (or starved of CPU) sees them,
and serves a record_odom stub that keeps each goal it is sent. The
follower must not send its goal, from which the lap is counted, until its
ROS time has reached the newest scan: it says it waits, then this node
lets the clock reach the scans, and the goal must carry a stamp no
earlier than theirs.

On wall time (follower_robot_clock.test) the scans are stamped by a robot
whose clock is ROBOT_AHEAD seconds ahead of this machine's, as a laptop
driving a TurtleBot3 over the network may see them: there is no clock to
wait for, and the goal must go out at once (record_odom allows for the
offset).
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
ROBOT_AHEAD = 100.0     # s
# Wall seconds between two publications of the world's clock and scan.
PERIOD = 0.05
WAIT_LIMIT = 20.0


class World(object):
    """Publishes /clock and a scan every PERIOD wall seconds, and keeps the goals sent."""

    def __init__(self, clock, scan_taken):
        """clock: the /clock to publish (None: none, on wall time); scan_taken: the
        scans' stamp, or a function giving it."""
        self.clock = clock
        self.scan = wall_on_the_right()
        self.scan_taken = scan_taken
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
            if self.clock is not None:
                self._clock_pub.publish(Clock(clock=self.clock))
            taken = self.scan_taken
            self.scan.header.stamp = taken() if callable(taken) else taken
            self._scan_pub.publish(self.scan)
            time.sleep(PERIOD)


class ClockLag(unittest.TestCase):

    def test_goal_stamp(self):
        if rospy.get_param('/use_sim_time', False):
            self.goal_waits_for_the_clock_to_reach_the_scans()
        else:
            self.goal_goes_at_once_whatever_the_robots_clock()

    def goal_goes_at_once_whatever_the_robots_clock(self):
        world = World(None, lambda: rospy.Time.now() + rospy.Duration(ROBOT_AHEAD))
        self.assertTrue(wait_until(lambda: world.goals, WAIT_LIMIT), 'no goal')

    def goal_waits_for_the_clock_to_reach_the_scans(self):
        log = RosoutLog(NODE)
        world = World(rospy.Time.from_sec(CLOCK_BEHIND), rospy.Time.from_sec(SCAN_TAKEN))
        waiting = 'waiting for ROS time'
        self.assertTrue(wait_until(lambda: world.goals or log.said(NODE, waiting), WAIT_LIMIT),
                        'neither a goal nor a wait for the clock')
        self.assertEqual(world.goals, [], 'goal sent while the clock lagged the scans, '
                         'stamped %s s; scans taken at %.1f s' % (world.goals, SCAN_TAKEN))
        world.clock = rospy.Time.from_sec(SCAN_TAKEN)
        self.assertTrue(wait_until(lambda: world.goals, WAIT_LIMIT), 'no goal once caught up')
        self.assertGreaterEqual(world.goals[0], SCAN_TAKEN)


if __name__ == '__main__':
    rospy.init_node('check_follower_goal_stamp')
    rostest.rosrun('wall_follower', 'check_follower_goal_stamp', ClockLag, sys.argv)
