"""Straight walls extracted from a laser scan.

"The shortest ray" points as readily at a chair leg, a box or a single
spurious beam as at a wall. A wall is better told by its shape: a long run
of neighbouring hits that lie on one straight line. This module cuts the
scan's hits into such runs, splits each run at its corners and fits a line
to every piece, so that a caller can ask for walls by length and straightness
and then keep track of one of them from scan to scan.
"""
import math
from collections import namedtuple

import numpy as np

from wall_follower.control.sensing.lines import Line, line_through
from wall_follower.rotation import wrap_angle

# A hit this much (m) nearer than the end of a run hides what lies beyond it.
OCCLUSION_STEP = 0.05


class Wall(namedtuple('Wall', ['line', 'length', 'rms', 'count', 'start', 'end', 'foot',
                               'start_open', 'end_open'])):
    """A straight piece of wall in the laser frame.

    line: the Line it lies on, its angle from the laser's x axis (0 =
        ahead, -pi/2 = right); distance, angle and normal are the line's.
    length: extent of the hits along the line (m); rms: their residual (m).
    count: number of hits. start, end, foot: positions along the line (m,
        from the hits' mean, increasing to the left seen from the laser) of
        the two outermost hits and of the foot of the perpendicular from the
        laser.
    start_open, end_open: True when the hits stop at that end only because
        something nearer hides the rest of the wall.
    """

    __slots__ = ()

    @property
    def distance(self):
        return self.line.distance

    @property
    def angle(self):
        return self.line.angle

    @property
    def normal(self):
        return self.line.normal

    def along_of(self, point):
        """Position along the line (m, as start, end and foot are) of the foot of the
        perpendicular from point (x, y) in the laser frame."""
        normal = self.line.normal
        return self.foot - normal[1] * point[0] + normal[0] * point[1]

    def point_at(self, along):
        """(x, y) in the laser frame of the point of the line at position along (m)."""
        normal = self.line.normal
        offset = along - self.foot
        return (self.distance * normal[0] - offset * normal[1],
                self.distance * normal[1] + offset * normal[0])

    def overlaps(self, other, margin=0.0):
        """True when this wall's seen extent, measured along other's line, overlaps
        other's or comes within margin (m) of it."""
        ends = sorted(other.along_of(self.point_at(along)) for along in (self.start, self.end))
        return ends[0] <= other.end + margin and ends[1] >= other.start - margin

    def seen_around(self, along, margin=0.0):
        """True when the wall was seen at position along, with at least margin (m) of
        wall on either side of it.

        At an open end the wall goes on out of sight, so the margin is not
        asked for there.
        """
        low = self.start if self.start_open else self.start + margin
        high = self.end if self.end_open else self.end - margin
        return low <= along <= high

    def foot_inside(self, margin=0.0):
        """True when the point of the wall straight across from the laser was seen,
        with at least margin (m) of wall on either side of it.

        Driving along the normal then ends on wall that is known to be there,
        not on wall merely extrapolated behind an obstacle, nor just short
        of a corner.
        """
        return self.seen_around(self.foot, margin)


def extract_walls(view, min_points=6, split_tolerance=0.05, max_gap=0.1,
                  gap_beams=3.0, max_rms=0.025, min_length=0.0):
    """Straight pieces of wall in a ScanView, nearest first.

    min_points: hits a piece needs to count at all.
    split_tolerance: a run is split where a hit lies farther than this (m)
        from the chord of the run, which cuts it at corners and steps.
    max_gap, gap_beams: two hits adjacent in angle belong to one run when
        they are closer than max_gap + gap_beams * range * angle between them;
        the second term lets far or grazing walls, whose hits spread out, stay
        in one piece.
    max_rms: pieces whose hits stray further from their line are not walls.
    min_length: pieces shorter than this (m) are left out.

    Isolated hits (no neighbour within the gap on either side) are dropped
    first, so a lone spurious beam can neither be a wall nor cut one in two.
    """
    hits = _connected_hits(view, min_points, max_gap, gap_beams)
    if hits is None:
        return []
    angles, ranges, breaks = hits
    points = np.column_stack((ranges * np.cos(angles), ranges * np.sin(angles)))
    walls = []
    for run in _runs(breaks, ranges):
        run_points = points[run]
        for first, stop in _merge_collinear(_split(run_points, split_tolerance), run_points,
                                            max_rms):
            wall = _fit(run_points[first:stop])
            if (wall is None or wall.count < min_points or wall.rms > max_rms
                    or wall.length < min_length):
                continue
            walls.append(_with_open_ends(wall, run, first == 0, stop == len(run), breaks,
                                         ranges))
    walls.sort(key=lambda wall: wall.distance)
    return walls


