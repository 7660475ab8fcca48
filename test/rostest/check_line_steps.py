#!/usr/bin/env python3
"""rostest: the lab's first steps on the line world's camera.

line_mask publishes a mono8 mask holding the yellow line (and nothing of
the white floor) and a debug image with the slice centroid's red dot;
bounds set through dynamic_reconfigure that exclude yellow empty the mask
from the next frame on. camera_view, with no display, writes PNG
snapshots of the camera's frames into ~snapshot_dir.
"""
import glob
import os
import shutil
import sys
import threading
import unittest

import cv2
import dynamic_reconfigure.client
import numpy as np
import rospy
import rostest
from cv_bridge import CvBridge
from sensor_msgs.msg import Image

from waiting import wait_until

LIMIT = 30.0      # wall s


class LineSteps(unittest.TestCase):

    def setUp(self):
        self.bridge = CvBridge()
        self.lock = threading.Lock()
        self.masks, self.debugs = [], []
        rospy.Subscriber('line_mask', Image, self._keep, self.masks, queue_size=1)
        rospy.Subscriber('line_debug', Image, self._keep, self.debugs, queue_size=1)

    def _keep(self, msg, kept):
        with self.lock:
            kept.append(self.bridge.imgmsg_to_cv2(msg))

    def _newest(self, kept, after):
        self.assertTrue(wait_until(lambda: len(kept) > after, LIMIT), 'no new image')
        with self.lock:
            return kept[-1], len(kept)

    def test_mask_debug_image_and_snapshots(self):
        mask, seen = self._newest(self.masks, 0)
        self.assertEqual(mask.dtype, np.uint8)
        self.assertEqual(set(np.unique(mask)) - {0, 255}, set())
        # The robot starts on the line: it runs up the middle of the lower image.
        lower = mask[mask.shape[0] // 2:]
        self.assertGreater((lower > 0).mean(), 0.01)
        self.assertLess((lower > 0).mean(), 0.5)
        debug, _ = self._newest(self.debugs, 0)
        red = (debug[:, :, 2] == 255) & (debug[:, :, 1] == 0) & (debug[:, :, 0] == 0)
        self.assertGreater(red.sum(), 10, 'no red dot on the debug image')
        rows = np.nonzero(red)[0]
        top = rospy.get_param('/line_mask/slice_top') * debug.shape[0]
        self.assertTrue(top - 10 <= rows.mean() <= top + 0.2 * debug.shape[0])

        client = dynamic_reconfigure.client.Client('line_mask', timeout=LIMIT)
        client.update_configuration({'hue_low': 100, 'hue_high': 130})

        def blank():
            with self.lock:
                return len(self.masks) > seen and self.masks[-1].max() == 0
        self.assertTrue(wait_until(blank, LIMIT), 'blue bounds still see yellow')

        directory = rospy.get_param('~snapshot_dir')
        self.addCleanup(shutil.rmtree, directory, True)   # line_steps.test's own folder
        self.assertTrue(wait_until(lambda: glob.glob(os.path.join(directory, '*.png')), LIMIT),
                        'camera_view wrote no snapshot')
        snapshot = cv2.imread(sorted(glob.glob(os.path.join(directory, '*.png')))[0])
        self.assertEqual(snapshot.shape[:2], mask.shape)


if __name__ == '__main__':
    rospy.init_node('check_line_steps')
    rostest.rosrun('wall_follower', 'check_line_steps', LineSteps, sys.argv)
