#!/usr/bin/env python3
"""rostest: on a Waffle, with no ~laser_x, the nodes take -0.064 m from tf and lap.

Against waffle.test. The simulator starts paused; /rosout is heard before
this check lets it go, and the nodes cannot read the mount before the first
scan, so every node's log line saying which laser_x it took is heard.
"""
import sys
import unittest

import rospy
import rostest
from drive_guard import DriveGuard
from rosout_log import RosoutLog

from wall_follower.evaluation.scoring.course import CourseMap
from wall_follower.nodes.shared.course_monitor import CourseMonitor
from wall_follower.sim.stage_interface import world_path

WAFFLE_LASER_X = -0.064
TAKEN = 'laser_x %.3f m (from tf base_link -> base_laser_link)' % WAFFLE_LASER_X
NODES = ('/wall_finder', '/wall_following')
# Wall seconds allowed for the monitor's subscriptions to connect.
CONNECT_LIMIT = 30.0
# Least clearance of the body [m]: more than a cell of the world's grid, which
# the simulator (as Stage) takes for contact when the body's edge enters it.
MIN_CLEARANCE = 0.025


class WaffleMount(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        cls.log = RosoutLog(*NODES)
        cls.guard = DriveGuard()
        cls.monitor = CourseMonitor(CourseMap(world_path(rospy.get_param('~world'))),
                                    start_on_goal=True)
        assert cls.monitor.start_world(CONNECT_LIMIT), 'the monitor could not connect'
        cls.monitor.wait()

    def test_each_node_took_the_waffles_laser_x_from_tf(self):
        for node in NODES:
            said = self.log.lines(node)
            self.assertTrue(any(TAKEN in text for text in said),
                            '%s did not log "%s": %s' % (node, TAKEN, said))
            self.assertFalse(any('Burger' in text for text in said), said)

    def test_the_chain_laps_within_the_limits_without_contact(self):
        score = self.monitor.summary()
        rospy.loginfo('waffle: %s', score)
        self.assertTrue(score['lap_closed'])
        self.assertFalse(score['contact'], 'touched a wall (clearance %.3f m)'
                         % score['min_clearance'])
        self.assertGreaterEqual(score['min_clearance'], MIN_CLEARANCE)
        self.guard.assert_safe(self)


if __name__ == '__main__':
    rospy.init_node('check_waffle')
    rostest.rosrun('wall_follower', 'check_waffle', WaffleMount, sys.argv)
