#!/usr/bin/env python3
"""Real Stage's reference camera frames: their worlds, and the built-in camera beside them.

Shared by tools/record_stage_camera.py, which runs real stageros on the
frames' worlds, and test/unit/test_sim_camera_reference.py, which renders
the same with the built-in camera (tools/ is no package: the test loads this
file by its path). Run, it prints each frame's yellow-mask intersection over
union and its other differing pixels, built-in against real:

    /usr/bin/python3 tools/stage_camera_frames.py

A frame's world is a line world of worlds/, or one of DATA_WORLDS: line
worlds that no other test or benchmark uses (drawn by tools/make_line_worlds.py
from the course files there; make_unseen_worlds redraws them) and a
calibration world. world_at copies it into a directory with what it
includes and its bitmaps beside it, the robot at the frame's pose and the
Waffle Pi's camera (worlds/waffle_pi.inc) moved and turned as the frame says.
"""
import glob
import importlib.util
import json
import os
import re
import shutil
import sys
import tempfile

import numpy as np
from PIL import Image

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
WORLDS = os.path.join(REPO, 'worlds')
DATA = os.path.join(REPO, 'test', 'data', 'stage_reference', 'camera')
DATA_WORLDS = os.path.join(DATA, 'worlds')

INCLUDE = re.compile(r'include "([^"]+)"')
BITMAP = re.compile(r'bitmap "([^"]+)"')
ROBOT_POSE = re.compile(r'(turtlebot3_waffle_pi\s*\(\s*name "turtlebot3"\s*pose \[)[^\]]*(\])')
CAMERA_POSE = re.compile(r'(raspicam_v2\( pose \[)[^\]]*(\])')
CAMERA_PANTILT = re.compile(r'(define raspicam_v2 camera\s*\([^)]*pantilt \[)[^\]]*(\])')


class WorldEditError(Exception):
    """A world file without the stanza a frame asks to change."""


def world_source(name):
    """The world file of a frame's world `name`: worlds/<name>.world, else DATA_WORLDS'."""
    for directory in (WORLDS, DATA_WORLDS):
        path = os.path.join(directory, name + '.world')
        if os.path.isfile(path):
            return path
    raise WorldEditError('no world "%s" in %s or %s' % (name, WORLDS, DATA_WORLDS))


def _substitute(pattern, replacement, text, what):
    text, count = pattern.subn(replacement, text)
    if count != 1:
        raise WorldEditError('%s: found %d times, not once' % (what, count))
    return text


def _numbers(values):
    return ' '.join('%.4f' % value for value in values)


def world_at(name, pose, camera, directory):
    """Path of a copy of world `name` in `directory`, with its includes and bitmaps
    beside it (each by its base name); the Waffle Pi at pose (x, y, yaw_deg) unless
    None; its camera at camera['pose'] (x, y, z, yaw_deg) and camera['pantilt']
    (pan, tilt) [deg] where given."""
    source = world_source(name)
    files = {}

    def copied(match):
        found = os.path.normpath(os.path.join(os.path.dirname(source), match.group(1)))
        files[os.path.basename(found)] = found
        return match.group(0).replace(match.group(1), os.path.basename(found))
    with open(source) as stream:
        text = BITMAP.sub(copied, INCLUDE.sub(copied, stream.read()))
    if pose is not None:
        text = _substitute(ROBOT_POSE, r'\g<1> %s 0 %s \g<2>' % (_numbers(pose[:2]),
                                                                 _numbers(pose[2:])),
                           text, '%s: the robot stanza' % name)
    for base, path in files.items():
        with open(path, 'rb') as stream:
            data = stream.read()
        if base == 'waffle_pi.inc' and camera:
            robot = data.decode()
            if 'pose' in camera:
                x, y, z, yaw = camera['pose']
                robot = _substitute(CAMERA_POSE, r'\g<1> %s 0 \g<2>' % _numbers((x, y, z)),
                                    robot, 'waffle_pi.inc: the camera\'s pose')
                if yaw:
                    raise WorldEditError('a camera yaw is not drawn by Stage: leave it 0')
            if 'pantilt' in camera:
                robot = _substitute(CAMERA_PANTILT, r'\g<1> %g %g \g<2>' % tuple(camera['pantilt']),
                                    robot, 'waffle_pi.inc: the camera\'s pantilt')
            data = robot.encode()
        with open(os.path.join(directory, base), 'wb') as stream:
            stream.write(data)
    path = os.path.join(directory, os.path.basename(source))
    with open(path, 'w') as stream:
        stream.write(text)
    return path


