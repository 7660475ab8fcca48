"""The move_arm node: planned moves of the arm (the stand-in for experiment 7's MoveIt where
MoveIt is not installed), the action move_arm (wall_follower/MoveArm).

A goal names an SRDF group state, or a point for the origin of the tool frame (`hand`)
in any frame tf knows. The node plans it with wall_follower.arm.planning (inverse
kinematics nearest the joints' current positions, the collision check of the
joint-space line, the timing within the velocity and acceleration limits of
robot_description_planning, scaled by the goal's velocity_scaling, which must be 0 (full
speed) or within wall_follower.arm.planning.MIN_VELOCITY_SCALING and 1) and sends it as
one trajectory on arm_controller/command, the arm controller's topic (ros_control's or the
built-in arm_controller). A goal that cannot be planned (a point that is not finite or has
no frame among them) ends aborted, with success false and the reason, and nothing is sent.
A new goal pre-empts the running one, and a cancel ends it: either way move_arm asks the
controller for its stop, an empty trajectory (JointTrajectoryController holds the arm's
actual position; the built-in controller brakes it to rest within the acceleration
limits), and the result says where the arm came to rest, from joint_states once it has
settled. The result's position_error is measured from tf (robot_state_publisher's `hand`).

Parameters: the table in wall_follower.params.arm.move_arm, tunable live
(`rosrun dynamic_reconfigure dynparam set /move_arm floor_margin 0.02`), in force from
the next goal.
"""
import collections
import threading
import time

import actionlib
import numpy as np
import rospy
import tf2_ros
from sensor_msgs.msg import JointState
from trajectory_msgs.msg import JointTrajectory, JointTrajectoryPoint

from wall_follower.arm.kinematics import tool_position
from wall_follower.arm.planning import Planner, PlanningError, velocity_factor
from wall_follower.cfg import MoveArmConfig
from wall_follower.msg import MoveArmAction, MoveArmFeedback, MoveArmResult
from wall_follower.nodes.shared.arm_description import arm_model, arm_semantics
from wall_follower.nodes.shared.parameters import NodeParameters
from wall_follower.nodes.shared.startup import init_node
from wall_follower.nodes.shared.tf_lookup import lookup
from wall_follower.params.arm.move_arm import TABLE
from wall_follower.rotation import matrix_of_quaternion

COMMAND = 'arm_controller/command'


ArmState = collections.namedtuple('ArmState', 'stamp positions velocities')
"""One joint_states of the arm: stamp [s]; positions [rad] and velocities [rad/s], arrays in
the model's joint order."""


class GoalFailed(Exception):
    """A goal ended early: the result's message."""


class JointStates(object):
    """The newest joint_states of the arm, as arrays in the model's joint order."""

    def __init__(self, names):
        self.names = names
        self._arrived = threading.Condition()
        self.latest = None    # the newest ArmState
        rospy.Subscriber('joint_states', JointState, self._on_state, queue_size=10)

    def _on_state(self, msg):
        if not set(self.names) <= set(msg.name):
            return
        order = [list(msg.name).index(name) for name in self.names]
        positions = np.array([msg.position[i] for i in order])
        velocities = np.array([msg.velocity[i] if len(msg.velocity) == len(msg.name) else 0.0
                               for i in order])
        with self._arrived:
            self.latest = ArmState(msg.header.stamp.to_sec(), positions, velocities)
            self._arrived.notify_all()

    def next(self, seen, timeout):
        """The first ArmState newer than seen (an ArmState, or None), waiting at most timeout
        wall seconds for it; None if none came."""
        deadline = time.time() + timeout
        with self._arrived:
            while self.latest is None or self.latest is seen:
                left = deadline - time.time()
                if left <= 0.0 or rospy.is_shutdown():
                    return None
                self._arrived.wait(left)
            return self.latest


