"""The safety guard of every rostest that drives: limits never exceeded, walls never touched.

Created once the test node is up, it hears every cmd_vel and every
`stalled` message of the built-in simulator from then on, whoever sends
them, so that a test fails on a command above the real robot's limits or
a touch even where its own scoring looks elsewhere.
"""
import threading

import rospy
from geometry_msgs.msg import Twist
from std_msgs.msg import Bool

from wall_follower.control.motion import MAX_ANGULAR, MAX_LINEAR

# Commands are floats on the wire; allow their rounding, nothing more.
LIMIT_SLACK = 1e-6


class DriveGuard(object):
    """Watches cmd_vel and stalled (names relative to namespace)."""

    def __init__(self, namespace=''):
        self._lock = threading.Lock()
        self.max_linear = 0.0
        self.max_angular = 0.0
        self.commands = 0
        self.touched_at = None
        self._subscribers = [
            rospy.Subscriber(namespace + 'cmd_vel', Twist, self._on_cmd, queue_size=1000),
            rospy.Subscriber(namespace + 'stalled', Bool, self._on_stalled, queue_size=1000),
        ]

    def _on_cmd(self, msg):
        with self._lock:
            self.commands += 1
            self.max_linear = max(self.max_linear, abs(msg.linear.x))
            self.max_angular = max(self.max_angular, abs(msg.angular.z))

    def _on_stalled(self, msg):
        if msg.data:
            with self._lock:
                if self.touched_at is None:
                    self.touched_at = rospy.get_time()

    def assert_safe(self, test):
        """Fail `test` (a unittest.TestCase) on a command above the limits or a touch."""
        with self._lock:
            test.assertLessEqual(self.max_linear, MAX_LINEAR + LIMIT_SLACK,
                                 'a command of %.3f m/s' % self.max_linear)
            test.assertLessEqual(self.max_angular, MAX_ANGULAR + LIMIT_SLACK,
                                 'a command of %.3f rad/s' % self.max_angular)
            test.assertIsNone(self.touched_at, 'touched a wall at %s s' % self.touched_at)
