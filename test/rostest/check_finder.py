#!/usr/bin/env python3
"""rostest: find_wall aligns the robot from five start poses in one world.

Each pose of config/find_trials.yaml is one test: the robot must end
the finder's wall_distance +- 0.03 m from the wall on its right, parallel within 5 deg, with no
contact and no command above the limits, judged from ground truth.
"""
import sys
import unittest

import rospy
import rostest
from drive_guard import DriveGuard

from wall_follower.nodes.evaluation.find_trials import FindTrials
from wall_follower.params import defaults
from wall_follower.params.course.wall_finder import FINDER

WALL_DISTANCE = defaults(FINDER)['wall_distance']


class FindWallFromPoses(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        world = rospy.get_param('~world')
        cls.starts = rospy.get_param('~poses')[world]
        cls.trials = FindTrials(world)
        cls.guard = DriveGuard()

    def check_start(self, index):
        result = self.trials.run(self.starts[index])
        rospy.loginfo('find_wall trial: %s', result)
        self.assertTrue(result['found'])
        self.assertAlmostEqual(result['distance'], WALL_DISTANCE, delta=0.03)
        self.assertLess(abs(result['heading_error_deg']), 5.0)
        self.assertFalse(result['contact'], 'touched an obstacle')
        self.guard.assert_safe(self)


for _index in range(5):
    setattr(FindWallFromPoses, 'test_start_%d' % _index,
            lambda self, i=_index: self.check_start(i))

if __name__ == '__main__':
    rospy.init_node('check_finder')
    rostest.rosrun('wall_follower', 'check_finder', FindWallFromPoses, sys.argv)
