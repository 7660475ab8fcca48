#!/usr/bin/env python3
"""rostest: odometry stops mid-lap; the record_odom goal is aborted, saying why.

The recorder hears odom through this node, which passes it on until the
feedback reaches STOP_AFTER and then stops, as a robot's base whose driver
died would. The goal must end (the simulator goes on), no sooner than the
recorder's ~timeout, aborted with a message naming the odometry, with the
points recorded so far; and the server must take a goal after it.
"""
import sys
import threading
import unittest

import actionlib
import rospy
import rostest
from actionlib_msgs.msg import GoalStatus
from nav_msgs.msg import Odometry

from wall_follower.action_registration import action_server_registered
from wall_follower.msg import OdomRecordAction, OdomRecordGoal

from waiting import wait_until

WAIT_LIMIT = 30.0       # wall seconds for the nodes, and for the feedback to come
STOP_AFTER = 1.0        # metres recorded before the odometry stops
# Simulated seconds the goal may end before ~timeout has passed here: odometry passed
# on just before it stopped may reach the recorder a moment later.
LATE_ODOMETRY = 0.5


class OdometryStops(unittest.TestCase):

    def setUp(self):
        self.passing = threading.Event()
        self.passing.set()
        self.relay = rospy.Publisher('odom_relayed', Odometry, queue_size=100)
        rospy.Subscriber('odom', Odometry, self._on_odom, queue_size=100)
        self.assertTrue(action_server_registered('record_odom', WAIT_LIMIT),
                        'no record_odom server')
        self.client = actionlib.SimpleActionClient('record_odom', OdomRecordAction)
        self.assertTrue(self.client.wait_for_server(rospy.Duration(WAIT_LIMIT)),
                        'no record_odom server')

    def _on_odom(self, msg):
        if self.passing.is_set():
            self.relay.publish(msg)

    def test_goal_aborted_with_the_points_so_far(self):
        timeout = rospy.get_param('/odom_recorder/timeout')
        feedback = []
        self.client.send_goal(OdomRecordGoal(),
                              feedback_cb=lambda fb: feedback.append(fb.current_total))
        self.assertTrue(wait_until(lambda: feedback and feedback[-1] >= STOP_AFTER,
                                   WAIT_LIMIT), 'no feedback past %.1f m' % STOP_AFTER)
        self.passing.clear()
        stopped = rospy.get_time()
        self.assertTrue(wait_until(lambda: self.client.get_state() != GoalStatus.ACTIVE,
                                   WAIT_LIMIT), 'the goal was left waiting')
        ended = rospy.get_time()
        # The goal's end comes on the status topic, its result on a connection of its own:
        # the status can come first, and the result is None until it comes.
        self.assertTrue(self.client.wait_for_result(rospy.Duration(WAIT_LIMIT)),
                        'no result for the aborted goal')
        self.assertEqual(self.client.get_state(), GoalStatus.ABORTED)
        self.assertGreater(ended - stopped, timeout - LATE_ODOMETRY,
                           'aborted %.1f s after the odometry stopped' % (ended - stopped))
        self.assertIn('no odometry on /odom_relayed', self.client.get_goal_status_text())
        points = self.client.get_result().list_of_odoms
        self.assertGreaterEqual(len(points), 2, 'the points so far were not returned')

        # The server is free again, and the next goal records once odometry is back.
        self.passing.set()
        feedback = []
        self.client.send_goal(OdomRecordGoal(),
                              feedback_cb=lambda fb: feedback.append(fb.current_total))
        self.assertTrue(wait_until(lambda: len(feedback) >= 2, WAIT_LIMIT),
                        'no feedback for a goal after the odometry came back')
        self.client.cancel_goal()
        self.assertTrue(wait_until(lambda: self.client.get_state() == GoalStatus.PREEMPTED,
                                   WAIT_LIMIT))


if __name__ == '__main__':
    rospy.init_node('check_recorder_odom_stops')
    rostest.rosrun('wall_follower', 'check_recorder_odom_stops', OdometryStops, sys.argv)
