#!/usr/bin/env python3
"""rostest: the slam node's parameters set live through dynamic_reconfigure (as `dynparam set`).

map_update_interval: the gaps between the stamps of the maps published,
in simulated time, are the default before the change and the new value
after it. delta: read at start only, so a change is refused (the server
answers with the value in force), the node says why, and the maps keep
their cell.
"""
import sys
import threading
import unittest

import rospy
import rostest
from dynamic_reconfigure.client import Client
from nav_msgs.msg import OccupancyGrid
from rosout_log import RosoutLog

from waiting import wait_until
from wall_follower.params import defaults
from wall_follower.params.mapping.slam import TABLE

DEFAULT = defaults(TABLE)
NEW_INTERVAL = 0.5   # s, a multiple of the laser's 0.1 s period
GAPS = 3             # gaps between maps measured at each interval
WALL_LIMIT = 60.0    # wall s, for any one wait


class SlamReconfigure(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        cls.lock = threading.Lock()
        cls.maps = []   # (stamp [s], resolution [m]) of every map heard
        cls.log = RosoutLog('/slam')
        cls.sub = rospy.Subscriber('map', OccupancyGrid, cls._on_map, queue_size=100)
        cls.client = Client('slam', timeout=WALL_LIMIT)

    @classmethod
    def _on_map(cls, msg):
        with cls.lock:
            cls.maps.append((msg.header.stamp.to_sec(), msg.info.resolution))

    def _wait_for_maps(self, count):
        self.assertTrue(wait_until(lambda: len(self.maps) >= count, WALL_LIMIT),
                        'only %d maps published' % len(self.maps))
        with self.lock:
            return list(self.maps)

    @staticmethod
    def _gaps(maps):
        return [round(later[0] - earlier[0], 6) for earlier, later in zip(maps, maps[1:])]

    def test_a_new_map_update_interval_sets_how_often_the_map_comes(self):
        # The latched first map may be heard late: count the gaps after it.
        before = self._wait_for_maps(GAPS + 2)
        self.assertEqual(self._gaps(before)[-GAPS:], [DEFAULT['map_update_interval']] * GAPS)
        applied = self.client.update_configuration({'map_update_interval': NEW_INTERVAL})
        self.assertEqual(applied['map_update_interval'], NEW_INTERVAL)
        changed = len(self._wait_for_maps(0))
        after = self._wait_for_maps(changed + GAPS + 1)
        self.assertEqual(self._gaps(after)[-GAPS:], [NEW_INTERVAL] * GAPS)

    def test_a_change_to_the_grid_is_refused(self):
        applied = self.client.update_configuration({'delta': 2 * DEFAULT['delta']})
        self.assertEqual(applied['delta'], DEFAULT['delta'])
        self.assertEqual(rospy.get_param('slam/delta'), DEFAULT['delta'])
        self.assertTrue(wait_until(lambda: self.log.said('/slam', '~delta read at start only'),
                                   WALL_LIMIT), 'slam did not say why delta was kept')
        count = len(self._wait_for_maps(0))
        maps = self._wait_for_maps(count + 1)
        self.assertAlmostEqual(maps[-1][1], DEFAULT['delta'], places=6)


if __name__ == '__main__':
    rospy.init_node('check_slam_reconfigure')
    rostest.rosrun('wall_follower', 'check_slam_reconfigure', SlamReconfigure, sys.argv)
