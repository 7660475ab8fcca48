"""Straight lines through laser hits: the one Line type, and the fits that make one.

A line is given by the foot of the perpendicular from the laser to it:
its distance and the direction of that perpendicular (the line's normal).
The walls of walls.py, the follower's walls (wall_fit.py) and the
evaluation's fits are all such lines. Which direction the angle is
measured from is the owner's to say: the laser's x axis here, the right
for the follower's walls.

Pure geometry on (N, 2) arrays of hits in the laser frame, free of any
scan or laser convention.
"""
import math
from collections import namedtuple

import numpy as np


class Line(namedtuple('Line', ['distance', 'angle'])):
    """A straight line: distance (m) from the laser to it, angle (rad) of its normal.

    The normal points from the laser towards the line.
    """

    __slots__ = ()

    @property
    def normal(self):
        """The unit normal as an array (x, y)."""
        return np.array([math.cos(self.angle), math.sin(self.angle)])

    def offsets(self, points):
        """Signed distances of (N, 2) points from the line, > 0 beyond it."""
        return points.dot(self.normal) - self.distance


def line_through(points):
    """Total-least-squares line through (N >= 2, 2) points in the laser frame.

    Returns (mean, normal, distance): the points' centroid, the unit normal
    pointing away from the laser, and the laser's perpendicular distance to
    the line. The principal direction of the points is the line's direction,
    which, unlike a least-squares y(x), does not care how the wall is turned.
    """
    mean = points.mean(axis=0)
    _, _, vt = np.linalg.svd(points - mean, full_matrices=False)
    normal = vt[1]
    distance = float(np.dot(mean, normal))
    if distance < 0.0:
        normal, distance = -normal, -distance
    return mean, normal, distance


def fit_line(points, min_points=5):
    """The Line through (N, 2) points, or None below min_points.

    For callers that pick their own points (e.g. only those near an
    earlier fit).
    """
    if len(points) < min_points:
        return None
    _, normal, distance = line_through(points)
    return Line(distance, float(math.atan2(normal[1], normal[0])))


def consensus_line(points, tolerance, min_points, max_pairs_points=40):
    """Line through points that the most of them lie near (within tolerance), or None.

    Every line through two of the points is a candidate (of at most
    max_pairs_points points spread evenly, to bound the work); the one with
    the most points near it wins and is refitted through them. Unlike a
    plain least-squares fit, a few stray hits (a beam grazing an obstacle's
    side, the other leg of a corner) cannot tilt it.
    """
    if len(points) < max(2, min_points):
        return None
    step = max(1, int(math.ceil(len(points) / float(max_pairs_points))))
    first, second = np.triu_indices(len(points[::step]), 1)
    ends = points[::step]
    along = ends[second] - ends[first]
    length = np.hypot(along[:, 0], along[:, 1])
    usable = length > 1e-9
    normals = np.column_stack((-along[usable, 1], along[usable, 0])) / length[usable, None]
    offsets = points.dot(normals.T) - np.sum(normals * ends[first][usable], axis=1)
    near = np.abs(offsets) < tolerance
    if not near.size:
        return None
    best = int(np.argmax(near.sum(axis=0)))
    return fit_line(points[near[:, best]], min_points)
