#!/usr/bin/env python3
"""rostest: a record_odom goal stamped far ahead of the odometry is aborted, saying why.

Such a goal comes from a client on another clock (wall time against
simulated time, say). Every odometry message is older than the goal, so
none is recorded; the goal must end rather than wait for ever. The goal is
published raw, as only then can its stamp be chosen. actionlib then takes
no goal stamped before this one, hence a launch of its own.
"""
import sys
import time
import unittest

import rospy
import rostest
from actionlib_msgs.msg import GoalStatus

from wall_follower.msg import OdomRecordActionGoal, OdomRecordActionResult

from waiting import wait_until

POLL = 0.1   # wall s
# Wall seconds to wait for the recorder to subscribe.
CONNECT_LIMIT = 30.0
# Seconds the goal's stamp is ahead of this clock.
CLOCK_AHEAD = 1000.0
GOAL_ID = 'stamped-ahead'


class GoalStampedAhead(unittest.TestCase):

    def test_aborted_with_a_message_and_no_points(self):
        results = []
        rospy.Subscriber('record_odom/result', OdomRecordActionResult, results.append)
        goals = rospy.Publisher('record_odom/goal', OdomRecordActionGoal, queue_size=1)
        self.assertTrue(wait_until(lambda: goals.get_num_connections() > 0, CONNECT_LIMIT),
                        'no record_odom server')
        goal = OdomRecordActionGoal()
        goal.goal_id.id = GOAL_ID
        goal.goal_id.stamp = rospy.Time.now() + rospy.Duration(CLOCK_AHEAD)
        goals.publish(goal)
        # The verdict is due after the recorder's ~timeout of ROS time and of wall
        # time both; allow it four of each.
        allowed = 4.0 * rospy.get_param('/odom_recorder/timeout')
        end, end_wall = rospy.get_time() + allowed, time.monotonic() + allowed

        def ours():
            return [r for r in results if r.status.goal_id.id == GOAL_ID]
        while not ours() and (rospy.get_time() < end or time.monotonic() < end_wall):
            time.sleep(POLL)
        self.assertTrue(ours(), 'the goal stamped ahead was left waiting')
        result = ours()[0]
        self.assertEqual(result.status.status, GoalStatus.ABORTED)
        self.assertIn('stamped since the goal', result.status.text)
        self.assertEqual(len(result.result.list_of_odoms), 0)


if __name__ == '__main__':
    rospy.init_node('check_recorder_clock_ahead')
    rostest.rosrun('wall_follower', 'check_recorder_clock_ahead', GoalStampedAhead, sys.argv)
