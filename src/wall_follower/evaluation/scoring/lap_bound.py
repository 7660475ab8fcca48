"""T*: the least time in which any robot under the speed limits can lap a world in the band.

A follower's lap time alone says little: a room with many corners takes
longer than one with few. Its ratio to the path length at full speed is
no better a yardstick, since a path that pivots at every corner is short.
T* is what the limits themselves allow: the least time to go once round
the band [0.20, 0.30] m from the wall, the laser (the point the band is
judged from) never leaving it, with |v| <= MAX_LINEAR and |w| <=
MAX_ANGULAR, commands taking effect at once as they do in the simulator.

Without an acceleration limit the time of a path is local: an arc of
length s that turns through a takes max(s / v_max, |a| / w_max), so a
path is fast where it is straight or turns no tighter than v_max / w_max
(0.39 m), and a pivot costs its angle at the full turn rate. The lap is
found by optimising a path through the band's corridor: stations every
SPACING metres along the band's middle line, the rotation centre free to
move along each station's normal, the laser held in the band by a
penalty. The path is flown as an arc from each station to the next and a
pivot at each station where the arcs' headings differ (_Flown). The
optimisation (scipy's L-BFGS-B) first times the path as if every turn
were spread over the stations either side of it, which is smooth, then
the arcs and pivots themselves; its variables are smoothed along the loop
(a change of variables), or it would take as many steps as there are
stations to carry a change round the loop. The fastest lap rides the
band's outer edge round convex corners at full speed and across inner
corners to the point 0.30 m from both walls, turning there.

The band is the course judge's: the nearest range within 30 degrees of the
robot's right, read from the laser. That is never nearer than the nearest
wall, and farther where the nearest wall is out of the judge's sector (a
lap that turns at an inner corner's far point reads the walls 45 degrees
round, 1 cm beyond the band). So the bound is judged as well: the judge's
reading at the stations holds each station's high edge down by what it
reads beyond the nearest wall (fastest_lap(judged=True)).

A bound is checked by driving it in the simulator: driven_bound.py.

Pure numpy and scipy, free of ROS; the world's walls come from its file.
"""
import math
from collections import namedtuple

import numpy as np
from scipy.ndimage import distance_transform_edt
from scipy.optimize import minimize
from scipy.sparse import csc_matrix, diags
from scipy.sparse.linalg import splu
from scipy.spatial import cKDTree

from wall_follower.evaluation.scoring.course import BAND, TARGET, CourseMap
from wall_follower.evaluation.scoring.geometry import segment_distance
from wall_follower.params.driving import MAX_ANGULAR, MAX_LINEAR
from wall_follower.rotation import wrap_angle

# Stations along the band, this far apart [m].
SPACING = 0.02
# The band's middle line is smoothed over this arc length each side of a
# station [m] before its normals are taken: a sharp inner corner of the
# middle line would make neighbouring normals cross inside the band.
SMOOTHING = 0.1
# How far inside its edges the laser is held [m]: the bound's lap must be
# one a judge scores in band.
MARGIN = 0.0015
# Grid step of the tabulated wall distance [m]; walls are sampled this
# densely along their edges for it.
GRID = 0.005
EDGE_SAMPLE = 0.001
# The step of the walk along the band's middle line [m].
WALK_STEP = 0.01
# The optimisation's stages: which timing of the path, the penalty weight on
# the laser's squared excursions out of the band [s/m^2], and the most steps.
STAGES = (('spread', 1e5, 3000), ('spread', 1e7, 1000), ('flown', 1e7, 500))
# The judged bound (fastest_lap(judged=True)): at most this many rounds of
# lowering the band's high edge where the judge reads out of it, each followed
# by the last stage again; done when the judge reads no more than
# JUDGED_TOLERANCE [m] past the edge anywhere. The high edge is never lowered
# to less than JUDGED_WIDTH [m] above the low one.
JUDGED_ROUNDS = 4
JUDGED_TOLERANCE = 0.001
JUDGED_WIDTH = 0.01
# The variables are smoothed along the loop over about this many stations.
CORRELATION = 10.0
# Smoothing of max() and abs() in the times [s] and [rad].
SMOOTH_TIME = 1e-3
SMOOTH_TURN = 1e-4

