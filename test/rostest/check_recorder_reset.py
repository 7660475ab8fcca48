#!/usr/bin/env python3
"""rostest: reset_positions mid-lap, as a user might call it, while record_odom records.

The robot drives off its spawn pose, then the goal is sent; once the
feedback passes RESET_AFTER the simulator puts the robot back at its spawn
pose, behind the lap's start line. The teleport must not count as travel
(the feedback never leaps by it), nor end the lap as the robot drives off
over the start line: the lap ends a full lap later, at the start, with a
distance that is the path truly driven and a lap time the speed limit
allows. The recorded list holds one jump, to the spawn pose. Scored from
ground truth.
"""
import math
import sys
import unittest

import actionlib
import rospy
import rostest
from actionlib_msgs.msg import GoalStatus
from nav_msgs.msg import Odometry
from std_srvs.srv import Empty

from wall_follower.action_registration import action_server_registered
from wall_follower.control.motion import MAX_LINEAR
from wall_follower.msg import OdomRecordAction, OdomRecordGoal
from wall_follower.nodes.shared.messages import pose_of

from waiting import wait_until

POLL = 0.1
WAIT_LIMIT = 30.0       # wall seconds for the nodes and services to come up
LAP_LIMIT = 180.0       # wall seconds for the lap, reset included
BEFORE_GOAL = 0.2       # metres driven off the spawn pose before the goal
RESET_AFTER = 3.0       # metres recorded before reset_positions: past min_travel
MIN_AFTER_RESET = 4.0 * RESET_AFTER / 3.0   # metres the lap goes on after the reset, at least
# Metres between two points: a sample period (two, should the recorder answer late
# once) at the speed limit, and some slack. The reset jumps far more.
LEAP = 2.0 * MAX_LINEAR + 0.05
SAME_POSE = 1e-3        # metres: odometry is the true pose here (localization gps)


