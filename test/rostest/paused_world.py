"""Let a simulator started paused go once a test node hears everything it scores.

A check that connects late misses the start of the run (and in lockstep the
robot may have driven a whole side by then), so the exercise rostests start
the simulator paused and unpause it from here.
"""
import threading
import time
import unittest

import rospy
from drive_guard import DriveGuard
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry
from std_msgs.msg import Bool
from std_srvs.srv import Empty
from waiting import wait_until

from wall_follower.nodes.shared.messages import pose_of

TRUTH_QUEUE = 100000   # ground truth messages held while the test is busy


def start_world(subscribers, limit=30.0):
    """Unpause the simulator once every subscriber has a publisher; False if that never came.

    rospy shares one connection per topic among a process's subscribers, so
    a subscriber passed here stands for every other one on its topic (the
    drive guard's among them).
    """
    started = time.monotonic()
    if not wait_until(lambda: all(sub.get_num_connections() > 0 for sub in subscribers), limit):
        return False
    left = max(1.0, limit - (time.monotonic() - started))
    rospy.wait_for_service('unpause_physics', timeout=left)
    rospy.ServiceProxy('unpause_physics', Empty)()
    return True


class GroundTruthRun(unittest.TestCase):
    """A rostest of a node that drives a paused world: the drive guard, and every
    ground-truth pose as (stamp, x, y, yaw) in self.truth (under self.lock),
    from the first step on."""

    def setUp(self):
        self.guard = DriveGuard()
        self.lock = threading.Lock()
        self.truth = []
        truth = rospy.Subscriber('base_pose_ground_truth', Odometry, self._on_truth,
                                 queue_size=TRUTH_QUEUE)
        listening = [truth, rospy.Subscriber('cmd_vel', Twist, lambda _: None),
                     rospy.Subscriber('stalled', Bool, lambda _: None)]
        self.assertTrue(start_world(listening), 'the simulator or the node never connected')

    def _on_truth(self, msg):
        with self.lock:
            self.truth.append((msg.header.stamp.to_sec(),) + pose_of(msg))