LapBound = namedtuple('LapBound', 'time length centres turns laser excursion')
LapBound.__doc__ = """time: T* [s]; length: the rotation centre's path length [m];
centres (M, 2): the rotation centre at each station, round the loop with the wall on the
right; turns (M,): the turn of the arc each piece, from one station to the next, is flown
with [rad] (see _Flown); laser: (x, y) of the laser in the robot's frame; excursion: the
farthest the laser goes past the band's edges held MARGIN inside, at the stations [m]
(0 when it keeps within)."""


class BoundError(Exception):
    """No lap through the band from the given start (no wall near it, or the band breaks)."""


class WallDistance(object):
    """Distance to a world's walls: nearest() from their edges sampled every EDGE_SAMPLE,
    and distance() and gradient() interpolated in a table on a GRID (tabulate()), fast
    enough for the thousands of calls of an optimisation."""

    def __init__(self, edges):
        self.edges = np.asarray(edges, dtype=float).reshape(-1, 2, 2)
        if not len(self.edges):
            raise BoundError('the world has no walls')
        samples, owners = [], []
        for index, (a, b) in enumerate(self.edges):
            count = max(2, int(math.ceil(math.hypot(*(b - a)) / EDGE_SAMPLE)) + 1)
            samples.append(a + np.linspace(0.0, 1.0, count)[:, None] * (b - a))
            owners.append(np.full(count, index))
        self.samples = np.concatenate(samples)
        self.sample_edges = np.concatenate(owners)
        self.tree = cKDTree(self.samples)
        self.origin = self.table = None

    def nearest(self, points):
        """Distances of (N, 2) points to the nearest wall, and unit vectors from it to them."""
        points = np.atleast_2d(points)
        distance, index = self.tree.query(points)
        away = (points - self.samples[index]) / np.maximum(distance, 1e-12)[:, None]
        return distance, away

    def tabulate(self, low, high, reach=1.0):
        """Tabulate the distance over the box from low (x, y) to high (x, y).

        A distance transform of the grid's cells finds, for each grid point,
        the nearest cell a wall passes through (walls within reach of the
        box counted); the point's distance is the exact one to the edges
        through that cell and the cells round it.
        """
        self.origin = np.asarray(low, dtype=float)
        size = np.ceil((np.asarray(high) - self.origin) / GRID).astype(int) + 1
        pad = int(math.ceil(reach / GRID))
        cells = np.round((self.samples - self.origin) / GRID).astype(int) + pad
        inside = np.all((cells >= 1) & (cells < size + 2 * pad - 1), axis=1)
        if not inside.any():
            raise BoundError('no wall near the band')
        owner = np.full(tuple(size[::-1] + 2 * pad), -1)
        owner[cells[inside, 1], cells[inside, 0]] = self.sample_edges[inside]
        rows, cols = distance_transform_edt(owner < 0, return_distances=False,
                                            return_indices=True)
        rows = rows[pad:pad + size[1], pad:pad + size[0]]
        cols = cols[pad:pad + size[1], pad:pad + size[0]]
        ys, xs = np.mgrid[0:size[1], 0:size[0]] * GRID
        points = np.stack((xs + self.origin[0], ys + self.origin[1]), axis=-1)
        self.table = np.full(rows.shape, np.inf)
        for row_step in (-1, 0, 1):
            for col_step in (-1, 0, 1):
                edge = owner[rows + row_step, cols + col_step]
                ends = self.edges[np.maximum(edge, 0)]
                distance = segment_distance(points, ends[..., 0, :], ends[..., 1, :])
                self.table = np.minimum(self.table, np.where(edge >= 0, distance, np.inf))

    def _cells(self, points):
        cell = (np.asarray(points, dtype=float) - self.origin) / GRID
        rows, cols = self.table.shape
        col = np.clip(cell[..., 0], 0.0, cols - 1.000001)
        row = np.clip(cell[..., 1], 0.0, rows - 1.000001)
        c0, r0 = col.astype(int), row.astype(int)
        t = self.table
        return col - c0, row - r0, t[r0, c0], t[r0, c0 + 1], t[r0 + 1, c0], t[r0 + 1, c0 + 1]

    def distance(self, points):
        """Distances of (..., 2) points to the nearest wall, interpolated in the table."""
        fc, fr, t00, t01, t10, t11 = self._cells(points)
        return (t00 * (1 - fc) + t01 * fc) * (1 - fr) + (t10 * (1 - fc) + t11 * fc) * fr

    def gradient(self, points):
        """(..., 2) gradients of distance() at points."""
        fc, fr, t00, t01, t10, t11 = self._cells(points)
        return np.stack(((t01 - t00) * (1 - fr) + (t11 - t10) * fr,
                         (t10 - t00) * (1 - fc) + (t11 - t01) * fc), axis=-1) / GRID


