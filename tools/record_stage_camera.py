#!/usr/bin/env python3
"""Records real Stage's camera frames for the built-in camera to be held to.

For each reference frame of FRAMES, writes a copy of its world with the
robot at the frame's pose and the camera moved and turned as it says
(stage_camera_frames.world_at), runs real stageros with its window under
`xvfb-run -a` (Stage's camera is read back from its OpenGL window: headless
stageros has none), and keeps the first image published after a few world
updates, with its camera_info and the base_link -> camera transform. The
robot never moves: every frame is its own run, so stock stage_ros 1.8 (no
cmd_pose) is enough. First the unseen line worlds of
test/data/stage_reference/camera/worlds/ are redrawn from their course
files. Written to test/data/stage_reference/camera/: one PNG per frame (the
rgba8 image as stageros published it, rows top-down) and camera.json
(frames, camera_info, tf, versions). test/unit/test_sim_camera_reference.py
renders the same frames with the built-in camera.

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
import shutil
import tempfile
import threading

import numpy as np
import rospy
from PIL import Image as PilImage
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import CameraInfo, Image
from tf2_msgs.msg import TFMessage

from real_stage_session import stage_session
from stage_camera_frames import DATA, make_unseen_worlds, world_at

# (world, x, y, yaw_deg, camera): the robot's pose (None: the world file's own) and what
# to change of the Waffle Pi's camera (worlds/waffle_pi.inc: on a mast, pose
# [0 0 0.16 0], pantilt [0 40]): its `pose` [x y z yaw], its `pantilt` [pan tilt].
LOWERED = {'pose': (0.0, 0.0, 0.03, 0.0)}
FRAMES = (
    # The course's worlds: on the line, beside it, across it, in bends both ways; the
    # camera lowered from its mast to just above the body, which it then sees.
    ('line_lab', -0.6, -1.0, 0.0, {}),
    ('line_lab', 0.3, -0.95, 10.0, {}),
    ('line_lab', 1.2, -0.9, 17.0, {}),
    ('line_lab', 1.45, -0.2, 75.0, {}),
    ('line_lab', 0.55, 0.9, 180.0, {}),
    ('line_lab', -0.2, 0.9, 190.0, {}),
    ('line_lab', -1.3, 0.2, -100.0, {}),
    ('line_tight', -0.6, -1.0, -30.0, {}),
    ('line_tight', 0.45, 0.52, 170.0, {}),
    ('line_open', 0.3, -1.3, -40.0, {}),
    ('line_lab', -0.6, -1.0, 0.0, LOWERED),
    ('line_lab', 1.2, -0.9, 17.0, {'pose': (0.0, 0.0, 0.06, 0.0)}),
    # Unseen line worlds, oblique views: the line crosses the view at 30 to 70 deg from
    # 0.35 to 0.8 m ahead (picked at random, kept where it shows).
    ('line_hairpins', 0.057, -0.123, -67.4, {}),
    ('line_hairpins', -0.543, -0.330, 68.9, {}),
    ('line_hairpins', -0.730, -0.174, -33.6, {}),
    ('line_hairpins', -0.393, -0.265, -62.3, {}),
    ('line_zigzag', -0.821, 0.106, -103.8, {}),
    ('line_zigzag', -1.236, -0.325, -23.0, {}),
    ('line_zigzag', -1.285, -0.128, -45.9, {}),
    ('line_zigzag', -0.290, -0.278, 113.7, {}),
    ('line_wave', 1.980, -0.628, 153.8, {}),
    ('line_wave', -1.188, 0.462, -57.7, {}),
    ('line_wave', 0.665, -0.499, 19.4, {}),
    ('line_wave', -0.774, -0.113, 136.1, {}),
    # The camera ahead of the robot's centre and tilted less than half its vertical field
    # of view: its own box shows above the horizon.
    ('line_hairpins', -0.730, -0.174, -33.6, {'pose': (0.05, 0.0, 0.16, 0.0),
                                              'pantilt': (0, 20)}),
    ('line_zigzag', -1.236, -0.325, -23.0, {'pose': (0.1, 0.03, 0.12, 0.0),
                                            'pantilt': (0, 8)}),
    # Panned, and turned by angles beyond a turn (as [40 40]: Stage takes any angle).
    ('line_wave', 0.665, -0.499, 19.4, {'pantilt': (-25, 55)}),
    ('line_wave', -1.188, 0.462, -57.7, {'pantilt': (400, -320)}),
    ('line_hairpins', 0.057, -0.123, -67.4, LOWERED),
    # Floating boxes before a level camera: every edge at a place written in the world.
    ('camera_calibration', None, None, None, {}),
)
# World updates to wait before a frame counts (Stage renders from its first update on).
SETTLE_UPDATES = 3


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


def record_frame(index, frame, wrapper, log, env, group, out):
    world, x, y, yaw_deg, camera = frame
    directory = tempfile.mkdtemp(prefix='stage-camera-world-')
    pose = None if x is None else (x, y, yaw_deg)
    path = world_at(world, pose, camera, directory)
    catch = Catch()
    stageros = group.start(wrapper + ['rosrun', 'stage_ros', 'stageros', path], env, log)
    try:
        if not catch.done.wait(60.0):
            raise RuntimeError('frame %d: no image, camera_info and camera tf within 60 s'
                               % index)
    finally:
        group.end(stageros)
        catch.close()
        shutil.rmtree(directory)
    image = catch.image
    if image.encoding != 'rgba8':
        raise RuntimeError('frame %d: image encoding %s, expected rgba8'
                           % (index, image.encoding))
    pixels = np.frombuffer(image.data, dtype=np.uint8).reshape(image.height, image.width, 4)
    name = 'frame_%02d.png' % index
    PilImage.fromarray(pixels[:, :, :3].copy()).save(os.path.join(out, name), optimize=True)
    info = catch.info
    t = catch.transform.transform
    return {'file': name, 'world': world, 'x': x, 'y': y, 'yaw_deg': yaw_deg,
            'camera': {key: list(value) for key, value in sorted(camera.items())},
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
    parser.add_argument('--out', default=DATA)
    args = parser.parse_args()
    if not os.path.isdir(args.out):
        os.makedirs(args.out)
    for path in make_unseen_worlds():
        print('redrew %s' % os.path.relpath(path))
    with stage_session('record_stage_camera') as (wrapper, log, env, group):
        rospy.set_param('/use_sim_time', True)
        frames = []
        for index, frame in enumerate(FRAMES):
            print('== frame %d: %s at %s, camera %s' % (index, frame[0], frame[1:4], frame[4]))
            frames.append(record_frame(index, frame, wrapper, log, env, group, args.out))
    document = {
        'schema': 'stage_camera/2',
        'description': 'Real Stage camera frames of line worlds (and one calibration world) '
                       'at fixed robot poses (the robot placed by the world file, never '
                       'moved; x, y, yaw_deg null: as the world file has it), the Waffle '
                       'Pi\'s camera changed as `camera` says (pose [x y z yaw], pantilt '
                       '[pan tilt]; see tools/stage_camera_frames.py)',
        'versions': 'Stage 4.3.0 (rtv/Stage tag v4.3.0) and stage_ros 1.8.0, built by '
                    'tools/build-real-stage; stageros with its window under xvfb-run -a '
                    '(Mesa\'s software rasteriser)',
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
