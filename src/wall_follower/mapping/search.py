"""Fits from many starts: the best of them after a slip, and whether one is alone.

A match is a local fit: from a start far off, Gauss-Newton settles on the
nearest fit, which need not be the true one (an octagon fits itself turned
45 degrees, but for its pillar). Where a pose must be found or confirmed
without odometry's support (after the odometry slipped; closing a loop),
the fits from starts all round are compared: the best is taken only where
it is sure, sends no beam through a wall the map holds (the turned
octagon's beams pass through its pillar), and explains the scan better by
a margin than any fit elsewhere.
"""
import math

import numpy as np

from .poses import between, compose

__all__ = ['alike', 'alone', 'best_fit', 'crossed']

# Two fits this close (x, y [m], yaw [rad]) are one.
AGREE = (0.02, math.radians(1.0))
# The starts round a guess that a fit must agree with to be alone (x, y [m], yaw [rad]).
STARTS = ((0.1, 0.0, 0.0), (-0.1, 0.0, 0.0), (0.0, 0.1, 0.0), (0.0, -0.1, 0.0),
          (0.0, 0.0, math.radians(8.0)), (0.0, 0.0, math.radians(-8.0)))
# The starts of a search, in search windows (x, y, yaw): the guess, and out to one
# window's travel and two of its turn round it.
SEARCH = ((0, 0, 0),) + tuple((x, y, a) for x in (-1, 0, 1) for y in (-1, 0, 1)
                              for a in (-2, -1, 0, 1, 2) if (x, y, a) != (0, 0, 0))
# How much more of the scan the best fit must explain than any other, and how many of
# its beams may pass through a mapped wall.
MARGIN = 0.02
CROSSED = 0.01
# Beams are sampled this far apart for walls they pass through [m].
CROSSING_STEP = 0.02


def alike(a, b):
    """True if poses a and b are one fit (within AGREE)."""
    apart = between(a, b)
    return math.hypot(apart[0], apart[1]) <= AGREE[0] and abs(apart[2]) <= AGREE[1]


def alone(matcher, points, guess, match, max_sigma):
    """True if the match (of points, from guess) is good, sure to max_sigma [m], and every
    good fit from the STARTS round guess is the same one."""
    if not match.ok or match.sigma > max_sigma:
        return False
    for offset in STARTS:
        other = matcher.match(points, compose(guess, offset))
        if other.ok and not alike(match.pose, other.pose):
            return False
    return True


def crossed(grid, origin, ends, short):
    """The share of beams from origin (x, y) to ends (N, 2), map frame, that pass through
    an occupied cell of grid more than `short` [m] before their end."""
    delta = ends - np.asarray(origin[:2], dtype=float)
    length = np.hypot(delta[:, 0], delta[:, 1])
    free = np.maximum(length - short, 0.0)
    if not len(free):
        return 0.0
    t = np.arange(0.0, float(free.max()), CROSSING_STEP)
    keep = t[None, :] < free[:, None]
    direction = delta / np.maximum(length, 1e-12)[:, None]
    samples = np.asarray(origin[:2]) + direction[:, None, :] * t[None, :, None]
    rows, cols, inside = grid.cells(samples.reshape(-1, 2))
    wall = np.zeros(len(rows), dtype=bool)
    wall[inside] = grid.logodds[rows[inside], cols[inside]] > 0.0
    return float((wall.reshape(keep.shape) & keep).any(axis=1).mean())


def best_fit(matcher, points, guess, window, max_sigma, crossing):
    """(the best fit, or None; why not in words) of points from the SEARCH starts round
    guess, window (metres, radians) apart. crossing(pose): the share of the scan's beams
    that pass through a mapped wall with the robot at pose."""
    steps = np.array([window[0], window[0], window[1]])
    fits = [matcher.match(points, compose(guess, tuple(steps * offset))) for offset in SEARCH]
    fits = [fit for fit in fits if fit.ok and fit.sigma <= max_sigma
            and crossing(fit.pose) <= CROSSED]
    if not fits:
        return None, 'no fit round it is good and sure'
    fits.sort(key=lambda fit: (-fit.explained, fit.misfit))
    best = fits[0]
    rivals = [fit.explained for fit in fits[1:] if not alike(fit.pose, best.pose)]
    if rivals and best.explained < max(rivals) + MARGIN:
        return None, ('%d fits round it explain the scan within %.0f %% of the best'
                      % (len(rivals), 100.0 * MARGIN))
    return best, ''
