"""ROS plumbing shared by every node that reads the laser or drives the robot."""
import math
import os
import threading
import time
from collections import namedtuple

import rospy
from geometry_msgs.msg import Pose, Twist
from sensor_msgs.msg import LaserScan

from wall_follower.control.motion import STOP, Command, clamp
from wall_follower.control.scan_check import check_scan
from wall_follower.control.stamps import ahead_problem
from wall_follower.nodes import signals
from wall_follower.params.driving import LASER_INPUT


FLUSH_WAIT = 0.5    # wall s a node's last stop may take to leave, at most
FLUSH_POLL = 0.005  # wall s between two looks


def to_twist(command):
    twist = Twist()
    twist.linear.x = command.linear
    twist.angular.z = command.angular
    return twist


class VelocityCommander(object):
    """Publishes clamped commands on a topic and stops the robot on shutdown.

    The limits (m/s, rad/s) are the node's parameters (params.driving's
    max_linear and max_angular); they may be changed between two commands.
    Shutdown sends one zero Twist, and nothing goes out after it: a
    controller thread still answering a scan must not follow it with a last
    move, and rospy closes the topic once its shutdown hooks have run (a
    publish then raises).
    """

    def __init__(self, topic, max_linear, max_angular):
        self.max_linear = abs(max_linear)
        self.max_angular = abs(max_angular)
        self._pub = rospy.Publisher(topic, Twist, queue_size=1)
        self._lock = threading.Lock()
        self._halted = False
        self.last = STOP
        rospy.on_shutdown(self._halt)

    def send(self, command):
        """Clamp and publish a Command; returns what was actually sent (after shutdown
        began: nothing more, and STOP, the last command sent)."""
        with self._lock:
            if not self._halted:
                self._publish(clamp(Command(*command), self.max_linear, self.max_angular))
            return self.last

    def stop(self):
        self.send(STOP)

    def _publish(self, command):
        self._pub.publish(to_twist(command))
        self.last = command

    def _halt(self):
        with self._lock:
            written = self._written()
            self._publish(STOP)
            self._halted = True
        self._wait_written(written)

    def _written(self):
        """connection id -> (messages written to it, whether it is open), from the
        publisher's bus statistics (what `rosnode info` shows)."""
        return dict((c[0], (c[2], c[3])) for c in self._pub.impl.get_stats()[2])

    def _wait_written(self, before):
        """Wait, at most FLUSH_WAIT wall s, until the stop is written to every subscriber
        connected before it.

        rospy writes a queued message from a thread of each connection, and
        closes the connections right after the shutdown hooks: a stop still
        queued then is never sent, and the robot's last command stays a move.
        """
        deadline = time.monotonic() + FLUSH_WAIT
        while time.monotonic() < deadline:
            now = self._written()
            if all(key not in now or now[key][0] > count or not now[key][1]
                   for key, (count, _) in before.items()):
                return
            time.sleep(FLUSH_POLL)


def init_node(name):
    """rospy.init_node, with SIGINT and SIGTERM answered from a thread of the node's own.

    rospy runs its shutdown hooks inside its signal handler, that is in the
    main thread wherever the signal caught it. A hook that publishes (every
    driving node's last stop) then deadlocks on a publisher lock whenever
    the signal lands while the main thread is publishing, and the node
    never exits. Here the handler only wakes a thread that shuts rospy down,
    by a byte written to a pipe: it takes no lock, so a second signal that
    lands while the first is being answered cannot block on one.

    The handler is in force before rospy.init_node starts, which can take
    seconds (registering with the master, reading /use_sim_time): a signal
    then ends the start-up, and the node exits quietly, having driven
    nothing. (Before this call, nodes.signals answers.)
    """
    caught = []
    wake_read, wake_write = os.pipe()
    os.set_blocking(wake_write, False)   # a pipe full of signals already holds a wake-up

    def shut_down():
        number = os.read(wake_read, 1)[0]
        rospy.signal_shutdown('signal %d' % number)

    def on_signal(number):
        caught.append(number)
        try:
            os.write(wake_write, bytes([number]))
        except BlockingIOError:
            pass

    threading.Thread(target=shut_down, name='shutdown', daemon=True).start()
    signals.answer_with(on_signal)
    try:
        rospy.init_node(name, disable_signals=True)
    except rospy.ROSInitException:
        if not caught:
            raise
    if caught:
        raise SystemExit(0)


Reading = namedtuple('Reading', ['check', 'view', 'taken', 'problem'])
"""What LatestScan holds: the ScanCheck (None before any scan), and either a
usable scan's view and time taken [s] or, both None, what is wrong."""


