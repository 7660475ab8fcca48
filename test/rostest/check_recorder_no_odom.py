#!/usr/bin/env python3
"""rostest: a record_odom goal with no odometry at all is aborted, not left hanging."""
import sys
import unittest

import actionlib
import rospy
import rostest
from actionlib_msgs.msg import GoalStatus

from wall_follower.action_registration import action_server_registered
from wall_follower.msg import OdomRecordAction, OdomRecordGoal


class NoOdometry(unittest.TestCase):

    def test_goal_aborted_with_a_message(self):
        self.assertTrue(action_server_registered('record_odom', 30.0))
        client = actionlib.SimpleActionClient('record_odom', OdomRecordAction)
        self.assertTrue(client.wait_for_server(rospy.Duration(30.0)))
        client.send_goal(OdomRecordGoal())
        # The recorder's ~timeout is 1 s here; its verdict must come well before 20 s.
        self.assertTrue(client.wait_for_result(rospy.Duration(20.0)))
        self.assertEqual(client.get_state(), GoalStatus.ABORTED)
        self.assertIn('odom', client.get_goal_status_text())
        self.assertEqual(len(client.get_result().list_of_odoms), 0)


if __name__ == '__main__':
    rospy.init_node('check_recorder_no_odom')
    rostest.rosrun('wall_follower', 'check_recorder_no_odom', NoOdometry, sys.argv)
