"""How well a run went, judged from the simulator's ground truth and the map.

Scores never come from the controller's own laser, which may be noisy or
wrong in exactly the cases a score should catch. The right-wall distance is
cast noise-free from the laser's true position in the world; clearance is
measured between the robot's footprint and the obstacles. Both use the
world's exact edges, not the simulator's grid, whose cells make obstacles
look up to a cell fatter. Where a lap left the band, the same reading on
that grid (CourseMap.grid_right_wall_distance) tells a follower that
misjudged the wall from a laser that misread it.
"""
import math

import numpy as np

from wall_follower.control.course.lap import LapRecorder
from wall_follower.control.motion import MAX_LINEAR
from wall_follower.control.sensing.lines import fit_line
from wall_follower.control.sensing.scan import RIGHT
from wall_follower.evaluation.scoring.geometry import cast_rays, polygon_clearance, solid_edges
from wall_follower.rotation import wrap_angle
from wall_follower.sim.compiled_raytrace import LibraryMissing
from wall_follower.sim.grid import OccupancyGrid, footprint_cells, footprint_corners
from wall_follower.sim.raytrace import stage_ranges
from wall_follower.sim.worldfile import WorldFileError, load_world

BAND = (0.20, 0.30)
TARGET = 0.25
# The course scores the wall "on the right" as the nearest wall within
# +-30 deg of the robot's right.
RIGHT_SECTOR = math.radians(30.0)
_SECTOR_BEAMS = 61
# How much further than the nearest pass of a trail another pass may be and
# still be the one where a recorded point was taken [m]: a few steps of travel.
PASS_TOLERANCE = 0.05


class CourseMap(object):
    """A world's obstacles and one of its robots, for measurements at true poses."""

    def __init__(self, world_path, robot=0):
        """Raises WorldFileError for a world that cannot be read, or has no such robot or
        no ranger on it."""
        self.world = load_world(world_path)
        self.edges = solid_edges(self.world)
        if robot >= len(self.world.robots):
            raise WorldFileError(world_path, 0, 'no robot %d to score (the world has %d)'
                                 % (robot, len(self.world.robots)))
        self.robot = self.world.robots[robot]
        ranger = self.robot.ranger
        if ranger is None:
            raise WorldFileError(world_path, 0, 'robot "%s" has no ranger' % self.robot.name)
        self.laser_offset = (ranger.pose[0], ranger.pose[1], ranger.pose[3])
        self.range_max = ranger.range_max
        self._sector = np.linspace(-RIGHT_SECTOR, RIGHT_SECTOR, _SECTOR_BEAMS)
        self._grid = None

    def laser_pose(self, pose):
        """World pose (x, y, yaw) of the laser when the robot is at pose."""
        x, y, yaw = pose
        lx, ly, lyaw = self.laser_offset
        c, s = math.cos(yaw), math.sin(yaw)
        return x + c * lx - s * ly, y + s * lx + c * ly, yaw + lyaw

    def _sector_beams(self, pose):
        """The judge's beams at pose: the laser's (x, y), and the beams' angles in its frame
        and in the world."""
        lx, ly, lyaw = self.laser_pose(pose)
        local = RIGHT + self._sector
        return lx, ly, local, lyaw + local

    def _right_sector(self, pose):
        lx, ly, local, angles = self._sector_beams(pose)
        return local, np.minimum(cast_rays(self.edges, lx, ly, angles), self.range_max)

    def right_wall_distance(self, pose):
        """Nearest noise-free range within +-30 deg of the right (inf if none)."""
        _, ranges = self._right_sector(pose)
        return self._nearest(ranges)

    def grid_right_wall_distance(self, pose):
        """right_wall_distance as a noise-free laser reads it in Stage, or None where the
        compiled raytrace is not built.

        The same beams from the same place, cast on the cells Stage draws
        the world into (sim/grid.py) instead of on its edges. Stage puts
        the hits up to a cell or two off the surface, by where the surface
        lies on its grid (DESIGN.md): a follower that holds the band by its
        laser is out of it by as much. Set beside the judge's reading where
        a lap left the band, it tells a follower that misjudged the wall
        from a laser that misread it.
        """
        if self._grid is None:
            self._grid = OccupancyGrid.from_world(self.world)
        lx, ly, _, angles = self._sector_beams(pose)
        body = footprint_cells(self.robot, pose, self._grid.ppm)
        try:
            ranges, _ = stage_ranges(self._grid, lx, ly, angles,
                                     self.range_max, height=self.robot.ranger.sensor_height,
                                     robot_cells=[body])
        except LibraryMissing:
            return None
        return self._nearest(ranges)

    def _nearest(self, ranges):
        hits = ranges[ranges < self.range_max]
        return float(hits.min()) if hits.size else math.inf

    def right_wall_alignment(self, pose):
        """(distance, heading error) of the wall on the right, or None.

        The wall is a line fitted to the noise-free hits within +-30 deg of
        the right; the heading error is how far the robot's heading is from
        parallel to it (rad, positive = turned left, away from the wall).
        """
        local, ranges = self._right_sector(pose)
        hit = ranges < self.range_max
        points = np.column_stack((ranges[hit] * np.cos(local[hit]),
                                  ranges[hit] * np.sin(local[hit])))
        fit = fit_line(points)
        if fit is None:
            return None
        distance, normal = fit
        return distance, float(wrap_angle(RIGHT - normal))

    def clearance(self, pose):
        """Smallest distance from the robot's footprint to an obstacle (0 = contact)."""
        return polygon_clearance(footprint_corners(self.robot, pose), self.edges)


