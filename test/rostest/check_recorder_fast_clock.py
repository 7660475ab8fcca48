#!/usr/bin/env python3
"""rostest: a recorder that falls behind a fast simulation does not abort the lap.

This node plays a simulator running STEP / WALL_STEP times faster than real
time. Mid-goal it withholds odometry for twice the recorder's ~timeout of
simulated time, as a loaded machine does to a recorder whose odometry queue
falls behind its /clock, yet for only a fraction of ~timeout in wall
seconds. The goal must go on recording once odometry comes again: the
odometry was late, not gone. (That odometry which really stops ends the
goal is shown by recorder_odom_stops.test and recorder_no_odom.test.)
"""
import sys
import unittest

import actionlib
import rospy
import rostest
from actionlib_msgs.msg import GoalStatus

from wall_follower.action_registration import action_server_registered
from wall_follower.msg import OdomRecordAction, OdomRecordGoal
from wall_follower.nodes.shared.waiting import wait_in_wall_time

from odometry_world import STEP, OdometryWorld
from waiting import wait_until

START_CLOCK = 100.0     # simulated s
WALL_STEP = 0.005       # wall seconds per world step: 20 times real time
WAIT_LIMIT = 20.0       # wall seconds for anything to happen
POINTS_BEFORE = 3       # feedback before the silence, and again after it


class FastClock(unittest.TestCase):

    def setUp(self):
        self.world = OdometryWorld(START_CLOCK, WALL_STEP)
        self.assertTrue(action_server_registered('record_odom', WAIT_LIMIT),
                        'no record_odom server')
        self.client = actionlib.SimpleActionClient('record_odom', OdomRecordAction)

    def tearDown(self):
        self.world.stop()

    def test_odometry_late_by_more_than_the_timeout_in_simulated_time_only(self):
        self.assertTrue(wait_in_wall_time(self.client.wait_for_server, WAIT_LIMIT),
                        'no record_odom server')
        timeout = rospy.get_param('/odom_recorder/timeout')
        silence = 2.0 * timeout
        self.assertLess(silence / STEP * WALL_STEP, timeout / 4.0,
                        'the silence is not short in wall time: the test proves nothing')
        feedback = []
        self.client.send_goal(OdomRecordGoal(), feedback_cb=feedback.append)
        self.assertTrue(wait_until(lambda: len(feedback) >= POINTS_BEFORE, WAIT_LIMIT),
                        'no feedback before the silence')
        self.world.silence(silence)
        resumed = self.world.now + silence
        self.assertTrue(wait_until(lambda: self.world.now > resumed + POINTS_BEFORE
                                   or self.client.get_state() != GoalStatus.ACTIVE, WAIT_LIMIT))
        self.assertEqual(self.client.get_state(), GoalStatus.ACTIVE,
                         'the goal ended: %s' % self.client.get_goal_status_text())
        before = len(feedback)
        self.assertTrue(wait_until(lambda: len(feedback) >= before + POINTS_BEFORE, WAIT_LIMIT),
                        'no feedback after the odometry came back')
        self.client.cancel_goal()


if __name__ == '__main__':
    rospy.init_node('check_recorder_fast_clock')
    rostest.rosrun('wall_follower', 'check_recorder_fast_clock', FastClock, sys.argv)
