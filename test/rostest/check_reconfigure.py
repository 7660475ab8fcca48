#!/usr/bin/env python3
"""rostest: target_distance set through dynamic_reconfigure mid-run moves the robot there.

The follower starts along the room's first wall at its default distance;
a few simulated seconds in, this node sets ~target_distance on
/wall_following with dynamic_reconfigure's client (what `dynparam set`
does). The distance to the wall on the right is measured from ground truth
and the world's exact geometry, at the poses where the robot runs parallel
to a wall (the straights, not the corners).
"""
import statistics
import sys
import threading
import unittest

import rospy
import rostest
from dynamic_reconfigure.client import Client
from nav_msgs.msg import Odometry
from std_srvs.srv import Empty

from waiting import wait_until
from wall_follower.evaluation.scoring.course import CourseMap
from wall_follower.nodes.shared.messages import pose_of
from wall_follower.params import defaults
from wall_follower.params.course.wall_following import TABLE
from wall_follower.sim.stage_interface import world_path

NEW_DISTANCE = 0.22
CHANGE_AT = 6.0         # simulated s: on the first straight, settled at the default
SETTLED_AFTER = 15.0    # simulated s after the change: the first corner has been turned
MEASURE_UNTIL = 60.0    # simulated s after the change: about a lap
PARALLEL = 0.05         # rad: a pose this near parallel to the wall counts as on a straight
TOLERANCE = 0.01        # m, on the median distance along the straights
WALL_LIMIT = 60.0       # wall s, for any one wait


class Reconfigure(unittest.TestCase):

    def setUp(self):
        self.course = CourseMap(world_path(rospy.get_param('~world')))
        self.lock = threading.Lock()
        self.poses = []   # (stamp, pose) of ground truth
        self.sub = rospy.Subscriber('base_pose_ground_truth', Odometry, self._on_truth,
                                    queue_size=1000)
        # The simulator starts paused, so that no ground truth goes by unheard.
        self.assertTrue(wait_until(lambda: self.sub.get_num_connections() > 0, WALL_LIMIT),
                        'no ground truth publisher')
        rospy.wait_for_service('unpause_physics', timeout=WALL_LIMIT)
        rospy.ServiceProxy('unpause_physics', Empty)()

    def _on_truth(self, msg):
        with self.lock:
            self.poses.append((msg.header.stamp.to_sec(), pose_of(msg)))

    def _latest(self):
        with self.lock:
            return self.poses[-1][0] if self.poses else -1.0

    def _straight_distances(self, start, end):
        with self.lock:
            poses = [pose for stamp, pose in self.poses if start <= stamp < end]
        distances = []
        for pose in poses:
            wall = self.course.right_wall_alignment(pose)
            if wall is not None and abs(wall[1]) < PARALLEL:
                distances.append(self.course.right_wall_distance(pose))
        return distances

    def test_target_distance_set_live_is_where_the_robot_settles(self):
        default = defaults(TABLE)['target_distance']
        self.assertTrue(wait_until(lambda: self._latest() >= CHANGE_AT, WALL_LIMIT),
                        'no ground truth up to %.0f s' % CHANGE_AT)
        before = self._straight_distances(CHANGE_AT / 2, CHANGE_AT)
        self.assertTrue(before, 'not parallel to the first wall before the change')
        self.assertAlmostEqual(statistics.median(before), default, delta=TOLERANCE)

        client = Client('wall_following', timeout=WALL_LIMIT)
        applied = client.update_configuration({'target_distance': NEW_DISTANCE})
        self.assertEqual(applied['target_distance'], NEW_DISTANCE)
        self.assertEqual(rospy.get_param('wall_following/target_distance'), NEW_DISTANCE)
        changed = self._latest()

        self.assertTrue(wait_until(lambda: self._latest() >= changed + MEASURE_UNTIL,
                                   WALL_LIMIT), 'ground truth stopped')
        after = self._straight_distances(changed + SETTLED_AFTER, changed + MEASURE_UNTIL)
        self.assertGreater(len(after), 100, 'too little of the lap parallel to a wall')
        rospy.loginfo('reconfigure: median distance on the straights %.3f m before, %.3f m '
                      'after (%d poses)', statistics.median(before), statistics.median(after),
                      len(after))
        self.assertAlmostEqual(statistics.median(after), NEW_DISTANCE, delta=TOLERANCE)


if __name__ == '__main__':
    rospy.init_node('check_reconfigure')
    rostest.rosrun('wall_follower', 'check_reconfigure', Reconfigure, sys.argv)
