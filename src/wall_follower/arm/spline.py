"""The polynomial between two trajectory points, as JointTrajectoryController has it:
quintic where both points give positions, velocities and accelerations, cubic where
they give positions and velocities, linear where only positions.
"""
import numpy as np

LINEAR, CUBIC, QUINTIC = 'linear', 'cubic', 'quintic'


class Segment(object):
    """One joint-space polynomial from start [s] to end [s] (absolute times).

    start_state and end_state are (positions, velocities, accelerations), arrays
    over the joints; velocities and accelerations may be None where not given,
    which chooses the kind: the most both ends give.
    """

    def __init__(self, start, end, start_state, end_state):
        self.start, self.end = float(start), float(end)
        duration = self.end - self.start
        p0, v0, a0 = start_state
        p1, v1, a1 = end_state
        p0, p1 = np.asarray(p0, dtype=float), np.asarray(p1, dtype=float)
        if v0 is not None and v1 is not None and a0 is not None and a1 is not None:
            self.kind = QUINTIC
        elif v0 is not None and v1 is not None:
            self.kind = CUBIC
        else:
            self.kind = LINEAR
        self.coefficients = _coefficients(self.kind, duration, p0, p1, v0, v1, a0, a1)

    def sample(self, time):
        """(positions, velocities, accelerations) at time, held at the ends outside it."""
        tau = min(max(time - self.start, 0.0), self.end - self.start)
        c = self.coefficients
        powers = np.array([tau ** k for k in range(6)])
        position = powers.dot(c)
        velocity = np.array([k * tau ** (k - 1) for k in range(1, 6)]).dot(c[1:])
        acceleration = np.array([k * (k - 1) * tau ** (k - 2) for k in range(2, 6)]).dot(c[2:])
        return position, velocity, acceleration


def _coefficients(kind, duration, p0, p1, v0, v1, a0, a1):
    """6 x joints polynomial coefficients (constant term first) in the time since the start."""
    c = np.zeros((6, len(p0)))
    c[0] = p0
    delta = p1 - p0
    if duration <= 0.0:
        c[0] = p1
        return c
    t = duration
    if kind == LINEAR:
        c[1] = delta / t
    elif kind == CUBIC:
        v0, v1 = np.asarray(v0, dtype=float), np.asarray(v1, dtype=float)
        c[1] = v0
        c[2] = (3.0 * delta - (2.0 * v0 + v1) * t) / t ** 2
        c[3] = (-2.0 * delta + (v0 + v1) * t) / t ** 3
    else:
        v0, v1, a0, a1 = (np.asarray(x, dtype=float) for x in (v0, v1, a0, a1))
        c[1] = v0
        c[2] = a0 / 2.0
        c[3] = (20.0 * delta - (8.0 * v1 + 12.0 * v0) * t - (3.0 * a0 - a1) * t ** 2) / \
            (2.0 * t ** 3)
        c[4] = (-30.0 * delta + (14.0 * v1 + 16.0 * v0) * t + (3.0 * a0 - 2.0 * a1) * t ** 2) / \
            (2.0 * t ** 4)
        c[5] = (12.0 * delta - 6.0 * (v1 + v0) * t - (a0 - a1) * t ** 2) / (2.0 * t ** 5)
    return c
