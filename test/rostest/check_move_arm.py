#!/usr/bin/env python3
"""rostest: move_arm plans and executes moves of the arm, and refuses what it cannot do.

In simulated time, the built-in controller driving /clock: moves to named targets and
to points (given in world and in a frame that moves with the arm) put the `hand` frame,
as tf has it, within 2 mm of the goal; an unreachable point, a point below the floor, a
point the hand can reach only through the floor, a point that is not finite, one with
no frame and a velocity_scaling too small to end fail with a message saying which, and
the arm does not move (nor does move_arm's memory grow); a new goal pre-empts the
running one and a cancel stops the arm short of its goal, within its acceleration
limits, and the result says where it came to rest: it goes no further. No joint_states
heard breaks a limit or puts a link into the floor or into another.
"""
import re
import threading
import unittest
from xmlrpc.client import ServerProxy

import numpy as np
import rosgraph
import rospy
import rostest
import tf2_ros
from actionlib_msgs.msg import GoalStatus
from geometry_msgs.msg import PointStamped

from arm_watch import WALL_LIMIT, ArmWatch
from waiting import wait_until
from wall_follower.action_registration import action_server_registered
from wall_follower.arm.kinematics import tool_position
from wall_follower.arm.model import read_acceleration_limits
from wall_follower.evaluation.goal_client import GoalClient
from wall_follower.msg import MoveArmAction, MoveArmActionFeedback, MoveArmGoal

POSITION_TOLERANCE = 0.002   # m
RESULT_LIMIT = 60.0   # wall s
# rad between where a result says the arm stopped (to 3 decimals) and where it rests
STOP_TOLERANCE = 0.002
# bytes move_arm's resident memory may grow by over a refused goal (a crawling goal once
# grew it by 70 MB a second)
MEMORY_GROWTH_LIMIT = 20e6


def point_goal(x, y, z, frame='world', scaling=0.0):
    target = PointStamped()
    target.header.frame_id = frame
    target.point.x, target.point.y, target.point.z = x, y, z
    return MoveArmGoal(target=target, velocity_scaling=scaling)


class FeedbackLog(object):
    """Every progress move_arm publishes, by goal, heard on a subscription of its own.

    Feedback and result come on connections of their own, and actionlib's client drops a
    goal's feedback that comes in after its result: the last feedback (1.0) is then never
    given to a feedback_cb, though move_arm sent it."""

    def __init__(self, action):
        self._lock = threading.Lock()
        self._progress = {}
        rospy.Subscriber(action + '/feedback', MoveArmActionFeedback, self._on_feedback)

    def _on_feedback(self, msg):
        with self._lock:
            self._progress.setdefault(msg.status.goal_id.id, []).append(msg.feedback.progress)

    def of(self, client):
        """The progress heard so far of a client's newest goal, in the order sent."""
        with self._lock:
            return list(self._progress.get(client.goal_id(), ()))


def resident_memory(node):
    """A node's resident memory [bytes], from /proc (the node runs on this machine)."""
    caller = rospy.get_name()
    _, _, pid = ServerProxy(rosgraph.Master(caller).lookupNode(node)).getPid(caller)
    with open('/proc/%d/status' % pid) as status:
        fields = dict(line.split(':', 1) for line in status)
    return int(fields['VmRSS'].split()[0]) * 1024


