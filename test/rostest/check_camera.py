#!/usr/bin/env python3
"""rostest: the builtin simulator's camera topics, as stageros offers them.

Runs against camera.test: a line world whose robot carries a camera and
starts on the line, facing along it. The camera's geometry is read from the
same world file, so no resolution or field of view is written here.
"""
import sys
import threading
import unittest

import numpy as np
import rospy
import rostest
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import CameraInfo, Image
from tf2_msgs.msg import TFMessage

from wall_follower.sim.camera import camera_intrinsics, camera_mount
from wall_follower.sim.stage_interface import world_path
from wall_follower.sim.worldfile import load_world

WAIT_LIMIT = 20.0
DT = 0.1
QUIET_TICKS = 5


class Recorder(object):
    """Keeps every /clock tick, camera_info, camera transform and image or depth frame."""

    def __init__(self):
        self.condition = threading.Condition()
        self.clock = []
        self.infos = []
        self.camera_tf = []
        self.images = []
        self.depths = []
        self.subs = [rospy.Subscriber('/clock', Clock, self._on_clock, queue_size=100),
                     rospy.Subscriber('camera_info', CameraInfo, self._keep, self.infos,
                                      queue_size=100),
                     rospy.Subscriber('/tf', TFMessage, self._on_tf, queue_size=100)]
        self.image_sub = None

    def _on_clock(self, msg):
        self._keep(msg.clock.to_sec(), self.clock)

    def _on_tf(self, msg):
        for transform in msg.transforms:
            if transform.child_frame_id == 'camera':
                self._keep(transform, self.camera_tf)

    def _keep(self, item, store):
        with self.condition:
            store.append(item)
            self.condition.notify_all()

    def wait_for(self, predicate, what):
        with self.condition:
            if not self.condition.wait_for(predicate, timeout=WAIT_LIMIT):
                raise AssertionError('timed out waiting for ' + what)

    def wait_ticks(self, count):
        first = len(self.clock)
        self.wait_for(lambda: len(self.clock) >= first + count, '%d clock ticks' % count)

    def watch(self, topic, store):
        """Subscribe to image or depth (one at a time), keeping what arrives in `store`."""
        self.unwatch()
        self.image_sub = rospy.Subscriber(topic, Image, self._keep, store, queue_size=100)

    def unwatch(self):
        if self.image_sub is not None:
            self.image_sub.unregister()
            self.image_sub = None

    def counts(self):
        with self.condition:
            return len(self.infos), len(self.camera_tf)


class CameraTopics(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        rospy.init_node('check_camera')
        cls.robot = load_world(world_path(rospy.get_param('~world'))).robots[0]
        cls.rec = Recorder()
        cls.rec.wait_ticks(3)

    def assert_falls_quiet(self):
        """camera_info and the camera tf stop once the last image or depth subscriber
        has gone (the simulator learns it when the connection closes, some steps later)
        and stay stopped for QUIET_TICKS steps."""
        deadline = rospy.get_time() + WAIT_LIMIT
        while True:
            before = self.rec.counts()
            self.rec.wait_ticks(QUIET_TICKS)
            if self.rec.counts() == before:
                return
            self.assertLess(rospy.get_time(), deadline, 'camera topics go on with no '
                            'image or depth subscriber')

    def test_camera_only_while_subscribed_once_per_step(self):
        self.rec.wait_ticks(QUIET_TICKS)
        self.assertEqual(self.rec.counts(), (0, 0),
                         'camera_info or tf published before anyone subscribed to image')
        images = []
        self.rec.watch('image', images)
        self.rec.wait_for(lambda: len(images) >= 6, 'six images')
        self.rec.unwatch()
        width, height = self.robot.camera.resolution
        stamps = [msg.header.stamp.to_sec() for msg in images]
        # Each topic has its own connection: let the others catch up with the images.
        self.rec.wait_for(
            lambda: self.rec.clock and self.rec.clock[-1] >= stamps[-1] and
            set(stamps) <= set(m.header.stamp.to_sec() for m in self.rec.infos) and
            set(stamps) <= set(t.header.stamp.to_sec() for t in self.rec.camera_tf),
            'the clock, camera_info and tf of every image step')
        for earlier, later in zip(stamps, stamps[1:]):
            self.assertAlmostEqual(later - earlier, DT, delta=1e-9, msg='not once per step')
        self.assertTrue(set(round(s, 6) for s in stamps) <=
                        set(round(s, 6) for s in self.rec.clock), 'stamps not the steps\' times')
        image = images[-1]
        self.assertEqual((image.encoding, image.width, image.height, image.step),
                         ('rgba8', width, height, 4 * width))
        self.assertEqual(image.header.frame_id, 'camera')
        pixels = np.frombuffer(image.data, dtype=np.uint8).reshape(height, width, 4)
        yellow = (pixels[:, :, 0] > 150) & (pixels[:, :, 1] > 150) & (pixels[:, :, 2] < 100)
        # On the line, facing along it: the line runs up the middle, wider in the near
        # (bottom, as rows run top-down) than in the far rows.
        bottom, top = np.nonzero(yellow[-1])[0], np.nonzero(yellow[0])[0]
        self.assertTrue(len(bottom) > len(top) > 0, 'rows not top-down, or no line')
        self.assertLess(abs(bottom.mean() - width / 2.0), width / 6.0)
        self.assertTrue((pixels[:, :, 3] == 255).all())
        fx, fy, cx, cy = camera_intrinsics(self.robot.camera)
        infos = [m for m in self.rec.infos if m.header.stamp.to_sec() in stamps]
        self.assertEqual(len(infos), len(stamps), 'camera_info not with every image')
        info = infos[-1]
        self.assertEqual((info.width, info.height, info.header.frame_id), (width, height, 'camera'))
        self.assertEqual(list(info.K), [fx, 0.0, cx, 0.0, fy, cy, 0.0, 0.0, 1.0])
        mount = camera_mount(self.robot)
        sent = [t for t in self.rec.camera_tf if t.header.stamp.to_sec() in stamps]
        self.assertEqual(len(sent), len(stamps), 'tf base_link -> camera not with every image')
        transform = sent[-1]
        self.assertEqual(transform.header.frame_id, 'base_link')
        translation = transform.transform.translation
        rotation = transform.transform.rotation
        self.assertEqual((translation.x, translation.y, translation.z), mount[:3])
        self.assertEqual((rotation.x, rotation.y, rotation.z, rotation.w), mount.rotation)
        self.assert_falls_quiet()

        depths = []
        self.rec.watch('depth', depths)
        self.rec.wait_for(lambda: len(depths) >= 2, 'two depth images')
        self.rec.unwatch()
        depth = depths[-1]
        self.assertEqual((depth.encoding, depth.width, depth.height, depth.step),
                         ('32FC1', width, height, 4 * width))
        values = np.frombuffer(depth.data, dtype=np.float32).reshape(height, width)
        near, far = self.robot.camera.range
        centre = values[height // 2, width // 2]
        # The floor straight ahead, along the optical axis: height / sin(tilt).
        tilt = self.robot.camera.pantilt[1]
        self.assertAlmostEqual(centre, self.robot.camera.height / np.sin(tilt), delta=0.01)
        self.assertTrue(((values > near) | np.isinf(values)).all())
        self.assert_falls_quiet()


if __name__ == '__main__':
    rostest.rosrun('wall_follower', 'check_camera', CameraTopics, sys.argv)
