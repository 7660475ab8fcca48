"""Angle-based queries on a laser scan, whatever the laser's conventions.

Lasers disagree on where beam 0 points (Stage: backwards, LDS-01 and
Gazebo: forwards), on the direction of the sweep and on how "no return" is
written (range_max, inf, NaN or 0.0). Every query here is by angle in the
laser frame (0 = ahead, +pi/2 = left, -pi/2 = right), and every
implausible reading is dropped instead of being taken for a wall.
"""
import math
import warnings

import numpy as np

FRONT = 0.0
LEFT = math.pi / 2
RIGHT = -math.pi / 2


def wrap_angle(angle):
    """Wrap an angle (scalar or array) into [-pi, pi)."""
    return (np.asarray(angle) + math.pi) % (2.0 * math.pi) - math.pi


class ScanView(object):
    """A LaserScan seen as (angle, range) pairs with invalid beams masked.

    A reading counts only if it is finite and inside [range_min, range_max).
    range_max itself is excluded because Stage writes it for "no return".
    """

    def __init__(self, ranges, angle_min, angle_increment, range_min, range_max):
        self.ranges = np.asarray(ranges, dtype=float)
        count = self.ranges.size
        self.angles = wrap_angle(angle_min + angle_increment * np.arange(count))
        self.range_min = float(range_min)
        self.range_max = float(range_max)
        with np.errstate(invalid='ignore'):
            self.valid = (np.isfinite(self.ranges)
                          & (self.ranges > 0.0)
                          & (self.ranges >= self.range_min)
                          & (self.ranges < self.range_max))
        # Half the beam spacing, so that a window never comes back empty
        # merely because no beam lies exactly on its edge.
        self.half_step = abs(float(angle_increment)) / 2.0 if count else 0.0

    @classmethod
    def from_msg(cls, msg):
        """Build a view of a sensor_msgs/LaserScan (or anything with its fields)."""
        return cls(msg.ranges, msg.angle_min, msg.angle_increment,
                   msg.range_min, msg.range_max)

    def in_sector(self, center, half_width):
        """Boolean mask of the beams within half_width of the angle center."""
        offset = np.abs(wrap_angle(self.angles - center))
        return offset <= half_width + self.half_step

    def _sector_ranges(self, center, half_width):
        mask = self.in_sector(center, half_width) & self.valid
        return self.ranges[mask]

    def range_at(self, angle, half_width=math.radians(5.0)):
        """Median of the valid readings within half_width of angle, or inf.

        The median of a small window is not fooled by one spurious beam,
        and inf (nothing seen) is safe for every caller's comparisons.
        """
        values = self._sector_ranges(angle, half_width)
        if values.size == 0:
            return math.inf
        return float(np.median(values))

    def min_range(self, center, half_width, percentile=None):
        """Closest valid reading in a sector (or a low percentile of it), or inf."""
        values = self._sector_ranges(center, half_width)
        if values.size == 0:
            return math.inf
        if percentile is None:
            return float(values.min())
        return float(np.percentile(values, percentile))

    def points(self, center=0.0, half_width=math.pi):
        """Valid hits in a sector as an (N, 2) array of x, y in the laser frame."""
        mask = self.in_sector(center, half_width) & self.valid
        r, a = self.ranges[mask], self.angles[mask]
        return np.column_stack((r * np.cos(a), r * np.sin(a)))

    def fit_wall(self, center, half_width, min_points=5):
        """Fit a straight wall to the hits in a sector.

        Returns (distance, angle) of the wall's nearest point, as the
        perpendicular distance from the laser and the direction of the
        wall's normal in the laser frame; None when fewer than min_points
        hits lie in the sector. Using many beams makes the heading estimate
        far steadier than the difference of two single rays.
        """
        return fit_line(self.points(center, half_width), min_points)

    def nearest(self, half_width=math.radians(3.0), min_hits=3):
        """Direction and distance of the nearest obstacle, robust to lone beams.

        Each beam's range is replaced by the median of its neighbours within
        half_width, and a direction is a candidate only if at least min_hits
        valid beams support it. Returns (distance, angle) or None.
        """
        if not self.valid.any():
            return None
        order = np.argsort(self.angles)
        angles = self.angles[order]
        ranges = np.where(self.valid[order], self.ranges[order], np.nan)
        step = max(self.half_step * 2.0, 1e-9)
        k = max(1, int(round(half_width / step)))
        # Circular padding so that the window wraps across +-pi.
        padded = np.concatenate((ranges[-k:], ranges, ranges[:k]))
        windows = np.lib.stride_tricks.as_strided(
            padded, shape=(ranges.size, 2 * k + 1),
            strides=(padded.strides[0], padded.strides[0]))
        hits = np.sum(np.isfinite(windows), axis=1)
        with np.errstate(all='ignore'):
            smooth = np.where(hits >= min_hits, _nanmedian_rows(windows), np.nan)
        smooth = np.where(np.isfinite(ranges), smooth, np.nan)
        if not np.isfinite(smooth).any():
            return None
        best = int(np.nanargmin(smooth))
        return float(smooth[best]), float(angles[best])


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
    """The wall through (N, 2) points as (distance, angle), or None below min_points.

    distance is the laser's perpendicular distance to the line, angle the
    direction of that perpendicular. Shared by ScanView.fit_wall and by
    callers that pick their own points (e.g. only those near an earlier fit).
    """
    if len(points) < min_points:
        return None
    _, normal, distance = line_through(points)
    return distance, float(math.atan2(normal[1], normal[0]))


def _nanmedian_rows(windows):
    """Row-wise median ignoring NaN, silent on all-NaN rows (numpy 1.17 safe)."""
    with warnings.catch_warnings():
        warnings.simplefilter('ignore', RuntimeWarning)
        return np.nanmedian(windows, axis=1)
