"""The safety guard of the exercise rostests: no command above the real robot's limits, no contact.

Not a test itself: a test node builds one MotionGuard before the robot
moves and asks it for problems() at the end. It listens to everything
sent on cmd_vel and to the simulator's stalled topic (true while the
robot's footprint touches an obstacle).
"""
import threading

import rospy
from geometry_msgs.msg import Twist
from std_msgs.msg import Bool

from wall_follower.control.motion import MAX_ANGULAR, MAX_LINEAR

# Commands are floats on the wire; allow their rounding, nothing more.
LIMIT_SLACK = 1e-6
QUEUE = 10000


class MotionGuard(object):

    def __init__(self, max_linear=MAX_LINEAR, max_angular=MAX_ANGULAR):
        self.max_linear = max_linear
        self.max_angular = max_angular
        self.lock = threading.Lock()
        self.commands = []          # (linear, angular) in the order sent
        self.stalls = 0
        self.subscribers = [rospy.Subscriber('cmd_vel', Twist, self._on_command, queue_size=QUEUE),
                      rospy.Subscriber('stalled', Bool, self._on_stalled, queue_size=QUEUE)]

    def _on_command(self, msg):
        with self.lock:
            self.commands.append((msg.linear.x, msg.angular.z))

    def _on_stalled(self, msg):
        if msg.data:
            with self.lock:
                self.stalls += 1

    def problems(self):
        """What went wrong so far, in words; empty when nothing did."""
        with self.lock:
            commands, stalls = list(self.commands), self.stalls
        found = []
        fast = [c for c in commands if abs(c[0]) > self.max_linear + LIMIT_SLACK
                or abs(c[1]) > self.max_angular + LIMIT_SLACK]
        if fast:
            found.append('%d command(s) above %.2f m/s or %.2f rad/s, the first %r'
                         % (len(fast), self.max_linear, self.max_angular, fast[0]))
        if stalls:
            found.append('the robot touched an obstacle (%d stalled step(s))' % stalls)
        return found