def band_middle(walls, start, target=TARGET, step=WALK_STEP, longest=200.0):
    """The closed line target from the walls that the walk from the point of it nearest
    start runs round, walked with the wall on the right: (N, 2) points about step apart.

    The loop closes where the walk comes back onto its own way, going the
    same way, which is most often where it began. In a notch between two
    walls less than twice target apart, though, the point nearest start can
    lie on a stretch of the line that the walk, once round, passes by a few
    centimetres off: the loop is then the one it has settled into.

    Raises BoundError when the walk does not come back within longest metres.
    """
    point = _onto_line(walls, np.asarray(start, dtype=float)[:2], target)
    walked, points = 0.0, [point]
    while walked < longest:
        # The way on is read a step ahead: past an inner corner's vertex it
        # is along the next wall already.
        along = _along(walls, point)
        ahead = _along(walls, point + step * along)
        moved = _onto_line(walls, point + step * ahead, target, rounds=3)
        if math.hypot(*(moved - point)) < 0.5 * step:
            # Less than a step short of an inner corner's vertex, the way
            # along the next wall can lead straight off the wall still
            # nearest, and the line pulls the point back where it was
            # (Stage's saw-tooth walls make such a point): step along
            # that wall, past the vertex.
            moved = _onto_line(walls, point + step * along, target, rounds=3)
        heading, point = moved - point, moved
        walked += step
        closed = _rejoined(points[:-20], point, heading, 0.75 * step)
        if closed is not None:
            return np.array(points[closed:])
        points.append(point)
    raise BoundError('the band from (%.2f, %.2f) does not close within %.0f m'
                     % (start[0], start[1], longest))


def _rejoined(points, point, heading, within):
    """Index of the point of points (a walk so far) that point, reached by the step heading,
    lies within `within` of with the walk going the same way there; None if there is none.

    Going the same way: out of a dead end as narrow as the band's middle
    line, the walk comes back along its own way the other way round.
    """
    if len(points) < 2:
        return None
    way = np.asarray(points)
    gaps = np.hypot(*(way[:-1] - point).T)
    near = np.flatnonzero(gaps < within)
    same = np.dot(way[near + 1] - way[near], heading) > 0.0
    return int(near[same][0]) if same.any() else None


def _along(walls, point):
    """The unit vector along the walls' distance lines at point, the wall on the right."""
    _, away = walls.nearest(point)
    return np.array((away[0, 1], -away[0, 0]))


def _onto_line(walls, point, target, rounds=20):
    """point moved along the distance's gradient onto the line target from the walls."""
    for _ in range(rounds):
        distance, away = walls.nearest(point)
        point = point - (distance[0] - target) * away[0]
    return point


