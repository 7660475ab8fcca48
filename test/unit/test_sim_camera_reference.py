"""The built-in camera against real Stage 4.3's frames.

test/data/stage_reference/camera/ holds what real stageros (with its window
under xvfb-run) published at fixed robot poses (tools/record_stage_camera.py):
the images, camera_info and the base_link -> camera transform, of the
course's line worlds, of line worlds no other test uses seen obliquely, with
the Waffle Pi's camera lowered onto its body, moved ahead of the robot's
centre so that its own box shows, panned, turned by more than a turn, and
of a calibration world of floating boxes. The built-in camera renders the
same worlds (tools/stage_camera_frames.py writes them as real Stage got
them): its yellow line must cover the same pixels (intersection over union
of the yellow masks >= MIN_IOU at every frame of a line world), the rest
may differ in a few pixels at most, the calibration frame in none, and its
geometry and camera_info must be stageros' own.
"""
import importlib.util
import os

import numpy as np
import pytest

from wall_follower.sim.camera import camera_intrinsics, camera_mount

HERE = os.path.dirname(os.path.abspath(__file__))
_SPEC = importlib.util.spec_from_file_location(
    'stage_camera_frames', os.path.join(HERE, os.pardir, os.pardir, 'tools',
                                        'stage_camera_frames.py'))
frames = importlib.util.module_from_spec(_SPEC)
_SPEC.loader.exec_module(frames)

FRAMES = frames.recorded_frames()
LINE_FRAMES = [frame for frame in FRAMES if frame['world'].startswith('line_')]
MIN_IOU = 0.98
# Pixels of the rest of the image (floor, walls, bodies, background) whose colour may
# differ from real Stage's: a few dozen of a 320 x 240 frame.
MAX_OTHER_DIFFERENT = 0.001
GRAY20 = 51   # the Waffle's body
BLACK = 0     # the camera's own box


def _frame_id(frame):
    return frame['file']


@pytest.fixture(scope='module')
def rendered(tmp_path_factory):
    """(RobotSpec, CameraFrame) of the built-in camera per recorded frame, by file."""
    directory = str(tmp_path_factory.mktemp('worlds'))
    return {frame['file']: frames.built_in_frame(frame, directory) for frame in FRAMES}


def _is(rgb, value):
    return np.all(rgb[..., :3] == value, axis=-1)


def test_the_frames_show_what_they_are_recorded_for():
    lowered = [frame for frame in FRAMES if frame['camera'].get('pose', [0, 0, 1])[2] < 0.1]
    ahead = [frame for frame in FRAMES if frame['camera'].get('pose', [0])[0] > 0]
    assert lowered and ahead and len(LINE_FRAMES) >= 20
    for frame in lowered:
        assert _is(frames.real_image(frame), GRAY20).mean() > 0.3
    for frame in ahead:
        box = _is(frames.real_image(frame), BLACK)
        assert box.mean() > 0.01 and not box[-1].any(), 'the box shows only above the horizon'


@pytest.mark.parametrize('frame', LINE_FRAMES, ids=_frame_id)
def test_yellow_line_covers_the_pixels_real_stage_draws(rendered, frame):
    _, ours = rendered[frame['file']]
    theirs = frames.real_image(frame)
    assert ours.rgba.shape[:2] == theirs.shape[:2]
    assert frames.yellow(theirs).sum() > 500, 'a reference frame should show a good length ' \
        'of line'
    iou, other = frames.comparison(ours.rgba, theirs)
    assert iou >= MIN_IOU, 'IoU %.3f' % iou
    assert other <= MAX_OTHER_DIFFERENT


def test_the_calibration_frame_is_real_stage_s_pixel_for_pixel(rendered):
    # Floating boxes before a level camera: every edge at a place its world file says,
    # so that a pixel's colour tells where in the pixel the scene is sampled.
    frame, = [frame for frame in FRAMES if frame['world'] == 'camera_calibration']
    _, ours = rendered[frame['file']]
    theirs = frames.real_image(frame)
    assert (_is(theirs, (0, 0, 255))).sum() > 1000
    assert np.array_equal(ours.rgba[..., :3], theirs)


@pytest.mark.parametrize('frame', FRAMES, ids=_frame_id)
def test_image_camera_info_and_tf_are_stageros_ones(rendered, frame):
    robot, ours = rendered[frame['file']]
    height, width = ours.depth.shape
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
