#!/usr/bin/env python3
"""rostest: one lap of mapping.launch with drifting odometry, judged from ground truth.

The saved map must match the world (precision and recall at least
~min_precision and ~min_recall, 99 % unless mapping.test is told
otherwise, and no occupied cell farther than ~max_wall_distance from a
true wall, 0.10 m; see wall_follower/evaluation/scoring/map_quality.py),
and once the robot has stopped after the lap, the mapper's pose (tf map ->
base_footprint) must be within 3 cm and 1 degree of the true pose, while
the raw odometry was off by more somewhere on the lap (a scale error
alone closes the lap again, as in the octagon).
The simulator starts paused and is let go once this check listens and the
mapper is connected to every topic of the simulator it reads (scan, tf,
clock): a mapper that misses the first steps starts its map on a scan taken
while turning, and Stage's odometry then runs a step ahead of the laser, which
tilts the whole map by that step's turn. Runs with either mapper of
slam.launch (~slam_methods). With ~json, the figures (precision, recall,
the worst cell's distance from a wall, the mapper's final pose error) are
written there as JSON, for benchmark mapping.
"""
import json
import math
import os
import sys
import threading
import time
import unittest
import xmlrpc.client

import rosgraph
import rospy
import rostest
import tf2_ros
from drive_guard import DriveGuard
from nav_msgs.msg import Odometry
from std_srvs.srv import Empty

from wall_follower.evaluation.scoring.course import CourseMap
from wall_follower.evaluation.scoring.map_quality import map_quality
from wall_follower.mapping.mapfile import load_map
from wall_follower.mapping.poses import between
from wall_follower.nodes.shared.messages import pose_of, yaw_of
from wall_follower.params import defaults
from wall_follower.params.mapping.slam import TABLE
from wall_follower.rotation import wrap_angle
from wall_follower.sim.stage_interface import world_path

# Wall seconds for the lap, the saved map and the robot to settle.
RUN_LIMIT = 280.0
# Simulated seconds the true pose must stay put to call the robot stopped.
STILL_FOR = 1.0


