"""The built-in camera against real Stage 4.3's frames of the line worlds.

test/data/stage_reference/camera/ holds what real stageros (with its window
under xvfb-run) published at fixed robot poses (tools/record_stage_camera.py):
the images, camera_info and the base_link -> camera transform. The built-in
camera renders the same poses; its yellow line must cover the same pixels
(intersection over union of the yellow masks >= MIN_IOU at every pose), and
its geometry and camera_info must be stageros' own. Some poses lower the camera
(`camera_z`, its pose z) to just above the body, which both then draw.
"""
import json
import math
import os

import numpy as np
import pytest
from PIL import Image

from wall_follower.sim.camera import CameraRenderer, CameraScene, camera_intrinsics, camera_mount
from wall_follower.sim.worldfile import load_world

HERE = os.path.dirname(os.path.abspath(__file__))
WORLDS = os.path.join(HERE, os.pardir, os.pardir, 'worlds')
DATA = os.path.join(HERE, os.pardir, 'data', 'stage_reference', 'camera')
with open(os.path.join(DATA, 'camera.json')) as _stream:
    RECORDING = json.load(_stream)
FRAMES = RECORDING['frames']
MIN_IOU = 0.9
# Pixels of the rest of the image (floor, walls, background) may differ in colour at
# the edges of what they show; the share that does is small.
MAX_OTHER_DIFFERENT = 0.01


def yellow(rgb):
    """The line's pixels: strong red and green, little blue (any HSV bounds would do)."""
    rgb = rgb.astype(int)
    return (rgb[..., 0] > 150) & (rgb[..., 1] > 150) & (rgb[..., 2] < 100)


@pytest.fixture(scope='module')
def renderers():
    cache = {}

    def get(world):
        if world not in cache:
            loaded = load_world(os.path.join(WORLDS, world + '.world'))
            robot = loaded.robots[0]
            cache[world] = (robot, CameraRenderer(CameraScene(loaded), robot.camera))
        return cache[world]
    return get


def _render(renderers, frame):
    robot, renderer = renderers(frame['world'])
    if frame['camera_z'] is not None:
        camera = robot.camera
        camera = camera._replace(pose=camera.pose[:2] + (frame['camera_z'],) + camera.pose[3:],
                                 height=robot.size[2] + frame['camera_z'])
        robot = robot._replace(camera=camera)
        renderer = CameraRenderer(renderer.scene, camera)
    pose = (frame['x'], frame['y'], math.radians(frame['yaw_deg']))
    return robot, renderer.render(pose, [(robot, pose)])


def test_some_poses_see_the_robot_body():
    lowered = [frame for frame in FRAMES if frame['camera_z'] is not None]
    assert lowered
    for frame in lowered:
        real = np.asarray(Image.open(os.path.join(DATA, frame['file'])).convert('RGB'))
        body = np.all(real == 51, axis=-1)   # the Waffle's gray20
        assert body.mean() > 0.3


@pytest.mark.parametrize('frame', FRAMES, ids=lambda frame: frame['file'])
def test_yellow_line_covers_the_pixels_real_stage_draws(renderers, frame):
    _, rendered = _render(renderers, frame)
    real = np.asarray(Image.open(os.path.join(DATA, frame['file'])).convert('RGB'))
    assert rendered.rgba.shape[:2] == real.shape[:2]
    ours, theirs = yellow(rendered.rgba[..., :3]), yellow(real)
    assert theirs.sum() > 500, 'a reference pose should show a good length of line'
    iou = (ours & theirs).sum() / float((ours | theirs).sum())
    assert iou >= MIN_IOU, 'IoU %.3f' % iou
    different = np.abs(rendered.rgba[..., :3].astype(int) - real.astype(int)).sum(axis=-1) > 30
    assert (different & ~(ours | theirs)).mean() <= MAX_OTHER_DIFFERENT


@pytest.mark.parametrize('frame', FRAMES, ids=lambda frame: frame['file'])
def test_image_camera_info_and_tf_are_stageros_ones(renderers, frame):
    robot, rendered = _render(renderers, frame)
    height, width = rendered.depth.shape
    assert (frame['width'], frame['height'], frame['encoding'], frame['step']) == \
        (width, height, 'rgba8', 4 * width)
    assert frame['frame_id'] == 'camera'
    info = frame['camera_info']
    fx, fy, cx, cy = camera_intrinsics(robot.camera)
    assert (info['width'], info['height'], info['frame_id']) == (width, height, 'camera')
    assert info['K'] == pytest.approx([fx, 0, cx, 0, fy, cy, 0, 0, 1], abs=1e-9)
    assert info['P'] == pytest.approx([fx, 0, cx, 0, 0, fy, cy, 0, 0, 0, 1, 0], abs=1e-9)
    assert info['D'] == [0.0] * 4
    mount = camera_mount(robot)
    tf = frame['tf']
    assert (tf['parent'], tf['child']) == ('base_link', 'camera')
    assert tf['translation'] == pytest.approx([mount.x, mount.y, mount.z], abs=1e-9)
    # q and -q are the same rotation.
    dot = abs(np.dot(tf['rotation_xyzw'], mount.rotation))
    assert dot == pytest.approx(1.0, abs=1e-9)