def make_unseen_worlds():
    """Redraw the line worlds of DATA_WORLDS from their course files with
    tools/make_line_worlds.py, their includes pointed at worlds/; the paths written."""
    spec = importlib.util.spec_from_file_location(
        'make_line_worlds', os.path.join(REPO, 'tools', 'make_line_worlds.py'))
    drawer = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(drawer)
    to_worlds = os.path.relpath(WORLDS, DATA_WORLDS)
    written = []
    for course in sorted(glob.glob(os.path.join(DATA_WORLDS, '*.course.yaml'))):
        for name, (data, _) in sorted(drawer.world_files(course).items()):
            if name.endswith('.world'):
                data = INCLUDE.sub(lambda match: 'include "%s/%s"' % (to_worlds, match.group(1)),
                                   data.decode()).encode()
            path = os.path.join(DATA_WORLDS, name)
            with open(path, 'wb') as stream:
                stream.write(data)
            written.append(path)
    return written


def recorded_frames():
    """The frames of DATA's camera.json (tools/record_stage_camera.py wrote them)."""
    with open(os.path.join(DATA, 'camera.json')) as stream:
        return json.load(stream)['frames']


def yellow(rgb):
    """The line's pixels: strong red and green, little blue (any HSV bounds would do)."""
    rgb = rgb.astype(int)
    return (rgb[..., 0] > 150) & (rgb[..., 1] > 150) & (rgb[..., 2] < 100)


def real_image(frame):
    """(height, width, 3) uint8: what real Stage drew for a recorded frame."""
    with Image.open(os.path.join(DATA, frame['file'])) as image:
        return np.asarray(image.convert('RGB'))


def built_in_frame(frame, directory):
    """(RobotSpec, CameraFrame): the robot of a recorded frame's world, as world_at writes
    it into `directory`, and what the built-in camera draws from its pose."""
    from wall_follower.sim.camera import CameraRenderer, CameraScene
    from wall_follower.sim.worldfile import load_world
    pose = None if frame['x'] is None else (frame['x'], frame['y'], frame['yaw_deg'])
    world = load_world(world_at(frame['world'], pose, frame['camera'], directory))
    robot = world.robots[0]
    rendered = CameraRenderer(CameraScene(world), robot.camera).render(
        robot.pose, [(robot, robot.pose)])
    return robot, rendered


def comparison(ours, theirs):
    """(yellow intersection over union or None where neither has yellow, share of the
    other pixels that differ by more than 30 in the sum of their channels)."""
    ours, theirs = ours[..., :3], theirs[..., :3]
    mine, real = yellow(ours), yellow(theirs)
    union = (mine | real).sum()
    iou = (mine & real).sum() / float(union) if union else None
    different = np.abs(ours.astype(int) - theirs.astype(int)).sum(axis=-1) > 30
    return iou, (different & ~(mine | real)).mean()


def main():
    directory = tempfile.mkdtemp(prefix='stage-camera-frames-')
    try:
        print('%-13s %-18s %-26s %-36s %7s %7s %6s %7s' % (
            'frame', 'world', 'pose (x, y, yaw)', 'camera', 'yellow', 'real', 'IoU',
            'other'))
        for frame in recorded_frames():
            _, rendered = built_in_frame(frame, directory)
            theirs = real_image(frame)
            iou, other = comparison(rendered.rgba, theirs)
            pose = '-' if frame['x'] is None else '(%.3f, %.3f, %.1f)' % (
                frame['x'], frame['y'], frame['yaw_deg'])
            camera = ' '.join('%s %s' % (key, value) for key, value in
                              sorted(frame['camera'].items())) or '-'
            print('%-13s %-18s %-26s %-36s %7d %7d %6s %6.2f%%' % (
                frame['file'], frame['world'], pose, camera, yellow(rendered.rgba).sum(),
                yellow(theirs).sum(), '-' if iou is None else '%.3f' % iou, 100.0 * other))
    finally:
        shutil.rmtree(directory)
    return 0


if __name__ == '__main__':
    sys.exit(main())