class MoveArmServer(object):

    def __init__(self):
        self.model = arm_model()
        self.semantics, self.velocity, self.acceleration = arm_semantics(self.model)
        self.params = NodeParameters(TABLE, MoveArmConfig)
        self.states = JointStates(self.model.names)
        self.command = rospy.Publisher(COMMAND, JointTrajectory, queue_size=1)
        self.buffer = tf2_ros.Buffer()
        self.listener = tf2_ros.TransformListener(self.buffer)
        self.server = actionlib.SimpleActionServer('move_arm', MoveArmAction, self.execute,
                                                   auto_start=False)
        self.server.start()
        rospy.loginfo('%s: ready; named targets %s', rospy.get_name(),
                      ', '.join(sorted(self.semantics.states)))

    def execute(self, goal):
        values = self.params.snapshot()
        result = MoveArmResult()
        try:
            result.message, result.position_error = self._move(goal, values)
            result.success = True
            rospy.loginfo('%s: %s (hand %.4f m from the goal)', rospy.get_name(),
                          result.message, result.position_error)
            self.server.set_succeeded(result, result.message)
        except GoalFailed as failure:
            result.message = str(failure)
            if self.server.is_preempt_requested():
                rospy.loginfo('%s: %s', rospy.get_name(), result.message)
                self.server.set_preempted(result, result.message)
            else:
                rospy.logwarn('%s: goal failed: %s', rospy.get_name(), result.message)
                self.server.set_aborted(result, result.message)

    def _move(self, goal, values):
        """Plan and follow one goal: (message, position error [m]); GoalFailed if it ends early."""
        try:
            scaling = velocity_factor(goal.velocity_scaling)
        except PlanningError as error:
            raise GoalFailed(str(error))
        state = self._current_state(values)
        planner = Planner(self.model, self.semantics, self.acceleration, self.velocity,
                          values['floor_margin'], values['self_margin'],
                          values['collision_step'])
        try:
            if goal.named_target:
                plan = planner.to_state(goal.named_target, state.positions, scaling)
                target = tool_position(self.model, plan.goal)
                what = 'named target %s' % goal.named_target
            else:
                target = self._in_root_frame(goal.target, values['tf_timeout'])
                plan = planner.to_point(target, state.positions, scaling)
                what = 'point (%.3f, %.3f, %.3f) in %s' % (tuple(target) + (self.model.root,))
        except PlanningError as error:
            raise GoalFailed(str(error))
        self._wait_for_controller(values['controller_timeout'])
        self.command.publish(self._trajectory(plan.move, values['waypoint_spacing']))
        final = self._follow(plan, state, values)
        error = np.linalg.norm(self._tool_in_tf(final.stamp, values['tf_timeout']) - target)
        return 'reached %s in %.2f s' % (what, plan.move.duration), float(error)

    def _current_state(self, values):
        """The newest joint state (the last goal's stop has settled before it ended)."""
        state = self.states.next(None, values['state_timeout'])
        if state is None:
            raise GoalFailed('no joint_states from the arm for %.1f s: is arm_controller '
                             'running?' % values['state_timeout'])
        return state

    def _wait_for_controller(self, timeout):
        """Wait until the arm controller subscribes to the command topic: a trajectory
        published before its subscription is connected is lost, and the arm never moves.
        The connection is made after the node starts, later on a busy machine."""
        deadline = time.time() + timeout
        while self.command.get_num_connections() == 0:
            if time.time() >= deadline or rospy.is_shutdown():
                raise GoalFailed('nothing subscribes to %s after %.1f s: is the arm controller '
                                 'running?' % (self.command.resolved_name, timeout))
            if self.server.is_preempt_requested():
                raise GoalFailed('pre-empted before the arm controller was there')
            time.sleep(0.01)

    def _follow(self, plan, state, values):
        """Wait, joint state by joint state, until the arm is at the plan's goal: the final
        ArmState; stops the arm and raises GoalFailed on a pre-emption, a cancel, stale
        joint_states or a goal not reached in time."""
        sent = state.stamp
        end = sent + plan.move.duration
        while True:
            newer = self.states.next(state, values['state_timeout'])
            if newer is None:
                self._ask_to_stop()
                raise GoalFailed('joint_states stopped coming: the arm was told to stop, last '
                                 'heard at %s' % self._joints(state))
            state = newer
            if self.server.is_preempt_requested():
                why = 'pre-empted by a new goal' if self.server.is_new_goal_available() \
                    else 'cancelled'
                raise GoalFailed('%s: %s' % (why, self._stopped(values)))
            self.server.publish_feedback(MoveArmFeedback(
                progress=plan.move.time_share(sent, state.stamp)))
            if state.stamp >= end and np.all(np.abs(state.positions - plan.goal) <=
                                             values['goal_tolerance']) and \
                    np.all(np.abs(state.velocities) < values['stopped_velocity']):
                return state
            if state.stamp > end + values['settle_timeout']:
                raise GoalFailed('the arm did not reach its goal within %.1f s of the '
                                 'trajectory\'s end (%s): %s' % (
                                     values['settle_timeout'], self._joints(state),
                                     self._stopped(values)))

    def _ask_to_stop(self):
        """Ask the arm controller for its stop: an empty trajectory, as JointTrajectoryController
        takes one (it holds the arm's actual position; the built-in controller brakes to it
        within the acceleration limits). Returns when it was asked, in ROS time [s]."""
        asked = rospy.Time.now().to_sec()
        self.command.publish(JointTrajectory(joint_names=self.model.names))
        return asked

    def _stopped(self, values):
        """Stop the arm and wait for it to settle: where it came to rest, in words, from the
        first joint state after the request in which every joint is slower than
        stopped_velocity (or, in words, why that was not seen within settle_timeout)."""
        asked = self._ask_to_stop()
        state = None
        while True:
            newer = self.states.next(state, values['state_timeout'])
            if newer is None:
                return 'the arm was told to stop, but joint_states stopped coming%s' % (
                    '' if state is None else ' (last heard at %s)' % self._joints(state))
            state = newer
            if state.stamp < asked:
                continue
            if np.all(np.abs(state.velocities) < values['stopped_velocity']):
                return 'the arm stopped at %s' % self._joints(state)
            if state.stamp > asked + values['settle_timeout']:
                return 'the arm was told to stop, but still moved %.1f s later (at %s)' % (
                    values['settle_timeout'], self._joints(state))

    def _joints(self, state):
        """An ArmState's positions in words: 'hip 0.532, shoulder ...' [rad]."""
        return ', '.join('%s %.3f' % pair for pair in zip(self.model.names, state.positions))

    def _trajectory(self, move, spacing):
        """The JointTrajectory of a TimedMove, from now (a zero stamp)."""
        msg = JointTrajectory(joint_names=self.model.names)
        for offset in move.waypoint_times(spacing):
            positions, velocities, accelerations = move.sample(offset)
            msg.points.append(JointTrajectoryPoint(
                positions=positions.tolist(), velocities=velocities.tolist(),
                accelerations=accelerations.tolist(), time_from_start=rospy.Duration(offset)))
        return msg

    def _in_root_frame(self, target, timeout):
        """A PointStamped's point in the model's root frame; GoalFailed if it names no frame
        (refused rather than guessed: a point meant in another frame would move the arm
        elsewhere)."""
        point = np.array([target.point.x, target.point.y, target.point.z])
        frame = target.header.frame_id
        if not frame.strip('/ '):
            raise GoalFailed('target has no frame_id: name the frame its point is given in '
                             '(the arm\'s base frame is %s)' % self.model.root)
        if frame.lstrip('/') == self.model.root:
            return point
        found, problem = lookup(self.buffer, self.model.root, frame.lstrip('/'), wait=timeout)
        if found is None:
            raise GoalFailed('cannot place the target: no transform from %s to %s (%s)' % (
                frame, self.model.root, problem))
        t = found.transform
        turn = matrix_of_quaternion((t.rotation.x, t.rotation.y, t.rotation.z, t.rotation.w))
        return turn.dot(point) + np.array([t.translation.x, t.translation.y, t.translation.z])

    def _tool_in_tf(self, stamp, timeout):
        """Where tf has the tool frame's origin at stamp [s], in the root frame."""
        tool = self.model.links[-1]
        found, problem = lookup(self.buffer, self.model.root, tool, rospy.Time.from_sec(stamp),
                                wait=timeout)
        if found is None:
            raise GoalFailed('moved, but tf has no %s in %s to measure it by (%s): is '
                             'robot_state_publisher running?' % (tool, self.model.root, problem))
        t = found.transform
        return np.array([t.translation.x, t.translation.y, t.translation.z])


def main():
    init_node('move_arm')
    MoveArmServer()
    rospy.spin()
    return 0