class LatestScan(object):
    """Keeps the newest scan, checked by check_scan, and knows when it has gone stale.

    Age is measured in ROS time from the scan's arrival, so it follows
    simulated time in simulation and does not depend on the laser host's
    clock. The time a scan was taken is its header stamp: the arrival
    time would race the /clock message of the same simulated step, and
    jitter by a step.
    """

    parameters = LASER_INPUT   # the node's parameters that set a DriveLoop on it

    def __init__(self, topic='scan'):
        self._latest = (None, None, None)   # (ScanCheck, arrival, taken), replaced as one
        self._arrived = threading.Condition()
        self._sub = rospy.Subscriber(topic, LaserScan, self._on_scan, queue_size=1)

    def _on_scan(self, msg):
        arrival = rospy.Time.now()
        taken = msg.header.stamp if not msg.header.stamp.is_zero() else arrival
        with self._arrived:
            self._latest = (check_scan(msg), arrival, taken)
            self._arrived.notify_all()

    @property
    def topic(self):
        """The scan topic's resolved name."""
        return self._sub.resolved_name

    def taken(self):
        """When the newest scan was taken (rospy.Time), usable or not; None before any."""
        return self._latest[2]

    def forget(self):
        """Drop the scan held, e.g. one that arrived on a clock that has since moved back."""
        self._latest = (None, None, None)

    def wait_for_newer(self, seen, timeout):
        """Wait until a scan newer than `seen` (a Reading's check) comes, at most timeout wall s.

        Lets a controller answer each scan as soon as it arrives instead of
        at its next timer tick: in lockstep simulation a command that merely
        repeats the last one would let the world step on a stale decision.
        """
        with self._arrived:
            if self._latest[0] is seen:
                self._arrived.wait(timeout)

    def _arrival_dated(self, now):
        """The newest (check, arrival, taken), a scan that came before this node's
        clock first ran dated from now.

        On simulated time ROS time reads 0 until the node's first /clock,
        which may come a second after its first scans: aged from 0, such a
        scan would look a second old the moment the clock starts, and a
        node with patience would give up on a laser that works.
        """
        with self._arrived:
            check, arrival, taken = self._latest
            if check is not None and arrival.is_zero() and not now.is_zero():
                arrival, taken = now, (now if taken.is_zero() else taken)
                self._latest = (check, arrival, taken)
            return check, arrival, taken

    def latest(self, timeout):
        """The newest scan as a Reading: its view and time taken [s] if usable and fresh,
        else None for both and the problem, in words.

        A scan stamped far ahead of this node's clock (control.stamps) is
        stale, however fresh its arrival: its stamp would time a controller's
        work on a moment that never comes.
        """
        now = rospy.Time.now()
        check, arrival, taken = self._arrival_dated(now)
        if check is None or (now - arrival).to_sec() > timeout:
            problem = 'no scan on %s for %.1f s' % (self.topic, timeout)
            return Reading(check, None, None, problem)
        if check.view is None:
            problem = 'the scan on %s is unusable: %s' % (self.topic, check.problem)
            return Reading(check, None, None, problem)
        ahead = ahead_problem(taken.to_sec(), now.to_sec())
        if ahead is not None:
            return Reading(check, None, None, 'the scan on %s is stale: %s' % (self.topic, ahead))
        return Reading(check, check.view, taken.to_sec(), None)


def yaw_of(orientation):
    """Yaw (rad) of a geometry_msgs/Quaternion."""
    q = orientation
    return math.atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z))


def pose_of(odometry):
    """(x, y, yaw) of a nav_msgs/Odometry message."""
    p = odometry.pose.pose
    return p.position.x, p.position.y, yaw_of(p.orientation)


def quaternion_z(yaw):
    """(z, w) of the unit quaternion of a rotation by yaw (rad) about the z axis."""
    return math.sin(yaw / 2.0), math.cos(yaw / 2.0)


def pose_message(x, y, yaw):
    """A geometry_msgs/Pose at (x, y) turned yaw (rad) about z."""
    pose = Pose()
    pose.position.x, pose.position.y = x, y
    pose.orientation.z, pose.orientation.w = quaternion_z(yaw)
    return pose


def wait_in_wall_time(wait, timeout):
    """wait()'s answer if it comes within timeout wall seconds, else False.

    wait is a call that blocks until what it waits for is there, or until
    rospy shuts down (actionlib's wait_for_server() with no time-out, say).
    The time-outs of actionlib's waits are counted in ROS time, which
    stands still on simulated time while nobody publishes /clock: a wait
    meant to give up after some seconds would then wait for ever. This one
    counts wall seconds. A wait still blocked when they are up goes on in a
    daemon thread, which ends with rospy and never keeps the process alive.
    """
    answer = []
    thread = threading.Thread(target=lambda: answer.append(wait()))
    thread.daemon = True
    thread.start()
    thread.join(timeout)
    return bool(answer and answer[0])
