"""The arm_controller node: the built-in stand-in for Gazebo + ros_control's
joint_trajectory_controller and joint_state_controller for the arm of robot_description.

Follows trajectory_msgs/JointTrajectory on arm_controller/command by the rules of
wall_follower.arm.trajectory (a rejected one is named in a warning, with the reason,
and the arm goes on as before; one stamped ahead is named in the log, with when it
starts), moves the joints as wall_follower.sim.arm_joints does (never past a limit of
the URDF) and publishes joint_states at ~rate. Where control_msgs is installed it also
serves arm_controller/follow_joint_trajectory (control_msgs/FollowJointTrajectory), the
interface MoveIt drives.

Its one stop, as JointTrajectoryController's: an empty command, a cancelled goal of the
action, or ROS time running backwards brakes the arm from its actual state to rest
within the acceleration limits of robot_description_planning (wall_follower.arm.
trajectory.stop), and holds it there. A command that replaces the trajectory of an
action goal ends that goal as pre-empted, as JTC does.

With ~publish_clock it drives /clock itself, one step of 1/~rate at a time, so that on
/use_sim_time a loaded machine slows simulated time instead of making the arm jump
(the rostests run it so).
"""
import threading
import time

import actionlib
import rospy
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import JointState
from trajectory_msgs.msg import JointTrajectory

from wall_follower.arm.trajectory import (Command, Rejected, Trajectory, TrajectoryPoint, accept,
                                          stop)
from wall_follower.nodes.shared.arm_description import arm_model, stop_acceleration
from wall_follower.nodes.shared.parameters import NodeParameters
from wall_follower.nodes.shared.startup import init_node
from wall_follower.params.arm.arm_controller import TABLE
from wall_follower.sim.arm_joints import ArmJoints

try:
    from control_msgs.msg import FollowJointTrajectoryAction, FollowJointTrajectoryResult
except ImportError:   # not packaged on Debian 12: the topic interface alone is served
    FollowJointTrajectoryAction = None

COMMAND = 'arm_controller/command'
ACTION = 'arm_controller/follow_joint_trajectory'


def command_of(msg):
    """A trajectory_msgs/JointTrajectory as a wall_follower.arm.trajectory.Command."""
    return Command(list(msg.joint_names), msg.header.stamp.to_sec(), [
        TrajectoryPoint(point.time_from_start.to_sec(), point.positions, point.velocities,
                        point.accelerations) for point in msg.points])


