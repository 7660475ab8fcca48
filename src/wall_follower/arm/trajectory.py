"""What a JointTrajectoryController does with a command: the rules of ros_control's
joint_trajectory_controller, free of ROS.

A Command is a trajectory_msgs/JointTrajectory as plain values. accept() checks it and
joins it to the trajectory being followed:

- joints are matched by name, in any order; every joint of the arm must be named
  once, and no other;
- a zero stamp means now; each point's time_from_start counts from the stamp, and
  must increase from point to point;
- every position must lie within the joint's limits;
- points whose time has already come (a point at time_from_start 0 of a zero stamp
  among them: it is due now) are dropped; if none is left the command is rejected and
  the current trajectory goes on;
- the new trajectory takes over at its start (its stamp, or now if that is past):
  a segment from the state the current trajectory has then (position, velocity,
  acceleration) to the first point left, so that the arm does not jump.
A rejection raises Rejected with the reason, and leaves the current trajectory alone.

An empty command (no points, whatever joints it names) is not a trajectory but a
request to stop: stop() is the controller's one stop, JointTrajectoryController's
way. JTC holds the arm's actual position, reached over its stop_trajectory_duration;
here the arm brakes from its actual state (where the joints are and how fast they
move, not where they were meant to be) to rest as fast as the acceleration limits
allow, and is held there.
"""
import bisect
import collections
import math

import numpy as np

from wall_follower.arm.spline import Segment
from wall_follower.arm.timing import stopping

TrajectoryPoint = collections.namedtuple(
    'TrajectoryPoint', 'time_from_start positions velocities accelerations')
"""A point of a Command: time_from_start [s]; positions, and velocities and accelerations
(empty where not given), in the Command's joint order."""

Command = collections.namedtuple('Command', 'joint_names stamp points')
"""A trajectory_msgs/JointTrajectory: stamp [s], 0 meaning now."""


class Rejected(ValueError):
    """A command not followed, with the reason in words."""


class Trajectory(object):
    """Desired joint states against time: Segments in time order, each followed from its
    start until the next one starts; held at the ends."""

    def __init__(self, segments):
        self.segments = list(segments)
        self._starts = [segment.start for segment in self.segments]

    @classmethod
    def hold(cls, positions, time):
        """Stand still at positions from time [s]."""
        positions = np.asarray(positions, dtype=float)
        zero = np.zeros_like(positions)
        return cls([Segment(time, time, (positions, zero, zero), (positions, zero, zero))])

    @property
    def end(self):
        """When the last segment ends [s]."""
        return self.segments[-1].end

    def sample(self, time):
        """(positions, velocities, accelerations) desired at time [s]."""
        index = max(0, bisect.bisect_right(self._starts, time) - 1)
        position, velocity, acceleration = self.segments[index].sample(time)
        if time >= self.segments[index].end:
            velocity, acceleration = np.zeros_like(velocity), np.zeros_like(acceleration)
        return position, velocity, acceleration

    def since(self, time):
        """The segments from the one followed at time on (those before are done with)."""
        index = max(0, bisect.bisect_right(self._starts, time) - 1)
        return self.segments[index:]


def stop(positions, velocities, time, acceleration):
    """The Trajectory that stops the arm from its actual state at time [s]: positions
    [rad] and velocities [rad/s] as the joints report them, braking within acceleration
    [rad/s^2] (arrays over the joints; inf: at once, as JTC with no
    stop_trajectory_duration holds the actual position) to rest, and held there."""
    positions = np.asarray(positions, dtype=float)
    velocities = np.asarray(velocities, dtype=float)
    place, duration = stopping(positions, velocities, acceleration)
    if not duration > 0.0:
        return Trajectory.hold(positions, time)
    zero = np.zeros_like(positions)
    return Trajectory([Segment(time, time + duration, (positions, velocities, zero),
                               (place, zero, zero))])


