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
the odometry has not moved since the scan before, or after `start_patience`
scans, whichever comes first.

A scan is matched every time, but drawn into the map only once the robot
has moved `linear_update` or turned `angular_update` since the last one
drawn (and always the first), as gmapping does: a robot standing still
would otherwise make every wall certain from one viewpoint. A scan whose
match is not trusted (see matcher.py) is not drawn at all: the robot's pose
goes on from the odometry's prediction, but a scan drawn there, where the
map says it does not fit, would draw its walls beside the true ones, and
those beyond the true walls would stay, since no later beam reaches them.
"""
import math

import numpy as np

from wall_follower.params import checked
from wall_follower.params.mapping.slam import GRID, MAPPER, RULES

from .grid import LogOddsGrid
from .matcher import DistanceField, ScanMatcher
from .poses import between, compose, inverse

__all__ = ['Mapper', 'scan_points', 'joined_walls']

# Odometry that moved less than this between two scans is at rest [m, rad].
AT_REST = 1e-4


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
    """

    def __init__(self, laser=(0.0, 0.0, 0.0), **params):
        config = checked(MAPPER, params, RULES)
        self.config = config
        box = (config['xmin'], config['ymin'], config['xmax'], config['ymax'])
        self.grid = LogOddsGrid(config['delta'], *box, hit=config['hit_logodds'],
                                miss=config['miss_logodds'])
        self.fine = LogOddsGrid(config['match_resolution'], *box, hit=config['hit_logodds'],
                                miss=config['miss_logodds'])
        self.field = DistanceField(self.fine, _field_reach(config))
        self.matcher = ScanMatcher(self.field, _window(config), _reaches(config),
                                   min_explained=config['match_min_explained'])
        self.laser = tuple(laser)
        self.pose = None          # robot in the map frame
        self.odom = None          # robot in the odometry frame at the same scan
        self._drawn_at = None     # map pose of the last scan drawn
        self.scans = 0
        self.drawn = 0
        self.last_match = None
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
        self.matcher.window = _window(config)
        self.matcher.reaches = _reaches(config)
        self.matcher.min_explained = config['match_min_explained']

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
        if self.pose is None:
            predicted = odom_pose
        else:
            predicted = compose(self.pose, between(self.odom, odom_pose))
        pose = predicted
        self.last_match = None
        if self.config['scan_matching'] and self.drawn:
            self.last_match = self.matcher.match(base_ends[hit], predicted)
            pose = self.last_match.pose
        self.pose, self.odom = pose, odom_pose
        self.scans += 1
        trusted = self.last_match is None or self.last_match.ok
        if trusted and self._due(pose):
            self._draw(pose, base_ends, hit)
        return pose

    def _may_start(self, odom_pose):
        previous = self._waiting[-1] if self._waiting else None
        self._waiting.append(odom_pose)
        if previous is not None:
            moved = between(previous, odom_pose)
            if math.hypot(moved[0], moved[1]) < AT_REST and abs(moved[2]) < AT_REST:
                return True
        return len(self._waiting) > self.config['start_patience']

    def _due(self, pose):
        if self._drawn_at is None:
            return True
        moved = between(self._drawn_at, pose)
        return (math.hypot(moved[0], moved[1]) >= self.config['linear_update']
                or abs(moved[2]) >= self.config['angular_update'])

    def _draw(self, pose, base_ends, hit):
        origin = compose(pose, self.laser)[:2]
        ends = _transform(pose, base_ends)
        self.grid.integrate(origin, ends, hit)
        drawn = self.fine.integrate(origin, ends, hit)
        self.fine.mark_hits(joined_walls(ends, hit, self.config['match_join_gap'],
                                         self.fine.resolution / 2.0), skip=drawn)
        self.field.update()
        self._drawn_at = pose
        self.drawn += 1


def _field_reach(config):
    return max(config['match_capture'], config['match_reach'])


def _window(config):
    return (config['search_window_linear'], config['search_window_angular'])


def _reaches(config):
    return (config['match_capture'], config['match_reach'])
