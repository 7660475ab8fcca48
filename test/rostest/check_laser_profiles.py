#!/usr/bin/env python3
"""rostest: each laser profile publishes its platform's scan convention.

Against laser_profiles.test: the arena, the robot at (-1.5, 0.3) facing -x,
so the laser (32 mm behind the axle, at x = -1.468) is 0.282 m from the nook's
back wall ahead and 3.218 m from the right wall behind, and the beams
towards the arena's far corner (3.69 m) return nothing, but for the LDS-02's,
which reach 8 m.
"""
import math
import sys
import time
import unittest

import numpy as np
import rospy
import rostest
from sensor_msgs.msg import LaserScan

FRONT = 0.282
BEHIND = 3.218
# Stage's cell-stepping raytrace reads up to a cell long; the TurtleBot3
# profiles add 1 cm sigma of noise on top.
STAGE_SLACK = 0.025
NOISY_SLACK = 0.07
WAIT_LIMIT = 20.0
# Scans of the LDS-02 heard in a row, to see its beam count change.
LDS02_SCANS = 10


def scan_of(profile):
    return rospy.wait_for_message(profile + '/base_scan', LaserScan, timeout=WAIT_LIMIT)


def scans_of(profile, count):
    """`count` successive scans of a profile (waiting in wall time: each
    simulator has its own clock, and this node none)."""
    heard = []
    subscriber = rospy.Subscriber(profile + '/base_scan', LaserScan, heard.append)
    deadline = time.monotonic() + WAIT_LIMIT
    while len(heard) < count and time.monotonic() < deadline and not rospy.is_shutdown():
        time.sleep(0.1)
    subscriber.unregister()
    return heard[:count]


def beams_towards(scan, angle, half_width=2):
    """Ranges of the beams within half_width beams of `angle` in the laser frame."""
    index = int(round((angle - scan.angle_min) / scan.angle_increment)) % len(scan.ranges)
    return [scan.ranges[(index + offset) % len(scan.ranges)]
            for offset in range(-half_width, half_width + 1)]


class LaserProfiles(unittest.TestCase):

    def assert_front_and_behind_skipping_dropouts(self, scan):
        """The walls ahead and behind, leaving out the readings of 0.0 that the real
        robot's lasers give for a no-return or a dropout."""
        for angle, expected in ((0.0, FRONT), (math.pi, BEHIND)):
            valid = [r for r in beams_towards(scan, angle) if r > 0.0]
            self.assertAlmostEqual(np.median(valid), expected, delta=NOISY_SLACK)

    def test_stage_as_stageros(self):
        scan = scan_of('stage')
        ranges = np.array(scan.ranges)
        self.assertEqual(len(ranges), 360)
        self.assertEqual(scan.angle_min, np.float32(-math.pi))
        self.assertEqual(scan.angle_max, np.float32(math.pi))
        self.assertEqual(scan.angle_increment, np.float32(2 * math.pi / 359))
        self.assertTrue(np.all(np.isfinite(ranges)), 'Stage never publishes inf or NaN')
        self.assertGreater(np.sum(ranges == np.float32(scan.range_max)), 0,
                           'no return should read range_max')
        self.assertEqual(len(scan.intensities), 360)
        self.assertTrue(np.all(np.array(scan.intensities)[ranges == np.float32(scan.range_max)]
                               == 0.0))
        # index 0 points backwards (-pi), the middle forwards
        self.assertAlmostEqual(ranges[0], BEHIND, delta=STAGE_SLACK)
        self.assertAlmostEqual(np.median(beams_towards(scan, 0.0)), FRONT, delta=STAGE_SLACK)

    def test_lds01_as_the_turtlebot3_driver(self):
        scan = scan_of('lds01')
        ranges = np.array(scan.ranges)
        self.assertEqual(len(ranges), 360)
        self.assertEqual(scan.angle_min, 0.0)
        self.assertAlmostEqual(scan.angle_increment, 2 * math.pi / 360, delta=1e-7)
        self.assertTrue(np.all(np.isfinite(ranges)), 'the LDS-01 reports no return as 0.0')
        self.assertGreater(np.sum(ranges == 0.0), 0, 'no return should read 0.0')
        valid = ranges[ranges > 0.0]
        self.assertGreaterEqual(valid.min(), scan.range_min)
        self.assertLessEqual(valid.max(), scan.range_max)
        # index 0 points forwards; dropouts read 0.0, so judge the valid neighbours
        self.assert_front_and_behind_skipping_dropouts(scan)

    def test_gazebo_as_the_turtlebot3_model(self):
        scan = scan_of('gazebo')
        ranges = np.array(scan.ranges)
        self.assertEqual(len(ranges), 360)
        self.assertEqual(scan.angle_min, 0.0)
        self.assertGreater(np.sum(np.isinf(ranges)), 0, 'no return should read inf')
        self.assertFalse(np.any(ranges == 0.0))
        self.assertFalse(np.any(np.isnan(ranges)))
        self.assertAlmostEqual(np.median(beams_towards(scan, 0.0)), FRONT, delta=NOISY_SLACK)
        self.assertAlmostEqual(np.median(beams_towards(scan, math.pi)), BEHIND,
                               delta=NOISY_SLACK)

    def test_lds02_as_the_ld08_driver(self):
        scans = scans_of('lds02', LDS02_SCANS)
        self.assertEqual(len(scans), LDS02_SCANS)
        counts = [len(scan.ranges) for scan in scans]
        self.assertTrue(all(230 <= count <= 260 for count in counts), counts)
        self.assertGreater(len(set(counts)), 1, 'the beam count should change: %s' % counts)
        for scan in scans:
            ranges = np.array(scan.ranges)
            self.assertEqual(scan.angle_min, 0.0)
            self.assertAlmostEqual(scan.angle_increment,
                                   (scan.angle_max - scan.angle_min) / len(ranges), delta=1e-6)
            self.assertEqual((scan.range_min, scan.range_max), (0.0, 100.0))
            self.assertTrue(np.all(np.isfinite(ranges)), 'the LDS-02 reports no return as 0.0')
            self.assertEqual(len(scan.intensities), len(ranges))
        self.assert_front_and_behind_skipping_dropouts(scans[-1])

    def test_course720_as_the_course_simulation(self):
        scan = scan_of('course720')
        ranges = np.array(scan.ranges)
        self.assertEqual(len(ranges), 720)
        self.assertEqual(scan.angle_min, np.float32(-math.pi))
        self.assertEqual(scan.angle_increment, np.float32(2 * math.pi / 720))
        self.assertGreater(np.sum(np.isinf(ranges)), 0, 'no return should read inf')
        self.assertFalse(np.any(ranges == 0.0))
        # index 0 points backwards, index 360 forwards
        self.assertAlmostEqual(np.median(beams_towards(scan, -math.pi)), BEHIND,
                               delta=NOISY_SLACK)
        self.assertAlmostEqual(np.median(ranges[358:363]), FRONT, delta=NOISY_SLACK)


if __name__ == '__main__':
    rospy.init_node('check_laser_profiles')
    rostest.rosrun('wall_follower', 'check_laser_profiles', LaserProfiles, sys.argv)
