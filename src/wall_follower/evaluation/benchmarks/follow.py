"""Wall following in every world and laser profile: laps from the world's start pose.

Runs main.launch without find_wall, in lockstep simulated time, and reads
the ground-truth figures written by course_report. The stage profile is
noise-free and drives the same path every time, so it runs once; its lap
time may still differ by a step (0.1 s) between runs, as the robot stands
after the record_odom goal for one step more or less (lockstep steps by
wall time while nobody drives). A noisy profile (lds01, lds02, gazebo,
course720) gives a different lap for every noise seed. At one seed the lap
is mostly the same from run to run (the noise is drawn only while someone
drives), but now and then the follower's first answer comes a step behind
and the lap goes another way, so one lap is a sample, not a figure: its row
is the mean over --seeds laps (seeds 0, 1, ...), with the worst lap's ratio
beside it.

--simulator stage runs the same laps on real stageros (stage_ros installed),
with its window (under xvfb-run without a display), at the world's pace and
not in lockstep, with Stage's own laser: one lap per world.

--generated N grades main.launch on N generated worlds of --seed in every
laser profile instead, as `grade` does (see follow_generated).

Beside each lap: T*, the least time any robot under the speed limits takes
to lap the world in the band (evaluation/scoring/lap_bound), and the lap's time over
it; then each T* lap as the built-in simulator drives it, its check.
"""
import argparse
import os
import sys
import tempfile

from wall_follower.evaluation.scoring import driven_bound, lap_bound
from wall_follower.evaluation.benchmarks import follow_generated
from wall_follower.evaluation.launching import (WORLDS, display_wrapper, laser_profile, run_launch,
                                                shipped_world)
from wall_follower.evaluation.tables import fmt, print_table
from wall_follower.sim.laser_profiles import PROFILES as LASER_PROFILES
from wall_follower.sim.stage_interface import world_path
from wall_follower.sim.worldfile import load_world

PROFILES = ('stage', 'lds01', 'lds02', 'course720')
NOISE_FREE = ('stage',)
MEANS = ('time_in_band', 'rms_error', 'lap_time', 'path_length', 'lap_time_ratio')


def combined(laps):
    """One row's figures from the figures of its laps: means, and the worst of the rest.

    None when no lap wrote its figures.
    """
    laps = [lap for lap in laps if lap]
    if not laps:
        return None
    row = {name: sum(lap[name] for lap in laps) / len(laps) for name in MEANS}
    row.update(min_clearance=min(lap['min_clearance'] for lap in laps),
               contact=any(lap['contact'] for lap in laps),
               max_linear=max(lap['max_linear'] for lap in laps),
               max_angular=max(lap['max_angular'] for lap in laps),
               worst_ratio=max(lap['lap_time_ratio'] for lap in laps),
               simulator='/'.join(sorted({lap.get('simulator') or '?' for lap in laps})),
               laps=len(laps))
    return row


def lap_args(simulator, world, profile, seed):
    """main.launch's arguments for one lap without find_wall, reported."""
    args = {'sim': 'true', 'simulator': simulator, 'world': world, 'find_wall': 'false',
            'report': 'true'}
    if simulator == 'stage':
        args['gui'] = 'true'
    else:
        args.update(laser_profile=profile, seed=str(seed), lockstep='true', speedup='0')
    return args


def bound_margin(text):
    """The argparse type of --bound-margin: a margin that leaves some of the band [m]."""
    try:
        value = float(text)
    except ValueError:
        value = float('nan')
    widest = 0.5 * (lap_bound.BAND[1] - lap_bound.BAND[0])
    if not 0.0 <= value < widest:
        raise argparse.ArgumentTypeError('%r is not a margin from 0 to under %g m (half the '
                                         'band)' % (text, widest))
    return value


