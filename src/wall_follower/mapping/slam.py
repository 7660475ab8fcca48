"""The mapper: each scan matched to the map so far, then drawn into it.

Frames as gmapping has them: the map frame starts on the odometry frame
(map -> odom is the identity until the first correction), the robot's pose
in the map is predicted from the last one by the odometry's motion since,
and scan matching corrects that prediction. map -> odom is then whatever
puts the odometry's pose of the robot where matching found it.

The fine grid scans are matched against also draws each wall between the
ends of neighbouring beams that hit it (see joined_walls), so that its
walls are lines rather than dots.

The map starts from a scan taken at rest: the odometry may be read a step
apart from the scan (Stage's "odom" localization reports the pose after
the move its laser has not seen yet), and while the robot moves that would
tilt the whole map by the step's turn. So the first scan is drawn only once
the odometry has not moved since the scan before, or where it still reads
its origin (nothing has moved since it began: the robot's very first scan,
before find_wall turns it, and before the odometry's own error has grown
into the map's frame); or, once `start_patience`
scans have gone by (a robot that never stands), at the first scan the
odometry did not turn since the scan before (`START_TURN`): a straight step
shifts the map by no more than the step, a turning one would tilt it all.

A scan is matched every time, but drawn into the map only once the robot
has moved `linear_update` or turned `angular_update` since the last one
drawn (and always the first), as gmapping does: a robot standing still
would otherwise make every wall certain from one viewpoint.

A scan is drawn only where its match is trusted: a good score (matcher.py),
a correction to the odometry's prediction that the prediction's covariance
makes likely, and a pose sure to `match_max_sigma` (tracking.py). Else the
robot's pose goes on from the prediction, and the scan is not drawn: drawn
where the map says it does not fit, or where a second fit put it, it would
draw its walls beside the true ones, and those beyond the true walls would
stay, since no later beam reaches them. Only where the prediction itself
no longer fits the scan (the odometry slipped: a wheel, a bump) may the
robot move further, to the best of the fits round the prediction, if one
is best beyond doubt (search.py); the scans after it are drawn again once
`SETTLE` of them in a row are trusted.

Each scan drawn is a keyframe of a pose graph (keyframes.py). Once the
robot is back where it has been, `loop_min_travel` or more before, its
scan is matched against the map those early keyframes alone make; a fit
there alone and within what the lap may have drifted ties the two ends of
the loop, the graph is relaxed, and the map is drawn again from every
keyframe at its relaxed pose (`_close_loop`).
"""
import math

import numpy as np

from wall_follower.params import checked
from wall_follower.params.mapping.slam import GRID, MAPPER, RULES

from .grid import LogOddsGrid, spared
from .keyframes import REDRAW, Keyframes
from .matcher import DistanceField, ScanMatcher
from .poses import between, compose, inverse
from .search import alone, best_fit, crossed
from .tracking import Prediction, in_frame, surprise

__all__ = ['Mapper', 'scan_points', 'joined_walls']

# Odometry that moved less than this between two scans is at rest [m, rad].
AT_REST = 1e-4
# Once start_patience has run out, the map starts at a scan whose odometry turned less than
# this since the scan before [rad]: the turn the map may be tilted by, as little as a match
# jitters. A map started while find_wall turned the robot at 0.49 rad/s was tilted by the
# step's 2.8 degrees, every wall drawn beside the true one (a generated room, issue 41).
START_TURN = math.radians(0.5)
# The fine grid's beams are sampled a cell apart (see LogOddsGrid).
FINE_STEP = 1.0
# What became of a scan: its pose trusted (drawn when due), not (the pose predicted or
# hardly sure, not drawn), or moved by a relocation (not drawn); or trusted, and it
# closed a loop.
TRUSTED, NOT_TRUSTED, RELOCATED = 'trusted', 'not trusted', 'relocated'
LOOP_CLOSED = 'loop closed'
# The published map's beams at a slant stop clearing at most this far short of their end
# [m] (grid.spared): at 87 degrees from a wall's normal, a cell of 5 cm across it.
SPARE_MOST = 1.0
# Scans in a row that must be trusted after a relocation before one is drawn again.
SETTLE = 3
# While the prediction does not fit, a relocation is tried at most every this many scans.
RELOCATION_EVERY = 5


