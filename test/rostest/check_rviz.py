#!/usr/bin/env python3
"""rostest: rviz starts with every shipped config, no display in error, the walls drawn.

Each config in config/*.rviz is opened by the launch it belongs to
(SCENARIOS; a config without one fails), with the built-in simulator in the
arena, on an Xvfb screen of the check's own. Screenshots are taken until
one shows what rviz should (or the time is up): no display's name in
rviz's error red in the Displays panel, and at least WALLS_SHARE of the
world's wall pixels, drawn at the config's scale, dark in the render panel
at one offset, within PLACE_SLACK of where the view puts the world's
walls (the scan drawn over the walls hides the rest). The last
screenshot of each config is kept under ROS_LOG_DIR (rviz_pictures/) and
its path printed.

Where rviz, Xvfb or ImageMagick is missing (CI without them), nothing is
run, and the one test that passes says so in its name and on stdout.
"""
import glob
import math
import os
import sys
import tempfile
import time
import unittest

import numpy as np
import rospkg
import rospy
import rostest
import yaml

from wall_follower.evaluation.rviz_picture import (error_text_pixels, expected_corner,
                                                   render_panel, wall_template, walls_drawn)
from wall_follower.evaluation.rviz_screen import Launch, VirtualScreen, missing_tools
from wall_follower.sim.world_map import world_map
from wall_follower.sim.worldfile import load_world

WORLD = 'arena'
SIMULATION = ['sim:=true', 'simulator:=builtin', 'world:=' + WORLD, 'rviz:=true']
# config file -> (launch file, its arguments besides SIMULATION) that opens rviz with it
SCENARIOS = {
    'wall_follower.rviz': ('main.launch', []),
    'exercises.rviz': ('exercise_wander.launch', []),
    'slam.rviz': ('mapping.launch', ['map_file:={tmp}/map']),
}
WALLS_SHARE = 0.5      # of the world's wall pixels, found dark in the render panel
PLACE_SLACK = 4.0      # pixels between where the walls are drawn and where they belong
LIMIT = 40.0           # wall seconds for rviz to show the picture
POLL = 1.0             # wall seconds between screenshots


def config_view(path):
    """(pixels per metre, focal point (x, y)) of a config's top-down view."""
    with open(path) as stream:
        config = yaml.safe_load(stream)
    view = config['Visualization Manager']['Views']['Current']
    assert view['Class'] == 'rviz/TopDownOrtho', '%s: not a top-down view' % path
    return float(view['Scale']), (float(view['X']), float(view['Y']))


class RvizPictures(unittest.TestCase):

    def setUp(self):
        package = rospkg.RosPack().get_path('wall_follower')
        self.configs = sorted(glob.glob(os.path.join(package, 'config', '*.rviz')))
        self.walls = world_map(load_world(os.path.join(package, 'worlds', WORLD + '.world')))
        self.out = os.path.join(os.environ.get('ROS_LOG_DIR', tempfile.gettempdir()),
                                'rviz_pictures')
        os.makedirs(self.out, exist_ok=True)

    def test_every_config_shows_the_walls_and_no_error(self):
        self.assertTrue(self.configs)
        with VirtualScreen() as screen, tempfile.TemporaryDirectory() as tmp:
            for path in self.configs:
                name = os.path.basename(path)
                self.assertIn(name, SCENARIOS, 'no launch to try %s with' % name)
                launch_file, args = SCENARIOS[name]
                args = [arg.format(tmp=tmp) for arg in args] + SIMULATION
                self.check_config(screen, path, launch_file, args, tmp)

    def check_config(self, screen, path, launch_file, args, tmp):
        name = os.path.basename(path)
        scale, focal = config_view(path)
        template = wall_template(self.walls.values, self.walls.resolution, scale)
        shot = os.path.join(self.out, name.replace('.rviz', '.png'))
        log_path = os.path.join(tmp, name + '.log')
        with open(log_path, 'w') as log:
            launch = Launch(screen, launch_file, args, log)
            started = time.monotonic()
            try:
                deadline = started + LIMIT
                while True:
                    rgb = screen.screenshot(shot)
                    errors = error_text_pixels(rgb)
                    share, corner = walls_drawn(rgb, template)
                    panel = render_panel(rgb)
                    off = (float('inf') if panel is None else math.hypot(*np.subtract(
                        corner, expected_corner(panel, self.walls.origin, template.shape,
                                                scale, focal))))
                    good = errors == 0 and share >= WALLS_SHARE and off <= PLACE_SLACK
                    if good or time.monotonic() > deadline or not launch.running():
                        break
                    time.sleep(POLL)
            finally:
                launch.stop()
        print('%s: %s after %.0f s (walls %.0f %% drawn, %.1f px from their place, %d error '
              'pixels)' % (name, shot, time.monotonic() - started, 100 * share, off, errors))
        with open(log_path) as log:
            output = log.read()[-3000:]
        self.assertEqual(errors, 0, '%s: a display in error, see %s\n%s' % (name, shot, output))
        self.assertGreaterEqual(share, WALLS_SHARE, '%s: the walls are not drawn, see %s\n%s'
                                % (name, shot, output))
        self.assertLessEqual(off, PLACE_SLACK, '%s: the walls are drawn %.0f px from where '
                             'the world has them, see %s' % (name, off, shot))


class NotRunRvizPictures(unittest.TestCase):

    def test_rviz_pictures_not_run__rviz_xvfb_or_imagemagick_missing(self):
        print('rviz pictures: NOT RUN: not installed: %s (apt-get install rviz xvfb '
              'imagemagick)' % ' '.join(missing_tools()))


if __name__ == '__main__':
    rospy.init_node('check_rviz')
    rostest.rosrun('wall_follower', 'check_rviz',
                   NotRunRvizPictures if missing_tools() else RvizPictures, sys.argv)
