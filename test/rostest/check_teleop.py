#!/usr/bin/env python3
"""rostest: teleop_key driven through a pipe produces ROBOTIS's command sequence, safely.

teleop_key runs as a child of this test with its standard input a pipe; the
test types keys into it and checks what comes out on cmd_vel: the ramp of
half a step per tick toward the target, the clamp at ~max_linear and
~max_angular, the stop at once on s, and a zero Twist when Ctrl-C's byte
quits it while the robot is moving, with a line saying so; with its
standard input closed, it stops at once with an error. Also: the targets
it prints, its exit status, and the drive guard (limits, no contact). The ramp is checked, one
tick (0.1 s) per half step, on the velocities the simulator applied in each
step, as its odom reports them, stamped with the step's ROS time: not on
when this test happened to hear each cmd_vel, which on a loaded machine
lags by whole steps behind when the node sent it. A command superseded
before a step took it (the newest counts) leaves a gap, which the check
allows; a value out of its tick by more than RAMP_JITTER fails it.
"""
import os
import subprocess
import sys
import threading
import unittest

import rospy
import rostest
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry
from std_msgs.msg import Bool

from drive_guard import DriveGuard
from paused_world import start_world
from waiting import wait_until

WAIT = 60.0
EXACT = 1e-6
TICK = 0.1             # ROS s between teleop_key's commands
RAMP_JITTER = 0.25     # ROS s: a value may be applied this much off its tick
ODOM_QUEUE = 100000    # odom messages held while the test is busy


class TeleopKey(unittest.TestCase):

    def setUp(self):
        self.guard = DriveGuard()
        self.lock = threading.Lock()
        self.sent = []
        self.applied = []      # (stamp, linear, angular) of each simulated step, from odom
        self.listening = [
            rospy.Subscriber('cmd_vel', Twist, self._on_command, queue_size=1000),
            rospy.Subscriber('odom', Odometry, self._on_odom, queue_size=ODOM_QUEUE),
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

    def _on_odom(self, msg):
        with self.lock:
            self.applied.append((msg.header.stamp.to_sec(), msg.twist.twist.linear.x,
                                 msg.twist.twist.angular.z))

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

    def applied_ramp(self, axis, start, top):
        """(values, stamps) of axis (1: linear, 2: angular) in the steps simulated from
        the first whose value exceeds start to the first that reaches top."""
        def reached():
            with self.lock:
                steps = list(self.applied)
            return steps if any(step[axis] >= top - EXACT for step in steps) else None
        steps = wait_until(reached, WAIT)
        self.assertTrue(steps, 'odom never showed %.2f' % top)
        first = next(i for i, step in enumerate(steps) if step[axis] > start + EXACT)
        last = next(i for i, step in enumerate(steps) if step[axis] >= top - EXACT)
        ramp = steps[first:last + 1]
        return [step[axis] for step in ramp], [step[0] for step in ramp]

    def assert_ramp(self, values, stamps, ramp):
        """values, applied at ROS times stamps, follow ramp (one value per tick) in order,
        in time."""
        self.assertAlmostEqual(values[0], ramp[0], delta=EXACT, msg='ramp %r' % values)
        self.assertAlmostEqual(values[-1], ramp[-1], delta=EXACT, msg='ramp %r' % values)
        ticks = []
        for value in values:
            tick = min(range(len(ramp)), key=lambda k: abs(ramp[k] - value))
            self.assertAlmostEqual(value, ramp[tick], delta=EXACT,
                                   msg='%r is not on the ramp %r' % (value, values))
            ticks.append(tick)
        self.assertEqual(ticks, sorted(set(ticks)), 'not one value per tick, in order: %r' % values)
        for tick, when in zip(ticks, stamps):
            self.assertLessEqual(abs(when - stamps[0] - tick * TICK), RAMP_JITTER,
                                 'ramp value %.3f applied %.2f s after the first, not %.1f s'
                                 % (ramp[tick], when - stamps[0], tick * TICK))

    def test_keys_ramp_clamp_stop_and_quit(self):
        self.start()
        self.assertTrue(start_world(self.listening), 'teleop_key never connected')
        self.wait_for(lambda c: True, 'a first command')
        self.type('w' * 25)
        top = self.wait_for(lambda c: c[0] >= 0.19 - EXACT, 'full speed')
        self.assert_ramp(*self.applied_ramp(1, 0.0, 0.19), ramp=[0.005 * k for k in range(1, 39)])
        commands = self.commands()
        self.assertTrue(all(abs(c[0] - 0.19) < EXACT for c in commands[top:]), 'not held at 0.19')

        self.type('a' * 8)
        turned = self.wait_for(lambda c: c[1] >= 0.49 - EXACT, 'full turn rate', after=top)
        self.assert_ramp(*self.applied_ramp(2, 0.0, 0.49),
                         ramp=[0.05 * k for k in range(1, 10)] + [0.49])

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