class ArmController(object):
    """The trajectory followed, the joints, and the clock they are stepped on."""

    def __init__(self, model, values):
        self.model = model
        self.period = 1.0 / values['rate']
        self.speedup = values['speedup']
        self.own_clock = values['publish_clock']
        initial = values['initial_positions']
        unknown = sorted(set(initial) - set(model.names))
        if unknown:
            rospy.logfatal('%s: cannot start: ~initial_positions names unknown joint(s) %s '
                           '(the arm has %s)', rospy.get_name(), ', '.join(unknown),
                           ', '.join(model.names))
            raise SystemExit(1)
        self.joints = ArmJoints([float(initial.get(name, 0.0)) for name in model.names],
                                model.lower, model.upper, model.velocity)
        self.acceleration = stop_acceleration(model)
        self._lock = threading.Lock()
        self._clock = rospy.Publisher('/clock', Clock, queue_size=1) if self.own_clock else None
        self.now = self.period if self.own_clock else rospy.Time.now().to_sec()
        self.trajectory = Trajectory.hold(self.joints.positions, self.now)
        self._states = rospy.Publisher('joint_states', JointState, queue_size=10)
        rospy.Subscriber(COMMAND, JointTrajectory, self.on_command, queue_size=10)
        if FollowJointTrajectoryAction is not None:
            self._server = actionlib.SimpleActionServer(ACTION, FollowJointTrajectoryAction,
                                                        self.on_goal, auto_start=False)
            self._server.start()
        rospy.loginfo('%s: following %s for joints %s; %s', rospy.get_name(),
                      rospy.resolve_name(COMMAND), ', '.join(model.names),
                      'serving ' + rospy.resolve_name(ACTION) if FollowJointTrajectoryAction
                      else 'control_msgs not installed: no %s' % rospy.resolve_name(ACTION))

    def follow(self, msg, source):
        """Take a JointTrajectory (an empty one: stop); the Trajectory now followed, or None
        if rejected (warned)."""
        command = command_of(msg)
        with self._lock:
            if not command.points:
                self._stop()
                return self.trajectory
            try:
                self.trajectory = accept(self.model, command, self.now, self.trajectory)
            except Rejected as error:
                rospy.logwarn('%s: trajectory on %s rejected: %s', rospy.get_name(), source,
                              error)
                return None
            if command.stamp > self.now:
                rospy.loginfo('%s: trajectory on %s is stamped %.3f s ahead: it starts then, '
                              'and until then the arm goes on as before', rospy.get_name(),
                              source, command.stamp - self.now)
            return self.trajectory

    def _stop(self):
        """Brake the arm from where it is and how fast it moves to rest (with the lock held)."""
        self.trajectory = stop(self.joints.positions, self.joints.velocities, self.now,
                               self.acceleration)

    def on_command(self, msg):
        self.follow(msg, rospy.resolve_name(COMMAND))

    def on_goal(self, goal):
        """FollowJointTrajectory: follow the goal's trajectory until its end, a cancel (the arm
        stops), or another trajectory or goal taking over (pre-empted, as JTC has it)."""
        result = FollowJointTrajectoryResult()
        followed = self.follow(goal.trajectory, rospy.resolve_name(ACTION))
        if followed is None:
            result.error_code = FollowJointTrajectoryResult.INVALID_GOAL
            result.error_string = 'rejected: see the warning'
            self._server.set_aborted(result, result.error_string)
            return
        rate = rospy.Rate(1.0 / self.period)
        while not rospy.is_shutdown() and self.now < followed.end:
            if self._server.is_preempt_requested():
                if self._server.is_new_goal_available():
                    self._server.set_preempted(result, 'replaced by a new goal')
                    return
                with self._lock:
                    self._stop()
                self._server.set_preempted(result, 'cancelled: the arm stops')
                return
            if self.trajectory is not followed:
                self._server.set_preempted(result, 'replaced by another trajectory')
                return
            rate.sleep()
        result.error_code = FollowJointTrajectoryResult.SUCCESSFUL
        self._server.set_succeeded(result)

    def run(self):
        """Step the joints and publish joint_states (and /clock with ~publish_clock) until
        shutdown."""
        rate = None if self.own_clock else rospy.Rate(1.0 / self.period)
        while not rospy.is_shutdown():
            try:
                self._tick(rate)
            except rospy.ROSException:
                if not rospy.is_shutdown():
                    raise
                break   # rospy closes the topics while it shuts down

    def _tick(self, rate):
        """One step: wait for its time (and publish it on /clock with ~publish_clock)."""
        if self.own_clock:
            time.sleep(self.period / self.speedup)
            now = self.now + self.period
            self._clock.publish(Clock(clock=rospy.Time.from_sec(now)))
        else:
            try:
                rate.sleep()
            except rospy.ROSTimeMovedBackwardsException:
                rospy.logwarn('%s: ROS time moved backwards: stopping the arm where it is',
                              rospy.get_name())
                with self._lock:
                    self.now = rospy.Time.now().to_sec()
                    self._stop()
                return
            now = rospy.Time.now().to_sec()
        self.step(now)

    def step(self, now):
        """Move the joints to time now [s] and publish their state."""
        with self._lock:
            elapsed, self.now = now - self.now, now
            desired, velocity, _ = self.trajectory.sample(now)
            self.joints.step(desired, velocity, elapsed)
            positions, velocities = self.joints.positions.copy(), self.joints.velocities.copy()
        state = JointState(name=self.model.names, position=positions, velocity=velocities)
        state.header.stamp = rospy.Time.from_sec(now)
        self._states.publish(state)


def main():
    init_node('arm_controller')
    values = NodeParameters(TABLE).snapshot()
    ArmController(arm_model(), values).run()
    return 0
