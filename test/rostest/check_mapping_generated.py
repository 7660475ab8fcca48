#!/usr/bin/env python3
"""rostest: mapping.test in generated rooms, not only the shipped ones.

A mapper tuned on the package's own rooms may fit them and not the cause
(issue 41): these are rooms of the grader's world generator, the same as
`benchmark mapping --generated` maps, with odometry drifting as that draws
it (mapping_generated.write_odom_world). Each is written to a folder of its
own and mapped by `rostest wall_follower mapping.test world:=...` (lockstep,
flat out: a lap of one takes a minute or two of wall time), held to the same
bars as the shipped rooms: precision and recall >= 99 %, no occupied cell
more than 0.10 m from a true wall, the mapper's final pose within 3 cm and
1 degree. The rooms (seed 41, which neither the tuning nor the benchmark's
reported seeds use) were picked for what they hold: a tilted wing and two
pillars; two chamfers, a tilted wing and an island.
"""
import os
import sys
import unittest

import rospkg
import rospy
import rostest
from nested_rostest import rostest_status
from scratch import ScratchFolders

from wall_follower.evaluation.benchmarks.mapping_generated import write_odom_world

SEED = 41
ROOMS = (5, 8)
# Wall seconds one room's mapping.test may take (its own time-limit is 300 s).
BOUND = 280.0


class GeneratedRooms(ScratchFolders, unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        cls.folder = cls.scratch('mapping_generated-')
        cls.include = os.path.join(rospkg.RosPack().get_path('wall_follower'), 'worlds',
                                   'burger.inc')

    def map_room(self, index):
        path, error = write_odom_world(SEED, index, self.folder, self.include)
        name = os.path.basename(path)[:-len('_odom.world')]
        status, output = rostest_status(
            ['mapping.test', 'world:=' + path[:-len('_odom.world')], 'test_name:=' + name,
             'map_file:=' + os.path.join(self.folder, name)], BOUND)
        self.assertEqual(status, 0, '%s (odom_error %s):\n%s' % (
            name, ' '.join('%.4f' % e for e in error), output[-4000:]))

    def test_room_with_a_tilted_wing_and_two_pillars(self):
        self.map_room(ROOMS[0])

    def test_room_with_chamfers_a_tilted_wing_and_an_island(self):
        self.map_room(ROOMS[1])


if __name__ == '__main__':
    rospy.init_node('check_mapping_generated')
    rostest.rosrun('wall_follower', 'check_mapping_generated', GeneratedRooms, sys.argv)
