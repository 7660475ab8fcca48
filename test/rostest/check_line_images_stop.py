#!/usr/bin/env python3
"""rostest: line_follower stops the robot within 0.5 s of its camera's last frame.

The follower reads `gated_image`, which this test relays from the
simulator's `image` while the gate is open. After ~drive simulated
seconds of following the line, the gate closes; from ~stop_within
simulated seconds after the last frame relayed (plus one world step, the
time a command takes to show in the ground truth) the robot must not move
again, and the drive guard holds every command to the limits.
"""
import sys
import threading

import numpy as np
import rospy
import rostest
from sensor_msgs.msg import Image

from paused_world import GroundTruthRun
from waiting import wait_until

STEP = 0.1            # simulated s per world step
STILL = 1e-4          # m, rad: a pose within this of the last one has not moved


class ImagesStop(GroundTruthRun):

    def setUp(self):
        self.gate_lock = threading.Lock()
        self.gate_open = True
        self.last_relayed = None
        self.gated = rospy.Publisher('gated_image', Image, queue_size=1)
        self.images = rospy.Subscriber('image', Image, self._on_image, queue_size=1,
                                       buff_size=2 ** 24)
        self.assertTrue(wait_until(lambda: self.gated.get_num_connections() > 0, 30.0),
                        'the follower never subscribed to gated_image')
        GroundTruthRun.setUp(self)

    def _on_image(self, msg):
        with self.gate_lock:
            if self.gate_open:
                self.gated.publish(msg)
                self.last_relayed = msg.header.stamp.to_sec()

    def _now(self):
        with self.lock:
            return self.truth[-1][0] if self.truth else 0.0

    def test_stops_once_the_images_stop(self):
        drive = rospy.get_param('~drive', 3.0)
        stop_within = rospy.get_param('~stop_within', 0.5)
        self.assertTrue(wait_until(lambda: self._now() >= drive, 60.0), 'the world never ran')
        with self.gate_lock:
            self.gate_open = False
            last = self.last_relayed
        self.assertIsNotNone(last, 'no image was ever relayed')
        self.assertTrue(wait_until(lambda: self._now() >= last + stop_within + 2.0, 60.0),
                        'the world stopped running without images')
        with self.lock:
            truth = np.array(self.truth)
        before = truth[truth[:, 0] <= last]
        self.assertGreater(np.hypot(*(before[-1, 1:3] - before[0, 1:3])), 0.2,
                           'the robot did not follow the line before the images stopped')
        after = truth[truth[:, 0] >= last + stop_within + STEP]
        moved = np.abs(after[1:, 1:] - after[:-1, 1:]).max() if len(after) > 1 else 0.0
        rospy.loginfo('images_stop: last image at %.2f s; moved %.6f after %.2f s', last, moved,
                      last + stop_within + STEP)
        self.assertGreater(len(after), 10)
        self.assertLessEqual(moved, STILL, 'the robot still moved %.2f s after the last image'
                             % stop_within)
        self.guard.assert_safe(self)


if __name__ == '__main__':
    rospy.init_node('check_line_images_stop')
    rostest.rosrun('wall_follower', 'check_line_images_stop', ImagesStop, sys.argv)
