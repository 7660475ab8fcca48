#!/usr/bin/env python3
"""rostest: a find_wall call made while another searches is refused at once, with a warning.

The first call is made from the middle of the room; once it is searching,
the world is paused (pause_physics), so that it cannot end before the
second call is made. The second must answer false and say why; after the
world goes on, the first must still find the wall.
"""
import sys
import threading
import time
import unittest

import rospy
import rostest
from drive_guard import DriveGuard
from rosout_log import RosoutLog
from std_srvs.srv import Empty

from wall_follower.srv import FindWall

from waiting import wait_until

WAIT_LIMIT = 30.0   # wall s


class TwoCalls(unittest.TestCase):

    def test_the_second_call_is_refused_while_the_first_searches(self):
        log = RosoutLog('/wall_finder')
        guard = DriveGuard()
        rospy.wait_for_service('find_wall', WAIT_LIMIT)
        find_wall = rospy.ServiceProxy('find_wall', FindWall)
        answers = []
        first = threading.Thread(target=lambda: answers.append(find_wall().wallfound))
        first.start()
        deadline = time.monotonic() + WAIT_LIMIT
        while not log.said('/wall_finder', 'ROTATE_TO_WALL'):
            self.assertLess(time.monotonic(), deadline, 'the first call never searched')
            time.sleep(0.01)
        rospy.ServiceProxy('pause_physics', Empty)()
        self.assertFalse(rospy.ServiceProxy('find_wall', FindWall)().wallfound)
        # The warning goes out on /rosout, a connection of its own: it may come later.
        self.assertTrue(wait_until(
            lambda: log.said('/wall_finder', 'refused: a search is already running'),
            WAIT_LIMIT), 'no warning')
        rospy.ServiceProxy('unpause_physics', Empty)()
        first.join(WAIT_LIMIT)
        self.assertEqual(answers, [True])
        guard.assert_safe(self)


if __name__ == '__main__':
    rospy.init_node('check_two_calls')
    rostest.rosrun('wall_follower', 'check_two_calls', TwoCalls, sys.argv)
