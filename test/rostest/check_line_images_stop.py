#!/usr/bin/env python3
"""rostest: line_follower stops the robot within 0.5 s of its camera's last good frame.

The follower reads `gated_image` and `gated_camera_info`, which this test
relays from the simulator's `image` and `camera_info` (with ~compressed, as
JPEG on gated_image/compressed, as the real Waffle Pi's raspicam sends
them). After ~drive simulated seconds of following the line (or from the
start, with ~from_start), the relay stops (~corrupt empty), or goes on with
each frame or camera_info spoilt (~corrupt, one of SPOILERS: frames cut
short, of the wrong size or encoding, empty; frames of no line: all
yellow, noise; a JPEG cut short; a camera_info whose size is not the
frames'; a step that fits another encoding; a stamp in the year 2100):
from ~stop_within simulated seconds after the last good frame (plus one
world step, the time a command takes to show in the ground truth) the
robot must not move, and the last command it was sent must be a stop. A
spoilt frame must be named in a warning, and the node must not die of it:
given good frames again, it drives on. The drive guard holds every command
to the limits.
"""
import sys
import threading
from collections import namedtuple

import cv2
import numpy as np
import rospy
import rostest
from cv_bridge import CvBridge
from geometry_msgs.msg import Twist
from rosgraph_msgs.msg import Log
from sensor_msgs.msg import CameraInfo, CompressedImage, Image

from paused_world import GroundTruthRun
from rosout_log import RosoutLog
from waiting import wait_until

STEP = 0.1            # simulated s per world step
STILL = 1e-4          # m, rad: a pose within this of the last one has not moved
LIMIT = 60.0          # wall s
YEAR_2100 = 4102444800   # s since 1970: a stamp that fits a header, not a Duration from now
NOISE = np.random.RandomState(37)


def _fill(msg, pixel):
    msg.data = bytes(bytearray(pixel) * (msg.width * msg.height))
    msg.step = msg.width * len(pixel)


def _noise(msg):
    msg.data = NOISE.randint(0, 256, len(msg.data), dtype=np.uint8).tobytes()


def _resized(msg, width, height):
    rgba = np.frombuffer(msg.data, np.uint8).reshape(msg.height, msg.width, 4)
    msg.data = cv2.resize(rgba, (width, height), interpolation=cv2.INTER_NEAREST).tobytes()
    msg.width, msg.height, msg.step = width, height, width * 4


def _scaled_info(info, factor):
    info.width, info.height = info.width * factor, info.height * factor
    info.K = [value * factor if index in (0, 2, 4, 5) else value
              for index, value in enumerate(info.K)]
    info.P = [value * factor if index in (0, 2, 5, 6) else value
              for index, value in enumerate(info.P)]


def _cut(msg):
    msg.data = msg.data[:800]


def _future(msg):
    msg.header.stamp = rospy.Time(YEAR_2100)


Spoiler = namedtuple('Spoiler', ['frame', 'info', 'words', 'compressed'])
"""How one kind of bad input is made: what is done to each frame (a raw Image, or with
compressed the CompressedImage) and to each camera_info (None: left alone), and what the
follower's warning must say of it."""

