"""A line-following run's ground-truth record: what the base truly did on a course's line.

nodes/evaluation/line_case.py gathers the base's true poses
(base_pose_ground_truth) and every command the solution sent; this turns
them into the case record that line_criteria grades, and says when a run
is over. Nothing the solution says about itself counts.

- Closed line: the lap is done once the base's progress along the
  centreline (scoring.line.progress, forward and back, across the start)
  reaches the line's length; the tracking and the mean speed are of the
  lap (from the base's first motion to the lap's end).
- Open line: the run ends once the base has neither moved nor turned for
  `still` simulated seconds (its stop); the tracking and the mean speed
  are of the drive up to the stop, and where it stopped is measured
  against the line's end.
- The cross-track error is the base's distance to the centreline. The
  worst of it is placed on the course: on which piece (a straight, or a
  bend of what radius and which way), and on the inside or the outside of
  a bend; and of the poses on bends more than OFF_BEND off the line, the
  share inside their bend (a base inside its bends cuts them).
- Commands: the largest |linear.x| and |angular.z|, and every non-finite
  value of any field, kept in words ('-inf'), since JSON has no infinity.
"""
import math

import numpy as np

from wall_follower.control.motion import MAX_ANGULAR, MAX_LINEAR
from wall_follower.evaluation.scoring.line import cross_track, progress, speed_bound

# m, rad: a pose within this of the one before has not moved (nor turned).
STILL = 1e-4
# m: a base this far from the centreline has left the line.
OFF_LINE = 0.1
# m: a base this far off the line on a bend is inside or outside it (nearer, it is on it).
OFF_BEND = 0.01
# Non-finite commands a record keeps (it counts them all).
NON_FINITE_KEPT = 5
TWIST_FIELDS = ('linear.x', 'linear.y', 'linear.z', 'angular.x', 'angular.y', 'angular.z')


class Commands(object):
    """What the solution commanded: when, how fast at most, and what was not a number."""

    def __init__(self):
        self.count = 0
        self.first = None
        self.latest = None
        self.max_linear = 0.0
        self.max_angular = 0.0
        self.non_finite = []
        self.non_finite_count = 0

    def add(self, time, values):
        """A command at simulated time `time`; values: {field of TWIST_FIELDS: number}."""
        self.count += 1
        self.first = time if self.first is None else self.first
        self.latest = time
        for field in TWIST_FIELDS:
            value = float(values.get(field, 0.0))
            if not math.isfinite(value):
                self.non_finite_count += 1
                if len(self.non_finite) < NON_FINITE_KEPT:
                    self.non_finite.append({'field': field, 'value': str(value), 'time': time})
        linear, angular = float(values.get('linear.x', 0.0)), float(values.get('angular.z', 0.0))
        if math.isfinite(linear):
            self.max_linear = max(self.max_linear, abs(linear))
        if math.isfinite(angular):
            self.max_angular = max(self.max_angular, abs(angular))

    def summary(self):
        return {'count': self.count, 'first_time': self.first, 'latest_time': self.latest,
                'max_linear': self.max_linear, 'max_angular': self.max_angular,
                'non_finite': list(self.non_finite), 'non_finite_count': self.non_finite_count}


def moves(poses):
    """(N-1,) whether the base moved or turned between consecutive poses (t, x, y, yaw)."""
    steps = np.diff(poses[:, 1:4], axis=0)
    steps[:, 2] = np.angle(np.exp(1j * steps[:, 2]))
    return np.abs(steps).max(axis=1) > STILL


def first_motion(poses):
    """Index of the pose where the base first moved (the one before its first step), or None."""
    if len(poses) < 2:
        return None
    moved = np.nonzero(moves(poses))[0]
    return int(moved[0]) if len(moved) else None


def still_from(poses, seconds):
    """Index of the pose from which the base, having moved, has neither moved nor turned for
    at least `seconds` up to the newest pose; None otherwise."""
    if len(poses) < 2:
        return None
    moved = np.nonzero(moves(poses))[0]
    if len(moved) == 0:
        return None
    stop = int(moved[-1]) + 1
    return stop if poses[-1, 0] - poses[stop, 0] >= seconds else None


def lap_index(centreline, poses):
    """Index of the pose at which a closed line's lap is done, or None."""
    if len(poses) < 2:
        return None
    driven = progress(centreline, poses[:, 1:3])
    done = np.nonzero(driven >= centreline.length)[0]
    return int(done[0]) if len(done) else None


def pieces_along(course):
    """[(start, end, piece)] of a course's path: where along the line [m] each piece lies."""
    found = []
    along = 0.0
    for piece in course['path']:
        if piece[0] == 'arc':
            length = float(piece[1]) * abs(math.radians(float(piece[2])))
        else:
            length = float(piece[1])
        found.append((along, along + length, piece))
        along += length
    return found


