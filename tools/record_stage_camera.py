#!/usr/bin/env python3
"""Records real Stage's camera frames for the built-in camera to be held to.

For each reference pose of POSES, writes a copy of the line world with the
robot at that pose, runs real stageros with its window under `xvfb-run -a`
(Stage's camera is read back from its OpenGL window: headless stageros has
none), and keeps the first image published after a few world updates, with
its camera_info and the base_link -> camera transform. The robot never
moves: every pose is its own run, so stock stage_ros 1.8 (no cmd_pose) is
enough. Written to test/data/stage_reference/camera/: one PNG per pose (the
rgba8 image as stageros published it, rows top-down) and camera.json (poses,
camera_info, tf, versions). test/unit/test_sim_camera_reference.py renders
the same poses with the built-in camera.

Needs real Stage and stage_ros (tools/build-real-stage) and this package's
workspace in the shell, and xvfb-run without a display:

    source PREFIX/setup.bash && source WS/devel/setup.bash --extend
    /usr/bin/python3 tools/record_stage_camera.py [--out DIR]

Everything runs on a private master on a free port; every process it starts
is stopped by its id.
"""
import argparse
import datetime
import json
import os
import re
import shutil
import tempfile
import threading

import numpy as np
import rospy
from PIL import Image as PilImage
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import CameraInfo, Image
from tf2_msgs.msg import TFMessage

from real_stage_session import stage_session, start, stop


REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
WORLDS = os.path.join(REPO, 'worlds')
OUT = os.path.join(REPO, 'test', 'data', 'stage_reference', 'camera')
# (world, x, y, yaw_deg, camera z or None): on the line, beside it, across it, in bends
# both ways; the last ones with the camera lowered from its mast (pose z 0.16 in
# waffle_pi.inc) to just above the body, which it then sees in the bottom rows.
POSES = (
    ('line_lab', -0.6, -1.0, 0.0, None),
    ('line_lab', 0.3, -0.95, 10.0, None),
    ('line_lab', 1.2, -0.9, 17.0, None),
    ('line_lab', 1.45, -0.2, 75.0, None),
    ('line_lab', 0.55, 0.9, 180.0, None),
    ('line_lab', -0.2, 0.9, 190.0, None),
    ('line_lab', -1.3, 0.2, -100.0, None),
    ('line_tight', -0.6, -1.0, -30.0, None),
    ('line_tight', 0.45, 0.52, 170.0, None),
    ('line_open', 0.3, -1.3, -40.0, None),
    ('line_lab', -0.6, -1.0, 0.0, 0.03),
    ('line_lab', 1.2, -0.9, 17.0, 0.06),
)
# World updates to wait before a frame counts (Stage renders from its first update on).
SETTLE_UPDATES = 3
FILES_OF_WORLD = ('burger.inc', 'waffle.inc', 'waffle_pi.inc')
ROBOT_POSE = re.compile(r'(turtlebot3_waffle_pi\s*\(\s*name "turtlebot3"\s*pose \[)[^\]]*(\])')
CAMERA_POSE = re.compile(r'(raspicam_v2\( pose \[)[^\]]*(\])')


def world_at(world, x, y, yaw_deg, camera_z, directory):
    """A copy of worlds/<world>.world in `directory` with the robot at the pose (and its
    camera at height camera_z above the body, unless None)."""
    with open(os.path.join(WORLDS, world + '.world')) as stream:
        text = stream.read()
    text, count = ROBOT_POSE.subn(r'\g<1> %.4f %.4f 0 %.4f \g<2>' % (x, y, yaw_deg), text)
    if count != 1:
        raise RuntimeError('%s.world: the robot stanza was not found' % world)
    for name in FILES_OF_WORLD + ('%s_line.png' % world,):
        shutil.copy(os.path.join(WORLDS, name), directory)
    if camera_z is not None:
        include = os.path.join(directory, 'waffle_pi.inc')
        with open(include) as stream:
            robot, count = CAMERA_POSE.subn(r'\g<1> 0 0 %.4f 0 \g<2>' % camera_z, stream.read())
        if count != 1:
            raise RuntimeError('waffle_pi.inc: the camera stanza was not found')
        with open(include, 'w') as stream:
            stream.write(robot)
    path = os.path.join(directory, '%s.world' % world)
    with open(path, 'w') as stream:
        stream.write(text)
    return path


