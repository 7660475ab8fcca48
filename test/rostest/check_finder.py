#!/usr/bin/env python3
"""rostest: find_wall aligns the robot from several start poses in one world.

The robot is teleported to each pose of finder_poses.yaml (the simulator's
cmd_pose), then /find_wall is called; ground truth and the map judge where
it ended: 0.30 +- 0.03 m from the wall on its right, parallel within 5 deg,
no contact, no command above the limits.
"""
import math
import sys
import unittest

import rospy
import rostest
from geometry_msgs.msg import Pose

from wall_follower.motion import MAX_ANGULAR, MAX_LINEAR
from wall_follower.nodes.common import world_path
from wall_follower.nodes.course_monitor import CourseMonitor
from wall_follower.scoring import CourseMap
from wall_follower.srv import FindWall

LIMIT_SLACK = 1e-6
# Simulated time for the scan and ground truth to show the new pose.
SETTLE = 0.5


def teleport_message(x, y, yaw_deg):
    pose = Pose()
    pose.position.x, pose.position.y = x, y
    yaw = math.radians(yaw_deg)
    pose.orientation.z, pose.orientation.w = math.sin(yaw / 2.0), math.cos(yaw / 2.0)
    return pose


class FindWallFromPoses(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        cls.world = rospy.get_param('~world')
        cls.poses = rospy.get_param('~poses')[cls.world]
        cls.map = CourseMap(world_path(cls.world))
        cls.teleport = rospy.Publisher('cmd_pose', Pose, queue_size=1, latch=True)
        rospy.wait_for_service('find_wall', timeout=30.0)
        cls.find_wall = rospy.ServiceProxy('find_wall', FindWall)

    def check_pose(self, index):
        x, y, yaw = self.poses[index]
        self.teleport.publish(teleport_message(x, y, yaw))
        rospy.sleep(SETTLE)
        monitor = CourseMonitor(self.map, start_on_goal=False)
        started = rospy.get_time()
        found = self.find_wall().wallfound
        took = rospy.get_time() - started
        rospy.sleep(SETTLE)
        end = monitor.pose
        monitor.close()
        score = monitor.score.summary()
        aligned = self.map.right_wall_alignment(end)
        rospy.loginfo('find_wall %s from %s: found=%s in %.1f s, end %s, wall %s',
                      self.world, (x, y, yaw), found, took, end, aligned)
        self.assertTrue(found)
        self.assertIsNotNone(aligned, 'no wall on the right at the end')
        self.assertAlmostEqual(aligned[0], 0.30, delta=0.03)
        self.assertLess(abs(math.degrees(aligned[1])), 5.0)
        self.assertFalse(score['contact'], 'touched an obstacle')
        self.assertLessEqual(score['max_linear'], MAX_LINEAR + LIMIT_SLACK)
        self.assertLessEqual(score['max_angular'], MAX_ANGULAR + LIMIT_SLACK)


def _add_pose_tests(count=5):
    for index in range(count):
        setattr(FindWallFromPoses, 'test_pose_%d' % index,
                lambda self, i=index: self.check_pose(i))


_add_pose_tests()

if __name__ == '__main__':
    rospy.init_node('check_finder')
    rostest.rosrun('wall_follower', 'check_finder', FindWallFromPoses, sys.argv)
