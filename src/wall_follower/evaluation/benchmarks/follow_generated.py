"""`benchmark follow --generated N --seed S`: this package graded on N generated worlds per laser.

Each case is exactly a case of `grade wall_follower main.launch` (the same
worlds, the same ground-truth record, the same criteria), so the grader's
verdicts and this benchmark's never differ. Per laser profile: how many
laps were genuine, any contact, and the distribution (median, 5th
percentile, worst) of the time in band, the RMS error, the lap's time over
T* (the least lap time any robot under the speed limits can take round that
loop of the band: evaluation/scoring/lap_bound), its ratio to the speed bound and
find_wall's distance and heading errors; then every case under MIN_IN_BAND
with its world file, to be opened and looked at; then how each T* lap went
when the built-in simulator drove it, its check.
"""
import os

import numpy as np

from wall_follower.evaluation.grading import grader
from wall_follower.evaluation.grading.criteria import MIN_IN_BAND, grade_case
from wall_follower.evaluation.scoring import driven_bound, lap_bound
from wall_follower.evaluation.tables import fmt, print_table
from wall_follower.params import defaults
from wall_follower.params.course.wall_finder import FINDER

# What find_wall aims for (inside the 0.25-0.35 m the grade asks of it).
FIND_WALL_TARGET = defaults(FINDER)['wall_distance']
# name, how to read it from a grade, which end is the worst, and its table format.
FIGURES = (
    ('in band %', lambda g: g['in_band'] and 100.0 * g['in_band'], min, '.1f'),
    ('RMS cm', lambda g: g['rms_error'] and 100.0 * g['rms_error'], max, '.2f'),
    ('lap / T*', lambda g: g['lap_over_bound'], max, '.3f'),
    ('lap ratio', lambda g: g['lap_time_ratio'], max, '.3f'),
    ('find_wall error cm', lambda g: g['find_wall_distance'] is not None
     and 100.0 * abs(g['find_wall_distance'] - FIND_WALL_TARGET), max, '.1f'),
    ('find_wall heading deg', lambda g: g['find_wall_heading_deg'] is not None
     and abs(g['find_wall_heading_deg']), max, '.1f'),
)


def distribution(values, worst):
    """(median, 5th percentile on the bad side, worst) of the figures that exist."""
    values = [v for v in values if v is not None and v is not False]
    if not values:
        return None, None, None
    bad_side = 5.0 if worst is min else 95.0
    return (float(np.median(values)), float(np.percentile(values, bad_side)),
            float(worst(values)))


def run(count, seed, profiles, jobs, out, room, bound_margin=lap_bound.MARGIN):
    """Grade main.launch on count worlds of seed in each profile; prints the tables
    (T* held bound_margin inside the band, see lap_bound.fastest_lap)."""
    rows, below = [], []
    bounds = Bounds(bound_margin)
    for profile in profiles:
        options = grader.parser().parse_args(
            ['wall_follower', 'main.launch', '--worlds', str(count), '--seed', str(seed),
             '--laser', profile, '--jobs', str(jobs), '--room', str(room[0]), str(room[1]),
             '--out', os.path.join(out, profile)])
        records = grader.run_cases(grader.Solution(options.solution), options,
                                   list(range(count)))
        if records is None:
            return 130
        graded = [bounds.graded(record) for record in records]
        row = [profile, '%d/%d' % (sum(g['lap_genuine'] for g in graded), len(graded)),
               str(sum(g['contact'] for g in graded)),
               str(sum(not g['reason'] for g in graded))]
        for _, read, worst, spec in FIGURES:
            median, percentile, extreme = distribution([read(g) for g in graded], worst)
            row.append('%s / %s / %s' % (fmt(median, spec), fmt(percentile, spec),
                                         fmt(extreme, spec)))
        rows.append(row)
        for record, grade in zip(records, graded):
            if grade['in_band'] is None or grade['in_band'] < MIN_IN_BAND:
                below.append([profile, record.get('name', '?'),
                              fmt(grade['in_band'] and 100.0 * grade['in_band'], '.1f'),
                              grade['reason'] or '-', str(record.get('world'))])
    print_table(['laser', 'genuine laps', 'contact', 'all passed']
                + ['%s (median / 5 %% / worst)' % name for name, _, _, _ in FIGURES], rows)
    print('\ncases under %.0f %% in band (or without a lap): %d' % (100 * MIN_IN_BAND,
                                                                    len(below)))
    if below:
        print_table(['laser', 'case', 'in band %', 'reason', 'world'], below)
    print('\ncase records, plots and worlds: %s/<laser>/' % out)
    bounds.print_checks()
    return 0


class Bounds(driven_bound.Bounds):
    """The T* of each case's loop, found once a world: every laser's grader writes the
    same world to a file of its own."""

    def __init__(self, margin=lap_bound.MARGIN):
        super(Bounds, self).__init__(margin)
        self._paths = {}

    def graded(self, record):
        """grade_case(record), with lap_over_bound: the lap's time over its T*."""
        grade = grade_case(record)
        grade['lap_over_bound'] = None
        start = record.get('figures', {}).get('lap_start')
        lap_time = record.get('figures', {}).get('lap_time')
        if grade['lap_genuine'] and start and lap_time and record.get('world'):
            world = self._paths.setdefault(os.path.basename(record['world']), record['world'])
            bound, _ = self.of(world, start)
            if bound is not None:
                grade['lap_over_bound'] = lap_time / bound.time
        return grade

    def print_checks(self):
        """How the T* laps went when driven: the distribution, and every odd one."""
        checked = [(world, bound, driven) for world, bound, driven in self.all()
                   if bound is not None]
        failed = [(world, reason) for world, bound, reason in self.all() if bound is None]
        print('\nT* laps (lap_bound: the laser, and the judge\'s reading, held %.1f mm inside '
              'the band) driven in the built-in simulator: %d, %d closed without contact' % (
                  1000.0 * self.margin, len(checked),
                  sum(d.closed and not d.contact for _, _, d in checked)))
        for name, values, worst in (
                ('driven / T*', [d.time / b.time for _, b, d in checked if d.closed], max),
                ('in band %', [100.0 * d.in_band for _, _, d in checked if d.closed], min)):
            median, percentile, extreme = distribution(values, worst)
            print('  %s (median / 5 %% / worst): %s / %s / %s' % (
                name, fmt(median, '.3f'), fmt(percentile, '.3f'), fmt(extreme, '.3f')))
        for world, reason in failed:
            print('  no T* for %s: %s' % (world, reason))