def _connected_hits(view, min_points, max_gap, gap_beams):
    """(angles, ranges, breaks) of the valid hits in angle order, isolated hits dropped;
    None when fewer than min_points remain."""
    angles = view.angles[view.valid]
    ranges = view.ranges[view.valid]
    order = np.argsort(angles, kind='mergesort')
    angles, ranges = angles[order], ranges[order]
    beam_step = max(2.0 * view.half_step, 1e-6)
    if angles.size < min_points:
        return None
    breaks = _breaks(angles, ranges, beam_step, max_gap, gap_beams)
    isolated = breaks & np.roll(breaks, 1)
    if isolated.any():
        angles, ranges = angles[~isolated], ranges[~isolated]
        if angles.size < min_points:
            return None
        breaks = _breaks(angles, ranges, beam_step, max_gap, gap_beams)
    return angles, ranges, breaks


def _with_open_ends(wall, run, at_run_start, at_run_end, breaks, ranges):
    """wall with start_open and end_open set.

    Only the ends of a run can be hidden (inside one, the hits go on), and
    an end is hidden when the hit just beyond the break is nearer. The hits
    run counter-clockwise, i.e. from the line's start to its end.
    """
    count = breaks.size
    before, after = (run[0] - 1) % count, (run[-1] + 1) % count
    hidden_first = at_run_start and breaks[before] and \
        ranges[before] < ranges[run[0]] - OCCLUSION_STEP
    hidden_last = at_run_end and breaks[run[-1]] and \
        ranges[after] < ranges[run[-1]] - OCCLUSION_STEP
    return wall._replace(start_open=bool(hidden_first), end_open=bool(hidden_last))


def _breaks(angles, ranges, beam_step, max_gap, gap_beams):
    """breaks[i] is True when hit i and the next one (circularly) are in different runs."""
    next_angles = np.roll(angles, -1)
    next_ranges = np.roll(ranges, -1)
    step = np.abs(wrap_angle(next_angles - angles))
    # A stretch of missing beams must not bridge arbitrarily wide gaps.
    step = np.clip(step, beam_step, 5.0 * beam_step)
    x0, y0 = ranges * np.cos(angles), ranges * np.sin(angles)
    x1, y1 = next_ranges * np.cos(next_angles), next_ranges * np.sin(next_angles)
    gap = np.hypot(x1 - x0, y1 - y0)
    limit = max_gap + gap_beams * np.maximum(ranges, next_ranges) * step
    return gap > limit


def _runs(breaks, ranges):
    """Index arrays of the runs between breaks, taken around the circle.

    With no break at all (a closed room seen whole) the circle is opened
    at the farthest hit, which is nearly always in a corner rather than in
    the middle of a wall.
    """
    count = breaks.size
    if breaks.any():
        first = int(np.flatnonzero(breaks)[0]) + 1
    else:
        first = int(np.argmax(ranges))
    ring = (np.arange(count) + first) % count
    cuts = np.flatnonzero(breaks[ring]) + 1
    return [run for run in np.split(ring, cuts) if run.size]


def _split(points, tolerance):
    """(start, stop) slices of points, split recursively at the hit farthest from the chord."""
    pieces = []
    stack = [(0, len(points))]
    while stack:
        start, stop = stack.pop()
        piece = points[start:stop]
        if stop - start < 3:
            pieces.append((start, stop))
            continue
        chord = piece[-1] - piece[0]
        length = math.hypot(chord[0], chord[1])
        offsets = piece - piece[0]
        if length < 1e-6:
            deviation = np.hypot(offsets[:, 0], offsets[:, 1])
        else:
            deviation = np.abs(chord[0] * offsets[:, 1] - chord[1] * offsets[:, 0]) / length
        worst = int(np.argmax(deviation))
        if deviation[worst] > tolerance and 0 < worst < stop - start - 1:
            stack.append((start + worst, stop))
            stack.append((start, start + worst))
        else:
            pieces.append((start, stop))
    pieces.sort()
    return pieces


def _merge_collinear(pieces, points, max_rms):
    """Join neighbouring pieces that one straight line fits (undoing splits at outliers)."""
    merged = []
    for piece in pieces:
        if merged:
            joined = (merged[-1][0], piece[1])
            wall = _fit(points[joined[0]:joined[1]])
            if wall is not None and wall.rms <= max_rms:
                merged[-1] = joined
                continue
        merged.append(piece)
    return merged


def _fit(points):
    """Total-least-squares line through points, as a Wall (None for fewer than 2)."""
    if len(points) < 2:
        return None
    mean, normal, distance = line_through(points)
    direction = np.array([-normal[1], normal[0]])
    along = (points - mean).dot(direction)
    across = (points - mean).dot(normal)
    return Wall(line=Line(distance, float(math.atan2(normal[1], normal[0]))),
                length=float(along.max() - along.min()),
                rms=float(np.sqrt(np.mean(across ** 2))),
                count=len(points),
                start=float(along.min()),
                end=float(along.max()),
                foot=float(-np.dot(mean, direction)),
                start_open=False,
                end_open=False)


