#!/usr/bin/env python3
"""rostest: waiting for record_odom ends in wall time while the ROS clock stands still.

/use_sim_time is set and nobody publishes /clock, so ROS time stays at 0;
no record_odom server runs. wall_following must log an error naming
record_odom and exit once its ~service_wait wall seconds are up, not
wait for a clock that never comes. Everything here is timed on the wall
clock, as this node's ROS clock stands still too.
"""
import sys
import time
import unittest

import rosnode
import rospy
import rostest
from rosgraph_msgs.msg import Log

from rosout_log import RosoutLog
from waiting import wait_until

NODE = '/wall_following'
# Wall seconds past the node's ~service_wait by which it must have exited: it starts
# before this test, and starting (slow on a loaded machine) and exiting take a while.
# Only a failing run waits this long; the old code never exited at all.
MARGIN = 30.0


def alive():
    return NODE in rosnode.get_node_names()


class WaitOnFrozenClock(unittest.TestCase):

    def test_gives_up_in_wall_time_with_an_error(self):
        started = time.time()
        log = RosoutLog(NODE)
        service_wait = rospy.get_param(NODE + '/service_wait')
        self.assertTrue(wait_until(alive, MARGIN), 'wall_following is not running')
        self.assertTrue(wait_until(lambda: not alive(), service_wait + MARGIN),
                        'wall_following still waits after %.0f wall s' % (time.time() - started))
        self.assertTrue(wait_until(lambda: log.said(NODE, 'record_odom', Log.ERROR), 1.0),
                        'no error naming record_odom: %s' % log.lines(NODE, '', Log.ERROR))
        self.assertEqual(rospy.get_time(), 0.0, 'the clock moved: the test proves nothing')


if __name__ == '__main__':
    rospy.init_node('check_recorder_wait_frozen_clock')
    rostest.rosrun('wall_follower', 'check_recorder_wait_frozen_clock', WaitOnFrozenClock,
                   sys.argv)