def piece_at(pieces, along):
    """The piece at `along` [m] of a course's pieces_along: {'kind': 'straight'} or
    {'kind': 'bend', 'radius': m, 'turn': 'left'|'right'}."""
    piece = next((p for start, end, p in pieces if start <= along < end), pieces[-1][2])
    if piece[0] != 'arc':
        return {'kind': 'straight'}
    return {'kind': 'bend', 'radius': float(piece[1]),
            'turn': 'left' if float(piece[2]) > 0 else 'right'}


def signed_offsets(centreline, xy):
    """(distance, along, offset) of (N, 2) positions: offset > 0 left of the line's direction."""
    distance, along = centreline.nearest(xy[:, 0], xy[:, 1])
    points = centreline.points
    index = np.clip(np.searchsorted(centreline.along, along, side='right') - 1,
                    0, len(points) - 2)
    tangent = points[index + 1] - points[index]
    relative = xy - points[index]
    side = np.sign(tangent[:, 0] * relative[:, 1] - tangent[:, 1] * relative[:, 0])
    return distance, along, np.where(side == 0, 1.0, side) * distance


def _place(pieces, pose, along, offset):
    """Where a pose lies on the course: its time, position, piece and side."""
    piece = piece_at(pieces, along)
    place = {'time': float(pose[0]), 'x': float(pose[1]), 'y': float(pose[2]),
             'along': float(along), 'offset': float(offset), 'piece': piece}
    if piece['kind'] == 'bend':
        place['inside'] = bool((offset > 0) == (piece['turn'] == 'left'))
    return place


def tracking(centreline, course, poses):
    """The cross-track figures of poses: RMS and worst [m], the worst's place, the RMS on
    bends and on straights, the share of the poses off the line on bends that are inside
    them (None if none is off), and where the base first left the line (None if never)."""
    xy = poses[:, 1:3]
    pieces = pieces_along(course)
    rms, worst = cross_track(centreline, xy)
    distance, along, offset = signed_offsets(centreline, xy)
    at = int(np.argmax(distance))
    places = [piece_at(pieces, a) for a in along]
    on_bend = np.array([place['kind'] == 'bend' for place in places])
    inside = np.array([place['kind'] == 'bend' and (o > 0) == (place['turn'] == 'left')
                       for place, o in zip(places, offset)])
    off_bend = on_bend & (distance > OFF_BEND)
    off = np.nonzero(distance > OFF_LINE)[0]

    def rms_of(mask):
        return float(math.sqrt(np.mean(distance[mask] ** 2))) if mask.any() else None
    return {'rms': rms, 'max': worst, 'worst': _place(pieces, poses[at], along[at], offset[at]),
            'rms_bends': rms_of(on_bend), 'rms_straights': rms_of(~on_bend),
            'inside_bends': float(np.mean(inside[off_bend])) if off_bend.any() else None,
            'left_line': _place(pieces, poses[off[0]], along[off[0]], offset[off[0]])
            if len(off) else None}


def run_record(centreline, course, poses, still, commands):
    """The record of a run on a course's line (its keys: see line_criteria).

    poses: (N, 4) true (t, x, y, yaw), the first at the run's start; still:
    the simulated seconds without motion that make a stop; commands: a
    Commands.
    """
    poses = np.asarray(poses, dtype=float).reshape(-1, 4)
    record = {'closed': centreline.closed, 'length': centreline.length,
              'speed_bound': speed_bound(centreline, MAX_LINEAR, MAX_ANGULAR),
              'commands': commands.summary(), 'poses': len(poses)}
    if len(poses) == 0:
        return dict(record, moved=False)
    motion = first_motion(poses)
    record.update(moved=motion is not None, start_time=float(poses[0, 0]),
                  end_time=float(poses[-1, 0]),
                  motion_time=float(poses[motion, 0]) if motion is not None else None)
    if centreline.closed:
        lap = lap_index(centreline, poses)
        scored = poses[:lap + 1] if lap is not None else poses
        driven = float(progress(centreline, poses[:, 1:3])[-1]) if len(poses) > 1 else 0.0
        record['lap'] = lap is not None
        record['driven'] = min(driven, centreline.length) if lap is not None else driven
    else:
        stop = still_from(poses, still)
        scored = poses[:stop + 1] if stop is not None else poses
        along = centreline.nearest(poses[:, 1], poses[:, 2])[1]
        end_distances = np.hypot(poses[:, 1] - centreline.end[0], poses[:, 2] - centreline.end[1])
        record['stop'] = None if stop is None else {
            'time': float(poses[stop, 0]), 'x': float(poses[stop, 1]), 'y': float(poses[stop, 2]),
            'end_distance': float(end_distances[stop]),
            'still_for': float(poses[-1, 0] - poses[stop, 0])}
        record['nearest_end'] = float(end_distances.min())
        last = stop if stop is not None else len(poses) - 1
        record['driven'] = float(along[last] - along[0])
    record['scored_until'] = float(scored[-1, 0])
    record['tracking'] = tracking(centreline, course, scored)
    timed = record['scored_until'] - record['motion_time'] if motion is not None else 0.0
    record['mean_speed'] = (max(record['driven'], 0.0) / timed) if timed > 0.0 else None
    return record