class MoveArmTest(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        rospy.init_node('check_move_arm')
        cls.watch = ArmWatch()
        cls.buffer = tf2_ros.Buffer()
        cls.listener = tf2_ros.TransformListener(cls.buffer)
        cls.feedback = FeedbackLog('move_arm')
        if not action_server_registered('move_arm', WALL_LIMIT):
            raise AssertionError('no move_arm action server')
        cls.client = GoalClient('move_arm', MoveArmAction)
        if not cls.client.wait_for_server(rospy.Duration(WALL_LIMIT)):
            raise AssertionError('no move_arm action server')

    def hand(self):
        """Where tf has the hand's origin in world at the newest joint state.

        A result and the joint states before it come on connections of their own: the
        states up to the result may still be on their way when it is in, so this waits
        for one stamped at or after the moment of asking."""
        self.assertTrue(self.watch.wait_for_time(rospy.get_time()), 'no joint state')
        stamp = rospy.Time.from_sec(self.watch.latest()[0])
        t = self.buffer.lookup_transform('world', 'hand', stamp, rospy.Duration(5.0)).transform
        return np.array([t.translation.x, t.translation.y, t.translation.z])

    def move(self, goal):
        self.client.send_goal(goal)
        self.assertTrue(self.client.wait_for_result(RESULT_LIMIT), 'move_arm did not answer')
        return self.client.get_state(), self.client.get_result()

    def assert_reached(self, goal, where):
        state, result = self.move(goal)
        self.assertEqual(state, GoalStatus.SUCCEEDED, result.message)
        self.assertTrue(result.success, result.message)
        self.assertLess(result.position_error, POSITION_TOLERANCE)
        error = np.linalg.norm(self.hand() - where)
        self.assertLess(error, POSITION_TOLERANCE, 'hand %.4f m from %s' % (error, where))
        # the last feedback may still be on its way when the result is in
        self.assertTrue(wait_until(lambda: self.feedback.of(self.client)[-1:] == [1.0],
                                   WALL_LIMIT), 'progress %s' % self.feedback.of(self.client)[-3:])
        progress = self.feedback.of(self.client)
        self.assertEqual(progress, sorted(progress))

    def assert_refused(self, goal, words):
        before = self.watch.latest()
        state, result = self.move(goal)
        self.assertEqual(state, GoalStatus.ABORTED)
        self.assertFalse(result.success)
        self.assertIn(words, result.message)
        self.assertTrue(self.watch.wait_for_time(before[0] + 0.5))
        for later in self.watch.since(before[0]):
            self.assertTrue(np.allclose(later[1], before[1], atol=1e-12), result.message)

    def test_1_named_targets(self):
        model = self.watch.model
        for name in ('ready', 'side', 'home'):
            joints = [self.watch.semantics.states[name][joint] for joint in model.names]
            self.assert_reached(MoveArmGoal(named_target=name), tool_position(model, joints))
            self.assertTrue(np.allclose(self.watch.latest()[1], joints, atol=0.01))

    def test_2_points(self):
        for point in ((0.4, -0.3, 0.6), (0.5, 0.2, 0.25), (-0.3, 0.4, 0.9), (0.0, 0.6, 0.3)):
            self.assert_reached(point_goal(*point, scaling=1.0), np.array(point))

    def test_3_a_point_in_a_frame_that_moves_with_the_arm(self):
        """The torso turns with the hip: a point in its frame is placed by tf at the goal."""
        model = self.watch.model
        side = [self.watch.semantics.states['side'][joint] for joint in model.names]
        self.assert_reached(MoveArmGoal(named_target='side'), tool_position(model, side))
        stamp = rospy.Time.from_sec(self.watch.latest()[0])
        t = self.buffer.lookup_transform('world', 'torso', stamp, rospy.Duration(5.0))
        yaw = 2.0 * np.arctan2(t.transform.rotation.z, t.transform.rotation.w)
        self.assertGreater(abs(yaw), 1.0)
        where = np.array([0.45 * np.cos(yaw), 0.45 * np.sin(yaw),
                          t.transform.translation.z + 0.35])
        self.assert_reached(point_goal(0.45, 0.0, 0.35, frame='torso'), where)

    def test_4_unreachable_below_the_floor_colliding_and_bad_goals_fail_without_motion(self):
        self.assert_refused(point_goal(2.0, 0.0, 0.5), 'unreachable: out of reach')
        self.assert_refused(point_goal(0.3, 0.0, -0.05), 'below the floor')
        self.assert_refused(point_goal(0.5, 0.0, 0.01), 'reachable only in collision')
        self.assert_refused(MoveArmGoal(named_target='dance'), "no named target 'dance'")
        self.assert_refused(MoveArmGoal(named_target='ready', velocity_scaling=1.5),
                            'velocity_scaling 1.5 is not within 0 to 1')
        self.assert_refused(point_goal(float('nan'), 0.0, 0.5), 'point (nan, 0.0, 0.5) is not '
                            'finite')
        self.assert_refused(point_goal(0.3, float('inf'), 0.5), 'is not finite')
        self.assert_refused(point_goal(0.4, -0.3, 0.6, frame=''), 'target has no frame_id')

    def test_4a_a_crawling_velocity_scaling_is_refused_and_the_memory_stays_flat(self):
        before = resident_memory('/move_arm')
        self.assert_refused(MoveArmGoal(named_target='ready', velocity_scaling=1e-9),
                            'velocity_scaling 1e-09 is below the least allowed, 0.01')
        self.assertLess(resident_memory('/move_arm') - before, MEMORY_GROWTH_LIMIT)
        ready = [self.watch.semantics.states['ready'][joint] for joint in self.watch.model.names]
        self.assert_reached(MoveArmGoal(named_target='ready', velocity_scaling=0.5),
                            tool_position(self.watch.model, ready))

    def test_5_a_new_goal_pre_empts_and_a_cancel_stops(self):
        self.assert_reached(MoveArmGoal(named_target='home'),
                            tool_position(self.watch.model, np.zeros(4)))
        first = point_goal(-0.5, -0.2, 0.4, scaling=0.3)
        self.client.send_goal(first)
        self.assertTrue(wait_until(lambda: self.feedback.of(self.client)[-1:] > [0.3],
                                   WALL_LIMIT))
        # a second client's goal, as another user would send it
        other = GoalClient('move_arm', MoveArmAction)
        self.assertTrue(other.wait_for_server(rospy.Duration(WALL_LIMIT)))
        other.send_goal(point_goal(0.4, 0.4, 0.5))
        self.assertTrue(self.client.wait_for_result(RESULT_LIMIT))
        self.assertEqual(self.client.get_state(), GoalStatus.PREEMPTED)
        self.assertFalse(self.client.get_result().success)
        pre_empted = self.client.get_result().message
        self.assertIn('pre-empted', pre_empted)
        self.assertTrue(other.wait_for_result(RESULT_LIMIT))
        self.assertEqual(other.get_state(), GoalStatus.SUCCEEDED, other.get_result().message)
        self.assertLess(np.linalg.norm(self.hand() - (0.4, 0.4, 0.5)), POSITION_TOLERANCE)

        far = point_goal(-0.4, 0.3, 0.2, scaling=0.3)
        self.client.send_goal(far)
        self.assertTrue(wait_until(lambda: self.feedback.of(self.client)[-1:] > [0.3],
                                   WALL_LIMIT))
        cancelled = self.watch.latest()[0]
        self.client.cancel_goal()
        self.assertTrue(self.client.wait_for_result(RESULT_LIMIT))
        self.assertEqual(self.client.get_state(), GoalStatus.PREEMPTED)
        message = self.client.get_result().message
        reported = self.stop_in(message)
        answered = self.watch.latest()[0]
        self.assertTrue(self.watch.wait_for_time(answered + 1.5))
        for state in self.watch.since(answered):      # where it said, and no further
            self.assertTrue(np.allclose(state[1], reported, atol=STOP_TOLERANCE),
                            'at %.2f s: joints at %s, stopped at %s by the result' % (
                                state[0], state[1], reported))
        self.assertTrue(all(np.allclose(s[2], 0.0) for s in self.watch.since(answered + 1.0)),
                        'still moving')
        acceleration = read_acceleration_limits(
            rospy.get_param('robot_description_planning'), self.watch.model)
        braking = self.watch.since(cancelled)
        for previous, state in zip(braking, braking[1:]):
            change = np.abs(state[2] - previous[2]) / (state[0] - previous[0])
            self.assertTrue((change <= acceleration * 1.001).all(),
                            'at %.2f s: %s rad/s^2' % (state[0], change))
        self.assertGreater(np.linalg.norm(self.hand() - (-0.4, 0.3, 0.2)), 0.1)
        self.assertIn('cancelled: the arm stopped at', message)
        self.assertIn('pre-empted by a new goal: the arm stopped at', pre_empted)

    def stop_in(self, message):
        """The joint positions that end a result's message ('... at hip 0.532, ...')."""
        found = re.search(r' at ((?:\w+ -?\d+\.\d+, )*\w+ -?\d+\.\d+)$', message)
        self.assertTrue(found, message)
        given = dict((name, float(value)) for name, value in
                     (pair.split() for pair in found.group(1).split(', ')))
        return np.array([given[name] for name in self.watch.model.names])

    def test_6_no_limit_broken_and_no_contact_in_any_joint_state(self):
        self.watch.assert_safe(self)


if __name__ == '__main__':
    rostest.rosrun('wall_follower', 'check_move_arm', MoveArmTest)
