"""Odometry recording for the record_odom action: path length, samples, lap end.

Plain classes fed one odometry pose at a time (time in seconds, x, y, yaw),
so the recording can be tested on synthetic trajectories without ROS.

Why the lap rule is not the course's "within 5 cm of the first pose": that
test is already true at the first sample, so the lap "ends" before the robot
moves, and a lap that comes back 6 cm to the side is never seen to end.
Here a lap can end only after the robot has both travelled a minimum
distance and been well away from the start, and it ends when the robot
crosses the line through the start point, perpendicular to the start
heading, heading roughly the way it started, close enough to the start.

A robot that starts in a corner (find_wall can leave it there) does not
come back that way: the lap cuts the corner, and passes the start point
mid-turn, across the start heading or short of the start line. There the
lap ends once the robot is past its nearest point to the start, near
enough, and heading roughly the way its path left the start point: the
first stretch of the path, up to where it first got close_tolerance from
the start, is kept to compare with. The middle of a figure of eight still
ends nothing: its two ways through the start cross at a wide angle.

Odometry can jump: a simulator's reset_positions puts the robot back at its
spawn pose, and a real robot's odometry can be reset to zero. A pose
further from the one before than the robot can drive in the time between
them is a jump, not travel: it is not counted, and the recording goes on
from the new pose with the lap's start kept where it was. The lap is armed
afresh, as at the start: it can end only once the robot has travelled the
minimum distance again and been away from the start, so a reset to a spawn
pose just behind the start line does not end the lap as the robot drives
off; no crossing is seen across the jump itself. After a simulator's reset
the lap so ends a full lap later; after a real robot's odometry reset the
start line keeps its coordinates, which now mark another place.
"""
import math

from wall_follower.control.course.odom_check import JumpDetector
from wall_follower.params import defaults
from wall_follower.params.course.odom_recorder import TABLE
from wall_follower.rotation import wrap_angle

# The path's first stretch (LapDetector) is kept a point every this many
# metres, and at most this many points (a robot can stand at its start).
STRETCH_SPACING = 0.01
STRETCH_POINTS = 200
# A robot is past its nearest point to the start once it has come no nearer
# for this much path [m]: one that turns on the spot there, odometry
# jittering by a millimetre, has not passed it.
PASS_TRAVEL = 0.01

# The defaults of the keyword arguments below: the odom_recorder node's.
_DEFAULT = defaults(TABLE)


class PathLength(object):
    """Distance travelled, summed over every pose given (the odometry rate)."""

    def __init__(self):
        self.total = 0.0
        self._last = None

    def add(self, x, y):
        if self._last is not None:
            self.total += math.hypot(x - self._last[0], y - self._last[1])
        self._last = (x, y)
        return self.total

    def jump_to(self, x, y):
        """Go on from (x, y) without counting the way there."""
        self._last = (x, y)


class PeriodicSampler(object):
    """Says when a sample is due: at the first call, then every `period` seconds.

    Due times stay on the grid start + k * period, so sampling does not
    drift late by a fraction of the input period each time; after a gap in
    the input, the next sample is simply the next one due.
    """

    def __init__(self, period=_DEFAULT['sample_period']):
        if period <= 0.0:
            raise ValueError('sample period must be positive, got %r' % period)
        self.period = float(period)
        self._next = None

    def due(self, stamp):
        if self._next is None:
            self._next = stamp + self.period
            return True
        if stamp + 1e-9 < self._next:
            return False
        missed = max(0, math.floor((stamp - self._next) / self.period))
        self._next += (missed + 1) * self.period
        return True


