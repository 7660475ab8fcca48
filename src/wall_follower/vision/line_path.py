"""The line's centreline traced through its floor points, and the memory of it.

The camera sees the line only from some way ahead of the robot, so the
path the base must follow now was seen a few frames ago. LinePath keeps
the traced centreline in the odometry frame: each frame it keeps what it
remembers up to the floor the camera sees now, and traces on from there
through what the camera sees, so that the base can be steered along the
part of the line the camera no longer sees.

Tracing walks along the line in steps of `step` [m]: the next centre is
the mean of the line's points within `radius` [m] of the point one step
on in the current direction (refined once), among points ahead. It stops
where no points are found, where that centre is not half a step on, or
after `max_length` [m]. Points are first
thinned to one per `cell` [m] square, so that the mean is not pulled
towards the near floor, where pixels are dense.
"""
import math

import numpy as np

from wall_follower.params import checked
from wall_follower.params.camera.line_follower import PATH

MIN_POINTS = 3        # line points within radius for a centre to count (specks do not)


def thin(points, cell):
    """(M, 2) one point (the mean) per cell x cell square of the (N, 2) points."""
    points = np.asarray(points, float).reshape(-1, 2)
    if len(points) == 0:
        return points
    keys = np.floor(points / cell).astype(np.int64)
    _, index, counts = np.unique(keys, axis=0, return_inverse=True, return_counts=True)
    index = index.reshape(-1)
    sums = np.zeros((len(counts), 2))
    np.add.at(sums, index, points)
    return sums / counts[:, None]


def trace(points, start, heading, step, radius, max_length, first_reach):
    """(K, 2) centreline from start (x, y), heading [rad] the way to go, through points.

    The first centre may lie up to first_reach [m] ahead of start (the
    floor the camera cannot see, from a standing start): it is the mean
    about the nearest point ahead within 45 deg of heading.
    """
    points = np.asarray(points, float).reshape(-1, 2)
    position = np.asarray(start, float)
    direction = np.array([math.cos(heading), math.sin(heading)])
    centre = _first_centre(points, position, direction, radius, first_reach)
    path = [position]
    length = 0.0
    while centre is not None and length < max_length:
        gap = centre - position
        if gap.dot(direction) < step / 2.0:
            break             # no line ahead but at the tracing point itself
        length += float(np.hypot(*gap))
        direction = gap / np.hypot(*gap)
        position = centre
        path.append(position)
        centre = _centre_near(points, position + step * direction, position, direction, radius)
    return np.array(path)


def _first_centre(points, position, direction, radius, reach):
    offsets = points - position
    along = offsets.dot(direction)
    distance = np.hypot(*offsets.T) if len(points) else np.zeros(0)
    candidates = (along > 0.0) & (along >= distance * math.cos(math.pi / 4.0)) & (
        distance <= reach)
    if not candidates.any():
        return None
    nearest = points[candidates][np.argmin(distance[candidates])]
    return _centre_near(points, nearest, position, direction, radius)


def _centre_near(points, guess, position, direction, radius):
    """The mean of the points ahead of position within radius of guess, refined once; None
    with fewer than MIN_POINTS."""
    centre = guess
    ahead = (points - position).dot(direction) > 0.0
    for _ in range(2):
        near = ahead & (np.hypot(*(points - centre).T) <= radius)
        if near.sum() < MIN_POINTS:
            return None
        centre = points[near].mean(axis=0)
    return centre


def path_length(path):
    path = np.asarray(path, float).reshape(-1, 2)
    return float(np.hypot(*np.diff(path, axis=0).T).sum()) if len(path) > 1 else 0.0


class LinePath(object):
    """The line's centreline in the odometry frame, and whether its far end is the line's end.

    step, radius, max_length, first_reach: as trace(); cell: as thin();
    keep_behind: how much of the path behind the base is kept [m].
    """

    def __init__(self, **params):
        self.reconfigure(**params)
        self.path = np.zeros((0, 2))
        self.end_seen = False

    def reconfigure(self, **params):
        """Go on under these parameters (PATH's defaults, overridden) from the next frame on."""
        self.p = checked(PATH, params)

    def forget(self):
        self.path = np.zeros((0, 2))
        self.end_seen = False

    def update(self, seen, in_view, base, end_in_view):
        """Take one frame's line points and trace the path on from what is remembered.

        seen: (N, 2) floor points of the line in this frame, odometry frame;
        in_view(points) -> (M,) bool: which floor points the camera sees now;
        base: (x, y, yaw) of the robot's base; end_in_view(point) -> bool:
        whether the floor at that point is in view, so that a trace that
        stops there has found the line's end.

        What is remembered up to just inside the view is kept as it was
        traced (traced again, it would be smoothed again, and bends would
        shrink); from there on the path is traced through this frame's
        points only. Returns the new path ((K, 2), odometry frame, from
        keep_behind behind the base on).
        """
        kept = self._kept(in_view, base)
        if len(kept):
            start = kept[-1]
            heading = _heading(kept) if len(kept) > 1 else base[2]
        else:
            start, heading = np.asarray(base[:2], float), base[2]
        traced = trace(thin(seen, self.p['cell']), start, heading, self.p['step'], self.p['radius'],
                       self.p['max_length'], self.p['first_reach'])[1:]
        if len(traced):
            path = np.vstack((kept, traced)) if len(kept) else np.vstack((start, traced))
        else:
            path = kept
        # An end is found by seeing the line up to it and the floor beyond it; with nothing
        # traced this frame (the line's last bit too short to trace, or no line in view at
        # all: a covered lens is no end), what was found before stands.
        ended = self.end_seen and len(path) > 0
        if len(traced) and len(path) > 1:
            beyond = path[-1] + self.p['step'] * _unit(path[-1] - path[-2])
            # The floor beyond an end already found may have left the view (near its edge)
            # while the line's last bit is still traced: the end stays where it was found.
            ended = bool(end_in_view(beyond)) or (
                self.end_seen and np.hypot(*(path[-1] - self.path[-1])) <= self.p['radius'])
        self.path, self.end_seen = path, ended
        return self.path

    def _kept(self, in_view, base):
        """The remembered path from keep_behind behind the base up to radius past its
        first point in view (a standing start keeps nothing)."""
        path = self.path
        if len(path) == 0:
            return path
        shown = np.nonzero(in_view(path))[0]
        if len(shown):
            # Keep radius more, inside the view's edge: traced again, it would be traced
            # from the mean of points that the edge cuts off, always ahead of where it was.
            cut = shown[0] + 1
            while cut < len(path) and path_length(path[shown[0]:cut + 1]) <= self.p['radius']:
                cut += 1
            path = path[:cut]
        if len(path) == 0:
            return path
        nearest = int(np.argmin(np.hypot(path[:, 0] - base[0], path[:, 1] - base[1])))
        first = nearest
        while first > 0 and path_length(path[first - 1:nearest + 1]) <= self.p['keep_behind']:
            first -= 1
        return path[first:]


def _heading(path):
    """The way the path runs at its last point [rad]."""
    dx, dy = path[-1] - path[-2]
    return math.atan2(dy, dx)


def _unit(vector):
    norm = np.hypot(*vector)
    return vector / norm if norm > 1e-12 else vector
