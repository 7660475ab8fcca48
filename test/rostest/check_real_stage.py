#!/usr/bin/env python3
"""rostest: the course on real Stage, when stage_ros is installed.

`main.launch sim:=true simulator:=stage gui:=true report:=true` in the room:
find_wall, one recorded lap, and the report scored from real stageros'
ground truth (the report must say it ran on stageros). Stage's window needs
a display: without one the launch runs under `xvfb-run -a`.

Where stage_ros is not installed (Debian, CI) or no display can be had,
nothing is run, and the one test that passes says so in its name and on
stdout: a notice, not a silent skip.
"""
import json
import os
import sys
import tempfile
import unittest

import rospy
import rostest

from installed import real_stage_suite
from wall_follower.evaluation.launching import (display_wrapper, free_port, launch_and_read,
                                                launch_command)
from wall_follower.params import defaults
from wall_follower.params.course.wall_finder import FINDER

WORLD = 'room'
# Wall seconds for the launch: real Stage runs at the world's pace (speedup
# 1), and the room's lap takes about 50 s after find_wall's 10 s.
BOUND = 180.0


class RealStageCourse(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        cls.figures = None
        with tempfile.TemporaryDirectory(prefix='real_stage-') as workdir:
            output = os.path.join(workdir, 'course.json')
            port = free_port()
            command = display_wrapper() + launch_command('main.launch', {
                'sim': 'true', 'simulator': 'stage', 'gui': 'true', 'world': WORLD,
                'report': 'true', 'json': output}, port)
            cls.output = launch_and_read(command, port, BOUND)[1]
            if os.path.exists(output):
                with open(output) as stream:
                    cls.figures = json.load(stream)

    def figure(self, name):
        self.assertIsNotNone(self.figures, 'the report wrote no figures (no lap recorded):\n'
                             + self.output[-3000:])
        return self.figures[name]

    def test_ran_on_real_stageros(self):
        self.assertEqual(self.figure('simulator'), 'stageros')

    def test_find_wall(self):
        self.assertAlmostEqual(self.figure('found_distance'), defaults(FINDER)['wall_distance'],
                               delta=0.03)
        self.assertLess(abs(self.figure('found_heading_error_deg')), 5.0)

    def test_one_lap(self):
        self.assertGreater(self.figure('points'), 10)
        self.assertLessEqual(self.figure('closing_gap'), 0.3)
        self.assertAlmostEqual(self.figure('recorded_distance'), self.figure('true_distance'),
                               delta=0.02 * self.figure('true_distance'))

    def test_report_scores_the_lap(self):
        self.assertGreaterEqual(self.figure('time_in_band'), 0.9)
        self.assertFalse(self.figure('contact'))
        self.assertLessEqual(self.figure('max_linear'), 0.19 + 1e-6)
        self.assertLessEqual(self.figure('max_angular'), 0.49 + 1e-6)


if __name__ == '__main__':
    rospy.init_node('check_real_stage')
    rostest.rosrun('wall_follower', 'check_real_stage',
                   real_stage_suite('real_stage', RealStageCourse), sys.argv)