class Corridor(object):
    """The band round one loop: stations along its smoothed middle line, each with the
    interval of offsets along its normal (to the left, away from the wall) where the
    band is, held MARGIN inside its edges."""

    def __init__(self, walls, middle, band=BAND, margin=MARGIN, spacing=SPACING):
        self.walls = walls
        middle = _resampled(middle, spacing)
        window = max(1, int(round(SMOOTHING / spacing)))
        for _ in range(2):
            middle = _periodic_mean(middle, window)
        self.stations = middle
        tangent = np.roll(middle, -1, axis=0) - np.roll(middle, 1, axis=0)
        tangent /= np.hypot(tangent[:, 0], tangent[:, 1])[:, None]
        self.normals = np.column_stack((-tangent[:, 1], tangent[:, 0]))
        self.low, self.top = band[0] + margin, band[1] - margin
        self.high = np.full(len(middle), self.top)
        self.offsets, lost = self._intervals()
        if lost.any():
            raise BoundError('the band is lost at (%.2f, %.2f)'
                             % tuple(self.stations[np.flatnonzero(lost)[0]]))

    def hold_judged(self, farther):
        """Lower each station's high edge so that the judge's reading, `farther` (M,) [m]
        beyond the laser's distance to the nearest wall there, stays within the band's
        (held margin inside). Never raised, nor lowered to less than JUDGED_WIDTH above
        the low edge, nor where the station's normal would then miss the band."""
        before, offsets = self.high, self.offsets
        self.high = np.maximum(np.minimum(self.high, self.top - farther),
                               self.low + JUDGED_WIDTH)
        self.offsets, lost = self._intervals()
        self.high[lost], self.offsets[lost] = before[lost], offsets[lost]

    def _intervals(self, reach=0.15, step=0.002):
        """(M, 2) offsets along each normal between which the band is, at each station,
        and (M,) whether the normal misses the band there (its interval then NaN)."""
        offsets = np.arange(-reach, reach + step / 2, step)
        points = self.stations[:, None, :] + offsets[None, :, None] * self.normals[:, None, :]
        distance = self.walls.distance(points)
        high = self.high[:, None]
        inside = (distance >= self.low) & (distance <= high)
        middle = np.argmin(np.abs(distance - 0.5 * (self.low + high))
                           + 10.0 * (np.abs(offsets) > 0.5 * reach)[None, :], axis=1)
        intervals = np.full((len(self.stations), 2), np.nan)
        lost = ~inside[np.arange(len(middle)), middle]
        for index, (row, centre) in enumerate(zip(inside, middle)):
            if lost[index]:
                continue
            outside = np.flatnonzero(~row)
            below, above = outside[outside < centre], outside[outside > centre]
            intervals[index] = (offsets[below[-1] + 1] if below.size else -reach,
                                offsets[above[0] - 1] if above.size else reach)
        return intervals, lost


def _resampled(loop, spacing):
    """A closed loop resampled at equal arc lengths about spacing apart."""
    closed = np.vstack((loop, loop[:1]))
    lengths = np.concatenate(([0.0], np.cumsum(np.hypot(*np.diff(closed, axis=0).T))))
    count = max(8, int(round(lengths[-1] / spacing)))
    at = np.arange(count) * lengths[-1] / count
    return np.column_stack((np.interp(at, lengths, closed[:, 0]),
                            np.interp(at, lengths, closed[:, 1])))


def _periodic_mean(points, window):
    """Each point of a closed loop replaced by the mean of the window points each side."""
    total = np.zeros_like(points)
    for shift in range(-window, window + 1):
        total += np.roll(points, shift, axis=0)
    return total / (2 * window + 1)


