#!/usr/bin/env python3
"""rostest: a headless `mapping.launch sim:=true` ends by itself once the map is saved.

One lap of the room with drifting odometry, in lockstep simulated time run
flat out, on a master of its own, as a script would start it (neither the
Stage window nor rviz): the launch must end within a bound, map_saver (its
required node) with status 0 and the map on disk, readable as map_server
reads it. This test's own master is not used.
"""
import os
import sys
import unittest

import numpy as np
import rospy
import rostest
from scratch import ScratchFolders

from wall_follower.evaluation.launching import free_port, launch_and_read, launch_command
from wall_follower.mapping.mapfile import load_map

# Wall seconds for the whole launch: start-up, a lap of the room (about a minute
# of simulated time, run flat out), the map saved and every node shut down.
BOUND = 120.0


class MappingEnds(ScratchFolders, unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        cls.directory = cls.scratch('mapping_ends-')
        cls.map_file = os.path.join(cls.directory, 'room')
        port = free_port()
        command = launch_command('mapping.launch', {
            'sim': 'true', 'simulator': 'builtin', 'world': 'room_odom', 'lockstep': 'true',
            'speedup': '0', 'map_file': cls.map_file}, port)
        cls.ended, cls.output = launch_and_read(command, port, BOUND)

    def test_launch_ends_within_bound(self):
        self.assertTrue(self.ended, 'the launch was still running after %.0f s:\n%s'
                        % (BOUND, self.output[-3000:]))

    def test_it_ends_because_map_saver_is_done(self):
        # roslaunch's words for a required node that exited with status 0
        self.assertRegex(self.output, r'REQUIRED process \[map_saver-\d+\] has died!\s*'
                         r'process has finished cleanly', self.output[-3000:])

    def test_the_map_is_saved(self):
        saved = load_map(self.map_file + '.yaml')
        self.assertGreater(int(np.count_nonzero(saved.data == 100)), 0)
        self.assertGreater(int(np.count_nonzero(saved.data == 0)), 0)


if __name__ == '__main__':
    rospy.init_node('check_mapping_ends')
    rostest.rosrun('wall_follower', 'check_mapping_ends', MappingEnds, sys.argv)
