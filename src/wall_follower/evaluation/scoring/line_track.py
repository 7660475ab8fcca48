"""The centreline of a line world's painted line, for scoring a line follower.

Each line world in worlds/ has a course file beside it (`<world>.course.yaml`)
that defines the line as a path of straights and arcs from a start pose;
tools/make_line_worlds.py draws the world's bitmap from the same file, so the
centreline here is exactly the one the camera sees. Course file keys:

    start: [x, y, heading_deg]     where the line begins, and its direction
    closed: true|false             a loop (the path must end where it began)
    width: 0.045                   the line's width [m]
    path:                          pieces, in order
      - [straight, length]
      - [arc, radius, angle_deg]   angle > 0 turns left, < 0 right

plus what the world generator needs (`robot`: the start pose, `room`: the
walls' free space). Distances are exact for the polyline, which follows each
arc within a micrometre.
"""
import math
import os

import numpy as np
import yaml

__all__ = ['CourseError', 'Centreline', 'load_centreline', 'course_path']

# Polyline step along the path [m]; an arc's chord then departs from it by
# step^2 / (8 radius), under a micrometre for any radius above 0.1 m.
STEP = 0.001
# Start and end of a closed path may miss each other by this much [m].
CLOSURE_TOLERANCE = 1e-6


class CourseError(Exception):
    """A course file that cannot be used; str() names the file and the problem."""


def course_path(world_path):
    """The course file beside a world file: worlds/x.world -> worlds/x.course.yaml."""
    base = world_path[:-len('.world')] if world_path.endswith('.world') else world_path
    return base + '.course.yaml'


class Centreline(object):
    """A line's centreline as a dense polyline, with distance queries.

    points: (N, 2) from the start to the end (a closed line repeats its start).
    """

    def __init__(self, points, closed, width):
        self.points = np.asarray(points, dtype=float)
        self.closed = bool(closed)
        self.width = float(width)
        segments = np.diff(self.points, axis=0)
        self._lengths = np.hypot(segments[:, 0], segments[:, 1])
        self._along = np.concatenate([[0.0], np.cumsum(self._lengths)])
        self.step = float(self._lengths.max()) if len(self._lengths) else 0.0
        from scipy.spatial import cKDTree
        self._tree = cKDTree(self.points)

    @property
    def length(self):
        """Length of the centreline [m]."""
        return float(self._along[-1])

    @property
    def along(self):
        """(N,) arc length [m] of each point from the start."""
        return self._along

    @property
    def start(self):
        return tuple(self.points[0])

    @property
    def end(self):
        """Where an open line ends (a closed one ends at its start)."""
        return tuple(self.points[-1])

    def nearest(self, x, y, within=np.inf):
        """(distance [m], arc length [m] of the nearest centreline point) for points x, y;
        points farther than `within` [m] (a shortcut for many far points) get inf, 0."""
        x = np.asarray(x, dtype=float)
        y = np.asarray(y, dtype=float)
        query = np.stack([x.ravel(), y.ravel()], axis=1)
        best = np.full(len(query), np.inf)
        along = np.zeros(len(query))
        # The nearest sample lies within half a step of the nearest point of the polyline.
        _, index = self._tree.query(query, distance_upper_bound=within + self.step)
        close = index < len(self.points)
        if not close.all():
            near_best, near_along = self.nearest(x.ravel()[close], y.ravel()[close])
            best[close], along[close] = near_best, near_along
            return best.reshape(x.shape), along.reshape(x.shape)
        last = len(self.points) - 2
        for offset in (-1, 0):
            seg = np.clip(index + offset, 0, last)
            a = self.points[seg]
            d = self.points[seg + 1] - a
            length2 = np.maximum(np.einsum('ij,ij->i', d, d), 1e-18)
            s = np.clip(np.einsum('ij,ij->i', query - a, d) / length2, 0.0, 1.0)
            foot = a + s[:, None] * d
            dist = np.hypot(query[:, 0] - foot[:, 0], query[:, 1] - foot[:, 1])
            better = dist < best
            best[better] = dist[better]
            along[better] = self._along[seg[better]] + s[better] * self._lengths[seg[better]]
        return best.reshape(x.shape), along.reshape(x.shape)

    def distance(self, x, y, within=np.inf):
        """Distance [m] from points (x, y) (scalars or arrays) to the centreline (inf for
        points farther than `within`)."""
        return self.nearest(x, y, within)[0]

    def distance_to_end(self, x, y):
        """Straight-line distance [m] from (x, y) to the end of the line."""
        return math.hypot(x - self.points[-1][0], y - self.points[-1][1])