def _highest(highest, value):
    """The higher of two command magnitudes, NaN once one was NaN: a NaN command is one no
    robot can follow, never one to drop (max() would drop it, or keep it by its order)."""
    if highest != highest or value != value:
        return float('nan')
    return max(highest, value)


class RunScore(object):
    """Accumulates a run, sample by sample, into the figures of the benchmark.

    Ground-truth poses give the right-wall distance, clearance and path
    length; commands give the highest speeds sent. The lap ends by the same
    rule the recorder uses, applied to ground truth, or where finish() says
    (the recorder's own verdict), whichever comes first.

    The run's clock starts at begin() (a goal's time), or else once the
    robot leaves the pose it was first heard at. A controller that comes up
    a few steps after the simulator leaves the robot standing meanwhile, a
    step or two longer on a busy machine, and timed from the first pose
    heard, the same lap read 0.1 s longer or shorter from run to run.
    """

    def __init__(self, course_map, band=BAND, target=TARGET, **lap_params):
        self.map = course_map
        self.band = band
        self.target = target
        self.lap = LapRecorder(**lap_params)
        self.start_time = None
        self.end_time = None
        self.lap_time = None
        self.weights = []
        self.poses = []
        self._measured = []
        self.max_linear = 0.0
        self.max_angular = 0.0
        self.stalled = False
        self._last = None
        self._end = None
        self._timed_from_pose = False

    def add_pose(self, stamp, pose):
        """Feed the ground-truth pose (x, y, yaw) at time stamp (s); ignored once the lap is over.

        Cheap on purpose: a monitor calls it for every simulated step, at
        whatever pace the simulator runs; distances and clearances are cast
        later, by summary().
        """
        if self.lap.closed or (self._last is not None and stamp <= self._last):
            return
        if self._end is not None and stamp > self._end:
            return
        if self._timed_from_pose and len(self.poses) == 1 and tuple(self.poses[0]) == tuple(pose):
            self.start_time = self._last = self.end_time = stamp
            return
        if self.start_time is None:
            self.start_time = stamp
            self._timed_from_pose = True
        weight = 0.0 if self._last is None else stamp - self._last
        self._last = self.end_time = stamp
        self.weights.append(weight)
        self.poses.append(pose)
        self.lap.add(stamp, *pose)
        if self.lap.closed:
            self.lap_time = stamp - self.start_time

    def begin(self, stamp):
        """Start the run's clock at time stamp (s), if no pose has started it yet."""
        if self.start_time is None:
            self.start_time = stamp

    def finish(self, stamp):
        """End the lap at time stamp (s); poses stamped up to it still count when they come."""
        if self._end is None and not self.lap.closed:
            self._end = stamp
            if self.start_time is not None:
                self.lap_time = stamp - self.start_time

    @property
    def finished(self):
        return self.lap.closed or self._end is not None

    def add_command(self, linear, angular):
        self.max_linear = _highest(self.max_linear, abs(linear))
        self.max_angular = _highest(self.max_angular, abs(angular))

    def add_stall(self, stalled):
        self.stalled = self.stalled or bool(stalled)

    @property
    def path_length(self):
        return self.lap.total_distance

    def _measure(self, count):
        """(right-wall distance, clearance) of the first count poses, cast once each."""
        for pose in self.poses[len(self._measured):count]:
            self._measured.append((self.map.right_wall_distance(pose), self.map.clearance(pose)))
        return self._measured[:count]

    def summary(self):
        """The run's figures as a dict (NaN where there is nothing to measure).

        Only the poses complete when it starts count: a monitor may still be
        adding one from its subscriber's thread (a pose's weight goes in
        before the pose).
        """
        count = len(self.poses)
        measured = self._measure(count)
        min_clearance = min((c for _, c in measured), default=math.inf)
        weights = np.asarray(self.weights[1:count], dtype=float)
        distances = np.asarray([d for d, _ in measured[1:]], dtype=float)
        total = weights.sum()
        if total > 0.0:
            low, high = self.band
            in_band = float(weights[(distances >= low) & (distances <= high)].sum() / total)
            finite = np.isfinite(distances)
            errors = np.where(finite, distances - self.target, self.band[1])
            rms = float(math.sqrt((weights * errors ** 2).sum() / total))
        else:
            in_band = rms = float('nan')
        lap_time = self.lap_time if self.lap_time is not None else float('nan')
        bound = self.path_length / MAX_LINEAR if self.path_length > 0.0 else float('nan')
        return {
            'duration': (self.end_time - self.start_time) if self.start_time is not None else 0.0,
            'lap_closed': self.finished,
            'lap_time': lap_time,
            'path_length': self.path_length,
            'lap_time_ratio': lap_time / bound if bound == bound and bound > 0 else float('nan'),
            'time_in_band': in_band,
            'rms_error': rms,
            'min_clearance': min_clearance,
            'contact': self.stalled or min_clearance <= 0.0,
            'max_linear': self.max_linear,
            'max_angular': self.max_angular,
            # Where the lap began: which loop a lap bound (lap_bound) is of.
            'lap_start': list(self.poses[0]) if count else None,
        }

    def stretches_out_of_band(self):
        """Each stretch of the lap out of band, as (seconds into the lap, duration s, pose
        where it began, the distance furthest from the band's middle, the pose where it
        was); inf for no wall seen.

        Over the poses summary() has measured, longest first: where a follower
        lost the band, for a report to point at.
        """
        low, high = self.band
        stretches = []
        elapsed = 0.0
        current = None
        for index, ((distance, _), weight) in enumerate(zip(self._measured, self.weights)):
            elapsed += weight
            if index == 0:
                continue
            if low <= distance <= high:
                current = None
                continue
            if current is None:
                current = [elapsed - weight, 0.0, self.poses[index], distance, self.poses[index]]
                stretches.append(current)
            current[1] += weight
            if abs(distance - self.target) > abs(current[3] - self.target):
                current[3] = distance
                current[4] = self.poses[index]
        return sorted((tuple(s) for s in stretches), key=lambda s: -s[1])