class _Timing(object):
    """A timing of a path through the corridor, with a penalty on the laser leaving the
    band: (value, gradient) of its variables, the first M of them the offsets of the
    rotation centre along the M stations' normals (the path is the polyline through
    the centres)."""

    def __init__(self, corridor, laser_mount):
        self.corridor = corridor
        self.laser_mount = np.asarray(laser_mount, dtype=float)

    def centres(self, offsets):
        return self.corridor.stations + offsets[:, None] * self.corridor.normals

    def pieces(self, offsets):
        """(centres, unit vectors along the pieces, their lengths, their directions)."""
        centre = self.centres(offsets)
        piece = np.roll(centre, -1, axis=0) - centre
        length = np.maximum(np.hypot(piece[:, 0], piece[:, 1]), 1e-12)
        return centre, piece / length[:, None], length, np.arctan2(piece[:, 1], piece[:, 0])

    def laser(self, centre, heading):
        """(where the laser is at the centres, on the headings; its derivative by them)."""
        c, s = np.cos(heading), np.sin(heading)
        x, y = self.laser_mount
        return (centre + np.column_stack((c * x - s * y, s * x + c * y)),
                np.column_stack((-s * x - c * y, c * x - s * y)))

    def excursions(self, laser):
        """How far the laser positions are outside the band (held MARGIN inside) [m], and
        the derivative of that by the positions."""
        walls = self.corridor.walls
        distance = walls.distance(laser)
        below = self.corridor.low - distance
        above = distance - self.corridor.high
        side = np.where(below > 0.0, -1.0, np.where(above > 0.0, 1.0, 0.0))
        return np.maximum(0.0, np.maximum(below, above)), side[:, None] * walls.gradient(laser)

    def penalty(self, centre, headings, weight):
        """(weight times the laser's squared excursions at the stations on each heading,
        their gradient by the centres (M, 2), by each heading (M,))."""
        value, by_centre, by_heading = 0.0, np.zeros_like(centre), []
        for heading in headings:
            laser, turning = self.laser(centre, heading)
            excursion, by_laser = self.excursions(laser)
            value += weight * float((excursion ** 2).sum())
            pull = (2.0 * weight * excursion)[:, None] * by_laser
            by_centre += pull
            by_heading.append((pull * turning).sum(axis=1))
        return value, by_centre, by_heading

    def excursion(self, centre, headings):
        """The farthest the laser is outside the band (held MARGIN inside) [m]."""
        return max(float(self.excursions(self.laser(centre, heading)[0])[0].max())
                   for heading in headings)

    def gradient(self, unit, length, by_length, by_direction, by_centre):
        """The gradient by the offsets, from those by the pieces' lengths and directions
        and by the centres."""
        across = np.column_stack((-unit[:, 1], unit[:, 0])) / length[:, None]
        by_end = by_length[:, None] * unit + by_direction[:, None] * across
        by_centre = by_centre + np.roll(by_end, 1, axis=0) - by_end
        return (by_centre * self.corridor.normals).sum(axis=1)


class _Spread(_Timing):
    """The path's time with each turn spread over the pieces either side of it.

    The turn at station i, the direction of piece i (to station i + 1) less that of
    piece i - 1, is flown over the halves of those two pieces, and takes max(their
    length / MAX_LINEAR, |turn| / MAX_ANGULAR). Smooth, so the optimiser gets far
    with it fast; but a pivot costs its angle and lets the robot cover those halves
    as it turns, which no robot can. The laser is checked at each station at the
    heading the robot has there, halfway between the pieces' directions, and at the
    directions of the pieces on either side.
    """

    @staticmethod
    def headings(direction):
        before = np.roll(direction, 1)
        return before + 0.5 * wrap_angle(direction - before), direction, before

    def __call__(self, offsets, weight):
        centre, unit, length, direction = self.pieces(offsets)
        turn = wrap_angle(direction - np.roll(direction, 1))
        time, by_moving, by_turn = _slower(0.5 * (length + np.roll(length, 1)), turn)
        headings = self.headings(direction)
        value, by_centre, (by_mean, by_after, by_before) = self.penalty(centre, headings,
                                                                        weight)
        by_length = 0.5 * (by_moving + np.roll(by_moving, -1))
        by_direction = (by_turn - np.roll(by_turn, -1) + by_after + 0.5 * by_mean
                        + np.roll(by_before + 0.5 * by_mean, -1))
        return (value + float(time.sum()),
                self.gradient(unit, length, by_length, by_direction, by_centre))


