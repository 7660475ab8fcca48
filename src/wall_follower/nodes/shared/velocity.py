"""The one way every node that drives publishes cmd_vel: clamped, and stopped on shutdown."""
import threading
import time

import rospy
from geometry_msgs.msg import Twist

from wall_follower.control.motion import STOP, Command, clamp

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
