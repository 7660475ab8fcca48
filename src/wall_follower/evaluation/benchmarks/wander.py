"""wander in every shipped world: the share of the free floor it visits in five simulated minutes.

Runs the wander rostest (test/rostest/wander.test: the simulator in
lockstep, scored from ground truth) once per world and laser profile and
prints the figures it writes: the share of the free floor's 0.2 m cells
that the robot's axle passed through (evaluation/scoring/coverage.py), the path
driven, the smallest clearance and whether anything was touched.
"""
import argparse

from wall_follower.evaluation.launching import WORLDS, laser_profile, run_rostest, shipped_world
from wall_follower.evaluation.tables import fmt, print_table

EXERCISE_WORLDS = WORLDS + ('pillars',)


def run_wander(world, profile, duration, timeout=900.0):
    """The figures of one wander run as a dict, or None when it wrote none."""
    return run_rostest('wander.test', {'world': world, 'laser_profile': profile,
                                       'duration': '%g' % duration}, timeout)


def main(argv=None):
    parser = argparse.ArgumentParser(prog='benchmark wander', description=__doc__)
    parser.add_argument('--worlds', nargs='+', default=list(EXERCISE_WORLDS),
                        type=shipped_world())
    parser.add_argument('--profiles', nargs='+', default=['stage'], type=laser_profile)
    parser.add_argument('--duration', type=float, default=300.0, help='simulated seconds')
    args = parser.parse_args(argv)
    rows = []
    for world in args.worlds:
        for profile in args.profiles:
            f = run_wander(world, profile, args.duration) or {}
            rows.append([world, profile, fmt(f.get('duration'), '.0f'),
                         fmt(100.0 * f.get('visited_share', float('nan')), '.1f'),
                         fmt(f.get('path_length'), '.1f'),
                         fmt(f.get('min_clearance'), '.3f'),
                         {True: 'yes', False: 'no'}.get(f.get('contact'), '-'),
                         fmt(f.get('max_linear'), '.3f'), fmt(f.get('max_angular'), '.3f')])
    print_table(['world', 'laser', 'sim s', 'visited %', 'path m', 'min clearance m', 'contact',
                 'max v', 'max w'], rows)
    print('\nvisited: share of the free floor (0.2 m cells the robot can stand in, reachable '
          'from the start) that its axle passed through')
    return 0
