#!/usr/bin/env python3
"""rostest: with no wall in laser range the chain ends cleanly and the robot never moves.

find_wall must answer false and say why, wall_following must exit saying
that it will not follow, and ground truth must show the robot where it
started, with the drive guard's limits kept throughout.
"""
import math
import sys
import time
import unittest

import rospy
import rostest
from drive_guard import DriveGuard
from nav_msgs.msg import Odometry
from paused_world import start_world
from rosout_log import RosoutLog
from sim_probe import SimProbe, pose_of
from waiting import wait_until

from wall_follower.nodes.shared.course_monitor import node_alive

EXIT_LIMIT = 60.0   # wall s


class NoWall(unittest.TestCase):

    def test_find_wall_fails_and_the_follower_exits_without_moving(self):
        # The world starts paused: both nodes say why at once when it goes.
        log = RosoutLog('/wall_finder', '/wall_following')
        guard = DriveGuard()
        probe = SimProbe()
        truth = rospy.Subscriber('base_pose_ground_truth', Odometry, lambda _: None)
        self.assertTrue(start_world([truth]), 'the simulator never connected')
        probe.wait_ready()
        start = pose_of(probe.latest_truth())
        deadline = time.monotonic() + EXIT_LIMIT
        while node_alive('/wall_following') and time.monotonic() < deadline:
            time.sleep(0.1)
        self.assertFalse(node_alive('/wall_following'), 'wall_following still runs')
        # Log lines come on /rosout, connections of their own: they may come later.
        self.assertTrue(wait_until(lambda: log.said('/wall_finder', 'no wall in range'),
                                   EXIT_LIMIT), 'find_wall did not say why')
        self.assertTrue(wait_until(lambda: log.said('/wall_following', 'found no wall'),
                                   EXIT_LIMIT), 'wall_following did not say why')
        end = pose_of(probe.latest_truth())
        self.assertLess(math.hypot(end[0] - start[0], end[1] - start[1]), 1e-3)
        guard.assert_safe(self)


if __name__ == '__main__':
    rospy.init_node('check_no_wall')
    rostest.rosrun('wall_follower', 'check_no_wall', NoWall, sys.argv)