def refine(view, wall, gate=0.05, min_points=6, max_gap=0.1, gap_beams=3.0):
    """The wall refitted to the valid hits within gate (m) of its line that run on from
    its own without a break (extract_walls' max_gap and gap_beams).

    A noisy wall may come out of extract_walls in pieces; refitting to all
    the hits near the line gathers the pieces again, and with them all the
    evidence there is for the wall's distance and direction. A wall in line
    beyond an opening (the mouth of a wing, a doorway) is another wall:
    gathered in, it made the opening look like seen wall, and a search
    that drove to the nearest seen point of the wall drove into the opening.
    """
    points = view.points()
    if len(points) == 0:
        return wall
    beam_step = max(2.0 * view.half_step, 1e-6)
    for _ in range(2):
        near = points[np.abs(wall.line.offsets(points)) <= gate]
        if len(near) >= min_points:
            near = _running_on(near, wall, beam_step, max_gap, gap_beams)
        if len(near) < min_points:
            return wall
        wall = _fit(near)
    return wall


def _running_on(points, wall, beam_step, max_gap, gap_beams):
    """The points in the runs (split as extract_walls splits them) that hold a point of
    wall's own extent, from start to end along its line."""
    angles = np.arctan2(points[:, 1], points[:, 0])
    order = np.argsort(angles, kind='mergesort')
    points, angles = points[order], angles[order]
    ranges = np.hypot(points[:, 0], points[:, 1])
    normal = np.asarray(wall.normal, dtype=float)
    along = points.dot(np.array((-normal[1], normal[0]))) + wall.foot
    own = (along >= wall.start) & (along <= wall.end)
    runs = _runs(_breaks(angles, ranges, beam_step, max_gap, gap_beams), ranges)
    kept = [run for run in runs if own[run].any()]
    return points[np.concatenate(kept)] if kept else points[:0]


def path_is_clear(view, wall, half_width, margin=0.08, origin=(0.0, 0.0)):
    """True when no hit lies in the corridor from origin straight to the wall.

    The corridor runs along the wall's normal, half_width to each side, and
    stops margin short of the wall so that the wall's own hits do not count.
    origin: where the path starts, (x, y) in the laser frame (see
    path_to_is_clear).
    """
    normal = np.asarray(wall.normal, dtype=float)
    origin = np.asarray(origin, dtype=float)
    foot = origin + (wall.distance - origin.dot(normal)) * normal
    return path_to_is_clear(view, foot, half_width, margin, origin=origin)


def path_to_is_clear(view, target, half_width, margin=0.08, wall=None, origin=(0.0, 0.0)):
    """True when no hit lies in the corridor from origin to the point target (x, y).

    The corridor is half_width to each side of the straight line there and
    stops margin short of target. With the wall target lies on, hits within
    margin of its line are its own and not in the way: a path that meets the
    wall at a slant runs along its near end. origin and target are in the
    laser frame; a robot that turns on the spot before it drives starts from
    its rotation centre, not from its laser.
    """
    origin = np.asarray(origin, dtype=float)
    way = np.asarray(target, dtype=float) - origin
    reach = math.hypot(*way)
    if reach <= 0.0:
        return True
    unit = way / reach
    points = view.points()
    relative = points - origin
    along = relative.dot(unit)
    across = np.abs(relative[:, 0] * unit[1] - relative[:, 1] * unit[0])
    blocking = (along > 0.0) & (along < reach - margin) & (across < half_width)
    if wall is not None:
        blocking &= np.abs(wall.line.offsets(points)) > margin
    return not blocking.any()


def nearest_seen_point(wall, margin=0.0):
    """(x, y) of the point of wall nearest the laser among those seen with margin of wall
    on either side (the middle of a piece shorter than twice that).

    Where the foot of the perpendicular was seen, that is the foot; where
    it lies beyond the seen piece (round its end, or behind something),
    the piece's end, pulled margin in.
    """
    low, high = wall.start + margin, wall.end - margin
    if low > high:
        low = high = 0.5 * (wall.start + wall.end)
    along = min(max(wall.foot, low), high) - wall.foot
    normal = np.asarray(wall.normal, dtype=float)
    return wall.distance * normal + along * np.array((-normal[1], normal[0]))


def closest_match(walls, reference, max_angle, max_distance):
    """The wall most like reference (same angle and distance within the limits, and seen
    where it was, within max_distance), or None.

    Used to keep hold of one wall while the robot turns and drives: from one
    scan to the next a tracked wall moves a little, a different wall (the
    other side of a corner, say) differs by far more. Angle and distance
    alone are the line's: a piece of some far wall that happens to lie in
    line with the tracked one, metres along from it, matched them exactly.
    """
    best, best_score = None, None
    for wall in walls:
        angle_error = abs(float(wrap_angle(wall.angle - reference.angle)))
        distance_error = abs(wall.distance - reference.distance)
        if (angle_error > max_angle or distance_error > max_distance
                or not wall.overlaps(reference, max_distance)):
            continue
        score = angle_error / max_angle + distance_error / max_distance
        if best_score is None or score < best_score:
            best, best_score = wall, score
    return best
