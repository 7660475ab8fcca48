#!/usr/bin/env python3
"""rostest: the follower alone laps a world, scored from ground truth.

The robot starts beside a wall (the world file's pose); the lap ends when
ground truth crosses the start line again. Parameters: ~world (name),
~min_in_band (share of the lap), ~time_limit (simulated s).
"""
import sys
import unittest

import rospy
import rostest
from drive_guard import DriveGuard

from wall_follower.evaluation.scoring.course import CourseMap
from wall_follower.nodes.shared.course_monitor import CourseMonitor
from wall_follower.sim.stage_interface import world_path


class FollowLap(unittest.TestCase):

    def test_full_lap_in_band_without_contact(self):
        world = rospy.get_param('~world')
        min_in_band = rospy.get_param('~min_in_band', 0.95)
        guard = DriveGuard()
        monitor = CourseMonitor(CourseMap(world_path(world)), start_on_goal=False)
        monitor.wait()
        score = monitor.summary()
        rospy.loginfo('follow %s: %s', world, score)
        self.assertTrue(score['lap_closed'])
        self.assertFalse(score['contact'], 'touched an obstacle (clearance %.3f m)'
                         % score['min_clearance'])
        self.assertGreaterEqual(score['time_in_band'], min_in_band)
        guard.assert_safe(self)


if __name__ == '__main__':
    rospy.init_node('check_follow')
    rostest.rosrun('wall_follower', 'check_follow', FollowLap, sys.argv)
