#!/usr/bin/env python3
"""rostest: an exercise node warns of a misspelt ~key and stops, by name, on a bad value.

wander runs as a child of this test (as `rosrun wall_follower wander
_key:=value` would start it), with no simulator: a misspelt key must be
named in a warning while the node goes on (and a SIGINT ends it cleanly); a
value out of range, or two that break a rule together, must stop it at
start with exit status 1 and a line naming the parameter, never a
traceback.
"""
import os
import signal
import subprocess
import sys
import threading
import unittest

import rospy
import rostest

from waiting import wait_until

WAIT = 30.0   # wall s, for a node to start or end


class NodeOutput(object):
    """A node started as a child process, its output (stdout and stderr) gathered by a thread."""

    def __init__(self, name, *params):
        # Unbuffered: Python holds a pipe's output back until its buffer fills, and
        # a line the node has logged must be read while it runs.
        self.process = subprocess.Popen(
            ['rosrun', 'wall_follower', 'wander', '__name:=' + name] + list(params),
            stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
            env=dict(os.environ, PYTHONUNBUFFERED='1'))
        self._lines = []
        self._lock = threading.Lock()
        thread = threading.Thread(target=self._read)
        thread.daemon = True
        thread.start()

    def _read(self):
        for line in self.process.stdout:
            with self._lock:
                self._lines.append(line.decode('utf-8', 'replace'))

    def text(self):
        with self._lock:
            return ''.join(self._lines)

    def ended(self):
        """The exit status once the process has ended (within WAIT), else None."""
        try:
            return self.process.wait(WAIT)
        except subprocess.TimeoutExpired:
            return None

    def kill(self):
        if self.process.poll() is None:
            self.process.kill()
            self.process.wait()


class ExerciseParameters(unittest.TestCase):

    def setUp(self):
        self.nodes = []

    def tearDown(self):
        for node in self.nodes:
            node.kill()

    def start(self, name, *params):
        node = NodeOutput(name, *params)
        self.nodes.append(node)
        return node

    def test_a_misspelt_key_is_named_in_a_warning_and_the_node_goes_on(self):
        node = self.start('wander_misspelt', '_speeed:=0.1')
        self.assertTrue(wait_until(lambda: 'ignoring unknown parameter(s) ~speeed' in node.text(),
                                   WAIT), 'no warning naming ~speeed: %s' % node.text())
        self.assertTrue(wait_until(lambda: 'wander: driving about' in node.text(), WAIT),
                        node.text())
        self.assertIsNone(node.process.poll(), 'stopped: %s' % node.text())
        node.process.send_signal(signal.SIGINT)
        self.assertEqual(node.ended(), 0, node.text())

    def assert_stops_naming(self, name, param, says):
        node = self.start(name, param)
        self.assertEqual(node.ended(), 1, node.text())
        self.assertIn('cannot start: ' + says, node.text())
        self.assertNotIn('Traceback', node.text())

    def test_a_value_out_of_range_stops_the_node_with_an_error_naming_it(self):
        self.assert_stops_naming('wander_out_of_range', '_cone_half_width:=10.0',
                                 '~cone_half_width must be at most 3.14')

    def test_a_value_of_the_wrong_type_stops_the_node_with_an_error_naming_it(self):
        self.assert_stops_naming('wander_wrong_type', '_speed:=fast', '~speed must be a number')

    def test_values_that_break_a_rule_stop_the_node_with_an_error_naming_them(self):
        self.assert_stops_naming('wander_rule', '_clear_distance:=0.3',
                                 '~clear_distance (0.3) must not be below obstacle_distance')


if __name__ == '__main__':
    rospy.init_node('check_exercise_parameters')
    rostest.rosrun('wall_follower', 'check_exercise_parameters', ExerciseParameters, sys.argv)
