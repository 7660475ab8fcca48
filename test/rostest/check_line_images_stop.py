#!/usr/bin/env python3
"""rostest: line_follower stops the robot within 0.5 s of its camera's last good frame.

The follower reads `gated_image`, which this test relays from the
simulator's `image` (with ~compressed, as JPEG on gated_image/compressed,
as the real Waffle Pi's raspicam sends them). After ~drive simulated seconds of following the
line, the relay stops (~corrupt empty), or goes on with each frame spoilt
(~corrupt: truncated, size, encoding or empty): from ~stop_within
simulated seconds after the last good frame (plus one world step, the
time a command takes to show in the ground truth) the robot must not move.
A spoilt frame must be named in a warning, and the node must not die of
it: given good frames again, it drives on. The drive guard holds every
command to the limits.
"""
import sys
import threading

import cv2
import numpy as np
import rospy
import rostest
from cv_bridge import CvBridge
from rosgraph_msgs.msg import Log
from sensor_msgs.msg import CompressedImage, Image

from paused_world import GroundTruthRun
from rosout_log import RosoutLog
from waiting import wait_until

STEP = 0.1            # simulated s per world step
STILL = 1e-4          # m, rad: a pose within this of the last one has not moved
LIMIT = 60.0          # wall s

# How each kind of spoilt frame is made, and what the warning must say of it.
SPOILERS = {
    'truncated': (lambda msg: setattr(msg, 'data', msg.data[:len(msg.data) // 2]),
                  'bytes of data'),
    'size': (lambda msg: setattr(msg, 'height', msg.height * 2), 'bytes of data'),
    'encoding': (lambda msg: setattr(msg, 'encoding', 'h264'), 'unknown encoding'),
    'empty': (lambda msg: (setattr(msg, 'height', 0), setattr(msg, 'width', 0),
                           setattr(msg, 'data', b'')), 'empty image'),
}


class ImagesStop(GroundTruthRun):

    def setUp(self):
        self.gate_lock = threading.Lock()
        self.relaying = 'good'         # good, spoilt, or none
        self.corrupt = rospy.get_param('~corrupt', '')
        self.last_good = None
        self.compressed = rospy.get_param('~compressed', False)
        self.assertFalse(self.compressed and self.corrupt, 'spoilt frames are raw frames')
        if self.compressed:
            self.bridge = CvBridge()
            self.gated = rospy.Publisher('gated_image/compressed', CompressedImage,
                                         queue_size=1)
        else:
            self.gated = rospy.Publisher('gated_image', Image, queue_size=1)
        self.images = rospy.Subscriber('image', Image, self._on_image, queue_size=1,
                                       buff_size=2 ** 24)
        self.assertTrue(wait_until(lambda: self.gated.get_num_connections() > 0, LIMIT),
                        'the follower never subscribed to %s' % self.gated.resolved_name)
        self.log = RosoutLog('/line_follower')
        GroundTruthRun.setUp(self)

    def _on_image(self, msg):
        with self.gate_lock:
            if self.relaying == 'good':
                self.gated.publish(self._compressed(msg) if self.compressed else msg)
                self.last_good = msg.header.stamp.to_sec()
            elif self.relaying == 'spoilt':
                SPOILERS[self.corrupt][0](msg)
                self.gated.publish(msg)

    def _compressed(self, msg):
        ok, data = cv2.imencode('.jpg', self.bridge.imgmsg_to_cv2(msg, 'bgr8'))
        return CompressedImage(header=msg.header, format='jpeg', data=data.tobytes())

    def _now(self):
        with self.lock:
            return self.truth[-1][0] if self.truth else 0.0

    def _truth(self):
        with self.lock:
            return np.array(self.truth)

    def test_stops_without_good_images(self):
        drive = rospy.get_param('~drive', 3.0)
        stop_within = rospy.get_param('~stop_within', 0.5)
        self.assertTrue(wait_until(lambda: self._now() >= drive, LIMIT), 'the world never ran')
        with self.gate_lock:
            self.relaying = 'spoilt' if self.corrupt else 'none'
            last = self.last_good
        self.assertIsNotNone(last, 'no image was ever relayed')
        self.assertTrue(wait_until(lambda: self._now() >= last + stop_within + 2.0, LIMIT),
                        'the world stopped running without good images')
        truth = self._truth()
        before = truth[truth[:, 0] <= last]
        self.assertGreater(np.hypot(*(before[-1, 1:3] - before[0, 1:3])), 0.2,
                           'the robot did not follow the line before the images stopped')
        after = truth[(truth[:, 0] >= last + stop_within + STEP)]
        moved = np.abs(after[1:, 1:] - after[:-1, 1:]).max() if len(after) > 1 else 0.0
        rospy.loginfo('images_stop %s: last good image at %.2f s; moved %.6f after %.2f s',
                      self.corrupt or 'none', last, moved, last + stop_within + STEP)
        self.assertGreater(len(after), 10)
        self.assertLessEqual(moved, STILL, 'the robot still moved %.2f s after the last good '
                             'image' % stop_within)
        if self.corrupt:
            words = SPOILERS[self.corrupt][1]
            self.assertTrue(wait_until(lambda: self.log.said('/line_follower', words, Log.WARN),
                                       LIMIT), 'no warning saying "%s"' % words)
            self.assertFalse(self.log.lines('/line_follower', 'Traceback'))
            with self.gate_lock:
                self.relaying = 'good'
            stopped = truth[-1, 1:3]
            self.assertTrue(wait_until(lambda: np.hypot(*(self._truth()[-1, 1:3] - stopped))
                                       > 0.1, LIMIT), 'did not drive on with good images again')
        self.guard.assert_safe(self)


if __name__ == '__main__':
    rospy.init_node('check_line_images_stop')
    rostest.rosrun('wall_follower', 'check_line_images_stop', ImagesStop, sys.argv)