SPOILERS = {
    'truncated': Spoiler(lambda msg: setattr(msg, 'data', msg.data[:len(msg.data) // 2]), None,
                         'bytes of data', False),
    'size': Spoiler(lambda msg: setattr(msg, 'height', msg.height * 2), None, 'bytes of data',
                    False),
    'encoding': Spoiler(lambda msg: setattr(msg, 'encoding', 'h264'), None, 'unknown encoding',
                        False),
    'empty': Spoiler(lambda msg: (setattr(msg, 'height', 0), setattr(msg, 'width', 0),
                                  setattr(msg, 'data', b'')), None, 'empty image', False),
    'yellow': Spoiler(lambda msg: _fill(msg, (255, 255, 0, 255)), None, 'no line:', False),
    'noise': Spoiler(_noise, None, 'no line:', False),
    'rgba_as_bgr8': Spoiler(lambda msg: setattr(msg, 'encoding', 'bgr8'), None,
                            'another encoding', False),
    'future': Spoiler(_future, None, 'ahead of this node', False),
    'frames_large': Spoiler(lambda msg: _resized(msg, 1920, 1080), None, 'camera_info says',
                            False),
    'info_large': Spoiler(None, lambda info: _scaled_info(info, 2), 'camera_info says', False),
    'jpeg_cut': Spoiler(_cut, None, 'JPEG cut short', True),
}


class ImagesStop(GroundTruthRun):

    def setUp(self):
        self.gate_lock = threading.Lock()
        self.relaying = 'good'         # good, spoilt, or none
        self.corrupt = rospy.get_param('~corrupt', '')
        self.spoiler = SPOILERS.get(self.corrupt)
        self.last_good = None
        self.first_spoilt = None
        self.last_command = None
        self.compressed = rospy.get_param('~compressed', False)
        if self.corrupt:
            self.assertIsNotNone(self.spoiler, 'no such spoiler: %r' % self.corrupt)
            self.assertEqual(self.compressed, self.spoiler.compressed,
                             '%s spoils %s frames' % (self.corrupt, 'compressed'
                                                      if self.spoiler.compressed else 'raw'))
        if rospy.get_param('~from_start', False):
            self.relaying = 'spoilt'
        if self.compressed:
            self.bridge = CvBridge()
            self.gated = rospy.Publisher('gated_image/compressed', CompressedImage,
                                         queue_size=1)
        else:
            self.gated = rospy.Publisher('gated_image', Image, queue_size=1)
        self.gated_info = rospy.Publisher('gated_camera_info', CameraInfo, queue_size=1)
        self.images = rospy.Subscriber('image', Image, self._on_image, queue_size=1,
                                       buff_size=2 ** 24)
        self.infos = rospy.Subscriber('camera_info', CameraInfo, self._on_info, queue_size=1)
        self.commands = rospy.Subscriber('cmd_vel', Twist, self._on_command, queue_size=1)
        for publisher in (self.gated, self.gated_info):
            self.assertTrue(wait_until(lambda: publisher.get_num_connections() > 0, LIMIT),
                            'the follower never subscribed to %s' % publisher.resolved_name)
        self.log = RosoutLog('/line_follower')
        GroundTruthRun.setUp(self)

    def _on_image(self, msg):
        with self.gate_lock:
            if self.relaying == 'good':
                self.gated.publish(self._compressed(msg) if self.compressed else msg)
                self.last_good = msg.header.stamp.to_sec()
            elif self.relaying == 'spoilt':
                if self.first_spoilt is None:
                    self.first_spoilt = msg.header.stamp.to_sec()
                if self.compressed:
                    msg = self._compressed(msg)
                if self.spoiler.frame is not None:
                    self.spoiler.frame(msg)
                self.gated.publish(msg)

    def _on_info(self, msg):
        with self.gate_lock:
            if self.relaying == 'spoilt' and self.spoiler.info is not None:
                self.spoiler.info(msg)
            self.gated_info.publish(msg)

    def _on_command(self, msg):
        self.last_command = (msg.linear.x, msg.angular.z)

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
        from_start = self.relaying == 'spoilt'
        if not from_start:
            self.assertTrue(wait_until(lambda: self._now() >= drive, LIMIT),
                            'the world never ran')
            with self.gate_lock:
                self.relaying = 'spoilt' if self.corrupt else 'none'
                last = self.last_good
            self.assertIsNotNone(last, 'no image was ever relayed')
        else:
            self.assertTrue(wait_until(lambda: self.first_spoilt is not None, LIMIT),
                            'no image was ever relayed')
            last = self.first_spoilt
        self.assertTrue(wait_until(lambda: self._now() >= last + stop_within + 2.0, LIMIT),
                        'the world stopped running without good images')
        truth = self._truth()
        if not from_start:
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
        self.assertEqual(self.last_command, (0.0, 0.0), 'the last command was not a stop')
        if self.corrupt:
            words = self.spoiler.words
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
