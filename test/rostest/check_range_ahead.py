#!/usr/bin/env python3
"""rostest: range_ahead prints the true distance straight ahead, or that there is none.

The robot is put at each of ~poses ("x y yaw_deg") in turn through the
simulator's cmd_pose; the first line range_ahead logs from a scan taken
there must give the distance ahead to within ~tolerance of the distance
cast from the laser's true pose through the world's exact geometry, or,
where that is beyond the laser's range, say that there is no valid reading.
"""
import math
import re
import sys
import threading
import unittest

import rospy
import rostest
from geometry_msgs.msg import Pose
from nav_msgs.msg import Odometry
from rosgraph_msgs.msg import Log

from waiting import wait_until
from wall_follower.evaluation.scoring.course import CourseMap
from wall_follower.evaluation.scoring.geometry import cast_rays
from wall_follower.nodes.shared.messages import pose_message, pose_of
from wall_follower.sim.stage_interface import world_path

QUEUE = 10000
WAIT = 60.0           # wall s for each pose
SETTLED = 0.25        # simulated s after the teleport before a line counts
NO_READING = 'no valid reading'
DISTANCE = re.compile(r'range ahead: ([0-9.]+) m$')


class RangeAhead(unittest.TestCase):

    def setUp(self):
        self.lock = threading.Lock()
        self.truth = None
        self.lines = []
        rospy.Subscriber('base_pose_ground_truth', Odometry, self._on_truth, queue_size=QUEUE)
        rospy.Subscriber('/rosout', Log, self._on_log, queue_size=QUEUE)
        self.teleport = rospy.Publisher('cmd_pose', Pose, queue_size=1, latch=True)

    def _on_truth(self, msg):
        with self.lock:
            self.truth = (msg.header.stamp.to_sec(),) + pose_of(msg)

    def _on_log(self, msg):
        if msg.name.lstrip('/') == 'range_ahead':
            with self.lock:
                self.lines.append((msg.header.stamp.to_sec(), msg.msg))

    def at(self, x, y, yaw):
        """The truth stamp at which the robot first stands at (x, y, yaw), after teleporting it."""
        self.teleport.publish(pose_message(x, y, yaw))

        def there():
            truth = self.truth
            return truth is not None and math.hypot(truth[1] - x, truth[2] - y) < 1e-3 and \
                abs(math.remainder(truth[3] - yaw, 2.0 * math.pi)) < 1e-3 and truth
        truth = wait_until(there, WAIT)
        self.assertTrue(truth, 'the robot never arrived at (%.2f, %.2f)' % (x, y))
        return truth

    def line_after(self, stamp):
        def line():
            with self.lock:
                return next((text for when, text in self.lines if when >= stamp), None)
        text = wait_until(line, WAIT)
        self.assertTrue(text, 'range_ahead printed nothing after %.1f s' % stamp)
        return text

    def test_the_true_distance_ahead_at_every_pose(self):
        course = CourseMap(world_path(rospy.get_param('~world')))
        tolerance = rospy.get_param('~tolerance', 0.02)
        self.assertTrue(wait_until(lambda: self.teleport.get_num_connections() > 0, WAIT))
        for text in rospy.get_param('~poses'):
            x, y, yaw_deg = (float(v) for v in text.split())
            stamp, tx, ty, tyaw = self.at(x, y, math.radians(yaw_deg))
            lx, ly, lyaw = course.laser_pose((tx, ty, tyaw))
            true = cast_rays(course.edges, lx, ly, [lyaw])[0]
            printed = self.line_after(stamp + SETTLED)
            rospy.loginfo('range_ahead at (%s): true %.3f m; printed "%s"', text, true, printed)
            if true >= course.range_max:
                self.assertIn(NO_READING, printed)
                continue
            match = DISTANCE.search(printed)
            self.assertTrue(match, 'no distance in "%s" (true %.3f m)' % (printed, true))
            self.assertLessEqual(abs(float(match.group(1)) - true), tolerance,
                                 'printed %s m, true %.3f m at (%s)' % (match.group(1), true, text))


if __name__ == '__main__':
    rospy.init_node('check_range_ahead')
    rostest.rosrun('wall_follower', 'check_range_ahead', RangeAhead, sys.argv)
