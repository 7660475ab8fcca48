#!/usr/bin/env python3
"""rostest: map_saver refuses a map that cannot be one, writes nothing, and ends.

Each bad map is published latched on a topic of its own; map_saver is
started as a user starts it (rosrun, -f into a fresh folder) with `map`
remapped there. It must exit with status 1 (it once printed a ValueError
traceback in its callback and then waited for ever), log why in one line,
print no traceback and leave the folder empty. A good map, published the
same way, is saved (so a failure here is the map's, not the set-up's), also
under a ~file that names the home folder as `~`.
"""
import math
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

import rospy
import rostest
from nav_msgs.msg import OccupancyGrid

WALL_LIMIT = 30.0   # wall s for the saver to start, hear the map and end


def grid(width=3, height=2, cells=None, resolution=0.05, x=0.0):
    msg = OccupancyGrid()
    msg.info.width, msg.info.height, msg.info.resolution = width, height, resolution
    msg.info.origin.position.x = x
    msg.info.origin.orientation.w = 1.0
    msg.data = [0] * (width * height if cells is None else cells)
    return msg


# (name, map, what the error must say; None: a good map, saved). The rest of what
# mapfile.map_problem refuses is unit-tested (test_map_files.py).
CASES = [
    ('short', grid(cells=5), '5 values do not fill 3 x 2 cells'),
    ('empty', grid(width=0, height=0), 'the map has no cells (0 x 0)'),
    ('nan_origin', grid(x=math.nan), 'origin [nan, 0.0, 0.0] is not three finite numbers'),
    ('zero_resolution', grid(resolution=0.0), 'resolution 0.0 is not a positive length'),
    ('good', grid(), None),
]


class MapSaverBadMap(unittest.TestCase):

    def setUp(self):
        self.folder = tempfile.mkdtemp(prefix='map_saver_bad_map_')

    def tearDown(self):
        shutil.rmtree(self.folder)

    def check_case(self, index):
        name, msg, says = CASES[index]
        topic = '/bad_map_%s' % name
        publisher = rospy.Publisher(topic, OccupancyGrid, queue_size=1, latch=True)
        publisher.publish(msg)
        done = subprocess.run(['rosrun', 'wall_follower', 'map_saver', '-f',
                               os.path.join(self.folder, name), 'map:=' + topic,
                               '__name:=saver_%s' % name],
                              stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                              universal_newlines=True, timeout=WALL_LIMIT)
        publisher.unregister()
        self.assertNotIn('Traceback', done.stdout)
        if says is None:
            self.assertEqual(done.returncode, 0, done.stdout)
            self.assertEqual(sorted(os.listdir(self.folder)), [name + '.pgm', name + '.yaml'])
            return
        self.assertEqual(done.returncode, 1, done.stdout)
        self.assertIn('map_saver: not saving the map on %s: ' % topic, done.stdout)
        self.assertIn(says, done.stdout)
        self.assertEqual(os.listdir(self.folder), [])

    def test_a_name_under_the_home_folder_is_expanded(self):
        # As a launch file's ~file:=~/map, which no shell expands.
        topic = '/good_map_home'
        publisher = rospy.Publisher(topic, OccupancyGrid, queue_size=1, latch=True)
        publisher.publish(grid())
        done = subprocess.run(['rosrun', 'wall_follower', 'map_saver', '_file:=~/home',
                               'map:=' + topic, '__name:=saver_home'],
                              env=dict(os.environ, HOME=self.folder),
                              stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                              universal_newlines=True, timeout=WALL_LIMIT)
        publisher.unregister()
        self.assertEqual(done.returncode, 0, done.stdout)
        saved = os.listdir(self.folder)     # beside ROS's own ~/.ros
        self.assertIn('home.pgm', saved)
        self.assertIn('home.yaml', saved)


for _index in range(len(CASES)):
    setattr(MapSaverBadMap, 'test_%s' % CASES[_index][0],
            lambda self, i=_index: self.check_case(i))

if __name__ == '__main__':
    rospy.init_node('check_map_saver_bad_map')
    rostest.rosrun('wall_follower', 'check_map_saver_bad_map', MapSaverBadMap, sys.argv)
