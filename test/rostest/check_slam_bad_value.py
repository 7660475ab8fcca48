#!/usr/bin/env python3
"""rostest: a bad parameter stops the slam node at start with an error naming it.

The node is started as a user starts it (rosrun, the value given as a
private parameter on the command line) against this test's master, once
for each kind of bad value: of the wrong type, out of its range, and a
grid that cannot be (xmax below xmin, which no one parameter's range
tells), and grids too large for memory (each value in its range, the cells
of all of them together not). Each time it must end with status 1 and a line that names the
problem, and print no traceback.
"""
import subprocess
import sys
import unittest

import rospy
import rostest

# (the bad values, as rosrun's arguments; what the error must say)
CASES = [
    (['_map_update_interval:=often'], 'cannot start: ~map_update_interval must be a number'),
    (['_delta:=-0.05'], 'cannot start: ~delta must be at least'),
    (['_xmax:=-20.0'], 'cannot start: ~xmax (-20.0) must be above xmin (-10.0)'),
    (['_xmin:=-100.0', '_xmax:=100.0', '_ymin:=-100.0', '_ymax:=100.0', '_delta:=0.005'],
     'cannot start: ~xmin, xmax, ymin, ymax, delta and match_resolution ask for'),
]
WALL_LIMIT = 30.0   # wall s for the node to start and stop


def run_slam(arguments, name):
    """The exit status and the output of a slam node started with arguments."""
    done = subprocess.run(['rosrun', 'wall_follower', 'slam'] + arguments + ['__name:=' + name],
                          stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                          universal_newlines=True, timeout=WALL_LIMIT)
    return done.returncode, done.stdout


class SlamBadValue(unittest.TestCase):

    def check_case(self, index):
        arguments, says = CASES[index]
        # A node name of its own: a private parameter stays on the master after its node.
        status, output = run_slam(arguments, 'slam_bad_%d' % index)
        self.assertEqual(status, 1, output)
        self.assertIn(says, output)
        self.assertNotIn('Traceback', output)


for _index in range(len(CASES)):
    setattr(SlamBadValue, 'test_case_%d' % _index, lambda self, i=_index: self.check_case(i))

if __name__ == '__main__':
    rospy.init_node('check_slam_bad_value')
    rostest.rosrun('wall_follower', 'check_slam_bad_value', SlamBadValue, sys.argv)
