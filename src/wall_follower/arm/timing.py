"""A straight joint-space move timed within each joint's velocity and acceleration limits.

Every joint starts and stops together, at rest, on the straight line from the
start to the goal: the path's progress s (0 to 1) follows a trapezoidal speed
profile (accelerate, cruise, brake), as fast as the joint for which the
limits bite hardest allows. Keeping the path straight keeps it the path the
collision check walked.
"""
import math

import numpy as np

# The most points waypoint_times gives, however long the move: a move slowed to a crawl
# (a tiny velocity scaling) is then sampled more coarsely instead of by millions of points.
# The trajectory's splines meet the timed move exactly at any spacing (see waypoint_times).
MAX_WAYPOINTS = 1000


def trapezoid_duration(distance, velocity, acceleration):
    """The least time [s] to go distance at rest to rest within velocity and acceleration."""
    if distance <= 0.0:
        return 0.0
    if distance >= velocity * velocity / acceleration:
        return distance / velocity + velocity / acceleration
    return 2.0 * math.sqrt(distance / acceleration)


def stopping(positions, velocities, acceleration):
    """Where a moving arm stops, and when [s], braking within its acceleration limits.

    One quintic from (positions, velocities, no acceleration) to (the place, at rest), as
    a trajectory controller spans a single point given with zero velocity and
    acceleration: it travels velocities * duration / 2, and its braking peaks at
    1.5 * velocities / duration, the acceleration limit of the joint that needs longest.
    """
    positions = np.asarray(positions, dtype=float)
    velocities = np.asarray(velocities, dtype=float)
    duration = 1.5 * float(np.max(np.abs(velocities) / np.asarray(acceleration, dtype=float)))
    return positions + velocities * duration / 2.0, duration


def fastest_duration(start, goal, velocity, acceleration):
    """The least time [s] the limits allow for the move, each joint on its own (a bound no
    synchronized move beats)."""
    return max(trapezoid_duration(abs(d), v, a) for d, v, a in
               zip(np.asarray(goal) - np.asarray(start), velocity, acceleration))


class TimedMove(object):
    """The move from start to goal (arrays over the joints), timed within velocity [rad/s]
    and acceleration [rad/s^2] limits (arrays over the joints)."""

    def __init__(self, start, goal, velocity, acceleration):
        self.start = np.asarray(start, dtype=float)
        self.delta = np.asarray(goal, dtype=float) - self.start
        moving = np.abs(self.delta) > 1e-12
        if not moving.any():
            self.rate = self.gain = 1.0
            self.ramp = self.cruise = self.duration = 0.0
            return
        # Limits of the progress s: no joint may exceed its own.
        self.rate = float(np.min(np.asarray(velocity)[moving] / np.abs(self.delta[moving])))
        self.gain = float(np.min(np.asarray(acceleration)[moving] / np.abs(self.delta[moving])))
        if self.rate * self.rate / self.gain <= 1.0:
            self.ramp = self.rate / self.gain
            self.cruise = 1.0 / self.rate - self.ramp
        else:
            self.rate = math.sqrt(self.gain)
            self.ramp = self.rate / self.gain
            self.cruise = 0.0
        self.duration = 2.0 * self.ramp + self.cruise

    def progress(self, time):
        """(s, ds/dt, d2s/dt2) at time [s] since the start."""
        t = min(max(time, 0.0), self.duration)
        if self.duration == 0.0:
            return 1.0, 0.0, 0.0
        if t < self.ramp:
            return 0.5 * self.gain * t * t, self.gain * t, self.gain
        if t <= self.ramp + self.cruise:
            return 0.5 * self.gain * self.ramp ** 2 + self.rate * (t - self.ramp), self.rate, 0.0
        left = self.duration - t
        return 1.0 - 0.5 * self.gain * left * left, self.gain * left, -self.gain

    def time_share(self, started, now):
        """The share of the move's time past at now, for a move begun at started (both in
        s): 0 to 1, and exactly 1 from its end (started + duration) on, so that a move
        judged ended is never reported a rounding short of done."""
        if self.duration == 0.0 or now >= started + self.duration:
            return 1.0
        return min(1.0, max(0.0, (now - started) / self.duration))

    def sample(self, time):
        """(positions, velocities, accelerations) at time [s] since the start."""
        s, rate, gain = self.progress(time)
        return self.start + self.delta * s, self.delta * rate, self.delta * gain

    def waypoint_times(self, spacing):
        """Times [s] from the start for trajectory points: every phase change and about every
        spacing seconds between, the last at the end (the first after 0); never more than
        MAX_WAYPOINTS of them, the spacing widened where the move is too long for it.

        Any spacing is exact: each phase is a polynomial of degree two at most, which the
        quintic spline through two of its points (positions, velocities and accelerations
        given) follows exactly."""
        marks = sorted(set([self.ramp, self.ramp + self.cruise, self.duration]))
        # each of the (at most three) phases gets at most one point more than its share
        spacing = max(spacing, self.duration / (MAX_WAYPOINTS - len(marks)))
        times = []
        previous = 0.0
        for mark in marks:
            if mark <= previous:
                continue
            count = max(1, int(math.ceil((mark - previous) / spacing - 1e-9)))
            times.extend(previous + (mark - previous) * (i + 1) / count for i in range(count))
            previous = mark
        return times
