#!/usr/bin/env python3
"""rostest: no node drives on a scan it cannot trust, says why, and goes on when scans are good.

wall_following (no find_wall, no record_odom) is fed a wall on its right
until it drives, then each kind of unusable scan: it must stop (for a scan
blind ahead: stop going forward, and turn in place toward its wall at
~blind_turn), log a warning naming what is wrong, send nothing else while
those scans last, and drive again once good scans come back. find_wall,
called while the laser sends only 0.0, must answer false without moving.
Runs in wall time; every wait is bounded and ends as soon as what it waits
for has happened.
"""
import sys
import threading
import time
import unittest

import rospy
import rostest
from geometry_msgs.msg import Twist
from rosout_log import RosoutLog
from sensor_msgs.msg import LaserScan
from synthetic_scans import unusable_scans, wall_on_the_right

from wall_follower.params.course.wall_following import BLIND_TURN
from wall_follower.srv import FindWall
from waiting import assert_soon

SCAN_PERIOD = 0.1
WAIT_LIMIT = 10.0
BAD_COMMANDS = 5   # commands to watch while the unusable scans last

# What the warning must name, for each kind of scan.
NAMED = {
    'all NaN': '360 NaN',
    'all 0.0': '360 0.0',
    'empty': 'it has 0 beams',
    'one beam': 'it has 1 beam',
    'zero increment': 'angle_increment is 0',
    'negative ranges': '360 negative',
    'range_max below range_min': 'range_max (0.12) is not above its range_min (3.5)',
    'ranges not matching the angles': 'ranges do not match its angles',
    'nothing valid ahead': 'no valid reading within 30 deg ahead',
    'one valid beam': 'only 1 of its 360 readings is usable (359 NaN)',
    'one valid beam ahead': 'beams within 30 deg ahead read valid (10% needed)',
}
# The kinds that leave the way ahead unseen, where the follower turns toward its wall.
BLIND_AHEAD = ('nothing valid ahead', 'one valid beam ahead')


class Feed(object):
    """Publishes one scan over and over at SCAN_PERIOD and records what comes back.

    scan: the first scan to publish (a wall on the right unless given); it is
    published from the start, so a test that wants a node never to see a
    good scan gives its bad one here rather than setting it afterwards.
    """

    def __init__(self, namespace='', scan=None):
        self.lock = threading.Lock()
        self.commands = []
        self.scan = scan if scan is not None else wall_on_the_right()
        self.publisher = rospy.Publisher(namespace + 'scan', LaserScan, queue_size=1)
        rospy.Subscriber(namespace + 'cmd_vel', Twist, self._on_cmd, queue_size=1000)
        threading.Thread(target=self._publish, daemon=True).start()

    def _on_cmd(self, msg):
        with self.lock:
            self.commands.append((msg.linear.x, msg.angular.z))

    def _publish(self):
        while not rospy.is_shutdown():
            scan = self.scan
            scan.header.stamp = rospy.Time.now()
            self.publisher.publish(scan)
            time.sleep(SCAN_PERIOD)

    def since(self, index):
        with self.lock:
            return list(self.commands[index:])

    def count(self):
        with self.lock:
            return len(self.commands)


class BadScans(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        cls.log = RosoutLog('/wall_following', '/finder/wall_finder')

    def test_the_follower_stops_on_each_unusable_scan_and_resumes_after(self):
        feed = Feed()
        for kind, scan in sorted(unusable_scans().items()):
            with self.subTest(kind=kind):
                feed.scan = wall_on_the_right()
                start = feed.count()
                assert_soon(self, WAIT_LIMIT, lambda: any(v > 0.1 for v, _ in feed.since(start)),
                            'driving on good scans before "%s"' % kind)
                start = feed.count()
                feed.scan = scan
                assert_soon(self, WAIT_LIMIT, lambda: any(v == 0.0 for v, _ in feed.since(start)),
                            'a stop on "%s"' % kind)
                first_stop = start + next(i for i, (v, _) in enumerate(feed.since(start))
                                          if v == 0.0)
                assert_soon(self, WAIT_LIMIT, lambda: feed.count() >= first_stop + BAD_COMMANDS,
                            'more commands on "%s"' % kind)
                self.assertEqual([v for v, _ in feed.since(first_stop)[:BAD_COMMANDS]],
                                 [0.0] * BAD_COMMANDS, 'drove forward on "%s"' % kind)
                if kind in BLIND_AHEAD:
                    self.assertEqual([w for _, w in feed.since(first_stop)[:BAD_COMMANDS]],
                                     [-BLIND_TURN] * BAD_COMMANDS,
                                     'did not turn toward the wall on "%s"' % kind)
                assert_soon(self, WAIT_LIMIT, lambda: self.log.said('/wall_following', NAMED[kind]),
                            'a warning naming "%s"' % NAMED[kind])
        feed.scan = wall_on_the_right()
        start = feed.count()
        assert_soon(self, WAIT_LIMIT, lambda: any(v > 0.1 for v, _ in feed.since(start)),
                    'driving again on good scans')

    def test_find_wall_answers_false_on_a_dead_laser_without_moving(self):
        feed = Feed('finder/', unusable_scans()['all 0.0'])
        # Connected first: a call that heard no scan at all would fail for that reason.
        assert_soon(self, WAIT_LIMIT, lambda: feed.publisher.get_num_connections() > 0,
                    'find_wall to subscribe')
        rospy.wait_for_service('finder/find_wall', timeout=WAIT_LIMIT)
        started = time.monotonic()
        found = rospy.ServiceProxy('finder/find_wall', FindWall)().wallfound
        self.assertFalse(found)
        self.assertLess(time.monotonic() - started, WAIT_LIMIT)
        self.assertTrue(all(v == 0.0 and w == 0.0 for v, w in feed.since(0)))
        assert_soon(self, WAIT_LIMIT, lambda: self.log.said('/finder/wall_finder', '360 0.0'),
                    'find_wall to say why')


if __name__ == '__main__':
    rospy.init_node('check_bad_scans')
    rostest.rosrun('wall_follower', 'check_bad_scans', BadScans, sys.argv)
