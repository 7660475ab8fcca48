"""Camera speed: frames per second of the built-in camera at 320x240 and 640x480.

Renders every line world's camera (its resolution replaced by each measured
one) at poses spaced along the line, facing along it, as a line follower's
camera sees it; and a world step with and without the camera image, the
cost a lockstep run pays per step for a subscribed camera.

    /usr/bin/python3 -m wall_follower.evaluation.benchmarks.camera [--frames 60]
"""
import argparse
import glob
import math
import os
import sys
import time

import numpy as np
import rospkg

from wall_follower.evaluation.tables import fmt, print_table
from wall_follower.evaluation.scoring.line_track import load_centreline
from wall_follower.sim import compiled_camera
from wall_follower.sim.camera import CameraRenderer, CameraScene
from wall_follower.sim.engine import Simulation
from wall_follower.sim.worldfile import load_world

RESOLUTIONS = ((320, 240), (640, 480))
# Frames per second at which the camera keeps up with a lockstep run at 5x real time
# (10 steps per simulated second), and at the larger size with one at real time.
GOALS = {(320, 240): 50.0, (640, 480): 10.0}


def line_worlds():
    worlds = os.path.join(rospkg.RosPack().get_path('wall_follower'), 'worlds')
    return sorted(glob.glob(os.path.join(worlds, 'line_*.world')))


def poses_along(path, count):
    """`count` poses on the world's line, each facing along it."""
    points = load_centreline(path).points
    index = np.linspace(0, len(points) - 2, count).astype(int)
    ahead = points[np.minimum(index + 20, len(points) - 1)]
    return [(p[0], p[1], math.atan2(q[1] - p[1], q[0] - p[0]))
            for p, q in zip(points[index], ahead)]


def frame_rate(path, resolution, frames):
    """(frames per wall second, CPU milliseconds per frame): the first is what a run
    sees, the second what the camera costs whatever else the machine is doing."""
    world = load_world(path)
    robot = world.robots[0]
    renderer = CameraRenderer(CameraScene(world), robot.camera._replace(resolution=resolution))
    poses = poses_along(path, frames)
    renderer.render(poses[0], [(robot, poses[0])])
    start, cpu = time.perf_counter(), time.process_time()
    for pose in poses:
        renderer.render(pose, [(robot, pose)])
    return (len(poses) / (time.perf_counter() - start),
            1000.0 * (time.process_time() - cpu) / len(poses))


def step_ms(path, steps, with_images):
    """Mean wall milliseconds of a world step (scan included) of a robot turning in place."""
    sim = Simulation(load_world(path))
    sim.step(with_images=with_images)
    start = time.perf_counter()
    for _ in range(steps):
        sim.set_command(0, 0.0, 0.3)
        sim.step(with_images=with_images)
    return 1000.0 * (time.perf_counter() - start) / steps


def main(argv=None):
    parser = argparse.ArgumentParser(prog='benchmark camera', description=__doc__.split('\n\n')[0])
    parser.add_argument('--frames', type=int, default=60, help='frames per world and size')
    args = parser.parse_args(argv)
    if not compiled_camera.available():
        sys.stderr.write('benchmark camera: error: %s\n' % compiled_camera.MISSING)
        return 1
    rows = []
    for path in line_worlds():
        name = os.path.basename(path)[:-len('.world')]
        for resolution in RESOLUTIONS:
            fps, cpu_ms = frame_rate(path, resolution, args.frames)
            rows.append(['%s, %dx%d' % ((name,) + resolution), fmt(fps, '.0f') + ' fps',
                         fmt(cpu_ms, '.1f') + ' ms', '>= %.0f fps' % GOALS[resolution]])
        plain, seen = step_ms(path, args.frames, False), step_ms(path, args.frames, True)
        rows.append(['%s, world step without / with the image' % name,
                     '%s / %s ms wall' % (fmt(plain, '.1f'), fmt(seen, '.1f')), '', ''])
    print_table(['camera', 'frames per wall second', 'CPU per frame', 'goal'], rows)
    print('\nload average (1 min) at the end: %.2f on %d cores; the figures are wall-clock '
          'bound, so a busy machine lowers them' % (os.getloadavg()[0], os.cpu_count()))
    return 0


if __name__ == '__main__':
    sys.exit(main())