class _Flown(_Timing):
    """The path's time flown as arcs and pivots; the variables after the offsets are the
    turns of the arcs.

    A piece flown as an arc turning through a whose chord it is leaves its station
    at its direction less a / 2 and arrives at the next at its direction plus a /
    2, taking max(length / MAX_LINEAR, |a| / MAX_ANGULAR); at a station the robot
    pivots from the heading it arrived with to the one it leaves with, at
    MAX_ANGULAR (flight_time()). A robot can fly that exactly. The laser is checked
    at each station at the headings the robot arrives and leaves with, and halfway
    between.
    """

    def split(self, variables):
        count = len(self.corridor.stations)
        return variables[:count], variables[count:]

    @staticmethod
    def headings(direction, turn):
        """The headings the laser is checked at (M,) each: arriving at each station,
        leaving it, and halfway between."""
        arrive = np.roll(direction + 0.5 * turn, 1)
        leave = arrive + wrap_angle(direction - 0.5 * turn - arrive)
        return arrive, leave, 0.5 * (arrive + leave)

    def __call__(self, variables, weight):
        offsets, turn = self.split(variables)
        centre, unit, length, direction = self.pieces(offsets)
        time, by_length, by_turn = _slower(length, turn)
        pivot = wrap_angle(direction - np.roll(direction, 1)) - 0.5 * (turn + np.roll(turn, 1))
        pivoting, by_pivot = _smooth_abs(pivot)
        by_pivot = by_pivot / MAX_ANGULAR
        value, by_centre, (by_arrive, by_leave, by_mean) = self.penalty(
            centre, self.headings(direction, turn), weight)
        by_arrive = by_arrive + 0.5 * by_mean
        by_leave = by_leave + 0.5 * by_mean
        by_direction = by_pivot - np.roll(by_pivot, -1) + by_leave + np.roll(by_arrive, -1)
        by_turn = (by_turn - 0.5 * (by_pivot + np.roll(by_pivot, -1))
                   + 0.5 * (np.roll(by_arrive, -1) - by_leave))
        value += float(time.sum() + pivoting.sum() / MAX_ANGULAR)
        return value, np.concatenate((self.gradient(unit, length, by_length, by_direction,
                                                    by_centre), by_turn))


def _slower(length, turn):
    """max(length / MAX_LINEAR, |turn| / MAX_ANGULAR), rounded off, and its derivatives
    by length and by turn."""
    moving = length / MAX_LINEAR
    arc, by_arc = _smooth_abs(turn)
    turning = arc / MAX_ANGULAR
    spread = np.sqrt((moving - turning) ** 2 + SMOOTH_TIME ** 2)
    by_moving = 0.5 * (1.0 + (moving - turning) / spread)
    return (0.5 * (moving + turning + spread), by_moving / MAX_LINEAR,
            (1.0 - by_moving) * by_arc / MAX_ANGULAR)


def _smooth_abs(values):
    """|values|, rounded off within SMOOTH_TURN of 0, and its derivative."""
    smooth = np.sqrt(values ** 2 + SMOOTH_TURN ** 2)
    return smooth, values / smooth


class _Smoothed(object):
    """A timing as a function of smoothed variables: offsets = S z, S the inverse of
    I + CORRELATION^2 L (L the second difference round the loop), so that a step of the
    optimiser moves neighbouring stations together. Offsets beyond bounds are
    penalised as the laser is."""

    def __init__(self, timing, bounds):
        count = len(bounds)
        self.timing, self.bounds = timing, bounds
        ones = np.ones(count)
        loop = diags([2.0 * ones, -ones[1:], -ones[1:], -ones[:1], -ones[:1]],
                     [0, 1, -1, count - 1, 1 - count])
        self.inverse = csc_matrix(diags([ones], [0]) + CORRELATION ** 2 * loop)
        self.smoothing = splu(self.inverse)

    def variables(self, smoothed):
        count = len(self.bounds)
        return np.concatenate((self.smoothing.solve(smoothed[:count]), smoothed[count:]))

    def smoothed(self, variables):
        count = len(self.bounds)
        return np.concatenate((self.inverse.dot(variables[:count]), variables[count:]))

    def __call__(self, smoothed, weight):
        count = len(self.bounds)
        variables = self.variables(smoothed)
        value, gradient = self.timing(variables, weight)
        offsets = variables[:count]
        outside = (np.minimum(0.0, offsets - self.bounds[:, 0])
                   + np.maximum(0.0, offsets - self.bounds[:, 1]))
        gradient[:count] += 2.0 * weight * outside
        gradient[:count] = self.smoothing.solve(gradient[:count])
        return value + weight * float((outside ** 2).sum()), gradient


