"""A lap bound (lap_bound.py) checked by driving it, and the bounds a benchmark asks about.

T* is found by optimising a path; whether a robot can fly that path in the
time it claims, in the band, is checked by flying it: the built-in
simulator (its kinematics, one Euler step a world update, and its
collisions) tracks the arcs and pivots in time, and the lap is scored
from ground truth as a follower's is (scoring.RunScore): its time, its
share in band, contact.

Pure numpy, free of ROS; the world comes from its file.
"""
import math
from collections import namedtuple

import numpy as np

from wall_follower.evaluation.scoring.course import CourseMap, RunScore
from wall_follower.evaluation.scoring.lap_bound import MARGIN, BoundError, fastest_lap
from wall_follower.params.driving import MAX_ANGULAR, MAX_LINEAR
from wall_follower.rotation import wrap_angle
from wall_follower.sim.engine import Simulation
from wall_follower.sim.worldfile import load_world

DrivenLap = namedtuple('DrivenLap', 'time in_band rms_error min_clearance contact closed')
DrivenLap.__doc__ = """A bound driven in the simulator, scored from ground truth
(scoring.RunScore): lap time [s], share of it in band, RMS error [m], smallest clearance
[m], any contact, and whether the lap closed."""


def drive(world_path, bound):
    """The bound's lap driven in the built-in simulator and scored from ground truth: a
    DrivenLap.

    The robot starts at the bound's first station and tracks its arcs and pivots
    (_Schedule). Each world update it finds where on the schedule it is (the
    nearest pose, a radian of heading counting as HEADING_WEIGHT metres) and is
    commanded, within the limits, the speed that brings it as far along as the
    schedule is an update later, and the turn rate that then heads it for where the
    schedule is the update after (where the schedule pivots, the schedule's
    heading). Falling behind the schedule costs time, never the band. The lap ends
    by the recorder's rule.
    """
    schedule = _Schedule(bound)
    start, _ = schedule.pose(0.0)
    simulation = Simulation(load_world(world_path), poses={0: start})
    score = RunScore(CourseMap(world_path))
    dt = simulation.dt
    at = 0.0
    while simulation.time < 2.0 * schedule.total and not score.lap.closed:
        frame = simulation.step(with_scans=False)
        truth = frame.robots[0].ground_truth
        score.add_pose(simulation.time, (truth.x, truth.y, truth.yaw))
        score.add_stall(frame.robots[0].stalled)
        # Where the robot stands on the schedule; a robot that has made no way
        # along it (held a hair past where its pivot begins) is moved on.
        at = max(schedule.nearest((truth.x, truth.y, truth.yaw), at), at + STALL_STEP * dt)
        linear, angular = _tracking(schedule, at, (truth.x, truth.y, truth.yaw), dt)
        score.add_command(linear, angular)
        simulation.set_command(0, linear, angular)
    figures = score.summary()
    return DrivenLap(figures['lap_time'], figures['time_in_band'], figures['rms_error'],
                     figures['min_clearance'], figures['contact'], score.lap.closed)


def _tracking(schedule, at, pose, dt, pivoting=0.005, choices=20):
    """The command (v, w) for the update after schedule time at, from pose (x, y, yaw).

    The update moves the robot along its present heading, then turns it: v
    brings it at most as far along as the schedule is at at + dt, and w heads it
    for where the schedule is at at + 2 dt (or turns it to the schedule's heading
    then, if that place is within pivoting metres). Where that takes a turn
    sharper than the turn rate allows (the robot has drifted outside a turn flown
    at the full rate), the fastest of choices slower speeds that allows it.
    """
    x, y, yaw = pose
    ahead = np.array((math.cos(yaw), math.sin(yaw)))
    (gx, gy, _), _ = schedule.pose(at + dt)
    fastest = min(max(float(np.dot((gx - x, gy - y), ahead)) / dt, 0.0), MAX_LINEAR)
    (gx, gy, heading), _ = schedule.pose(at + 2.0 * dt)
    for linear in np.linspace(fastest, 0.0, choices + 1):
        nx, ny = x + linear * dt * ahead[0], y + linear * dt * ahead[1]
        if math.hypot(gx - nx, gy - ny) <= pivoting:
            angular = wrap_angle(heading - yaw) / dt
            break
        angular = wrap_angle(math.atan2(gy - ny, gx - nx) - yaw) / dt
        if abs(angular) <= MAX_ANGULAR:
            break
    return float(linear), float(min(max(angular, -MAX_ANGULAR), MAX_ANGULAR))


