#!/usr/bin/env python3
"""rostest: odometry stops mid-lap; the follower stops the robot and exits, saying why.

The recorder hears odom through this node, which stops passing it on once
the follower's recording has passed STOP_AFTER metres. record_odom must
abort the goal, and wall_following must then log why, stop the robot (as
ground truth shows) and end, so that nothing waits for a lap that cannot
come.
"""
import math
import sys
import threading
import time
import unittest

import rospy
import rostest
from drive_guard import DriveGuard
from rosout_log import RosoutLog
from nav_msgs.msg import Odometry
from sim_probe import SimProbe, pose_of
from waiting import wait_until

from wall_follower.msg import OdomRecordActionFeedback
from wall_follower.nodes.shared.course_monitor import node_alive

WAIT_LIMIT = 60.0   # wall s
STOP_AFTER = 1.0    # metres recorded before the odometry stops


class ChainOdometryStops(unittest.TestCase):

    def test_the_follower_stops_when_the_recording_is_aborted(self):
        passing = threading.Event()
        passing.set()
        feedback = []
        log = RosoutLog('/wall_following')
        relay = rospy.Publisher('odom_relayed', Odometry, queue_size=100)
        rospy.Subscriber('odom', Odometry,
                         lambda msg: relay.publish(msg) if passing.is_set() else None,
                         queue_size=100)
        rospy.Subscriber('record_odom/feedback', OdomRecordActionFeedback,
                         lambda msg: feedback.append(msg.feedback.current_total), queue_size=100)
        guard = DriveGuard()
        probe = SimProbe()
        probe.wait_ready()
        deadline = time.monotonic() + WAIT_LIMIT
        while not (feedback and feedback[-1] >= STOP_AFTER):
            self.assertLess(time.monotonic(), deadline, 'no feedback past %.1f m' % STOP_AFTER)
            time.sleep(0.01)
        passing.clear()
        while node_alive('/wall_following'):
            self.assertLess(time.monotonic(), deadline, 'wall_following still runs')
            time.sleep(0.1)
        self.assertTrue(wait_until(lambda: log.said('/wall_following',
                                                    'record_odom aborted the lap'), WAIT_LIMIT),
                        'wall_following did not say why')
        ended = rospy.get_time()
        probe.wait_for(lambda: probe.truths_since(ended + 1.0), '1 s of simulation')
        poses = [pose_of(msg) for msg in probe.truths_since(ended)]
        self.assertLess(math.hypot(poses[-1][0] - poses[0][0], poses[-1][1] - poses[0][1]),
                        1e-4, 'the robot moved on after the follower ended')
        guard.assert_safe(self)


if __name__ == '__main__':
    rospy.init_node('check_chain_odom_stops')
    rostest.rosrun('wall_follower', 'check_chain_odom_stops', ChainOdometryStops, sys.argv)
