#!/usr/bin/env python3
"""rostest: move_arm sends a planned trajectory only to an arm controller that listens.

A trajectory published before the controller's subscription is connected is lost and
the arm never moves (a goal sent right after start-up on a busy machine failed so). With
no controller the goal is aborted, saying what is missing; with one that subscribes
after the goal was accepted, the controller gets the whole trajectory.
"""
import threading
import time
import unittest

import rospy
import rostest
from actionlib_msgs.msg import GoalStatus
from sensor_msgs.msg import JointState
from trajectory_msgs.msg import JointTrajectory

from arm_watch import WALL_LIMIT
from waiting import wait_until
from wall_follower.action_registration import action_server_registered
from wall_follower.arm.model import read_srdf, read_urdf
from wall_follower.evaluation.goal_client import GoalClient
from wall_follower.msg import MoveArmAction, MoveArmGoal

# Wall seconds the late controller waits, after the goal is active, before it subscribes:
# long enough that a trajectory published without waiting for it has surely gone.
LATE = 0.5


class LateControllerTest(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        rospy.init_node('check_move_arm_controller_late')
        cls.model = read_urdf(rospy.get_param('robot_description'))
        cls.semantics = read_srdf(rospy.get_param('robot_description_semantic'), cls.model)
        cls.states = rospy.Publisher('joint_states', JointState, queue_size=10)
        cls.timer = rospy.Timer(rospy.Duration(0.02), cls.publish_state)
        if not action_server_registered('move_arm', WALL_LIMIT):
            raise AssertionError('no move_arm action server')
        cls.client = GoalClient('move_arm', MoveArmAction)
        if not cls.client.wait_for_server(rospy.Duration(WALL_LIMIT)):
            raise AssertionError('no move_arm action server')

    @classmethod
    def publish_state(cls, _event):
        """The arm standing still at home, as a controller would report it."""
        zero = [0.0] * len(cls.model.names)
        state = JointState(name=cls.model.names, position=zero, velocity=zero)
        state.header.stamp = rospy.Time.now()
        cls.states.publish(state)

    def test_1_no_controller_aborts_saying_so(self):
        self.client.send_goal(MoveArmGoal(named_target='ready'))
        self.assertTrue(self.client.wait_for_result(WALL_LIMIT))
        self.assertEqual(self.client.get_state(), GoalStatus.ABORTED)
        self.assertIn('nothing subscribes to /arm_controller/command',
                      self.client.get_result().message)

    def test_2_a_late_controller_gets_the_trajectory(self):
        received = []
        arrived = threading.Event()

        def on_command(msg):
            received.append(msg)
            arrived.set()

        self.client.send_goal(MoveArmGoal(named_target='ready'))
        self.assertTrue(wait_until(lambda: self.client.get_state() == GoalStatus.ACTIVE,
                                   WALL_LIMIT))
        time.sleep(LATE)
        command = rospy.Subscriber('arm_controller/command', JointTrajectory, on_command)
        self.assertTrue(arrived.wait(WALL_LIMIT), 'the late controller got no trajectory')
        command.unregister()
        self.client.cancel_goal()
        trajectory = received[0]
        self.assertEqual(list(trajectory.joint_names), self.model.names)
        ready = [self.semantics.states['ready'][joint] for joint in self.model.names]
        for got, wanted in zip(trajectory.points[-1].positions, ready):
            self.assertAlmostEqual(got, wanted, places=6)


if __name__ == '__main__':
    rostest.rosrun('wall_follower', 'check_move_arm_controller_late', LateControllerTest)