class Mapping(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        cls.world = world_path(rospy.get_param('~world'))
        cls.map_file = rospy.get_param('~map_file')
        cls.min_precision = rospy.get_param('~min_precision')
        cls.min_recall = rospy.get_param('~min_recall')
        cls.max_wall_distance = rospy.get_param('~max_wall_distance')
        course = CourseMap(cls.world)
        cls.start = course.robot.pose
        # The range up to which beams draw walls: ~max_range (builtin), ~maxUrange (gmapping).
        cls.max_range = rospy.get_param('/slam/max_range', rospy.get_param(
            '/slam/maxUrange', defaults(TABLE)['max_range']))
        cls.guard = DriveGuard()
        cls.truth = []   # (stamp, pose)
        cls.odom = None
        cls.odom_stamped = {}   # stamp -> odometry pose
        cls.lock = threading.Lock()
        rospy.Subscriber('base_pose_ground_truth', Odometry, cls.on_truth, queue_size=100)
        rospy.Subscriber('odom', Odometry, cls.on_odom, queue_size=10)
        # The mapper may fall behind a simulation running flat out: keep enough tf.
        cls.buffer = tf2_ros.Buffer(cache_time=rospy.Duration(600.0))
        cls.listener = tf2_ros.TransformListener(cls.buffer)
        deadline = time.monotonic() + RUN_LIMIT
        # Let the world go only once the mapper hears the laser, or it misses the start.
        assert cls.wait_for(cls.mapper_listens, deadline), \
            'slam never connected to the simulator'
        rospy.wait_for_service('unpause_physics', timeout=30.0)
        rospy.ServiceProxy('unpause_physics', Empty)()
        cls.saved = cls.wait_for(lambda: os.path.exists(cls.map_file + '.yaml'), deadline)
        cls.still = cls.wait_for(cls.stopped, deadline)
        with cls.lock:
            cls.final_stamp, cls.final_truth = cls.truth[-1] if cls.truth else (0.0, None)
            cls.final_odom = cls.odom
            cls.lap = [(pose, cls.odom_stamped[stamp]) for stamp, pose in cls.truth
                       if stamp in cls.odom_stamped]
        cls.mapper_pose = None
        cls.wait_for(lambda: cls.mapper_pose_at(cls.final_stamp), deadline)
        cls.quality = None
        if cls.saved:
            with cls.lock:
                path = [pose for _, pose in cls.truth]
            cls.quality = map_quality(load_map(cls.map_file + '.yaml'), cls.world, cls.start,
                                      path, cls.max_range)
            rospy.loginfo('map: %s', cls.quality)
        if rospy.get_param('~json', ''):
            cls.write_figures(rospy.get_param('~json'))

    @classmethod
    def tearDownClass(cls):
        # The map is the test's own (mapping.test's map_file): scored, it is removed.
        for path in (cls.map_file + '.yaml', cls.map_file + '.pgm'):
            if os.path.exists(path):
                os.remove(path)

    @classmethod
    def write_figures(cls, path):
        figures = {'lap_closed': cls.saved}
        if cls.quality is not None:
            figures.update(cls.quality._asdict())
        if cls.mapper_pose is not None and cls.final_truth is not None:
            figures['pose_error'] = cls.errors(cls.mapper_pose)
        with open(path, 'w') as out:
            json.dump(figures, out)

    @classmethod
    def mapper_listens(cls):
        """True once the mapper is connected to every topic the simulator publishes and
        it subscribes to: registered with the master is not yet connected."""
        master = rosgraph.Master(rospy.get_name())
        publishers, subscribers, _ = master.getSystemState()
        simulators = dict(publishers).get(rospy.resolve_name('scan'), [])
        if len(simulators) != 1:
            return False
        simulator = simulators[0]
        wanted = {topic for topic, nodes in subscribers if '/slam' in nodes} & \
            {topic for topic, nodes in publishers if simulator in nodes}
        if rospy.resolve_name('scan') not in wanted:
            return False
        try:
            _, _, connections = xmlrpc.client.ServerProxy(
                master.lookupNode(simulator)).getBusInfo(rospy.get_name())
        except (IOError, rosgraph.MasterError, xmlrpc.client.Error):
            return False
        # (id, subscriber, direction, transport, topic, connected, ...)
        connected = {info[4] for info in connections
                     if info[1] == '/slam' and info[2] == 'o' and info[5]}
        return wanted <= connected

    @classmethod
    def mapper_pose_at(cls, stamp):
        """True once the mapper has placed the robot at stamp (it may lag behind)."""
        try:
            t = cls.buffer.lookup_transform('map', 'base_footprint', rospy.Time.from_sec(stamp))
        except (tf2_ros.LookupException, tf2_ros.ConnectivityException,
                tf2_ros.ExtrapolationException):
            return False
        t = t.transform
        cls.mapper_pose = (t.translation.x, t.translation.y, yaw_of(t.rotation))
        return True

    @classmethod
    def wait_for(cls, condition, deadline):
        while not condition():
            if rospy.is_shutdown() or time.monotonic() > deadline:
                return False
            time.sleep(0.05)
        return True

    @classmethod
    def on_truth(cls, msg):
        with cls.lock:
            cls.truth.append((msg.header.stamp.to_sec(), pose_of(msg)))

    @classmethod
    def on_odom(cls, msg):
        with cls.lock:
            cls.odom = pose_of(msg)
            cls.odom_stamped[msg.header.stamp.to_sec()] = cls.odom

    @classmethod
    def stopped(cls):
        with cls.lock:
            if not cls.truth:
                return False
            last_stamp, last = cls.truth[-1]
            recent = [pose for stamp, pose in cls.truth if stamp >= last_stamp - STILL_FOR]
            span = cls.truth[-1][0] - cls.truth[0][0]
        return span > STILL_FOR and all(pose == last for pose in recent)

    def test_drove_within_limits_without_contact(self):
        self.guard.assert_safe(self)

    @classmethod
    def errors(cls, pose, true_pose=None):
        truth = between(cls.start, true_pose or cls.final_truth)
        return (math.hypot(pose[0] - truth[0], pose[1] - truth[1]),
                abs(math.degrees(wrap_angle(pose[2] - truth[2]))))

    def test_saved_map_matches_the_world(self):
        self.assertTrue(self.saved, 'no map saved at %s.yaml' % self.map_file)
        quality = self.quality
        self.assertGreaterEqual(quality.precision, self.min_precision, quality)
        self.assertGreaterEqual(quality.recall, self.min_recall, quality)
        self.assertLessEqual(quality.worst_distance, self.max_wall_distance, quality)

    def test_mapper_pose_is_true_and_odometry_is_not(self):
        self.assertTrue(self.still, 'the robot never stopped after the lap')
        self.assertIsNotNone(self.mapper_pose, 'no tf map -> base_footprint')
        mapper = self.errors(self.mapper_pose)
        odom = self.errors(self.final_odom)
        self.assertTrue(self.lap, 'no odometry stamped as the ground truth')
        drift = max((self.errors(o, t) for t, o in self.lap),
                    key=lambda e: e[0] + math.radians(e[1]))
        rospy.loginfo('final pose error: mapper %.1f cm %.2f deg, odometry %.1f cm %.2f deg '
                      '(on the lap at worst %.1f cm %.2f deg)', 100 * mapper[0], mapper[1],
                      100 * odom[0], odom[1], 100 * drift[0], drift[1])
        self.assertLess(mapper[0], 0.03)
        self.assertLess(mapper[1], 1.0)
        self.assertTrue(drift[0] > 0.03 or drift[1] > 1.0, 'odometry did not drift: %s' % (drift,))
        self.assertGreater(drift[0] + math.radians(drift[1]),
                           mapper[0] + math.radians(mapper[1]))


if __name__ == '__main__':
    rospy.init_node('check_mapping')
    rostest.rosrun('wall_follower', 'check_mapping', Mapping, sys.argv)
