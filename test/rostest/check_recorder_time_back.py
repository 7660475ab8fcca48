#!/usr/bin/env python3
"""rostest: record_odom survives ROS time moving backwards, and malformed odometry.

This node plays a simulator: it publishes /clock and odometry of a robot
driving along x. Mid-goal the simulator "restarts": the clock jumps back
from OLD_CLOCK to NEW_CLOCK and the robot drives on at y = NEW_Y. The goal
recorded on the old clock must end, saying why; the goal status must keep
coming; a new goal must start from a pose heard since it, not from the
poses stamped on the old clock. Then the simulator restarts again between
goals, to LAST_CLOCK and LAST_Y, and the next goal must be taken and
recorded as well, though stamped before the goals served. Odometry with a NaN position or a
quaternion that is no rotation, mixed into the stream, must be skipped with
a warning. All waits are bounded in wall time: this node's own ROS clock
is the one that jumps.
"""
import math
import sys
import unittest

import actionlib
import rospy
import rostest
from actionlib_msgs.msg import GoalStatus, GoalStatusArray
from rosgraph_msgs.msg import Log

from wall_follower.action_registration import action_server_registered
from wall_follower.msg import OdomRecordAction, OdomRecordGoal
from wall_follower.nodes.shared.waiting import wait_in_wall_time

from odometry_world import SPEED, STEP, OdometryWorld
from rosout_log import RosoutLog
from waiting import wait_until

OLD_CLOCK = 1000.0      # simulated seconds before the jump
NEW_CLOCK = 10.0        # and after it
NEW_Y = 5.0             # metres: where the robot drives after the jump
LAST_CLOCK = 5.0        # and after the second jump
LAST_Y = 9.0
WALL_STEP = 0.02        # wall seconds per world step (odometry_world.STEP): 5 times real time
WAIT_LIMIT = 20.0       # wall seconds for anything to happen
RECORDER = '/odom_recorder'
# Goal status messages to see from the recorder on the new clock, with no goal
# changing state meanwhile: only its periodic timer sends them then.
STATUS_COUNT = 10
POINTS_BEFORE_CANCEL = 3


class TimeMovesBack(unittest.TestCase):

    def setUp(self):
        self.statuses = []
        self.log = RosoutLog(RECORDER)
        rospy.Subscriber('record_odom/status', GoalStatusArray, self.statuses.append)
        self.world = OdometryWorld(OLD_CLOCK, WALL_STEP)
        self.assertTrue(action_server_registered('record_odom', WAIT_LIMIT),
                        'no record_odom server')
        self.client = actionlib.SimpleActionClient('record_odom', OdomRecordAction)

    def tearDown(self):
        self.world.stop()

    def warnings(self):
        return self.log.lines(RECORDER, '', Log.WARN)

    def points(self, feedback, count):
        return wait_until(lambda: len(feedback) >= count, WAIT_LIMIT)

    def assert_records_afresh(self, before_clock, y):
        """A goal sent now records from a pose published since, at y, on the new clock."""
        # The recorder's clock has moved back, as has this node's, which stamps the goal.
        self.assertTrue(wait_until(lambda: self.statuses[-1].header.stamp.to_sec() < before_clock
                                   and rospy.get_time() < before_clock, WAIT_LIMIT))
        feedback = []
        goal_time = rospy.get_time()
        self.client.send_goal(OdomRecordGoal(), feedback_cb=feedback.append)
        self.assertTrue(self.points(feedback, POINTS_BEFORE_CANCEL),
                        'no feedback on the clock from %.0f s' % before_clock)
        self.client.cancel_goal()
        self.assertTrue(wait_in_wall_time(self.client.wait_for_result, WAIT_LIMIT),
                        'no result after the cancel')
        self.assertEqual(self.client.get_state(), GoalStatus.PREEMPTED)
        points = self.client.get_result().list_of_odoms
        self.assertGreaterEqual(len(points), POINTS_BEFORE_CANCEL)
        first = points[0]
        self.assertEqual(first.y, y, 'the first point (%.2f, %.2f) is a pose from an old '
                         'clock' % (first.x, first.y))
        stamp = next(t for t, px, py in self.world.published
                     if py == y and abs(px - first.x) < SPEED * STEP / 2.0)
        self.assertGreaterEqual(stamp, goal_time - 2.0 * STEP,
                                'the first point was published %.1f s before the goal'
                                % (goal_time - stamp))
        self.assertTrue(all(math.isfinite(p.x) and math.isfinite(p.y) for p in points))
        self.assertTrue(all(math.isfinite(f.current_total) for f in feedback))

    def test_a_goal_after_the_jump_starts_fresh_and_status_keeps_coming(self):
        self.assertTrue(wait_in_wall_time(self.client.wait_for_server, WAIT_LIMIT),
                        'no record_odom server')
        self.assertTrue(wait_until(lambda: self.world.odom.get_num_connections() > 0,
                                   WAIT_LIMIT), 'record_odom is not on odom')
        feedback = []
        self.client.send_goal(OdomRecordGoal(), feedback_cb=feedback.append)
        self.assertTrue(self.points(feedback, 2), 'no feedback on the old clock')

        self.world.restart(NEW_CLOCK, NEW_Y)
        self.assertTrue(wait_until(lambda: self.client.get_state() == GoalStatus.ABORTED,
                                   WAIT_LIMIT), 'the goal on the old clock did not end')
        self.assertIn('moved back', self.client.get_goal_status_text())
        ended = len(self.statuses)
        self.assertTrue(wait_until(lambda: len(self.statuses) - ended >= STATUS_COUNT,
                                   WAIT_LIMIT),
                        'goal status stopped after the jump (%d messages)'
                        % (len(self.statuses) - ended))
        self.assertLess(self.statuses[-1].header.stamp.to_sec(), OLD_CLOCK)

        self.world.malformed = True
        self.assert_records_afresh(OLD_CLOCK, NEW_Y)
        # One throttled warning for both kinds: whichever comes first.
        self.assertTrue(wait_until(lambda: any('not finite' in w or 'not a unit quaternion' in w
                                               for w in self.warnings()), WAIT_LIMIT),
                        'no warning about malformed odometry: %s' % self.warnings())

        before = rospy.get_time()
        self.world.restart(LAST_CLOCK, LAST_Y)
        self.assert_records_afresh(before, LAST_Y)


if __name__ == '__main__':
    rospy.init_node('check_recorder_time_back')
    rostest.rosrun('wall_follower', 'check_recorder_time_back', TimeMovesBack, sys.argv)