class ResetMidLap(unittest.TestCase):

    def setUp(self):
        self.truths = []
        rospy.Subscriber('base_pose_ground_truth', Odometry, self._on_truth, queue_size=10000)
        self.assertTrue(action_server_registered('record_odom', WAIT_LIMIT),
                        'no record_odom server')
        self.client = actionlib.SimpleActionClient('record_odom', OdomRecordAction)
        self.assertTrue(self.client.wait_for_server(rospy.Duration(WAIT_LIMIT)),
                        'no record_odom server')
        for name in ('pause_physics', 'unpause_physics', 'reset_positions'):
            rospy.wait_for_service(name, WAIT_LIMIT)
        self.pause = rospy.ServiceProxy('pause_physics', Empty)
        self.unpause = rospy.ServiceProxy('unpause_physics', Empty)
        self.reset = rospy.ServiceProxy('reset_positions', Empty)

    def _on_truth(self, msg):
        self.truths.append((msg.header.stamp.to_sec(), pose_of(msg)[:2]))

    def driven(self, since=0.0, until=math.inf):
        """Metres of ground truth stamped from `since` to `until`, teleports left out."""
        trail = [xy for t, xy in list(self.truths) if since <= t <= until]
        steps = [math.hypot(b[0] - a[0], b[1] - a[1]) for a, b in zip(trail, trail[1:])]
        return sum(step for step in steps if step < LEAP)

    def test_reset_mid_lap(self):
        self.unpause()
        self.assertTrue(wait_until(lambda: self.driven() >= BEFORE_GOAL, WAIT_LIMIT),
                        'the robot did not drive off')
        # The goal goes out with the world paused: in transit, wall milliseconds
        # would be simulated seconds of driving.
        self.pause()
        goal_time = rospy.get_time()
        totals = []
        self.client.send_goal(OdomRecordGoal(),
                              feedback_cb=lambda fb: totals.append(fb.current_total))
        self.assertTrue(wait_until(lambda: self.client.get_state() == GoalStatus.ACTIVE,
                                   WAIT_LIMIT), 'record_odom took no goal')
        self.unpause()
        self.assertTrue(wait_until(lambda: totals and totals[-1] >= RESET_AFTER,
                                   LAP_LIMIT), 'no feedback past %.1f m' % RESET_AFTER)
        reset_time = rospy.get_time()
        self.reset()
        self.assertTrue(wait_until(lambda: self.client.get_state() != GoalStatus.ACTIVE,
                                   LAP_LIMIT), 'no lap after the reset')
        # The goal's end comes on the status topic, its result on a connection of its own.
        self.assertTrue(self.client.wait_for_result(rospy.Duration(WAIT_LIMIT)),
                        'no result for the lap')
        self.assertEqual(self.client.get_state(), GoalStatus.SUCCEEDED,
                         self.client.get_goal_status_text())
        points = [(p.x, p.y) for p in self.client.get_result().list_of_odoms]

        # The reset happened, and far from the spawn pose.
        trail = [xy for _, xy in list(self.truths)]
        teleport = max(math.hypot(b[0] - a[0], b[1] - a[1]) for a, b in zip(trail, trail[1:]))
        self.assertGreater(teleport, 1.0, 'reset_positions moved the robot %.2f m' % teleport)

        # The teleport is never counted: counted, it would grow the total by at least
        # its length at once, far more than the robot drives between two feedbacks.
        # (Not checked against the path driven until each feedback arrived: that
        # leans on this node's clock, which lags under load.)
        growth = max(b - a for a, b in zip(totals, totals[1:]))
        self.assertLess(growth, teleport, 'the feedback grew by %.2f m at once: %s'
                        % (growth, totals))

        # The list: one jump, from where the robot was to its spawn pose, and back at the
        # start at the end.
        steps = [math.hypot(b[0] - a[0], b[1] - a[1]) for a, b in zip(points, points[1:])]
        jumps = [i for i, step in enumerate(steps) if step >= LEAP]
        self.assertEqual(len(jumps), 1, 'steps between points: %s' % steps)
        after_jump = points[jumps[0] + 1]
        spawn = trail[[math.hypot(b[0] - a[0], b[1] - a[1]) for a, b in
                       zip(trail, trail[1:])].index(teleport) + 1]
        self.assertLess(math.hypot(after_jump[0] - spawn[0], after_jump[1] - spawn[1]), LEAP)
        close_tolerance = rospy.get_param('/odom_recorder/close_tolerance')
        self.assertLess(math.hypot(points[-1][0] - points[0][0], points[-1][1] - points[0][1]),
                        close_tolerance + LEAP / 2.0, 'the lap ended away from its start')

        # The lap ends where ground truth passes the last point, a full lap after the
        # reset; under load that truth may arrive seconds after the result. Not where it
        # passed that point just after the reset: the lap ends by its start, and from the
        # spawn pose the simulator drives the robot the way it went before the goal,
        # within SAME_POSE once the follower has settled on its line.
        def closing():
            return next((t for t, (x, y) in list(self.truths) if t > reset_time and
                         math.hypot(x - points[-1][0], y - points[-1][1]) < SAME_POSE and
                         self.driven(reset_time, t) > MIN_AFTER_RESET), None)
        self.assertTrue(wait_until(lambda: closing() is not None, WAIT_LIMIT),
                        'ground truth never came to the last point %s' % (points[-1],))
        closing_time = closing()
        after_reset = self.driven(reset_time)
        self.assertGreater(after_reset, MIN_AFTER_RESET,
                           'the lap ended %.2f m after the reset' % after_reset)
        total = totals[-1]
        truth = self.driven(goal_time) - self.driven(closing_time)
        self.assertAlmostEqual(total, truth, delta=0.02 * truth + 0.05)
        lap_time = closing_time - goal_time
        self.assertGreaterEqual(lap_time, total / MAX_LINEAR)
        rospy.loginfo('reset mid-lap: %.1f s for %.2f m (ground truth %.2f m), %d points, '
                      'teleported %.2f m', lap_time, total, truth, len(points), teleport)


if __name__ == '__main__':
    rospy.init_node('check_recorder_reset')
    rostest.rosrun('wall_follower', 'check_recorder_reset', ResetMidLap, sys.argv)
