"""Wall following in every world and laser profile: one lap from the world's start pose.

Runs main.launch without find_wall, in lockstep simulated time, and reads
the ground-truth figures written by course_report.
"""
import argparse

from wall_follower.benchmarks.launching import WORLDS, fmt, print_table, run_launch

PROFILES = ('stage', 'lds01')


def main(argv=None):
    parser = argparse.ArgumentParser(prog='benchmark follow', description=__doc__)
    parser.add_argument('--worlds', nargs='+', default=list(WORLDS))
    parser.add_argument('--profiles', nargs='+', default=list(PROFILES))
    args = parser.parse_args(argv)
    rows = []
    for world in args.worlds:
        for profile in args.profiles:
            f = run_launch('main.launch', {
                'world': world, 'laser_profile': profile, 'find_wall': 'false',
                'report': 'true', 'lockstep': 'true', 'speedup': '0'}) or {}
            rows.append([world, profile,
                         fmt(100.0 * f.get('time_in_band', float('nan')), '.1f'),
                         fmt(100.0 * f.get('rms_error', float('nan')), '.2f'),
                         fmt(f.get('min_clearance'), '.3f'),
                         {True: 'yes', False: 'no'}.get(f.get('contact'), '-'),
                         fmt(f.get('lap_time'), '.1f'),
                         fmt(f.get('path_length'), '.2f'),
                         fmt(f.get('lap_time_ratio'), '.3f'),
                         fmt(f.get('max_linear'), '.3f'),
                         fmt(f.get('max_angular'), '.3f')])
    print_table(['world', 'laser', 'in band %', 'RMS cm', 'min clearance m', 'contact',
                 'lap s', 'path m', 'lap / (path/0.19)', 'max v', 'max w'], rows)
    print('\ngoals: in band >= 97 %, RMS <= 2 cm, lap ratio <= 1.2, no contact, '
          'max v <= 0.19, max w <= 0.49')
    return 0
