#!/usr/bin/env python3
"""rostest: the follower killed mid-lap leaves a standing robot.

The test starts wall_following itself, as a child process, lets it drive,
and kills it: with SIGINT (Ctrl-C) the last command it sent must be a zero
Twist and it must exit by itself; with SIGKILL, which it cannot answer,
the simulator's 0.2 s cmd_vel watchdog must stop the robot within 0.3 s
of simulated time, judged from ground truth.
"""
import math
import signal
import subprocess
import sys
import threading
import time
import unittest

import rospy
import rostest
from geometry_msgs.msg import Twist
from sim_probe import SimProbe, pose_of
from waiting import wait_until

EXIT_LIMIT = 10.0     # wall s for the node to exit after SIGINT
SIGINT_ATTEMPTS = 5
WATCHDOG_STOP = 0.3   # simulated s


def moved(truths):
    poses = [pose_of(msg) for msg in truths]
    return max([math.hypot(b[0] - a[0], b[1] - a[1]) for a, b in zip(poses, poses[1:])] or [0.0])


class Kill(unittest.TestCase):

    def setUp(self):
        self.lock = threading.Lock()
        self.commands = []
        rospy.Subscriber('cmd_vel', Twist, self._on_cmd, queue_size=1000)
        self.probe = SimProbe()
        self.probe.wait_ready()

    def _on_cmd(self, msg):
        with self.lock:
            self.commands.append((msg.linear.x, msg.angular.z))

    def start_follower(self):
        """wall_following as a child process, once it drives and this node hears its
        commands; and the index in self.commands of its first one."""
        with self.lock:
            first = len(self.commands)
        node = subprocess.Popen(['rosrun', 'wall_follower', 'wall_following.py',
                                 '__name:=wall_following', '_find_wall:=false',
                                 '_record_odom:=false'])
        start = rospy.get_time()
        self.probe.wait_for(lambda: moved(self.probe.truths_since(start)) > 0.01,
                            'the follower to drive', limit=60.0)
        self.probe.wait_for(lambda: any(v != 0.0 for v, _ in self.commands_since(first)),
                            'its commands to be heard', limit=60.0)
        return node, first

    def commands_since(self, first):
        with self.lock:
            return self.commands[first:]

    def test_sigint_ends_with_a_stop(self):
        # A signal can land anywhere, publishing included: try it a few times.
        for attempt in range(SIGINT_ATTEMPTS):
            node, first = self.start_follower()
            node.send_signal(signal.SIGINT)
            deadline = time.monotonic() + EXIT_LIMIT
            while node.poll() is None and time.monotonic() < deadline:
                time.sleep(0.05)
            exited = node.poll() is not None
            if not exited:
                node.kill()
            self.assertTrue(exited, 'attempt %d: still running %.0f s after SIGINT'
                            % (attempt, EXIT_LIMIT))
            # Its last command may still be on its way when it has exited.
            self.assertTrue(wait_until(lambda: self.commands_since(first)[-1] == (0.0, 0.0),
                                       EXIT_LIMIT),
                            'attempt %d: last command %s' % (attempt,
                                                             self.commands_since(first)[-1]))

    def test_sigkill_is_stopped_by_the_watchdog(self):
        node, _ = self.start_follower()
        node.kill()
        killed = rospy.get_time()
        node.wait()
        self.probe.wait_for(lambda: self.probe.truths_since(killed + 2.0), '2 s of simulation')
        self.assertLess(moved(self.probe.truths_since(killed + WATCHDOG_STOP)), 1e-4,
                        'still moving %.1f s after SIGKILL' % WATCHDOG_STOP)


if __name__ == '__main__':
    rospy.init_node('check_kill')
    rostest.rosrun('wall_follower', 'check_kill', Kill, sys.argv)
