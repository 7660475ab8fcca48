#!/usr/bin/env python3
"""rostest: stage_sim says what a world asks of its cameras and cannot have, and draws
what real Stage would.

camera_limits.world has no window, so real stageros would draw its cameras
in its own 600 x 400 window and cap them at its 600 x 370 drawing area; the
robot's camera asks 10000 x 10000 pixels (a frame of 800 MB, which the
simulator once took tens of seconds to draw) and a pantilt of [1000 -1000]
(a pan of -80 deg and a tilt of 80 deg, as real Stage turns it); a second
camera on the robot, a camera in the world and one on a model are not
published by stageros. The simulator, started as a user starts it, must
warn of each, publish 600 x 370 images and camera_info, and end on Ctrl-C;
the same camera in a window that holds more than 1920 x 1080 pixels is
refused with one line.
"""
import math
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import unittest

import rospkg
import rospy
import rostest
from sensor_msgs.msg import CameraInfo, Image

WAIT_LIMIT = 30.0   # wall s for a frame, and for the simulator to end
CAPPED = (600, 370)


def world():
    return os.path.join(rospkg.RosPack().get_path('wall_follower'), 'test', 'rostest',
                        'camera_limits.world')


def stage_sim(name, world_file, log):
    """A stage_sim started as a user starts it, in a session of its own, its output to log."""
    return subprocess.Popen(['rosrun', 'wall_follower', 'stage_sim', world_file,
                             '_speedup:=0', '__name:=' + name], stdout=log,
                            stderr=subprocess.STDOUT, start_new_session=True)


def end(sim):
    """Ctrl-C to a stage_sim that still runs, and its exit status; one that does not end
    within WAIT_LIMIT is killed (status None)."""
    if sim.poll() is None:
        os.killpg(sim.pid, signal.SIGINT)
    try:
        return sim.wait(WAIT_LIMIT)
    except subprocess.TimeoutExpired:
        os.killpg(sim.pid, signal.SIGKILL)
        sim.wait()
        return None


class First(object):
    """The first message of a topic."""

    def __init__(self, topic, kind):
        self.message = None
        self.arrived = threading.Event()
        self.subscriber = rospy.Subscriber(topic, kind, self._on_message, queue_size=1)

    def _on_message(self, message):
        if self.message is None:
            self.message = message
            self.arrived.set()


class CameraLimits(unittest.TestCase):

    def setUp(self):
        self.directory = tempfile.mkdtemp(prefix='camera-limits-')
        self.log = open(os.path.join(self.directory, 'stage_sim.log'), 'w+')

    def tearDown(self):
        self.log.close()
        shutil.rmtree(self.directory)

    def output(self):
        self.log.flush()
        self.log.seek(0)
        return self.log.read()

    def test_capped_frames_and_a_warning_for_each_camera_stageros_would_not_draw(self):
        image, info = First('image', Image), First('camera_info', CameraInfo)
        sim = stage_sim('limits_sim', world(), self.log)
        try:
            self.assertTrue(image.arrived.wait(WAIT_LIMIT) and info.arrived.wait(WAIT_LIMIT),
                            'no image and camera_info: ' + self.output())
        finally:
            status = end(sim)
        output = self.output()
        self.assertEqual(status, 0, output)
        self.assertNotIn('Traceback', output)
        width, height = CAPPED
        self.assertEqual((image.message.width, image.message.height, image.message.encoding),
                         (width, height, 'rgba8'))
        self.assertEqual(len(image.message.data), width * height * 4)
        self.assertEqual((info.message.width, info.message.height), CAPPED)
        # Real stageros' camera_info of a capped camera: its field of view (60 x 45 deg)
        # over the pixels it draws.
        fx = width / (2.0 * math.tan(math.radians(60.0) / 2.0))
        fy = height / (2.0 * math.tan(math.radians(45.0) / 2.0))
        for got, expected in zip(info.message.K, [fx, 0.0, width / 2.0, 0.0, fy, height / 2.0,
                                                  0.0, 0.0, 1.0]):
            self.assertAlmostEqual(got, expected, places=9)
        for says in ('camera resolution [10000 10000] is capped at [600 370], as real Stage '
                     'caps it',
                     'camera pantilt [1000 -1000] is beyond [-180, 180] x [-90, 90] deg',
                     '(a pan of -80 deg, a tilt of 80 deg)',
                     'robot "robot" has a second camera',
                     'camera "on_the_floor" is in the world, not directly in a robot\'s position',
                     'camera "on_the_stand" is in model "stand", not directly in a robot\'s '
                     'position'):
            self.assertIn(says, output)

    def test_more_pixels_than_the_simulator_draws_are_refused_in_one_line(self):
        with open(world()) as stream:
            text = stream.read()
        big = os.path.join(self.directory, 'big_window.world')
        with open(big, 'w') as stream:
            stream.write('window( size [ 3000 3000 ] )\n' + text)
        sim = stage_sim('limits_refused', big, self.log)
        try:
            sim.wait(WAIT_LIMIT)
        except subprocess.TimeoutExpired:
            pass
        status = end(sim)
        output = self.output()
        self.assertEqual(status, 1, output)
        self.assertIn('stage_sim: error: %s:' % big, output)
        self.assertIn('camera resolution [3000 2970] is more than the 2073600 pixels '
                      '(1920 x 1080) this simulator draws', output)
        self.assertNotIn('Traceback', output)


if __name__ == '__main__':
    rospy.init_node('check_camera_limits')
    rostest.rosrun('wall_follower', 'check_camera_limits', CameraLimits, sys.argv)