def true_lap_length(trail, start, leave_radius=0.5, near=0.3):
    """Path length at which a ground-truth trail first comes back to its start.

    The return is the first local minimum of the distance to start, within
    `near` metres, after the trail has been `leave_radius` away. This is a
    different rule from the recorder's start-line crossing, so it can judge
    whether the recorder declared its lap too early. None if it never
    came back.
    """
    xy = np.asarray(trail, dtype=float)
    if len(xy) < 3:
        return None
    lengths = np.concatenate(([0.0], np.cumsum(np.hypot(*np.diff(xy, axis=0).T))))
    gaps = np.hypot(xy[:, 0] - start[0], xy[:, 1] - start[1])
    away = np.nonzero(gaps >= leave_radius)[0]
    if away.size == 0:
        return None
    for i in range(int(away[0]) + 1, len(xy) - 1):
        if gaps[i] <= near and gaps[i] <= gaps[i - 1] and gaps[i] <= gaps[i + 1]:
            return float(lengths[i])
    return None


def stretches_on_trail(trail, points):
    """(first, last) index of the trail stretch where each recorded point was taken, in order.

    Recorded points are odometry poses, true poses under the worlds' "gps"
    localization, so each is the trail position nearest to it at or after
    the previous point's: searching forward keeps a point near the start
    from matching the lap's end, where the trail passes again. Timing the
    points this way, rather than by the messages around them, holds however
    late a loaded machine lets the recorder start or answer; where the trail
    passes a point more than once, the first pass counts. Where the
    robot stood still, the trail holds one pose many times over, and a
    point taken there may have been taken at any of them; elsewhere
    first == last.
    """
    xy = np.asarray(trail, dtype=float).reshape(-1, 2)
    if not len(xy):
        return []
    stretches = []
    start = 0
    for point in points:
        rest = xy[start:]
        distance = np.hypot(rest[:, 0] - point[0], rest[:, 1] - point[1])
        # The first pass within PASS_TOLERANCE of the nearest: a trail that goes
        # round a pillar again and again passes each point many times.
        close = distance <= distance.min() + PASS_TOLERANCE
        first = int(np.argmax(close))
        leaves = np.flatnonzero(~close[first:])
        end = first + (int(leaves[0]) if leaves.size else len(close) - first)
        nearest = first + int(np.argmin(distance[first:end]))
        after = np.flatnonzero(np.any(rest[nearest:] != rest[nearest], axis=1))
        same = int(after[0]) if after.size else len(rest) - nearest
        start += nearest
        stretches.append((start, start + same - 1))
    return stretches


def taken_every(spans, period, tolerance):
    """True when points taken in these (earliest, latest) time spans can be period apart each.

    A point taken while the robot stood still has a span of times rather
    than one (see stretches_on_trail); each next point must be able to
    follow its previous one by period, within tolerance.
    """
    return all(later[0] - earlier[1] - tolerance <= period <= later[1] - earlier[0] + tolerance
               for earlier, later in zip(spans, spans[1:]))
