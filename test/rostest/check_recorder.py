#!/usr/bin/env python3
"""rostest: record_odom's goal life cycle against a robot that follows the wall.

A cancel mid-lap returns the points so far; a second goal starts from zero
at the robot's pose of that moment, carrying nothing over from the first.
Each recording starts exactly at its goal's stamp.
"""
import math
import sys
import unittest

import actionlib
import numpy as np
import rospy
import rostest
from actionlib_msgs.msg import GoalStatus
from nav_msgs.msg import Odometry
from std_srvs.srv import Empty

from wall_follower.action_registration import action_server_registered
from wall_follower.evaluation.scoring.course import stretches_on_trail, taken_every
from wall_follower.msg import OdomRecordAction, OdomRecordActionGoal, OdomRecordGoal
from wall_follower.nodes.shared.messages import pose_of

from waiting import wait_until

POLL = 0.1
# Wall seconds to wait for the goal to be taken while the world is paused, or for
# messages on other connections to catch up.
WAIT_LIMIT = 10.0
# Metres: a recorded point is this near the true pose it was taken at (odometry is exact
# here, localization gps); a step at full speed moves some twenty times as far.
SAME_POSE = 1e-3
# Metres driven before each goal is cancelled.
FIRST_GOAL_DISTANCE = 2.0
SECOND_GOAL_DISTANCE = 0.5


class RecordOdomGoals(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        assert action_server_registered('record_odom', 30.0), 'no record_odom server'
        cls.client = actionlib.SimpleActionClient('record_odom', OdomRecordAction)
        assert cls.client.wait_for_server(rospy.Duration(30.0)), 'no record_odom server'
        cls.period = rospy.get_param('/odom_recorder/sample_period', 1.0)
        cls.truths = []
        cls.goal_stamps = []
        cls.pause = rospy.ServiceProxy('pause_physics', Empty)
        cls.unpause = rospy.ServiceProxy('unpause_physics', Empty)
        rospy.Subscriber('base_pose_ground_truth', Odometry, cls._on_truth,
                         queue_size=10000)
        rospy.Subscriber('record_odom/goal', OdomRecordActionGoal, cls._on_goal)

    @classmethod
    def _on_truth(cls, msg):
        cls.truths.append((msg.header.stamp.to_sec(), pose_of(msg)))

    @classmethod
    def _on_goal(cls, msg):
        cls.goal_stamps.append(msg.goal_id.stamp.to_sec())

    def record(self, until_distance):
        """Send a goal, cancel it once the feedback reaches until_distance.

        The goal is sent with the world paused and the world resumes once
        the server has taken it: the simulator runs many times faster than
        real time, and the wall milliseconds the goal spends in transit would
        otherwise be simulated seconds of driving.

        Returns the goal's stamp, the feedback, the final state and the result.
        """
        feedback = []
        # Ground truth from before the goal on, to know the pose at the goal.
        while not (self.truths and self.truths[0][0] < rospy.get_time()):
            rospy.sleep(POLL)
        goals_before = len(self.goal_stamps)
        self.pause()
        self.client.send_goal(OdomRecordGoal(),
                              feedback_cb=lambda fb: feedback.append(fb.current_total))
        self.assertTrue(wait_until(lambda: self.client.get_state() == GoalStatus.ACTIVE,
                                   WAIT_LIMIT), 'record_odom took no goal')
        self.unpause()
        while not feedback or feedback[-1] < until_distance:
            rospy.sleep(POLL)
        self.client.cancel_goal()
        self.assertTrue(self.client.wait_for_result(rospy.Duration(10.0)))
        result = self.client.get_result()
        self.assertTrue(wait_until(lambda: len(self.goal_stamps) > goals_before, WAIT_LIMIT),
                        'the goal was not heard')
        goal_stamp = self.goal_stamps[-1]
        # The result comes on a connection of its own and can overtake the ground
        # truth of the steps before it.
        last = result.list_of_odoms[-1]
        self.assertTrue(wait_until(lambda: self.heard_at(last, goal_stamp), WAIT_LIMIT),
                        'no ground truth through the last point (%.3f, %.3f)' % (last.x, last.y))
        return goal_stamp, feedback, self.client.get_state(), result

    def heard_at(self, point, since):
        """True once ground truth stamped since `since` has passed through the recorded point."""
        return any(t >= since and math.hypot(x - point.x, y - point.y) < SAME_POSE
                   for t, (x, y, _) in list(self.truths))

    def odometry_at(self, stamp):
        """(x, y) of the odometry stamped at this step: the true pose before the step."""
        return [pose[:2] for t, pose in list(self.truths) if t < stamp][-1]

    def spans_of(self, points, goal_stamp):
        """(earliest, latest) time each recorded point may have been taken, from ground truth.

        The two differ only while the robot stood still (see scoring.stretches_on_trail).
        The trail starts at the step before the goal, whose pose the odometry
        stamped at the goal holds.
        """
        truths = list(self.truths)
        after = next((i for i, (t, _) in enumerate(truths) if t >= goal_stamp), len(truths))
        truths = truths[max(after - 1, 0):]
        stretches = stretches_on_trail([pose[:2] for _, pose in truths],
                                       [(p.x, p.y) for p in points])
        return [(truths[first][0], truths[last][0]) for first, last in stretches]

    def assert_starts_at_goal(self, result, goal_stamp):
        first = result.list_of_odoms[0]
        x, y = self.odometry_at(goal_stamp)
        self.assertLess(math.hypot(first.x - x, first.y - y), SAME_POSE,
                        'the first point (%.3f, %.3f) is not the pose at the goal (%.3f, %.3f)'
                        % (first.x, first.y, x, y))

    def test_cancel_returns_points_and_next_goal_starts_clean(self):
        goal_stamp, _, state, result = self.record(until_distance=FIRST_GOAL_DISTANCE)
        self.assertEqual(state, GoalStatus.PREEMPTED)
        self.assert_starts_at_goal(result, goal_stamp)
        spans = self.spans_of(result.list_of_odoms, goal_stamp)
        self.assertGreater(len(spans), 5)
        self.assertTrue(taken_every(spans, self.period, 1e-3),
                        'points taken at %s s' % np.round(spans, 3).tolist())
        first_run_start = result.list_of_odoms[0]

        goal_stamp, feedback, state, result = self.record(until_distance=SECOND_GOAL_DISTANCE)
        self.assertEqual(state, GoalStatus.PREEMPTED)
        # Carried over, the total would start at the first goal's distance or more; the
        # recorder's first feedback can come a second or so of driving after the goal.
        self.assertLess(feedback[0], FIRST_GOAL_DISTANCE / 2.0,
                        'the second goal did not start from zero')
        self.assert_starts_at_goal(result, goal_stamp)
        first = result.list_of_odoms[0]
        self.assertGreater(math.hypot(first.x - first_run_start.x, first.y - first_run_start.y),
                           1.0, 'the second goal kept the first goal\'s start')


if __name__ == '__main__':
    rospy.init_node('check_recorder')
    rostest.rosrun('wall_follower', 'check_recorder', RecordOdomGoals, sys.argv)