def trace_path(start, pieces, step=STEP):
    """Polyline (N, 2) of `pieces` ([straight, L] / [arc, R, deg]) from start (x, y, heading
    [rad]); raises ValueError on a malformed piece."""
    x, y, heading = start
    points = [(x, y)]
    for piece in pieces:
        if not isinstance(piece, (list, tuple)) or not piece:
            raise ValueError('path piece %r: expected [straight, L] or [arc, R, deg]' % (piece,))
        kind = piece[0]
        if kind == 'straight' and len(piece) == 2 and float(piece[1]) > 0:
            length = float(piece[1])
            count = max(1, int(math.ceil(length / step)))
            s = np.arange(1, count + 1) * (length / count)
            points.extend(zip(x + s * math.cos(heading), y + s * math.sin(heading)))
            x, y = points[-1]
        elif kind == 'arc' and len(piece) == 3 and float(piece[1]) > 0 and float(piece[2]):
            radius, turn = float(piece[1]), math.radians(float(piece[2]))
            side = 1.0 if turn > 0 else -1.0
            cx, cy = x - side * radius * math.sin(heading), y + side * radius * math.cos(heading)
            count = max(1, int(math.ceil(abs(turn) * radius / step)))
            angles = heading - side * math.pi / 2.0 + np.arange(1, count + 1) * (turn / count)
            points.extend(zip(cx + radius * np.cos(angles), cy + radius * np.sin(angles)))
            x, y = points[-1]
            heading += turn
        else:
            raise ValueError('path piece %r: expected [straight, L>0] or [arc, R>0, deg!=0]'
                             % (piece,))
    return np.array(points, dtype=float)


def read_course(path):
    """The parsed course file (a dict); raises CourseError with the file's name."""
    try:
        with open(path) as stream:
            course = yaml.safe_load(stream)
    except (IOError, OSError) as error:
        raise CourseError('%s: cannot read course file (%s)' % (path, error))
    except yaml.YAMLError as error:
        raise CourseError('%s: not YAML (%s)' % (path, error))
    if not isinstance(course, dict):
        raise CourseError('%s: expected a mapping of keys' % path)
    for key in ('start', 'path', 'width'):
        if key not in course:
            raise CourseError('%s: missing key "%s"' % (path, key))
    return course


def centreline_of(course, path='course'):
    """Centreline of a parsed course (raises CourseError naming `path`)."""
    try:
        sx, sy, heading = (float(v) for v in course['start'])
        points = trace_path((sx, sy, math.radians(heading)), course['path'])
        width = float(course['width'])
    except (TypeError, ValueError) as error:
        raise CourseError('%s: %s' % (path, error))
    closed = bool(course.get('closed', False))
    if closed:
        gap = math.hypot(*(points[-1] - points[0]))
        if gap > CLOSURE_TOLERANCE:
            raise CourseError('%s: closed, but the path ends %.6f m from its start'
                              % (path, gap))
        points[-1] = points[0]
    return Centreline(points, closed, width)


def load_centreline(path):
    """Centreline of a course file, or of the course file beside a .world file."""
    if path.endswith('.world'):
        path = course_path(path)
    if not os.path.isfile(path):
        raise CourseError('%s: no course file' % path)
    return centreline_of(read_course(path), path)
