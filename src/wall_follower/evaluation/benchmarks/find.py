"""find_wall from the start poses of config/find_trials.yaml in every world.

Runs launch/find_trials.launch in lockstep simulated time and reads the
ground-truth figures of each trial. The distance error is counted from
where the finder aims (its ~wall_distance), not from the course's 0.3 m,
which is the edge of the following band.
"""
import argparse

from wall_follower.evaluation.launching import WORLDS, laser_profile, run_launch, shipped_world
from wall_follower.evaluation.tables import fmt, print_table
from wall_follower.params import defaults
from wall_follower.params.course.wall_finder import FINDER

# Where find_trials.launch's wall_finder, on its defaults, leaves the laser from the wall [m].
TARGET = defaults(FINDER)['wall_distance']


def trial_row(world, trial):
    """One trial's row of the table: world, start, found, time, distance and heading errors,
    contact."""
    x, y, yaw = trial['start']
    return [world, '%.2f %.2f %.0f' % (x, y, yaw),
            'yes' if trial['found'] else 'NO',
            fmt(trial['time'], '.1f'),
            fmt(100.0 * abs(trial['distance'] - TARGET), '.2f'),
            fmt(abs(trial['heading_error_deg']), '.2f'),
            'yes' if trial['contact'] else 'no']


def main(argv=None):
    parser = argparse.ArgumentParser(prog='benchmark find', description=__doc__)
    parser.add_argument('--worlds', nargs='+', default=list(WORLDS), type=shipped_world())
    parser.add_argument('--laser-profile', default='stage', type=laser_profile)
    args = parser.parse_args(argv)
    rows = []
    for world in args.worlds:
        f = run_launch('find_trials.launch', {
            'world': world, 'laser_profile': args.laser_profile,
            'lockstep': 'true', 'speedup': '0'})
        rows.extend(trial_row(world, trial) for trial in (f or {}).get('trials', []))
        if not f:
            rows.append([world, '(run failed)', '-', '-', '-', '-', '-'])
    print_table(['world', 'start x y yaw', 'found', 'time s', '|dist - %.2f| cm' % TARGET,
                 '|heading| deg', 'contact'], rows)
    print('\ngoals: time <= 20 s, distance error <= 1.5 cm, heading error <= 3 deg, no contact')
    return 0