def fastest_lap(world_path, start, spacing=SPACING, margin=MARGIN, judged=True):
    """T* of the band loop nearest start ((x, y) in the world of world_path): a LapBound.

    margin: how far inside the band's edges the laser is held [m]. judged:
    hold the judge's reading in the band too (the nearest range within
    RIGHT_SECTOR of the right, course.CourseMap.right_wall_distance), not
    only the laser's distance to the nearest wall. The two differ where the
    nearest wall is outside the judge's sector: across an inner corner, the
    judge reads the wall beside the robot, farther than the one ahead. The
    judge's reading is taken at the stations; where it leaves the band the
    station's high edge is lowered by the difference, and the path optimised
    again from where it was, at most JUDGED_ROUNDS times. Raises BoundError when
    there is no band loop there.
    """
    course = CourseMap(world_path)
    laser = course.laser_offset[:2]
    walls = WallDistance(course.edges)
    middle = band_middle(walls, start)
    walls.tabulate(middle.min(axis=0) - 0.2, middle.max(axis=0) + 0.2)
    corridor = Corridor(walls, middle, margin=margin, spacing=spacing)
    spread, flying = _Spread(corridor, laser), _Flown(corridor, laser)
    variables = np.zeros(len(corridor.stations))
    for timing, weight, steps in STAGES:
        if timing == 'flown' and len(variables) == len(corridor.stations):
            _, _, length, direction = spread.pieces(variables)
            variables = np.concatenate((variables, spread_turns(direction)))
        variables = _optimised(spread if timing == 'spread' else flying, variables, weight,
                               steps)
    for _ in range(JUDGED_ROUNDS if judged else 0):
        farther, beyond = _judged(course, flying, variables)
        if beyond <= JUDGED_TOLERANCE:
            break
        corridor.hold_judged(farther)
        variables = _optimised(flying, variables, STAGES[-1][1], STAGES[-1][2])
    offsets, turns = flying.split(variables)
    centres, _, length, direction = flying.pieces(offsets)
    time = flight_time(length, direction, turns)
    excursion = flying.excursion(centres, _Flown.headings(direction, turns))
    return LapBound(time, float(length.sum()), centres, turns, tuple(laser), excursion)


def _optimised(timing, variables, weight, steps):
    """variables after at most steps of L-BFGS-B on timing, in its corridor's bounds."""
    bounds = timing.corridor.offsets.copy()
    # The centre may stand off the laser's interval by the laser's own offset.
    bounds += np.array((-1.0, 1.0)) * (math.hypot(*timing.laser_mount) + 0.01)
    smoothed = _Smoothed(timing, bounds)
    return smoothed.variables(minimize(
        smoothed, smoothed.smoothed(variables), args=(weight,), jac=True,
        method='L-BFGS-B', options={'maxiter': steps, 'maxcor': 20}).x)


def _judged(course, flying, variables):
    """How much farther the judge reads than the laser's distance to the nearest wall at
    each station, the most over the headings flown there (M,) [m]; and how far the
    judge's reading goes past the corridor's high edge at most [m]."""
    offsets, turns = flying.split(variables)
    centres, _, _, direction = flying.pieces(offsets)
    farther = np.zeros(len(centres))
    beyond = 0.0
    for heading in _Flown.headings(direction, turns):
        distance = flying.corridor.walls.nearest(flying.laser(centres, heading)[0])[0]
        reading = np.array([course.right_wall_distance((x, y, yaw))
                            for (x, y), yaw in zip(centres, heading)])
        farther = np.maximum(farther, reading - distance)
        beyond = max(beyond, float(np.max(reading - flying.corridor.top)))
    return farther, beyond


def flight_time(length, direction, turns):
    """The time of a lap through stations, pieces of length and direction, each flown as
    an arc turning through turns (see _Flown), with a pivot at each station between."""
    pivots = wrap_angle(direction - np.roll(direction, 1)) - 0.5 * (turns + np.roll(turns, 1))
    return float(np.maximum(length / MAX_LINEAR, np.abs(turns) / MAX_ANGULAR).sum()
                 + np.abs(pivots).sum() / MAX_ANGULAR)


def spread_turns(direction):
    """Turns for the pieces of a polyline that share each station's bend between the
    pieces either side of it: no pivot where the polyline bends evenly."""
    bend = wrap_angle(direction - np.roll(direction, 1))
    return 0.5 * (bend + np.roll(bend, -1))