class Catch(object):
    """The first image, camera_info and camera transform after SETTLE_UPDATES clock ticks."""

    def __init__(self):
        self.ticks = 0
        self.done = threading.Event()
        self.image = self.info = self.transform = None
        self.subs = [rospy.Subscriber('/clock', Clock, self.on_clock),
                     rospy.Subscriber('/image', Image, self.on_image, queue_size=5),
                     rospy.Subscriber('/camera_info', CameraInfo, self.on_info, queue_size=5),
                     rospy.Subscriber('/tf', TFMessage, self.on_tf, queue_size=50)]

    def on_clock(self, _msg):
        self.ticks += 1

    def on_image(self, msg):
        if self.ticks >= SETTLE_UPDATES and self.image is None:
            self.image = msg
        self._check()

    def on_info(self, msg):
        if self.info is None:
            self.info = msg
        self._check()

    def on_tf(self, msg):
        for transform in msg.transforms:
            if transform.child_frame_id == 'camera' and self.transform is None:
                self.transform = transform
        self._check()

    def _check(self):
        if self.image is not None and self.info is not None and self.transform is not None:
            self.done.set()

    def close(self):
        for sub in self.subs:
            sub.unregister()


def record_pose(index, pose, wrapper, log, env, out):
    world, x, y, yaw_deg, camera_z = pose
    directory = tempfile.mkdtemp(prefix='stage-camera-world-')
    path = world_at(world, x, y, yaw_deg, camera_z, directory)
    catch = Catch()
    stageros = start(wrapper + ['rosrun', 'stage_ros', 'stageros', path], log, env)
    try:
        if not catch.done.wait(60.0):
            raise RuntimeError('pose %d: no image, camera_info and camera tf within 60 s'
                               % index)
    finally:
        stop(stageros)
        catch.close()
        shutil.rmtree(directory)
    image = catch.image
    if image.encoding != 'rgba8':
        raise RuntimeError('pose %d: image encoding %s, expected rgba8' % (index, image.encoding))
    pixels = np.frombuffer(image.data, dtype=np.uint8).reshape(image.height, image.width, 4)
    name = 'pose_%02d.png' % index
    PilImage.fromarray(pixels[:, :, :3].copy()).save(os.path.join(out, name), optimize=True)
    info = catch.info
    t = catch.transform.transform
    return {'file': name, 'world': world, 'x': x, 'y': y, 'yaw_deg': yaw_deg,
            'camera_z': camera_z,
            'stamp': image.header.stamp.to_sec(), 'frame_id': image.header.frame_id,
            'encoding': image.encoding, 'width': image.width, 'height': image.height,
            'step': image.step,
            'camera_info': {'frame_id': info.header.frame_id, 'width': info.width,
                            'height': info.height, 'K': list(info.K), 'P': list(info.P),
                            'D': list(info.D), 'distortion_model': info.distortion_model},
            'tf': {'parent': catch.transform.header.frame_id,
                   'child': catch.transform.child_frame_id,
                   'translation': [t.translation.x, t.translation.y, t.translation.z],
                   'rotation_xyzw': [t.rotation.x, t.rotation.y, t.rotation.z, t.rotation.w]}}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    parser.add_argument('--out', default=OUT)
    args = parser.parse_args()
    if not os.path.isdir(args.out):
        os.makedirs(args.out)
    with stage_session('record_stage_camera') as (wrapper, log, env):
        rospy.set_param('/use_sim_time', True)
        frames = []
        for index, pose in enumerate(POSES):
            print('== pose %d: %s (%.2f, %.2f, %.1f deg), camera z %s' % ((index,) + pose))
            frames.append(record_pose(index, pose, wrapper, log, env, args.out))
    document = {
        'schema': 'stage_camera/1',
        'description': 'Real Stage camera frames of the line worlds at fixed robot poses '
                       '(the robot placed by the world file, never moved)',
        'versions': 'Stage 4.3.0 (rtv/Stage tag v4.3.0) and stage_ros 1.8.0, built by '
                    'tools/build-real-stage; stageros with its window under xvfb-run -a',
        'recorded_utc': datetime.datetime.utcnow().strftime('%Y-%m-%dT%H:%M:%SZ'),
        'capture': 'first /image after %d /clock ticks; PNGs hold its RGB (alpha is 255)'
                   % SETTLE_UPDATES,
        'frames': frames,
    }
    with open(os.path.join(args.out, 'camera.json'), 'w') as stream:
        json.dump(document, stream, indent=1)
        stream.write('\n')
    print('wrote %s (logs in %s)' % (args.out, env['ROS_LOG_DIR']))


if __name__ == '__main__':
    main()
