#!/usr/bin/env python3
"""rostest: the builtin simulator offers stageros' interface and behaviour.

Runs against simulator.test: room world (wall faces x = +-1.5, y = +-1.2),
the robot started at (0.8, 0, 0) facing the x = 1.5 wall, lockstep on, and a
second simulator in /pair with two robots.
"""
import math
import sys
import time
import unittest

import numpy as np
import rospy
import rostest
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import LaserScan
from std_srvs.srv import Empty

from sim_probe import SimProbe, pose_of, yaw_of
from wire_reader import WireReader

DT = 0.1
START = (0.8, 0.0, 0.0)
WALL_X = 1.5
BODY_FRONT = -0.032 + 0.138 / 2   # front face of the footprint, ahead of base_link
LASER_MOUNT = (-0.032, 0.0, 0.192)
EXACT = 1e-6
# Wall seconds: for a step already under way when pause_physics returns to
# publish, then a window in which a paused world must publish nothing.
PAUSE_SETTLE = 0.2
PAUSE_WATCH = 0.5                      # float32 twists and 7-digit reasoning need no more
# Steps a controller answers on the wire. rospy's per-connection send threads sent a
# clock before its scan only now and then, under load (once in 1500 steps beside three
# busy loops): this check is exact, but catches that old fault only on a busy machine.
WIRE_STEPS = 500


def moves(truths):
    """Per-step displacements and turns between consecutive ground truths."""
    poses = [pose_of(msg) for msg in truths]
    return [(math.hypot(b[0] - a[0], b[1] - a[1]), abs(b[2] - a[2]))
            for a, b in zip(poses, poses[1:])]


