#!/usr/bin/env python3
"""rostest: record_odom's goal life cycle against a robot that follows the wall.

A cancel mid-lap returns the points so far; a second goal starts from zero
at the robot's pose of that moment, carrying nothing over from the first.
"""
import math
import sys
import time
import unittest

import actionlib
import numpy as np
import rospy
import rostest
from actionlib_msgs.msg import GoalStatus
from nav_msgs.msg import Odometry
from std_srvs.srv import Empty

from wall_follower.msg import OdomRecordAction, OdomRecordGoal
from wall_follower.nodes.common import pose_of
from wall_follower.scoring import stretches_on_trail, taken_every

POLL = 0.1
# Wall seconds: polling for the goal to be taken while the world is paused, and the limit;
# also the limit on waiting for ground truth to catch up with a result.
WALL_POLL = 0.01
ACCEPT_LIMIT = 10.0
# Metres: a recorded point is this near the true pose it was taken at (odometry is exact
# here, localization gps); a step at full speed moves some twenty times as far.
SAME_POSE = 1e-3
# Simulated seconds around a goal's sending in which its first point must lie.
FIRST_POINT_WINDOW = (-0.5, 2.0)
# Metres driven before each goal is cancelled.
FIRST_GOAL_DISTANCE = 2.0
SECOND_GOAL_DISTANCE = 0.5


class RecordOdomGoals(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        cls.client = actionlib.SimpleActionClient('record_odom', OdomRecordAction)
        assert cls.client.wait_for_server(rospy.Duration(30.0)), 'no record_odom server'
        cls.period = rospy.get_param('/odom_recorder/sample_period', 1.0)
        cls.truths = []
        cls.pause = rospy.ServiceProxy('pause_physics', Empty)
        cls.unpause = rospy.ServiceProxy('unpause_physics', Empty)
        rospy.Subscriber('base_pose_ground_truth', Odometry, cls._on_truth,
                         queue_size=10000)

    @classmethod
    def _on_truth(cls, msg):
        cls.truths.append((msg.header.stamp.to_sec(), pose_of(msg)))

    def truths_near(self, stamp):
        low, high = FIRST_POINT_WINDOW
        return [pose for t, pose in list(self.truths) if stamp + low <= t <= stamp + high]

    def record(self, until_distance):
        """Send a goal, cancel it once the feedback reaches until_distance.

        The goal is sent with the world paused and the world resumes once
        the server has taken it: the simulator runs many times faster than
        real time, and the wall milliseconds the goal spends in transit would
        otherwise be simulated seconds of driving.
        """
        feedback = []
        while not self.truths:
            rospy.sleep(POLL)
        self.pause()
        started = rospy.get_time()
        self.client.send_goal(OdomRecordGoal(),
                              feedback_cb=lambda fb: feedback.append(fb.current_total))
        deadline = time.time() + ACCEPT_LIMIT
        while self.client.get_state() != GoalStatus.ACTIVE and time.time() < deadline:
            time.sleep(WALL_POLL)   # simulated time stands still while paused
        self.assertEqual(self.client.get_state(), GoalStatus.ACTIVE, 'record_odom took no goal')
        self.unpause()
        while not feedback or feedback[-1] < until_distance:
            rospy.sleep(POLL)
        self.client.cancel_goal()
        self.assertTrue(self.client.wait_for_result(rospy.Duration(10.0)))
        result = self.client.get_result()
        self.wait_for_truth_at(result.list_of_odoms[-1], since=started)
        return started, feedback, self.client.get_state(), result

    def wait_for_truth_at(self, point, since):
        """Wait until ground truth after `since` has passed through the recorded point.

        The result comes on a connection of its own and can overtake the
        ground truth of the steps before it; timing the points on a trail
        that lacks the last steps would place the last point too early.
        """
        def heard():
            return any(t >= since and math.hypot(x - point.x, y - point.y) < SAME_POSE
                       for t, (x, y, _) in list(self.truths))
        deadline = time.time() + ACCEPT_LIMIT
        while not heard() and time.time() < deadline:
            time.sleep(WALL_POLL)
        self.assertTrue(heard(), 'no ground truth through the last recorded point (%.3f, %.3f)'
                        % (point.x, point.y))

    def spans_of(self, points, since):
        """(earliest, latest) time each recorded point may have been taken, from ground truth after `since`.

        The two differ only while the robot stood still (see scoring.stretches_on_trail).
        Odometry stamped at a step holds the pose before it, so a point stamped
        at `since` is the truth one step earlier: the trail starts there.
        """
        truths = list(self.truths)
        after = next((i for i, (t, _) in enumerate(truths) if t >= since), len(truths))
        truths = truths[max(after - 1, 0):]
        stretches = stretches_on_trail([pose[:2] for _, pose in truths],
                                       [(p.x, p.y) for p in points])
        return [(truths[first][0], truths[last][0]) for first, last in stretches]

    def test_cancel_returns_points_and_next_goal_starts_clean(self):
        started, _, state, result = self.record(until_distance=FIRST_GOAL_DISTANCE)
        self.assertEqual(state, GoalStatus.PREEMPTED)
        spans = self.spans_of(result.list_of_odoms, since=started)
        self.assertGreater(len(spans), 5)
        self.assertTrue(taken_every(spans, self.period, 1e-3),
                        'points taken at %s s' % np.round(spans, 3).tolist())
        first_run_start = result.list_of_odoms[0]

        started, feedback, state, result = self.record(until_distance=SECOND_GOAL_DISTANCE)
        self.assertEqual(state, GoalStatus.PREEMPTED)
        # Carried over, the total would start at the first goal's distance or more; the
        # recorder's first feedback can come a second or so of driving after the goal.
        self.assertLess(feedback[0], FIRST_GOAL_DISTANCE / 2.0,
                        'the second goal did not start from zero')
        first = result.list_of_odoms[0]
        # Odometry is exact here (localization gps): the first point is the
        # true pose of a step just after the goal was sent.
        gap = min(math.hypot(first.x - x, first.y - y) for x, y, _ in self.truths_near(started))
        self.assertLess(gap, 0.01)
        self.assertGreater(math.hypot(first.x - first_run_start.x, first.y - first_run_start.y),
                           1.0, 'the second goal kept the first goal\'s start')


if __name__ == '__main__':
    rospy.init_node('check_recorder')
    rostest.rosrun('wall_follower', 'check_recorder', RecordOdomGoals, sys.argv)