# A driven robot's place on its schedule moves on at least by this share of
# an update each update.
STALL_STEP = 0.2
# In finding where on its schedule a driven robot is, a radian of heading
# counts as this many metres of position [m/rad].
HEADING_WEIGHT = 0.05


class _Schedule(object):
    """A bound's lap against time: at each station a pivot, then the arc to the next."""

    def __init__(self, bound):
        centres = bound.centres
        piece = np.roll(centres, -1, axis=0) - centres
        self.length = np.hypot(piece[:, 0], piece[:, 1])
        direction = np.arctan2(piece[:, 1], piece[:, 0])
        self.turns = bound.turns
        arrive = np.roll(direction + 0.5 * self.turns, 1)
        pivot = wrap_angle(direction - 0.5 * self.turns - arrive)
        # Headings kept continuous round the lap: each pivot and arc adds its turn.
        steps = np.column_stack((pivot, self.turns)).ravel()
        self.headings = arrive[0] + np.concatenate(([0.0], np.cumsum(steps)))
        durations = np.column_stack((np.abs(pivot) / MAX_ANGULAR,
                                     np.maximum(self.length / MAX_LINEAR,
                                                np.abs(self.turns) / MAX_ANGULAR))).ravel()
        self.starts = np.concatenate(([0.0], np.cumsum(durations)))
        self.total = float(self.starts[-1])
        self.centres = centres
        self.durations = durations

    def nearest(self, pose, after, window=1.0, step=0.005):
        """The time within window seconds from after [s] at which the schedule is nearest
        to pose (x, y, heading)."""
        times = after + np.arange(0.0, window, step)
        poses = np.array([self.pose(time)[0] for time in times])
        off = np.hypot(poses[:, 0] - pose[0], poses[:, 1] - pose[1]) + \
            HEADING_WEIGHT * np.abs(wrap_angle(poses[:, 2] - pose[2]))
        return float(times[int(np.argmin(off))])

    def pose(self, time):
        """((x, y, heading) at time [s] into the lap, repeated after it), and which station's
        pivot or arc it is on."""
        time %= self.total
        part = min(int(np.searchsorted(self.starts, time, side='right')) - 1,
                   len(self.durations) - 1)
        share = (time - self.starts[part]) / max(self.durations[part], 1e-12)
        station = part // 2
        start = self.headings[part]
        heading = start + share * (self.headings[part + 1] - start)
        x, y = self.centres[station]
        if part % 2:
            turn, length = self.turns[station], self.length[station]
            if abs(turn) < 1e-9:
                x += share * length * math.cos(start)
                y += share * length * math.sin(start)
            else:
                radius = 0.5 * length / math.sin(0.5 * turn)
                x += radius * (math.sin(heading) - math.sin(start))
                y += radius * (math.cos(start) - math.cos(heading))
        return (x, y, heading), station


class Bounds(object):
    """The bound of every lap a benchmark asks about, and its check by driving it: each
    loop of a world optimised and driven once, however many laps go round it.

    of() answers (LapBound, DrivenLap), or (None, the reason) where there is no
    bound (no band loop near the lap's start, say). margin: fastest_lap's.
    """

    # A lap whose start is this near a known bound's path goes round its loop [m].
    SAME_LOOP = 0.2

    def __init__(self, margin=MARGIN):
        self.margin = margin
        self._known = {}

    def of(self, world_path, start):
        """The bound of the loop nearest start (x, y, ...) in the world of world_path."""
        start = np.asarray(start[:2], dtype=float)
        known = self._known.setdefault(world_path, [])
        for bound, driven in known:
            if bound is not None and np.hypot(*(bound.centres - start).T).min() <= self.SAME_LOOP:
                return bound, driven
        try:
            bound = fastest_lap(world_path, start, margin=self.margin)
        except BoundError as error:
            known.append((None, str(error)))
        else:
            known.append((bound, drive(world_path, bound)))
        return known[-1]

    def all(self):
        """(world path, LapBound or None, DrivenLap or the reason there is none) of each
        bound known, worlds in the order asked about."""
        return [(world, bound, driven) for world, known in self._known.items()
                for bound, driven in known]