def checked_points(model, command):
    """The command's points as (time_from_start, positions, velocities, accelerations) in
    model.names' order (velocities and accelerations None where not given); Rejected if a
    joint is unknown, missing or named twice, a point malformed, times not increasing or
    a position outside the limits."""
    names = list(command.joint_names)
    twice = sorted(set(name for name in names if names.count(name) > 1))
    if twice:
        raise Rejected('joint(s) %s named more than once' % ', '.join(twice))
    unknown = [name for name in names if name not in model.names]
    if unknown:
        raise Rejected('unknown joint(s) %s (the arm\'s joints are %s)' % (
            ', '.join(unknown), ', '.join(model.names)))
    missing = [name for name in model.names if name not in names]
    if missing:
        raise Rejected('joint(s) %s missing: every joint of the arm must be given'
                       % ', '.join(missing))
    order = [names.index(name) for name in model.names]
    points = []
    previous = None
    for number, point in enumerate(command.points):
        values = []
        for field in ('positions', 'velocities', 'accelerations'):
            given = list(getattr(point, field))
            if field != 'positions' and not given:
                values.append(None)
                continue
            if len(given) != len(names):
                raise Rejected('point %d has %d %s for %d joints' % (
                    number, len(given), field, len(names)))
            if not all(math.isfinite(v) for v in given):
                raise Rejected('point %d has %s that are not finite' % (number, field))
            values.append(np.array([given[i] for i in order], dtype=float))
        if values[2] is not None and values[1] is None:
            raise Rejected('point %d gives accelerations without velocities' % number)
        time = float(point.time_from_start)
        if not math.isfinite(time) or time < 0.0:
            raise Rejected('point %d has time_from_start %r: it must be finite and not negative'
                           % (number, time))
        if previous is not None and time <= previous:
            raise Rejected('time_from_start must increase: point %d at %.3f s follows one at '
                           '%.3f s' % (number, time, previous))
        problems = model.outside_limits(values[0])
        if problems:
            raise Rejected('point %d: %s' % (number, '; '.join(problems)))
        previous = time
        points.append((time,) + tuple(values))
    return points


def accept(model, command, now, current):
    """The Trajectory to follow from now [s] on, given the current one; Rejected (the current
    one goes on) if the command cannot be followed. An empty command is a stop (see stop()),
    not for accept()."""
    if not command.points:
        raise Rejected('no points: an empty command is a stop, not a trajectory')
    points = checked_points(model, command)
    start = command.stamp if command.stamp > 0.0 else now
    due = [(start + point[0],) + point[1:] for point in points if start + point[0] > now]
    if not due:
        late = now - start - points[-1][0]
        if late <= 1e-9:
            raise Rejected('its last point is due now (time_from_start %.3f s from %s): a point '
                           'due now is dropped like those already past, as ros_control\'s '
                           'JointTrajectoryController drops it, and none is left; give it a '
                           'time_from_start above 0, the time the arm has to get there: the '
                           'current trajectory goes on' % (
                               points[-1][0], 'a zero stamp, which means now'
                               if command.stamp <= 0.0 else 'its stamp'))
        raise Rejected('every point is in the past (the last was due %.3f s ago): '
                       'the current trajectory goes on' % late)
    takeover = max(start, now)
    segments = [segment for segment in current.since(now) if segment.start < takeover]
    state = current.sample(takeover)
    if not segments:
        segments = Trajectory.hold(state[0], takeover).segments
    if due[0][0] <= takeover + 1e-9:
        # A first point due at the takeover itself (a stamp still to come, time 0): the
        # arm is sent straight there; the joints' speed limits still hold it back.
        first = due.pop(0)
        takeover, state = first[0], first[1:]
        segments.append(Segment(takeover, takeover, state, state))
    for point in due:
        segments.append(Segment(takeover, point[0], state, point[1:]))
        takeover, state = point[0], point[1:]
    return Trajectory(segments)