class LapDetector(object):
    """Decides when a lap around the start pose (x, y, yaw) is complete.

    min_travel: path length (m) the robot must have covered first.
    leave_radius: the robot must also have been at least this far (m) from
        the start point, so wiggling on the spot never counts as a lap.
    close_tolerance: the lap ends when the robot crosses the start line
        (through the start point, perpendicular to the start heading, in the
        start direction) at most this far (m) to the side of the start point.
    max_heading_error: and only if its heading then is within this angle
        (rad) of the start heading, so that a path crossing the start line
        obliquely (the middle of a figure of eight) does not end the lap.
        Otherwise the lap ends past the nearest point to the start, within
        close_tolerance of it, heading within this angle of the path's
        first stretch there (see the module's docstring).
    """

    def __init__(self, start, min_travel=_DEFAULT['min_travel'],
                 leave_radius=_DEFAULT['leave_radius'],
                 close_tolerance=_DEFAULT['close_tolerance'],
                 max_heading_error=_DEFAULT['max_heading_error']):
        self.x0, self.y0, self.yaw0 = start
        self.min_travel = min_travel
        self.leave_radius = leave_radius
        self.close_tolerance = close_tolerance
        self.max_heading_error = max_heading_error
        self.left_start = False
        self.closed = False
        self._previous = self._frame(self.x0, self.y0)
        self._travelled_before = 0.0   # path length (m) before the latest jump
        # The path's first stretch, (along, across, yaw) in the start frame,
        # until it first gets close_tolerance from the start.
        self._first_stretch = [(0.0, 0.0, self.yaw0)]
        self._first_stretch_over = False
        # (distance, travelled): the nearest distance to the start on this pass by
        # it, and the path length there.
        self._nearest = None

    def _frame(self, x, y):
        """(along, across) position relative to the start pose's heading."""
        dx, dy = x - self.x0, y - self.y0
        c, s = math.cos(self.yaw0), math.sin(self.yaw0)
        return dx * c + dy * s, -dx * s + dy * c

    def resume_at(self, x, y, travelled):
        """Go on from (x, y) after a jump, `travelled` metres into the recording.

        The jump itself crosses no line, and the lap is armed afresh.
        """
        self._previous = self._frame(x, y)
        self._travelled_before = travelled
        self.left_start = False

    def update(self, x, y, yaw, travelled):
        """Feed the next pose and the distance travelled so far; True once the lap is closed."""
        if self.closed:
            return True
        along, across = self._frame(x, y)
        previous_along, previous_across = self._previous
        self._previous = (along, across)
        distance = math.hypot(along, across)
        self._extend_first_stretch(along, across, yaw, distance)
        if distance >= self.leave_radius:
            self.left_start = True
        if not (self.left_start and travelled - self._travelled_before >= self.min_travel):
            return False
        self.closed = (self._crossed_start_line(previous_along, previous_across, along, across, yaw)
                       or self._passed_start_point(along, across, yaw, distance, travelled))
        return self.closed

    def _crossed_start_line(self, previous_along, previous_across, along, across, yaw):
        """True on crossing the start line near the start point, heading the start's way."""
        if not (previous_along < 0.0 <= along):
            return False
        # Where, to the side of the start point, the start line was crossed.
        share = -previous_along / (along - previous_along)
        crossing = previous_across + share * (across - previous_across)
        heading_error = abs(float(wrap_angle(yaw - self.yaw0)))
        return abs(crossing) <= self.close_tolerance and heading_error <= self.max_heading_error

    def _passed_start_point(self, along, across, yaw, distance, travelled):
        """True past the nearest point to the start, near it, heading the first stretch's way.

        Past it means no nearer for PASS_TRAVEL of path: a robot that turns on
        the spot short of the start (a left turn just before it) comes no
        nearer for a while without having passed it, and the lap ended
        there, short of the start line it crossed next.
        """
        if distance > self.close_tolerance:
            self._nearest = None
            return False
        if self._nearest is None or distance < self._nearest[0]:
            self._nearest = (distance, travelled)
            return False
        if travelled - self._nearest[1] < PASS_TRAVEL:
            return False
        # The first stretch's heading where it came nearest to here.
        _, _, first_yaw = min(self._first_stretch,
                              key=lambda point: math.hypot(point[0] - along, point[1] - across))
        return abs(float(wrap_angle(yaw - first_yaw))) <= self.max_heading_error

    def _extend_first_stretch(self, along, across, yaw, distance):
        """Keep the path's first stretch, a point every STRETCH_SPACING, up to close_tolerance."""
        if self._first_stretch_over:
            return
        if distance > self.close_tolerance or len(self._first_stretch) >= STRETCH_POINTS:
            self._first_stretch_over = True
            return
        last_along, last_across, _ = self._first_stretch[-1]
        if math.hypot(along - last_along, across - last_across) >= STRETCH_SPACING:
            self._first_stretch.append((along, across, yaw))


class LapRecorder(object):
    """One recording: path length, a pose every sample_period, and the lap's end.

    Feed it every odometry pose with add(); it keeps the first pose as the
    first point, appends the latest pose whenever a sample is due, and
    appends the closing pose when the lap ends. Points are (x, y, yaw).
    The lap parameters are those of LapDetector.

    start: poses stamped before this time (s) are skipped. A recorder that
    has fallen behind its odometry still holds poses from before it was
    asked to record; they are not part of the recording.
    max_speed, jump_allowance: a pose further from the one before than
    these allow (see JumpDetector) is a jump, recorded in `jumps` as
    (stamp, distance) and not counted (see the module's docstring).
    """

    def __init__(self, sample_period=_DEFAULT['sample_period'], start=None,
                 max_speed=_DEFAULT['max_speed'], jump_allowance=_DEFAULT['jump_allowance'],
                 **lap_params):
        self.start = start
        self.sampler = PeriodicSampler(sample_period)
        self.length = PathLength()
        self.jump_detector = JumpDetector(max_speed, jump_allowance)
        self.lap_params = lap_params
        self.lap = None
        self.points = []
        self.jumps = []

    @property
    def total_distance(self):
        return self.length.total

    @property
    def closed(self):
        return self.lap is not None and self.lap.closed

    def takes(self, stamp):
        """True for a pose stamped at or after the recording's start."""
        return self.start is None or stamp >= self.start

    def add(self, stamp, x, y, yaw):
        """Feed one pose at time stamp (s); True when a point was appended."""
        if self.closed or not self.takes(stamp):
            return False
        pose = (x, y, yaw)
        jump = self.jump_detector.jump(stamp, x, y)
        if jump is not None:
            self.jumps.append((stamp, jump))
            self.length.jump_to(x, y)
            self.lap.resume_at(x, y, self.length.total)
        travelled = self.length.add(x, y)
        if self.lap is None:
            self.lap = LapDetector(pose, **self.lap_params)
        sampled = self.sampler.due(stamp)
        if self.lap.update(x, y, yaw, travelled) or sampled:
            self.points.append(pose)
            return True
        return False
