"""A test-side view of a running simulator: records everything it publishes,
per simulated step, and drives it in step with /clock.

Shared by the simulator rostests. Waits are on conditions; their wall-clock
limits only bound how long a failing test takes.
"""
import threading

import rospy
from geometry_msgs.msg import Pose, Twist
from nav_msgs.msg import Odometry
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import LaserScan
from std_msgs.msg import Bool
from std_srvs.srv import Empty
from tf2_msgs.msg import TFMessage

from wall_follower.nodes.shared.messages import (  # noqa: F401 (re-exported)
    pose_message, pose_of, yaw_of)

WAIT_LIMIT = 20.0


class SimProbe(object):
    """Subscribes to one robot's topics and to its simulator's /clock and /tf.

    namespace: where the simulator runs ('' or 'pair/'); a namespaced
    simulator in these tests has its /clock and /tf remapped into it.
    robot: stageros' robot prefix ('' for a lone robot, 'robot_1/').
    Every message is kept, so tests can line the topics up step by step.
    drive() sends one command per /clock tick, as a controller on a steady
    ROS-time rate does.
    """

    def __init__(self, namespace='', robot='', scan_topic='scan'):
        topic = namespace + robot
        self._condition = threading.Condition()
        self.clock = []
        self.scans = []
        self.odoms = []
        self.truths = []
        self.stalls = []
        self.transforms = []
        self._plan = []
        self._plan_done = threading.Event()
        self._cmd = rospy.Publisher(topic + 'cmd_vel', Twist, queue_size=10)
        self._pose = rospy.Publisher(topic + 'cmd_pose', Pose, queue_size=1)
        self._reset = rospy.ServiceProxy(namespace + 'reset_positions', Empty)
        self._subscribers = [
            rospy.Subscriber(namespace + 'clock' if namespace else '/clock', Clock,
                             self._on_clock, queue_size=100),
            rospy.Subscriber(namespace + 'tf' if namespace else '/tf', TFMessage, self._keep_tf,
                             queue_size=100),
            rospy.Subscriber(topic + scan_topic, LaserScan, self._keep, self.scans, queue_size=100),
            rospy.Subscriber(topic + 'odom', Odometry, self._keep, self.odoms, queue_size=100),
            rospy.Subscriber(topic + 'base_pose_ground_truth', Odometry, self._keep, self.truths,
                             queue_size=100),
            rospy.Subscriber(topic + 'stalled', Bool, self._keep_stalled, queue_size=100),
        ]

    # -- recording -------------------------------------------------------------------
    def _keep(self, msg, store):
        with self._condition:
            store.append(msg)
            self._condition.notify_all()

    def _keep_stalled(self, msg):
        with self._condition:
            self.stalls.append(msg.data)
            self._condition.notify_all()

    def _keep_tf(self, msg):
        with self._condition:
            self.transforms.extend(msg.transforms)
            self._condition.notify_all()

    def _on_clock(self, msg):
        with self._condition:
            self.clock.append(msg.clock.to_sec())
            twist = self._plan.pop(0) if self._plan else None
            if twist is not None and not self._plan:
                self._plan_done.set()
            self._condition.notify_all()
        if twist is not None:
            self._cmd.publish(twist)

    def wait_for(self, predicate, what, limit=WAIT_LIMIT):
        with self._condition:
            if not self._condition.wait_for(predicate, timeout=limit):
                raise AssertionError('timed out waiting for ' + what)

    def wait_ready(self):
        """Waits until the simulator hears our commands and we have heard each
        of its streams: every subscription connects on its own, so ground
        truth arriving says nothing of the scans."""
        self.wait_for(lambda: self._cmd.get_num_connections() > 0 and
                      self._pose.get_num_connections() > 0 and
                      self.scans and self.odoms and self.truths and self.transforms,
                      'the simulator to connect')

    def wait_ticks(self, count):
        """Waits for `count` more /clock ticks; returns the index of the first."""
        with self._condition:
            first = len(self.clock)
        self.wait_for(lambda: len(self.clock) >= first + count, '%d clock ticks' % count)
        return first

    # -- driving ---------------------------------------------------------------------
    def drive(self, v, w, ticks, then_stop=True):
        """Sends (v, w) on each of the next `ticks` clock ticks, then one zero
        Twist (unless then_stop is False), and waits until all are sent."""
        twist = Twist()
        twist.linear.x = v
        twist.angular.z = w
        plan = [twist] * ticks + ([Twist()] if then_stop else [])
        with self._condition:
            self._plan_done.clear()
            self._plan = list(plan)
        if not self._plan_done.wait(WAIT_LIMIT):
            raise AssertionError('could not send %d commands' % len(plan))

    def send_once(self, v, w):
        twist = Twist()
        twist.linear.x = v
        twist.angular.z = w
        self._cmd.publish(twist)

    def teleport(self, x, y, yaw):
        self._pose.publish(pose_message(x, y, yaw))

    def reset(self):
        """reset_positions, then waits until the reset pose is on ground truth."""
        self._reset()
        self.wait_ticks(2)

    def truths_since(self, stamp):
        """Ground truth messages stamped `stamp` or later."""
        with self._condition:
            return [msg for msg in self.truths if msg.header.stamp.to_sec() > stamp - 1e-6]

    def latest_truth(self):
        with self._condition:
            return self.truths[-1]
