"""Scoring a line follower from ground truth against a course's centreline (line_track).

The base's distance to the centreline at each pose (cross-track), the
progress along a closed line (a lap is its length), and the best mean
speed a robot can lap a line at while staying on it: on a bend of radius
r the turn-rate limit caps the speed at max_angular * r, so on a course
of tight bends the speed limit alone is not a fair bound.
"""
import math

import numpy as np

CURVATURE_CHORD = 0.01    # m: the chord over which the centreline's curvature is measured


def progress(centreline, xy):
    """(N,) arc length [m] driven along a closed centreline at each (N, 2) position, from the
    first, counting forward and back and across the start."""
    _, along = centreline.nearest(xy[:, 0], xy[:, 1])
    length = centreline.length
    steps = (np.diff(along) + length / 2.0) % length - length / 2.0
    return np.concatenate(([0.0], np.cumsum(steps)))


def cross_track(centreline, xy):
    """(RMS, worst) distance [m] of (N, 2) positions to the centreline."""
    errors = centreline.distance(xy[:, 0], xy[:, 1])
    return float(math.sqrt(np.mean(errors ** 2))), float(errors.max())


def speed_bound(centreline, max_linear, max_angular):
    """The highest mean speed [m/s] along the centreline with every speed at most max_linear
    and every turn rate (speed x curvature) at most max_angular."""
    points = centreline.points
    lengths = np.hypot(*np.diff(points, axis=0).T)
    along = np.concatenate(([0.0], np.cumsum(lengths)))
    stations = np.arange(0.0, along[-1], CURVATURE_CHORD)
    if len(stations) < 3:
        return max_linear
    resampled = np.column_stack((np.interp(stations, along, points[:, 0]),
                                 np.interp(stations, along, points[:, 1])))
    headings = np.arctan2(*np.diff(resampled, axis=0).T[::-1])
    curvature = np.abs(np.angle(np.exp(1j * np.diff(headings)))) / CURVATURE_CHORD
    speeds = np.minimum(max_linear, max_angular / np.maximum(curvature, 1e-12))
    return float(len(speeds) * CURVATURE_CHORD / np.sum(CURVATURE_CHORD / speeds))
