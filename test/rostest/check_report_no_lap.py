#!/usr/bin/env python3
"""rostest: `main.launch sim:=true report:=true` ends when find_wall fails.

The robot stands where no wall is in laser range (open_field.world, as in
fault_no_wall.test): find_wall answers false, the follower ends, and no lap
can ever come. The report must then say so and end (it is the launch's
required node, so the whole launch ends) within a bound, with a non-zero
status and no plot, instead of waiting for ever. The launch runs on a master of its own, as a
user would start it; this test's own master is not used.
"""
import os
import re
import sys
import unittest

import rospy
import rostest
from scratch import ScratchFolders

from wall_follower.evaluation.launching import free_port, launch_and_read, launch_command

WORLD = os.path.join(os.path.dirname(os.path.abspath(__file__)), 'open_field.world')
# Wall seconds for the whole launch: start-up, find_wall's answer, and the
# report's start limit for a follower it never saw (20 s) with room to spare.
BOUND = 60.0


class ReportWithoutLap(ScratchFolders, unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        cls.plot = os.path.join(cls.scratch('report_no_lap-'), 'course.png')
        port = free_port()
        command = launch_command('main.launch', {
            'sim': 'true', 'simulator': 'builtin', 'world': WORLD, 'report': 'true',
            'lockstep': 'true', 'speedup': '0', 'plot': cls.plot}, port)
        cls.ended, cls.output = launch_and_read(command, port, BOUND)

    def test_launch_ends_within_bound(self):
        self.assertTrue(self.ended, 'the launch was still running after %.0f s:\n%s'
                        % (BOUND, self.output[-3000:]))

    def test_report_says_no_lap_can_come(self):
        self.assertRegex(self.output, r'course_report: the follower /wall_following .*'
                         r'no lap can come', self.output[-3000:])

    def test_report_exits_non_zero(self):
        status = re.search(r'REQUIRED process \[course_report-\d+\] has died!\s*'
                           r'process has died \[pid \d+, exit code (-?\d+)', self.output)
        self.assertIsNotNone(status, 'course_report did not end:\n' + self.output[-3000:])
        self.assertEqual(status.group(1), '1')

    def test_no_plot_without_a_lap(self):
        self.assertFalse(os.path.exists(self.plot))


if __name__ == '__main__':
    rospy.init_node('check_report_no_lap')
    rostest.rosrun('wall_follower', 'check_report_no_lap', ReportWithoutLap, sys.argv)