def scan_points(ranges, angles, range_min, range_max, max_range):
    """Beam ends in the laser frame, split into hits and free stretches.

    A reading in [range_min, range_max) within max_range is a hit. One at or
    past range_max (including +inf: no return) proves free space, and so does
    a hit beyond max_range, each up to min(range_max, max_range). NaN, 0.0,
    -inf and anything below range_min tell nothing and are dropped.
    Returns (ends (N, 2), hit (N,) bool).
    """
    ranges = np.asarray(ranges, dtype=float)
    angles = np.asarray(angles, dtype=float)
    with np.errstate(invalid='ignore'):
        valid = ranges >= range_min
        hit = valid & (ranges < range_max) & (ranges <= max_range)
        free = valid & ~hit
    reach = min(range_max, max_range)
    length = np.where(hit, ranges, reach)[hit | free]
    used = angles[hit | free]
    ends = np.column_stack((length * np.cos(used), length * np.sin(used)))
    return ends, hit[hit | free]


def joined_walls(ends, hit, max_gap, spacing):
    """Points every `spacing` or less along the line between the ends (N, 2) of
    neighbouring beams that both hit and lie at most max_gap apart.

    Such a pair saw one surface: its beams' ends alone draw it as a dotted
    line, a cell per beam, and a scan matched to dots can settle with its
    points in the gaps, a degree or more off on a wall seen at a slant.
    """
    a, b = ends[:-1], ends[1:]
    gap = np.hypot(b[:, 0] - a[:, 0], b[:, 1] - a[:, 1])
    pair = hit[:-1] & hit[1:] & (gap <= max_gap) & (gap > spacing)
    if max_gap <= spacing or not pair.any():
        return np.zeros((0, 2))
    steps = int(math.ceil(max_gap / spacing))
    t = np.arange(1, steps)[None, :, None] / float(steps)
    a, b = a[pair][:, None, :], b[pair][:, None, :]
    return (a + t * (b - a)).reshape(-1, 2)


def _transform(pose, points):
    c, s = math.cos(pose[2]), math.sin(pose[2])
    return np.column_stack((pose[0] + c * points[:, 0] - s * points[:, 1],
                            pose[1] + s * points[:, 0] + c * points[:, 1]))


