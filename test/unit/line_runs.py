"""Synthetic line-following runs for the grading tests: a base's true poses laid along a
course's centreline, at a speed and an offset of the test's choosing, and its commands;
and a student's graded directory of such cases, as grade leaves it."""
import json
import math
import os

import numpy as np

from wall_follower.evaluation.grading.line_record import Commands, pieces_along, run_record
from wall_follower.evaluation.pictures.line_plot import plot_line_run
from wall_follower.evaluation.scoring.line_track import centreline_of

# A loop of four 0.35 m bends to the left (counter-clockwise), 1.0 m straights between.
LOOP = {'start': [0.0, 0.0, 0.0], 'closed': True, 'width': 0.045,
        'path': [['straight', 1.0], ['arc', 0.35, 90.0]] * 4, 'robot': [0.3, 0.0, 0.0]}
# An open line: a straight, a bend to the right, a straight to its end.
OPEN = {'start': [0.0, 0.0, 0.0], 'closed': False, 'width': 0.045,
        'path': [['straight', 1.0], ['arc', 0.5, -90.0], ['straight', 1.0]],
        'robot': [0.3, 0.0, 0.0]}
DT = 0.1


def drive(course, speed=0.17, offset=None, until=None, start=0.3, still=6.0):
    """True poses (t, x, y, yaw) of a base driven along the course's centreline at speed
    from `start` m along, offset [m] to the left of it as offset(alongs) says (an array
    of each pose's), up to `until` m along (a closed line: one lap and 0.2 m), then
    standing still for `still` s."""
    centreline = centreline_of(course)
    length = centreline.length
    until = until if until is not None else (start + length + 0.2 if centreline.closed
                                             else length)
    alongs = np.arange(start, until, speed * DT)
    alongs = alongs % length if centreline.closed else alongs
    points = centreline.points
    index = np.minimum(np.searchsorted(centreline.along, alongs, side='right') - 1,
                       len(points) - 2)
    tangent = points[index + 1] - points[index]
    yaw = np.arctan2(tangent[:, 1], tangent[:, 0])
    share = (alongs - centreline.along[index]) / np.maximum(np.hypot(*tangent.T), 1e-12)
    xy = points[index] + share[:, None] * tangent
    d = offset(alongs) if offset is not None else np.zeros(len(alongs))
    poses = np.column_stack((np.arange(len(alongs)) * DT, xy[:, 0] - d * np.sin(yaw),
                             xy[:, 1] + d * np.cos(yaw), yaw))
    last = poses[-1]
    standing = np.tile(last, (int(still / DT), 1))
    standing[:, 0] = last[0] + DT * np.arange(1, len(standing) + 1)
    return np.vstack((poses, standing))


def commands(values=None, times=(0.0, 10.0)):
    log = Commands()
    for t in times:
        log.add(t, values or {'linear.x': 0.17, 'angular.z': 0.3})
    return log


def record(course, poses, log=None, **extra):
    case = run_record(centreline_of(course), course, poses, 5.0, log or commands())
    case.update(extra)
    return case


def cutting(depth, course=LOOP):
    """An offset that takes the base inside every bend (to the left: LOOP's), `depth` at
    its middle, as a follower that steers its camera's view onto the line cuts it."""
    bends = [(start, end) for start, end, piece in pieces_along(course) if piece[0] == 'arc']

    def offset(alongs):
        found = np.zeros(len(alongs))
        for start, end in bends:
            inside = (alongs >= start) & (alongs < end)
            found[inside] = depth * np.sin(math.pi * (alongs[inside] - start) / (end - start))
        return found
    return offset


def write_case(directory, name, course, poses, log=None, **extra):
    """A case of the line task as grade leaves it in DIR/cases/: NAME.json (the record, as
    line_case writes it and grade completes it) and NAME.png (its plot)."""
    cases = os.path.join(directory, 'cases')
    if not os.path.isdir(cases):
        os.makedirs(cases)
    case = record(course, poses, log, **extra)
    plot = os.path.join(cases, name + '.png')
    plot_line_run(centreline_of(course), poses, case, plot, title=name, end_distance=0.35)
    case.update(name=name, task='line', world='/worlds/%s.world' % name, plot=plot,
                solution_command='my_line line.launch')
    with open(os.path.join(cases, name + '.json'), 'w') as stream:
        json.dump(case, stream)
    return case