class SimulatorInterface(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        cls.sim = SimProbe()
        cls.sim.wait_ready()

    def run_from_start(self, drive):
        """Resets, runs `drive`, waits a few ticks; returns the ground truths since the reset."""
        self.sim.reset()
        since = self.sim.latest_truth().header.stamp.to_sec()
        drive()
        self.sim.wait_ticks(4)
        return self.sim.truths_since(since)

    def test_every_topic_once_per_step_with_stageros_headers(self):
        first = self.sim.wait_ticks(21)
        self.sim.wait_ticks(3)   # stragglers of the last step on other connections
        ticks = self.sim.clock[first:first + 21]
        for earlier, later in zip(ticks, ticks[1:]):
            self.assertAlmostEqual(later - earlier, DT, delta=1e-9)
        wanted = set(round(t, 6) for t in ticks)
        for name, store in (('scan', self.sim.scans), ('odom', self.sim.odoms),
                            ('ground truth', self.sim.truths)):
            stamps = [round(msg.header.stamp.to_sec(), 6) for msg in store]
            self.assertTrue(wanted <= set(stamps), '%s missing steps' % name)
            self.assertEqual(len(stamps), len(set(stamps)), '%s repeated a step' % name)
        chain = {('odom', 'base_footprint'), ('base_footprint', 'base_link'),
                 ('base_link', 'base_laser_link')}
        for tick in ticks:
            sent = set((t.header.frame_id, t.child_frame_id) for t in self.sim.transforms
                       if abs(t.header.stamp.to_sec() - tick) < 1e-6)
            self.assertEqual(sent, chain, 'tf at %.1f' % tick)
        laser = [t.transform for t in self.sim.transforms if t.child_frame_id == 'base_laser_link']
        translation = laser[-1].translation
        self.assertEqual((translation.x, translation.y, translation.z), LASER_MOUNT)
        self.assertEqual(yaw_of(laser[-1].rotation), 0.0)
        scan = self.sim.scans[-1]
        self.assertEqual(scan.header.frame_id, 'base_laser_link')
        self.assertEqual(len(scan.ranges), 360)
        self.assertEqual(scan.angle_min, np.float32(-math.pi))
        self.assertEqual(scan.angle_increment, np.float32(2 * math.pi / 359))
        self.assertEqual((scan.range_min, scan.range_max), (np.float32(0.12), 3.5))
        for odometry in (self.sim.odoms[-1], self.sim.truths[-1]):
            self.assertEqual((odometry.header.frame_id, odometry.child_frame_id), ('odom', ''))

    def test_a_command_stream_drives_v_times_t(self):
        truths = self.run_from_start(lambda: self.sim.drive(0.15, 0.0, 20))
        steps = [d for d, _ in moves(truths) if d > 1e-9]
        # one step per command; under heavy load the first may merge with the second
        self.assertIn(len(steps), (19, 20))
        start, end = pose_of(truths[0]), pose_of(truths[-1])
        self.assertAlmostEqual(end[0] - start[0], 0.15 * DT * len(steps), delta=EXACT)
        self.assertAlmostEqual(end[1], start[1], delta=EXACT)
        moving = [msg for msg in self.sim.odoms if msg.twist.twist.linear.x > 0.0]
        self.assertAlmostEqual(moving[-1].twist.twist.linear.x, 0.15, delta=EXACT)

    def test_a_spin_turns_w_times_t_in_place(self):
        truths = self.run_from_start(lambda: self.sim.drive(0.0, 0.49, 10))
        turns = [a for _, a in moves(truths) if a > 1e-9]
        self.assertIn(len(turns), (9, 10))
        start, end = pose_of(truths[0]), pose_of(truths[-1])
        self.assertAlmostEqual(end[2] - start[2], 0.49 * DT * len(turns), delta=EXACT)
        self.assertAlmostEqual(math.hypot(end[0] - start[0], end[1] - start[1]), 0.0,
                               delta=EXACT)

    def test_the_watchdog_stops_a_single_command_after_two_steps(self):
        truths = self.run_from_start(lambda: self.sim.send_once(0.19, 0.0))
        steps = [d for d, _ in moves(truths) if d > 1e-9]
        self.assertEqual(len(steps), 2)
        self.assertAlmostEqual(sum(steps), 0.038, delta=EXACT)

    def test_driving_into_a_wall_stalls_at_it_without_penetrating(self):
        # 50 steps of 0.019 m; the wall is 0.663 m ahead of the footprint
        truths = self.run_from_start(lambda: self.sim.drive(0.19, 0.0, 50))
        fronts = [pose_of(msg)[0] + BODY_FRONT for msg in truths]
        self.assertLessEqual(max(fronts), WALL_X)
        self.assertLess(WALL_X - fronts[-1], 0.019 + 1e-9, 'stopped short of the wall')
        self.assertTrue(self.sim.stalls[-1], 'stalled should stay true at the wall')
        pushing = [d for d, _ in moves(truths)[-10:]]
        self.assertEqual(max(pushing), 0.0, 'moved while pushing')
        self.sim.drive(-0.19, 0.0, 5)
        self.sim.wait_ticks(3)
        self.assertFalse(self.sim.stalls[-1], 'still stalled after backing off')
        self.assertLess(pose_of(self.sim.latest_truth())[0] + BODY_FRONT, WALL_X - 0.09)

    def test_reset_positions_restores_the_start_pose(self):
        self.sim.drive(0.19, 0.4, 10)
        self.assertNotAlmostEqual(pose_of(self.sim.latest_truth())[0], START[0], delta=0.1)
        self.sim.reset()
        self.sim.wait_ticks(1)
        for msg in (self.sim.latest_truth(), self.sim.odoms[-1]):
            for got, wanted in zip(pose_of(msg), START):
                self.assertAlmostEqual(got, wanted, delta=1e-9)

    def test_cmd_pose_teleports_the_robot(self):
        target = (0.0, 0.5, math.pi / 2)
        self.sim.teleport(*target)
        self.sim.wait_for(lambda: all(abs(got - wanted) < 1e-9 for got, wanted
                                      in zip(pose_of(self.sim.truths[-1]), target)),
                          'ground truth at the cmd_pose target')
        self.sim.reset()

    def test_a_steps_scan_is_on_the_wire_before_its_clock(self):
        """A controller woken by /clock acts on the newest scan it has, so each step's
        scan must be sent before its clock, on every step, however busy the simulator's
        threads are. Answering each clock at once keeps the lockstep as fast as it goes."""
        caller = rospy.get_name() + '_wire'   # a publisher keeps one connection per caller
        clock = WireReader(caller, '/clock', Clock)
        scan = WireReader(caller, 'scan', LaserScan)
        try:
            newest = scan.next().header.stamp.to_sec()
            late = []
            for _ in range(WIRE_STEPS):
                tick = clock.next()
                self.assertIsNotNone(tick, 'the clock stopped')
                stamps = [msg.header.stamp.to_sec() for msg in scan.pending()]
                newest = max([newest] + stamps)
                if newest < tick.clock.to_sec() - EXACT:
                    late.append((tick.clock.to_sec(), newest))
                self.sim.send_once(0.0, 0.3)
        finally:
            self.sim.send_once(0.0, 0.0)
            clock.close()
            scan.close()
        self.assertEqual(late, [], '(clock, newest scan on the wire) when the clock came')

    def test_pause_physics_holds_every_step_until_unpaused(self):
        pause = rospy.ServiceProxy('pause_physics', Empty)
        unpause = rospy.ServiceProxy('unpause_physics', Empty)
        pause()
        time.sleep(PAUSE_SETTLE)         # a step already under way may still publish
        held = len(self.sim.clock)
        time.sleep(PAUSE_WATCH)
        self.assertEqual(len(self.sim.clock), held, 'the clock moved while paused')
        unpause()
        self.sim.wait_ticks(2)

    def test_several_robots_get_stageros_prefixed_names_and_their_own_commands(self):
        robots = [SimProbe('pair/', 'robot_%d/' % i, scan_topic='base_scan') for i in range(2)]
        for robot in robots:
            robot.wait_ready()
        robots[1].wait_ticks(2)
        for index, robot in enumerate(robots):
            prefix = 'robot_%d/' % index
            self.assertEqual(robot.scans[-1].header.frame_id, prefix + 'base_laser_link')
            self.assertEqual(robot.odoms[-1].header.frame_id, prefix + 'odom')
            self.assertEqual(robot.truths[-1].header.frame_id, prefix + 'odom')
            pairs = set((t.header.frame_id, t.child_frame_id) for t in robot.transforms)
            self.assertIn((prefix + 'odom', prefix + 'base_footprint'), pairs)
            self.assertIn((prefix + 'base_link', prefix + 'base_laser_link'), pairs)
        before = [pose_of(robot.latest_truth()) for robot in robots]
        robots[1].drive(0.1, 0.0, 10)
        robots[1].wait_ticks(3)
        after = [pose_of(robot.latest_truth()) for robot in robots]
        self.assertEqual(after[0], before[0], 'robot_0 moved on robot_1 commands')
        self.assertGreater(math.hypot(after[1][0] - before[1][0], after[1][1] - before[1][1]),
                           0.05)


if __name__ == '__main__':
    rospy.init_node('check_simulator')
    rostest.rosrun('wall_follower', 'check_simulator', SimulatorInterface, sys.argv)
