#!/usr/bin/env python3
"""rostest: a lap of the lab's line on real Stage, when stage_ros is installed.

`line_following.launch sim:=true simulator:=stage gui:=true` on line_lab,
on a master of its own (under `xvfb-run -a` without a display: real
stageros renders its camera only with its window), scored by
line_lap_score.py from real stageros' ground truth: the base within the
same bounds as in the built-in simulator (line_follow.test).

Where stage_ros is not installed (Debian, CI) or no display can be had,
nothing is run, and the one test that passes says so in its name and on
stdout: a notice, not a silent skip.
"""
import json
import os
import signal
import subprocess
import sys
import tempfile
import unittest

import rospy
import rostest

from installed import real_stage_suite
from wall_follower.evaluation.launching import display_wrapper, free_port, launch_command

WORLD = 'line_lab'
# Wall seconds: real Stage runs at the world's pace (speedup 1); the lab's lap takes 50 s.
BOUND = 150.0


class RealStageLap(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        cls.figures = None
        with tempfile.TemporaryDirectory(prefix='line_real_stage-') as workdir:
            output = os.path.join(workdir, 'lap.json')
            port = free_port()
            env = dict(os.environ, ROS_MASTER_URI='http://localhost:%d' % port)
            command = display_wrapper() + launch_command('line_following.launch', {
                'sim': 'true', 'simulator': 'stage', 'gui': 'true', 'world': WORLD}, port)
            score = os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                 'line_lap_score.py')
            with tempfile.TemporaryFile('w+') as log:
                launch = subprocess.Popen(command, env=env, stdout=log,
                                          stderr=subprocess.STDOUT, start_new_session=True)
                try:
                    subprocess.run([sys.executable, score, WORLD, str(BOUND), output], env=env,
                                   stdout=log, stderr=subprocess.STDOUT, timeout=BOUND + 30.0)
                finally:
                    os.killpg(launch.pid, signal.SIGINT)
                    launch.wait()
                log.seek(0)
                cls.output = log.read()
            if os.path.exists(output):
                with open(output) as stream:
                    cls.figures = json.load(stream)

    def test_a_lap_on_the_line(self):
        self.assertIsNotNone(self.figures, 'no figures:\n' + self.output[-3000:])
        self.assertTrue(self.figures['lapped'], self.figures)
        self.assertLessEqual(self.figures['rms'], 0.015, self.figures)
        self.assertLessEqual(self.figures['max'], 0.05, self.figures)
        self.assertGreaterEqual(self.figures['mean_speed'], 0.15, self.figures)


if __name__ == '__main__':
    rospy.init_node('check_line_real_stage')
    rostest.rosrun('wall_follower', 'check_line_real_stage',
                   real_stage_suite('line_real_stage', RealStageLap), sys.argv)
