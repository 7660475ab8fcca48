"""The camera line follower in every line world, beside the lab's pixel-P follower on one camera.

Runs the line_follow rostest (test/rostest/line_follow.test: the built-in
simulator in lockstep, scored from ground truth against the course's
centreline) once per world and controller, and prints the figures it
writes: on a closed line, one lap's time and mean speed, and the cross-track
distance of the base (RMS and worst); on an open line, the same up to the
stop and the stop's distance from the line's end. `pursuit` is
line_follower's own controller, `pixel_p` the lab's follower_p.py (turn
rate proportional to the slice centroid's pixel offset), run on the same
camera as a baseline. Then the frame rate of line_follower's own step
(vision.line_step: mask, line check, floor projection, path, pursuit; no
simulator) at two camera sizes; the
simulator's camera has its own benchmark where it is built (`benchmark
camera`).
"""
import argparse
import math
import time

import numpy as np

from wall_follower.evaluation.launching import run_rostest
from wall_follower.evaluation.scoring.line import speed_bound
from wall_follower.evaluation.scoring.line_track import load_centreline
from wall_follower.evaluation.tables import fmt, print_table
from wall_follower.params import defaults
from wall_follower.params.camera.line_follower import CONTROLLERS, TABLE
from wall_follower.params.driving import MAX_ANGULAR, MAX_LINEAR
from wall_follower.sim.stage_interface import world_path
from wall_follower.vision.floor import FloorProjection, Intrinsics, level_camera_axes
from wall_follower.vision.line_step import LineStep

LINE_WORLDS = ('line_lab', 'line_tight', 'line_open')


def run_line(world, controller, timeout=600.0):
    """The figures of one line_follow run as a dict, or None when it wrote none."""
    return run_rostest('line_follow.test', {'world': world, 'controller': controller}, timeout)


def pipeline_rate(width, height, frames=50):
    """Frames per second of line_follower's step on synthetic frames of a camera of this
    size (the Waffle Pi's field of view, 0.3 m up, 40 deg down) seeing a curved yellow line."""
    values = defaults(TABLE)
    fx = width / (2.0 * math.tan(math.radians(62.2) / 2.0))
    fy = height / (2.0 * math.tan(math.radians(48.8) / 2.0))
    projection = FloorProjection(
        Intrinsics.from_camera_info([fx, 0, width / 2.0, 0, fy, height / 2.0, 0, 0, 1],
                                    width, height),
        level_camera_axes(math.radians(40.0)), (0.0, 0.0, 0.3), values['max_distance'])
    image = np.full((height, width, 3), 255, np.uint8)
    rows = np.arange(height // 3, height)
    for row in rows:
        centre = int(width / 2 + 0.3 * width * ((height - row) / float(height)) ** 2)
        half = max(1, int(0.05 * width * row / float(height)))
        image[row, max(0, centre - half):centre + half] = (0, 255, 255)
    step = LineStep(values)
    step.update(image, projection, (0.0, 0.0, 0.0), values['ahead_half_width'])
    started = time.perf_counter()
    for frame in range(frames):
        step.update(image, projection, (0.01 * frame, 0.0, 0.0), values['ahead_half_width'])
    return frames / (time.perf_counter() - started)


def main(argv=None):
    parser = argparse.ArgumentParser(prog='benchmark line', description=__doc__)
    parser.add_argument('--worlds', nargs='+', default=list(LINE_WORLDS))
    parser.add_argument('--controllers', nargs='+', default=list(CONTROLLERS),
                        choices=CONTROLLERS)
    args = parser.parse_args(argv)
    rows = []
    for world in args.worlds:
        line = load_centreline(world_path(world))
        bound = speed_bound(line, MAX_LINEAR, MAX_ANGULAR)
        for controller in args.controllers:
            f = run_line(world, controller) or {}
            if line.closed:
                outcome = 'lap' if f.get('lapped') else 'lost after %s m' % fmt(
                    f.get('driven'), '.2f')
            else:
                outcome = 'stop %s m from the end' % fmt(f.get('end_distance'), '.3f') \
                    if f.get('stopped') else 'no stop'
            speed = f.get('mean_speed')
            if speed is None and f.get('time'):
                speed = f['path_length'] / f['time']
            rows.append([world, controller, outcome, fmt(f.get('time'), '.1f'), fmt(speed, '.3f'),
                         fmt(bound, '.3f'), fmt(100.0 * f.get('rms', float('nan')), '.2f'),
                         fmt(100.0 * f.get('max', float('nan')), '.2f'),
                         fmt(f.get('max_linear'), '.3f'), fmt(f.get('max_angular'), '.3f')])
    print_table(['world', 'controller', 'outcome', 'sim s', 'mean m/s', 'bound m/s', 'RMS cm',
                 'max cm', 'max v', 'max w'], rows)
    print('\nmean: along the centreline per simulated second (open line: path driven); bound: '
          'the best mean speed on the line within 0.19 m/s and 0.49 rad/s; RMS, max: the '
          "base's distance to the centreline, from ground truth")
    print()
    print_table(['camera', 'vision frames/s'],
                [['%dx%d' % size, fmt(pipeline_rate(*size), '.0f')]
                 for size in ((320, 240), (640, 480))])
    return 0
