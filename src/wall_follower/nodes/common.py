"""ROS plumbing shared by every node that reads the laser or drives the robot."""
import math
import threading

import rospkg
import rospy
from geometry_msgs.msg import Pose, Twist
from sensor_msgs.msg import LaserScan

from wall_follower.control.motion import MAX_ANGULAR, MAX_LINEAR, STOP, Command, clamp
from wall_follower.control.scan import ScanView


def to_twist(command):
    twist = Twist()
    twist.linear.x = command.linear
    twist.angular.z = command.angular
    return twist


class VelocityCommander(object):
    """Publishes clamped commands on cmd_vel and stops the robot on shutdown.

    The limits are the private parameters ~max_linear and ~max_angular,
    defaulting to the real robot's 0.19 m/s and 0.49 rad/s.
    """

    def __init__(self, topic='cmd_vel'):
        self.max_linear = abs(float(rospy.get_param('~max_linear', MAX_LINEAR)))
        self.max_angular = abs(float(rospy.get_param('~max_angular', MAX_ANGULAR)))
        self._pub = rospy.Publisher(topic, Twist, queue_size=1)
        self.last = STOP
        rospy.on_shutdown(self.stop)

    def send(self, command):
        """Clamp and publish a Command; returns what was actually sent."""
        self.last = clamp(Command(*command), self.max_linear, self.max_angular)
        self._pub.publish(to_twist(self.last))
        return self.last

    def stop(self):
        self.send(STOP)


class LatestScan(object):
    """Keeps the newest scan as a ScanView and knows when it has gone stale.

    Age is measured in ROS time from the scan's arrival, so it follows
    simulated time in simulation and does not depend on the laser host's
    clock. The time a scan was taken is its header stamp: the arrival
    time would race the /clock message of the same simulated step, and
    jitter by a step.
    """

    def __init__(self, topic='scan'):
        self._latest = (None, None, None)   # (view, arrival, taken), replaced as one
        self._arrived = threading.Condition()
        self._sub = rospy.Subscriber(topic, LaserScan, self._on_scan, queue_size=1)

    def _on_scan(self, msg):
        arrival = rospy.Time.now()
        taken = msg.header.stamp if not msg.header.stamp.is_zero() else arrival
        self._latest = (ScanView.from_msg(msg), arrival, taken)
        with self._arrived:
            self._arrived.notify_all()

    def wait_for_newer(self, view, timeout):
        """Wait until the latest scan is not `view`, at most timeout wall seconds.

        Lets a controller answer each scan as soon as it arrives instead of
        at its next timer tick: in lockstep simulation a command that merely
        repeats the last one would let the world step on a stale decision.
        """
        with self._arrived:
            if self._latest[0] is view:
                self._arrived.wait(timeout)

    def fresh(self, timeout):
        """The latest scan if it is younger than timeout seconds, else None."""
        return self.fresh_stamped(timeout)[0]

    def fresh_stamped(self, timeout):
        """(view, time taken in s) of the latest scan if it arrived within timeout s, else (None, None)."""
        view, arrival, taken = self._latest
        if view is None or (rospy.Time.now() - arrival).to_sec() > timeout:
            return None, None
        return view, taken.to_sec()


def world_path(world):
    """The .world file meant by a launch file's `world` argument.

    A bare name (`arena`) is a world shipped in this package's worlds/; an
    absolute path is taken as it is, as simulation.launch does.
    """
    if world.startswith('/'):
        return world
    name = world if world.endswith('.world') else world + '.world'
    return '%s/worlds/%s' % (rospkg.RosPack().get_path('wall_follower'), name)


def yaw_of(orientation):
    """Yaw (rad) of a geometry_msgs/Quaternion."""
    q = orientation
    return math.atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z))


def pose_of(odometry):
    """(x, y, yaw) of a nav_msgs/Odometry message."""
    p = odometry.pose.pose
    return p.position.x, p.position.y, yaw_of(p.orientation)


def pose_message(x, y, yaw):
    """A geometry_msgs/Pose at (x, y) turned yaw (rad) about z."""
    pose = Pose()
    pose.position.x, pose.position.y = x, y
    pose.orientation.z, pose.orientation.w = math.sin(yaw / 2.0), math.cos(yaw / 2.0)
    return pose
