"""The line follower's controller: pure pursuit on the remembered path, as a small state machine.

FOLLOW drives the base along the path (odometry frame, from LinePath).
It plans a speed: the lowest of `speed`, what takes the sharpest bend
within `preview` [m] ahead at `bend_share` of `turn_rate` (so that it
slows before a tight bend, not in it), and, when the path ends at the
line's end, what stops within the rest of the path at `decel` [m/s^2].
The target is the first point of the path ahead at least the lookahead
from the base: `lookahead_time` [s] at that speed, not under `lookahead`
[m] (a short one in bends, where a long one cuts them). The arc through
the target tangent to the robot's heading gives the curvature to drive;
on a bend of constant curvature that arc is the bend itself, so the base
stays on the line. The speed is lowered further to keep that curvature
within `turn_rate`. A target more than `max_bearing` [rad] off the
heading is turned to in place.

FINISHED: the base has come within `stop_distance` [m] of the line's end;
it stays stopped. SEARCH: less than `min_ahead` [m] of path is left ahead
and the line's end was not seen: the line is lost, and the robot only
turns in place (toward the side the line went), at most `search_angle`
[rad], never driving on blind; LOST: that search found nothing; it stays
stopped until the line is seen again.

Each command comes with whether the line is known ahead of the base (a
point of the path within the drive loop's half width of its heading):
the loop drives forward on nothing less.
"""
import math

import numpy as np

from wall_follower.control.motion import STOP, Answer, Command
from wall_follower.params import checked
from wall_follower.params.camera.line_follower import PURSUIT
from wall_follower.rotation import wrap_angle
from wall_follower.vision.line_path import path_length

FOLLOW = 'follow'
SEARCH = 'search'
LOST = 'lost'
FINISHED = 'finished'

BEND_CHORD = 0.1       # m: the chord over which a bend's curvature is measured
CREEP = 0.02           # m/s: the least speed toward the line's end, so that it is reached


def in_base_frame(path, base):
    """(N, 2) path points (odometry frame) in the frame of the base at (x, y, yaw)."""
    x, y, yaw = base
    c, s = math.cos(yaw), math.sin(yaw)
    offsets = np.asarray(path, float).reshape(-1, 2) - (x, y)
    return np.column_stack((c * offsets[:, 0] + s * offsets[:, 1],
                            -s * offsets[:, 0] + c * offsets[:, 1]))


def from_base_frame(points, base):
    """(N, 2) points given in the frame of the base at (x, y, yaw), in the odometry frame."""
    x, y, yaw = base
    c, s = math.cos(yaw), math.sin(yaw)
    points = np.asarray(points, float).reshape(-1, 2)
    return np.column_stack((x + c * points[:, 0] - s * points[:, 1],
                            y + s * points[:, 0] + c * points[:, 1]))


def known_ahead(path, base, half_width):
    """Whether a path (odometry frame) has a point ahead of the base at (x, y, yaw) within
    half_width [rad] of its heading."""
    local = in_base_frame(path, base)
    return bool(np.any((local[:, 0] > 0.0)
                       & (np.abs(np.arctan2(local[:, 1], local[:, 0])) <= half_width)))


def path_ahead(local):
    """The part of a path (base frame) from its point nearest the base on."""
    if len(local) == 0:
        return local
    return local[int(np.argmin(np.hypot(*local.T))):]


def resample(path, spacing):
    """Points every spacing [m] of arc length along a path (its first point included)."""
    lengths = np.concatenate(([0.0], np.cumsum(np.hypot(*np.diff(path, axis=0).T))))
    if lengths[-1] < spacing:
        return path[:1]
    stations = np.arange(0.0, lengths[-1] + 1e-9, spacing)
    return np.column_stack((np.interp(stations, lengths, path[:, 0]),
                            np.interp(stations, lengths, path[:, 1])))


def sharpest_bend(path, reach):
    """The largest curvature [1/m] of the path within reach [m] of its start, measured
    as the turn between successive BEND_CHORD chords; 0 for a shorter path."""
    points = resample(path, BEND_CHORD)
    stations = int(reach / BEND_CHORD) + 2
    points = points[:stations]
    if len(points) < 3:
        return 0.0
    headings = np.arctan2(*np.diff(points, axis=0).T[::-1])
    turns = np.angle(np.exp(1j * np.diff(headings)))
    return float(np.max(np.abs(turns))) / BEND_CHORD


class LinePursuit(object):
    """Commands from the remembered path; see the module for the states and parameters."""

    def __init__(self, **params):
        self.reconfigure(**params)
        self.state = FOLLOW
        self._turn_side = 1.0          # +1: the line went left, -1: right
        self._searched = 0.0           # rad turned in this search
        self._last_yaw = None

    def reconfigure(self, **params):
        """Go on under these parameters (PURSUIT's defaults, overridden) from the next frame on."""
        self.p = checked(PURSUIT, params)

    def update(self, path, end_seen, base, half_width):
        """The Answer for the path (odometry frame, LinePath's), whether it ends at the
        line's end, and the base's pose (x, y, yaw) in the same frame: the command, and
        whether the path is known ahead within half_width [rad] of the heading."""
        known = bool(len(path)) and known_ahead(path, base, half_width)
        return Answer(self._command(path, end_seen, base), known)

    def _command(self, path, end_seen, base):
        turned = 0.0 if self._last_yaw is None else abs(wrap_angle(base[2] - self._last_yaw))
        self._last_yaw = base[2]
        if self.state == FINISHED:
            return STOP
        ahead = path_ahead(in_base_frame(path, base))
        left = path_length(ahead) + (math.hypot(*ahead[0]) if len(ahead) else 0.0)
        if end_seen and len(ahead) and left <= self.p['stop_distance']:
            self.state = FINISHED
            return STOP
        if left < self.p['min_ahead'] and not end_seen:
            return self._search(turned)
        self.state = FOLLOW
        return self._pursue(ahead, end_seen, left)

    def _search(self, turned):
        if self.state == FOLLOW:
            self.state, self._searched = SEARCH, 0.0
        elif self.state == SEARCH:
            self._searched += turned
            if self._searched >= self.p['search_angle']:
                self.state = LOST
        if self.state == LOST:
            return STOP
        return Command(0.0, self._turn_side * self.p['search_rate'])

    def _pursue(self, ahead, end_seen, left):
        speed = self.p['speed']
        bend = sharpest_bend(ahead, self.p['preview'])
        if bend > 1e-9:
            speed = min(speed, self.p['bend_share'] * self.p['turn_rate'] / bend)
        if end_seen:
            speed = min(speed, max(CREEP, math.sqrt(2.0 * self.p['decel']
                                                    * max(0.0, left - self.p['stop_distance']))))
        lookahead = max(self.p['lookahead'], self.p['lookahead_time'] * speed)
        distances = np.hypot(*ahead.T)
        beyond = np.nonzero(distances >= lookahead)[0]
        target = ahead[beyond[0]] if len(beyond) else ahead[-1]
        distance = float(np.hypot(*target))
        if distance < 1e-6:
            return STOP
        bearing = math.atan2(target[1], target[0])
        if abs(target[1]) > 1e-6:
            self._turn_side = math.copysign(1.0, target[1])
        if abs(bearing) > self.p['max_bearing']:
            return Command(0.0, math.copysign(self.p['turn_rate'], bearing))
        curvature = 2.0 * target[1] / (distance * distance)
        if abs(curvature) > 1e-9:
            speed = min(speed, self.p['turn_rate'] / abs(curvature))
        return Command(speed, speed * curvature)