def main(argv=None):
    parser = argparse.ArgumentParser(prog='benchmark follow', description=__doc__)
    parser.add_argument('--worlds', nargs='+', default=list(WORLDS), type=shipped_world())
    parser.add_argument('--profiles', nargs='+', type=laser_profile,
                        help='laser profiles (default: %s; with --generated, every one)'
                        % ' '.join(PROFILES))
    parser.add_argument('--seeds', type=int, default=5,
                        help='laps per noisy laser profile, one per noise seed (default 5)')
    parser.add_argument('--simulator', choices=('builtin', 'stage'), default='builtin',
                        help='stage: real stageros, one lap per world with its own laser')
    parser.add_argument('--generated', type=int, metavar='N',
                        help='grade main.launch on N generated worlds per laser profile instead')
    parser.add_argument('--seed', type=int, default=0, help='with --generated: the worlds\' seed')
    parser.add_argument('--jobs', type=int, default=1, help='with --generated: cases at once')
    parser.add_argument('--room', type=float, nargs=2, default=(2.4, 4.0),
                        help='with --generated: sides of the main rooms [m]')
    parser.add_argument('--out', help='with --generated: directory for the cases '
                        '(default: a new temporary one)')
    parser.add_argument('--bound-margin', type=bound_margin, default=lap_bound.MARGIN,
                        metavar='M',
                        help='T* holds the laser this far inside the band\'s edges [m] '
                        '(default %(default)s)')
    args = parser.parse_args(argv)
    if args.generated:
        return follow_generated.run(args.generated, args.seed,
                                    args.profiles or list(LASER_PROFILES),
                                    args.jobs, args.out or tempfile.mkdtemp(prefix='follow-'),
                                    args.room, args.bound_margin)
    wrapper = ()
    if args.simulator == 'stage':
        wrapper = display_wrapper()
        if wrapper is None:
            sys.stderr.write('benchmark follow: real Stage needs a display: no DISPLAY and '
                             'no xvfb-run\n')
            return 1
        args.profiles, args.seeds = ['stage'], 1
    args.profiles = args.profiles or list(PROFILES)
    rows = []
    bounds = driven_bound.Bounds(args.bound_margin)
    for world in args.worlds:
        # Every lap begins at the world's start pose.
        path = world_path(world)
        bound, _ = bounds.of(path, load_world(path).robots[0].pose)
        for profile in args.profiles:
            seeds = range(1 if profile in NOISE_FREE else max(1, args.seeds))
            f = combined([run_launch('main.launch', lap_args(args.simulator, world, profile, seed),
                                     wrapper=wrapper)
                          for seed in seeds]) or {}
            t_star = bound.time if bound else float('nan')
            rows.append([world, f.get('simulator', '-'), profile, str(f.get('laps', 0)),
                         fmt(100.0 * f.get('time_in_band', float('nan')), '.1f'),
                         fmt(100.0 * f.get('rms_error', float('nan')), '.2f'),
                         fmt(f.get('min_clearance'), '.3f'),
                         {True: 'yes', False: 'no'}.get(f.get('contact'), '-'),
                         fmt(f.get('lap_time'), '.1f'),
                         fmt(t_star, '.1f'),
                         fmt(f.get('lap_time', float('nan')) / t_star, '.3f'),
                         fmt(f.get('path_length'), '.2f'),
                         fmt(f.get('lap_time_ratio'), '.3f'),
                         fmt(f.get('worst_ratio'), '.3f'),
                         fmt(f.get('max_linear'), '.3f'),
                         fmt(f.get('max_angular'), '.3f')])
    print_table(['world', 'simulator', 'laser', 'laps', 'in band %', 'RMS cm', 'min clearance m',
                 'contact', 'lap s', 'T* s', 'lap / T*', 'path m', 'lap / (path/0.19)',
                 'worst lap', 'max v', 'max w'], rows)
    print('\nmeans over the laps, but min clearance, contact, worst lap and max v, w '
          'over all of them')
    print('goals: in band >= 97 %, RMS <= 2 cm, lap / T* <= 1.08, no contact, '
          'max v <= 0.19, max w <= 0.49\n')
    print_bounds(bounds)
    return 0


def print_bounds(bounds):
    """The table of every T* lap as the built-in simulator drives it: its check."""
    rows = []
    for path, bound, driven in bounds.all():
        world = os.path.splitext(os.path.basename(path))[0]
        if bound is None:
            rows.append([world, '-', '-', '-', '-', '-', driven])
            continue
        rows.append([world, fmt(bound.time, '.1f'), fmt(bound.length, '.2f'),
                     fmt(driven.time, '.1f'), fmt(driven.time / bound.time, '.3f'),
                     fmt(100.0 * driven.in_band, '.1f'),
                     'contact' if driven.contact else ('' if driven.closed else 'no lap')])
    print('T*, the least lap time (lap_bound: the laser, and the judge\'s reading, held '
          '%.1f mm inside the band), each lap driven in the built-in simulator:'
          % (1000.0 * bounds.margin))
    print_table(['world', 'T* s', 'path m', 'driven s', 'driven / T*', 'in band %', ''], rows)