class Mapper(object):
    """Builds the map from (scan, odometry pose) pairs; laser: its pose on the robot.

    Its parameters (keyword arguments; their defaults, ranges and meanings
    are the MAPPER table) are the defaults overridden by those given.
    `outcome` says what became of the last scan (TRUSTED, NOT_TRUSTED,
    RELOCATED or LOOP_CLOSED), `decision` why, in words, and `counts` tells
    of all of them.
    """

    def __init__(self, laser=(0.0, 0.0, 0.0), **params):
        config = checked(MAPPER, params, RULES)
        self.config = config
        box = (config['xmin'], config['ymin'], config['xmax'], config['ymax'])
        self.grid = LogOddsGrid(config['delta'], *box, hit=config['hit_logodds'],
                                miss=config['miss_logodds'])
        self.fine = LogOddsGrid(config['match_resolution'], *box, hit=config['hit_logodds'],
                                miss=config['miss_logodds'], step=FINE_STEP)
        self.field = DistanceField(self.fine, _field_reach(config))
        self.matcher = ScanMatcher(self.field, _reaches(config),
                                   min_explained=config['match_min_explained'],
                                   max_misfit=config['match_max_misfit'])
        self.prediction = Prediction(config['odom_drift'])
        self.laser = tuple(laser)
        self.pose = None          # robot in the map frame
        self.odom = None          # robot in the odometry frame at the same scan
        self._step = None         # the odometry's motion up to the last scan
        self._drawn_at = None     # map pose of the last scan drawn
        self._settle = 0          # trusted scans still to come before one is drawn
        self._relocate_after = 0  # the scan count from which a relocation may be tried
        self.keyframes = Keyframes()
        self.travel = self.turned = 0.0
        self.scans = 0
        self.drawn = 0
        self.last_match = None
        self.decision = ''
        self.outcome = None
        self.counts = {NOT_TRUSTED: 0, RELOCATED: 0, 'loops closed': 0}
        self._waiting = []        # odometry of the scans seen before the map started

    def reconfigure(self, **params):
        """Go on under these parameters (the defaults, overridden) from the next scan on.

        The grids' cells and extent (the GRID section) cannot change on a map
        being built: a change to one is a ValueError.
        """
        config = checked(MAPPER, params)
        fixed = [p.name for p in GRID.parameters if config[p.name] != self.config[p.name]]
        if fixed:
            raise ValueError('%s cannot change on a map being built' % ', '.join(fixed))
        self.config = config
        for grid in (self.grid, self.fine):
            grid.hit, grid.miss = config['hit_logodds'], config['miss_logodds']
        self.field.set_reach(_field_reach(config))
        self.matcher.reaches = _reaches(config)
        self.matcher.min_explained = config['match_min_explained']
        self.matcher.max_misfit = config['match_max_misfit']
        self.prediction.drift = config['odom_drift']

    @property
    def started(self):
        return self.pose is not None

    def map_to_odom(self):
        """The map -> odom transform (x, y, yaw): identity until the first scan."""
        if self.pose is None:
            return (0.0, 0.0, 0.0)
        return compose(self.pose, inverse(self.odom))

    def occupancy_map(self, margin=5):
        """(values, origin): the observed part of the map, widened by margin cells, as
        nav_msgs/OccupancyGrid values (row 0 at the bottom) and the map-frame (x, y, yaw)
        of its lower-left corner; None before the first scan."""
        box = self.grid.observed_box(margin)
        if box is None:
            return None
        r0, r1, c0, c1 = box
        values = self.grid.occupancy()[r0:r1, c0:c1]
        res = self.grid.resolution
        return values, (self.grid.origin[0] + c0 * res, self.grid.origin[1] + r0 * res, 0.0)

    def add_scan(self, ranges, angles, range_min, range_max, odom_pose):
        """Place one scan (laser-frame ranges at angles) taken at odom_pose; returns the
        robot's map pose, or None while waiting to start the map at rest."""
        odom_pose = tuple(float(v) for v in odom_pose)
        if self.pose is None and not self._may_start(odom_pose):
            return None
        ends, hit = scan_points(ranges, angles, range_min, range_max, self.config['max_range'])
        base_ends = _transform(self.laser, ends)
        self.last_match = None
        if self.pose is None:
            pose, verdict, self.decision = odom_pose, TRUSTED, 'the first scan'
        else:
            step = between(self.odom, odom_pose)
            self.prediction.moved(step, self._step)
            self._step = step
            self.travel += math.hypot(step[0], step[1])
            self.turned += abs(step[2])
            predicted = compose(self.pose, step)
            if self.config['scan_matching'] and self.drawn:
                pose, verdict = self._place(base_ends[hit], predicted)
            else:
                pose, verdict, self.decision = predicted, TRUSTED, 'placed by odometry'
        self.pose, self.odom = pose, odom_pose
        self.outcome = verdict
        self.scans += 1
        if verdict != TRUSTED:
            self.counts[verdict] += 1
            self._settle = SETTLE if self._settle or verdict == RELOCATED else 0
        elif self._settle:
            self._settle -= 1
        elif self._due(pose):
            self._draw_keyframe(pose, base_ends, hit)
            if self.config['loop_closure'] and self.config['scan_matching']:
                self._close_loop(base_ends[hit])
        return self.pose

    def _place(self, points, predicted):
        """(pose, verdict: TRUSTED, NOT_TRUSTED or RELOCATED) of a scan whose base-frame
        hits are points, from the prediction; says why in self.decision."""
        match = self.last_match = self.matcher.match(points, predicted,
                                                     self.prediction.covariance())
        if not match.ok:
            if self.matcher.judge(predicted, points).ok:
                self.decision = 'match not trusted: ' + match.reason
                return predicted, NOT_TRUSTED
            return self._relocate(points, predicted)
        correction, distance = surprise(predicted, self.prediction, match.pose)
        window = _window(self.config)
        if (distance > self.config['match_gate'] or abs(correction[2]) > window[1]
                or math.hypot(correction[0], correction[1]) > window[0]):
            if self.matcher.judge(predicted, points).ok:
                self.decision = ('match not trusted: %.1f cm, %.1f deg from the prediction, '
                                 '%.1f standard deviations, where the prediction fits too'
                                 % (100.0 * math.hypot(correction[0], correction[1]),
                                    math.degrees(correction[2]), distance))
                return predicted, NOT_TRUSTED
            return self._relocate(points, predicted)
        if not match.sigma <= self.config['match_max_sigma']:
            self.decision = ('match not trusted: the pose stays uncertain by %.1f cm'
                             % (100.0 * match.sigma))
            return match.pose, NOT_TRUSTED
        self.prediction.fixed(in_frame(match.covariance, match.pose[2]))
        self.decision = 'matched'
        return match.pose, TRUSTED

    def _relocate(self, points, predicted):
        """The prediction does not fit the scan, and no match near it does: the odometry
        slipped (a wheel, a bump). The robot is moved to the best of the fits found round
        the prediction (search.best_fit; the scan not drawn), if one is. Tried at most
        every RELOCATION_EVERY scans while the prediction does not fit."""
        if self.scans < self._relocate_after:
            self.decision = 'match not trusted: the prediction does not fit the scan'
            return predicted, NOT_TRUSTED
        self._relocate_after = self.scans + RELOCATION_EVERY
        best, why = best_fit(self.matcher, points, predicted, _window(self.config),
                             self.config['match_max_sigma'],
                             lambda pose: self._crossed(pose, points))
        if best is None:
            self.decision = ('match not trusted: the prediction does not fit the scan, and %s'
                             % why)
            return predicted, NOT_TRUSTED
        self.last_match = best
        self.prediction.fixed()
        moved = between(predicted, best.pose)
        self.decision = ('relocated: the odometry slipped %.1f cm, %.1f deg; not drawn'
                         % (100.0 * math.hypot(moved[0], moved[1]), math.degrees(moved[2])))
        return best.pose, RELOCATED

    def _crossed(self, pose, points):
        """The share of the hits (base frame) whose beam, from the laser at pose, passes
        through a wall of the fine grid short of the reach of its end."""
        return crossed(self.fine, compose(pose, self.laser), _transform(pose, points),
                       2.0 * self.config['match_reach'])

    def _may_start(self, odom_pose):
        previous = self._waiting[-1] if self._waiting else None
        self._waiting.append(odom_pose)
        if previous is None:
            return odom_pose == (0.0, 0.0, 0.0) or self.config['start_patience'] == 0
        moved = between(previous, odom_pose)
        if math.hypot(moved[0], moved[1]) < AT_REST and abs(moved[2]) < AT_REST:
            return True
        return len(self._waiting) > self.config['start_patience'] and abs(moved[2]) < START_TURN

    def _due(self, pose):
        if self._drawn_at is None:
            return True
        moved = between(self._drawn_at, pose)
        return (math.hypot(moved[0], moved[1]) >= self.config['linear_update']
                or abs(moved[2]) >= self.config['angular_update'])

    def _draw_keyframe(self, pose, base_ends, hit):
        self.keyframes.add(pose, base_ends, hit, self.travel, self.turned)
        self._draw(pose, base_ends, hit)
        self.field.update()
        self._drawn_at = pose
        self.drawn += 1

    def _draw(self, pose, base_ends, hit, grids=None):
        origin = compose(pose, self.laser)[:2]
        ends = _transform(pose, base_ends)
        coarse, fine = grids or (self.grid, self.fine)
        if coarse is not None:
            coarse.integrate(origin, ends, hit,
                             spared(origin, ends, hit, coarse.resolution, SPARE_MOST))
        drawn = fine.integrate(origin, ends, hit)
        fine.mark_hits(joined_walls(ends, hit, self.config['match_join_gap'],
                                    fine.resolution / 2.0), skip=drawn)

    def _close_loop(self, points):
        """Tie the newest keyframe to the early ones it is back beside, if the map they
        alone make places it without doubt and within what the lap may have drifted;
        then relax the graph and, where that moved a keyframe, redraw the map."""
        loop = self.keyframes.loop(self.config['loop_min_travel'], self.config['loop_radius'])
        if loop is None:
            return
        anchor, early = loop
        pose = self.pose
        matcher = self._early_map(early)
        match = matcher.match(points, pose)
        error = between(pose, match.pose)
        allowed = self.keyframes.allowed(anchor, self.config['match_gate'])
        if (math.hypot(error[0], error[1]) > allowed[0] or abs(error[2]) > allowed[1]
                or not alone(matcher, points, pose, match, self.config['match_max_sigma'])):
            self.decision = 'matched; no loop closed with the map of the early scans here'
            return
        moved, turned = self.keyframes.close(anchor, between(self.keyframes.pose(anchor),
                                                             match.pose),
                                             self.config['loop_min_travel'])
        self.counts['loops closed'] += 1
        self.outcome = LOOP_CLOSED
        redraw = moved >= REDRAW[0] or turned >= REDRAW[1]
        self.decision = ('loop closed: %.1f cm, %.2f deg off; the graph relaxed (poses moved '
                         'up to %.1f cm, %.2f deg)%s'
                         % (100.0 * math.hypot(error[0], error[1]), math.degrees(error[2]),
                            100.0 * moved, math.degrees(turned),
                            ', the map redrawn' if redraw else ''))
        if redraw:
            self._redraw()
        self.pose = self._drawn_at = self.keyframes.pose(self.keyframes.frames[-1])

    def _early_map(self, early):
        """A matcher on the map the early keyframes alone make."""
        ends = np.concatenate([_transform(self.keyframes.pose(k), k.ends) for k in early])
        margin = self.field.reach + self.config['loop_radius'] + self.config['match_reach']
        low = np.maximum(ends.min(axis=0) - margin, (self.config['xmin'], self.config['ymin']))
        high = np.minimum(ends.max(axis=0) + margin, (self.config['xmax'], self.config['ymax']))
        fine = LogOddsGrid(self.fine.resolution, low[0], low[1], high[0], high[1],
                           hit=self.fine.hit, miss=self.fine.miss, step=FINE_STEP)
        for k in early:
            self._draw(self.keyframes.pose(k), k.ends, k.hit, (None, fine))
        field = DistanceField(fine, self.field.reach)
        field.update()
        return ScanMatcher(field, self.matcher.reaches, min_explained=self.matcher.min_explained,
                           max_misfit=self.matcher.max_misfit)

    def _redraw(self):
        """Both grids drawn anew from every keyframe at its pose in the graph."""
        for grid in (self.grid, self.fine):
            grid.clear()
        for k in self.keyframes:
            self._draw(self.keyframes.pose(k), k.ends, k.hit)
        self.field.values.fill(self.field.reach)
        self.field.update()


def _field_reach(config):
    return max(config['match_capture'], config['match_reach'])


def _window(config):
    return (config['search_window_linear'], config['search_window_angular'])


def _reaches(config):
    return (config['match_capture'], config['match_reach'])
