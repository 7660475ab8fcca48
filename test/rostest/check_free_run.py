#!/usr/bin/env python3
"""rostest: a free-running simulator drops no odometry or ground truth.

Against free_run.test: the obstacles world at speedup 0 without lockstep,
started paused. A recorder sums every odometry message and a monitor scores
every ground truth, so neither topic may lose one, however far the
simulator runs ahead of its subscribers.
"""
import sys
import threading
import time
import unittest

import rospy
import rostest
from nav_msgs.msg import Odometry
from std_srvs.srv import Empty

DT = 0.1
# Simulated seconds to watch: 30000 steps, a few wall seconds flat out.
WATCH = 3000.0
# Wall seconds: limits on connecting and on the watch, that only bound a failing run.
CONNECT_LIMIT = 20.0
WATCH_LIMIT = 120.0


class FreeRun(unittest.TestCase):

    def setUp(self):
        self.stamps = {'odom': [], 'base_pose_ground_truth': []}
        self.done = threading.Event()
        self.subs = [rospy.Subscriber(topic, Odometry, self.on_message, topic, queue_size=100000)
                     for topic in self.stamps]

    def on_message(self, msg, topic):
        self.stamps[topic].append(msg.header.stamp.to_sec())
        if all(stamps and stamps[-1] >= WATCH for stamps in self.stamps.values()):
            self.done.set()

    def test_every_step_arrives_in_order(self):
        deadline = time.monotonic() + CONNECT_LIMIT
        while not all(sub.get_num_connections() for sub in self.subs):
            self.assertLess(time.monotonic(), deadline, 'could not connect to the simulator')
            time.sleep(0.01)
        rospy.wait_for_service('unpause_physics', timeout=CONNECT_LIMIT)
        rospy.ServiceProxy('unpause_physics', Empty)()
        self.assertTrue(self.done.wait(WATCH_LIMIT), 'the simulator did not run far enough')
        for topic, stamps in self.stamps.items():
            steps = [round(stamp / DT) for stamp in stamps if stamp <= WATCH]
            gaps = [(a, b) for a, b in zip(steps, steps[1:]) if b != a + 1]
            self.assertEqual(steps[0], 1, topic + ': the first step is missing')
            self.assertEqual(len(steps), round(WATCH / DT),
                             '%s: %d of %d steps arrived; first gaps (step before, after): %s'
                             % (topic, len(steps), round(WATCH / DT), gaps[:5]))
            self.assertEqual(gaps, [], topic + ': steps out of order')


if __name__ == '__main__':
    rospy.init_node('check_free_run')
    rostest.rosrun('wall_follower', 'check_free_run', FreeRun, sys.argv)
