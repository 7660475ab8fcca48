#!/usr/bin/env python3
"""rostest: main.launch end to end: find_wall, then a recorded lap.

Judged from ground truth: where find_wall left the robot, whether the
feedback rose steadily and matched the true distance, and whether the lap
was declared where the robot really came back to its start. The follower
keeps following after the lap (stop_after_lap false) so that the true
return to the start is seen even if the recorder declared early. The
simulator starts paused and this check unpauses it once it is listening,
so no run can outpace it.
"""
import math
import sys
import unittest

import numpy as np
import rospy
import rostest
from drive_guard import DriveGuard

from wall_follower.evaluation.scoring.course import CourseMap, taken_every, true_lap_length
from wall_follower.nodes.shared.course_monitor import CourseMonitor
from wall_follower.params import defaults
from wall_follower.params.course.wall_finder import FINDER
from wall_follower.sim.stage_interface import world_path

# Ground truth is kept this long after the result, to see the true return.
AFTER_RESULT = 10.0
# Wall seconds allowed for the monitor's subscriptions to connect.
CONNECT_LIMIT = 30.0


class Course(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        cls.world = rospy.get_param('~world')
        cls.tolerance = rospy.get_param('/odom_recorder/close_tolerance', 0.3)
        cls.period = rospy.get_param('/odom_recorder/sample_period', 1.0)
        cls.guard = DriveGuard()
        cls.monitor = CourseMonitor(CourseMap(world_path(cls.world)), start_on_goal=True)
        # The simulator starts paused: nothing moves until the monitor hears everything.
        assert cls.monitor.start_world(CONNECT_LIMIT), 'the monitor could not connect'
        cls.monitor.wait()
        rospy.sleep(AFTER_RESULT)

    def test_wall_found_before_recording(self):
        self.assertIsNotNone(self.monitor.goal_pose, 'no record_odom goal: find_wall failed?')
        distance, heading = self.monitor.score.map.right_wall_alignment(self.monitor.goal_pose)
        self.assertAlmostEqual(distance, defaults(FINDER)['wall_distance'], delta=0.03)
        self.assertLess(abs(math.degrees(heading)), 5.0)

    def test_feedback_rises_and_matches_true_distance(self):
        feedback = self.monitor.feedback
        self.assertGreater(len(feedback), 10)
        self.assertTrue(all(b >= a for a, b in zip(feedback, feedback[1:])),
                        'feedback went down')
        truth = self.monitor.truth_at_result
        self.assertAlmostEqual(feedback[-1], truth, delta=0.02 * truth)

    def test_one_point_a_second_and_closed(self):
        points = self.monitor.result
        spans = self.monitor.recorded_spans
        self.assertGreater(len(points), 10)
        # The last point is the closing pose, taken when the lap ends, off the grid.
        self.assertTrue(taken_every(spans[:-1], self.period, 1e-3),
                        'points taken at %s s' % np.round(spans, 3).tolist())
        self.assertLessEqual(spans[-1][0] - spans[-2][1], self.period + 1e-3)
        gap = math.hypot(points[-1][0] - points[0][0], points[-1][1] - points[0][1])
        self.assertLessEqual(gap, self.tolerance)

    def test_within_the_limits_without_contact(self):
        self.guard.assert_safe(self)

    def test_lap_declared_where_the_robot_came_back(self):
        start = self.monitor.goal_pose
        lap = true_lap_length(self.monitor.trail, start)
        self.assertIsNotNone(lap, 'ground truth never came back to the start')
        declared = self.monitor.truth_at_result
        self.assertGreaterEqual(declared, 0.9 * lap)
        self.assertLessEqual(declared, 1.1 * lap)


if __name__ == '__main__':
    rospy.init_node('check_course')
    rostest.rosrun('wall_follower', 'check_course', Course, sys.argv)
