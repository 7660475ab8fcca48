#!/usr/bin/env python3
"""rostest: teleop_key driven through a pipe produces ROBOTIS's command sequence, safely.

teleop_key runs as a child of this test with its standard input a pipe; the
test types keys into it and checks what comes out on cmd_vel: the ramp of
half a step per tick toward the target, the clamp at ~max_linear and
~max_angular, the stop at once on s, and a zero Twist when Ctrl-C's byte
quits it while the robot is moving, with a line saying so; with its
standard input closed, it stops at once with an error. Also: the targets
it prints, its exit status, and the drive guard (limits, no contact). The ramp is checked on
the ROS time each command is heard at, one tick (0.1 s) per half step
within RAMP_JITTER, so that a command superseded before it was sent (the
publisher keeps only the newest) does not fail it.
"""
import os
import subprocess
import sys
import threading
import unittest

import rospy
import rostest
from geometry_msgs.msg import Twist
from std_msgs.msg import Bool

from drive_guard import DriveGuard
from paused_world import start_world
from waiting import wait_until

WAIT = 60.0
EXACT = 1e-6
TICK = 0.1             # ROS s between teleop_key's commands
RAMP_JITTER = 0.25     # ROS s: when a command is heard may lag when it was sent


class TeleopKey(unittest.TestCase):

    def setUp(self):
        self.guard = DriveGuard()
        self.lock = threading.Lock()
        self.sent = []
        self.heard = []
        self.listening = [rospy.Subscriber('cmd_vel', Twist, self._on_command, queue_size=1000),
                          rospy.Subscriber('stalled', Bool, lambda _: None)]
        self.node = None

    def start(self, **stdin):
        """teleop_key with its standard input a pipe, or as stdin (Popen's arguments) says."""
        self.node = subprocess.Popen(['rosrun', 'wall_follower', 'teleop_key'],
                                     stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                     env=dict(os.environ), **(stdin or {'stdin': subprocess.PIPE}))

    def _on_command(self, msg):
        with self.lock:
            self.sent.append((msg.linear.x, msg.angular.z))
            self.heard.append(rospy.get_time())

    def tearDown(self):
        if self.node is not None and self.node.poll() is None:
            self.node.kill()
            self.node.wait()

    def type(self, keys):
        self.node.stdin.write(keys.encode('latin-1'))
        self.node.stdin.flush()

    def commands(self):
        with self.lock:
            return list(self.sent)

    def wait_for(self, condition, what, after=0, then=3):
        """The index of the first command from index after on that meets condition,
        once `then` more commands have come after it."""
        def found():
            commands = self.commands()
            hits = [i for i in range(after, len(commands)) if condition(commands[i])]
            return (hits[0],) if hits and len(commands) > hits[0] + then else None
        index = wait_until(found, WAIT)
        self.assertTrue(index, 'never: ' + what)
        return index[0]

    def assert_ramp(self, values, heard, ramp):
        """values, heard at ROS times heard, follow ramp (one value per tick) in order, in time."""
        self.assertAlmostEqual(values[0], ramp[0], delta=EXACT, msg='ramp %r' % values)
        self.assertAlmostEqual(values[-1], ramp[-1], delta=EXACT, msg='ramp %r' % values)
        ticks = []
        for value in values:
            tick = min(range(len(ramp)), key=lambda k: abs(ramp[k] - value))
            self.assertAlmostEqual(value, ramp[tick], delta=EXACT,
                                   msg='%r is not on the ramp %r' % (value, values))
            ticks.append(tick)
        self.assertEqual(ticks, sorted(set(ticks)), 'not one value per tick, in order: %r' % values)
        for tick, when in zip(ticks, heard):
            self.assertLessEqual(abs(when - heard[0] - tick * TICK), RAMP_JITTER,
                                 'ramp value %.3f heard %.2f s after the first, not %.1f s'
                                 % (ramp[tick], when - heard[0], tick * TICK))

    def test_keys_ramp_clamp_stop_and_quit(self):
        self.start()
        self.assertTrue(start_world(self.listening), 'teleop_key never connected')
        self.wait_for(lambda c: True, 'a first command')
        self.type('w' * 25)
        top = self.wait_for(lambda c: c[0] >= 0.19 - EXACT, 'full speed')
        commands = self.commands()
        first = next(i for i, c in enumerate(commands) if c[0] > 0.0)
        self.assert_ramp([c[0] for c in commands[first:top + 1]], self.heard[first:top + 1],
                         [0.005 * k for k in range(1, 39)])
        self.assertTrue(all(abs(c[0] - 0.19) < EXACT for c in commands[top:]), 'not held at 0.19')

        self.type('a' * 8)
        turned = self.wait_for(lambda c: c[1] >= 0.49 - EXACT, 'full turn rate', after=top)
        commands = self.commands()
        start = next(i for i in range(top, len(commands)) if commands[i][1] > 0.0)
        self.assert_ramp([c[1] for c in commands[start:turned + 1]],
                         self.heard[start:turned + 1], [0.05 * k for k in range(1, 10)] + [0.49])

        self.type('s')
        stopped = self.wait_for(lambda c: c == (0.0, 0.0), 'a stop', after=turned)
        before = self.commands()[stopped - 1]
        self.assertAlmostEqual(before[0], 0.19, delta=EXACT, msg='ramped down instead of stopping')
        self.assertAlmostEqual(before[1], 0.49, delta=EXACT, msg='ramped down instead of stopping')

        self.type('www')
        moving = self.wait_for(lambda c: c[0] >= 0.03 - EXACT, 'moving again', after=stopped)
        self.type('\x03')
        self.assertEqual(self.node.wait(WAIT), 0)
        output = self.node.stdout.read().decode('utf-8', 'replace')
        last = wait_until(lambda: self.commands()[-1] == (0.0, 0.0) and self.commands()[-1], 5.0)
        self.assertTrue(last, 'the last command was %r, not a zero Twist' % (self.commands()[-1],))
        self.assertGreater(len(self.commands()), moving)
        self.assertIn('target: linear 0.19 m/s, angular 0.00 rad/s', output)
        self.assertIn('target: linear 0.19 m/s, angular 0.49 rad/s', output)
        self.assertIn('target: linear 0.00 m/s, angular 0.00 rad/s', output)
        self.assertNotIn('0.20 m/s', output)
        self.assertNotIn('0.50 rad/s', output)
        self.assertIn('teleop_key: Ctrl-C (byte 0x03) read; stopping', output)
        self.guard.assert_safe(self)

    def test_a_closed_standard_input_stops_it_with_an_error(self):
        # rosrun's shell, then the node, start with no file descriptor 0 at all.
        self.start(stdin=None, preexec_fn=lambda: os.close(0))
        self.assertEqual(self.node.wait(WAIT), 1)
        output = self.node.stdout.read().decode('utf-8', 'replace')
        self.assertIn('teleop_key: no standard input to read keys from (it is closed); '
                      'stopping', output)
        self.assertNotIn('Traceback', output)
        self.assertTrue(all(command == (0.0, 0.0) for command in self.commands()),
                        'it drove: %r' % self.commands())


if __name__ == '__main__':
    rospy.init_node('check_teleop')
    rostest.rosrun('wall_follower', 'check_teleop', TeleopKey, sys.argv)
