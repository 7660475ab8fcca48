"""Angle-based queries on a laser scan, whatever the laser's conventions.

Lasers disagree on where beam 0 points (Stage: backwards, LDS-01 and
Gazebo: forwards), on the direction of the sweep and on how "no return" is
written (range_max, inf, NaN or 0.0). Every query here is by angle in the
laser frame (0 = ahead, +pi/2 = left, -pi/2 = right), and every
implausible reading is dropped instead of being taken for a wall.
"""
import math

import numpy as np

from wall_follower.rotation import wrap_angle

FRONT = 0.0
LEFT = math.pi / 2
RIGHT = -math.pi / 2


class ScanView(object):
    """A LaserScan seen as (angle, range) pairs with invalid beams masked.

    valid: the hits, readings finite and inside [range_min, range_max).
    free: the no-returns written as range_max or +inf (Stage, Gazebo),
    which prove the beam's direction free up to range_max. known: either.
    Everything else (0.0, NaN, -inf, negative, below range_min) proves
    nothing, as an LDS-01 writes 0.0 both for "no return" and for a
    dropout.
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
            self.free = self.ranges >= self.range_max
        self.known = self.valid | self.free
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

    def known_share_in_sector(self, center, half_width):
        """(known, beams): how many of the beams within half_width of center are a hit or
        prove free space, and how many beams lie there."""
        sector = self.in_sector(center, half_width)
        return int((sector & self.known).sum()), int(sector.sum())

    def points(self, center=0.0, half_width=math.pi):
        """Valid hits in a sector as an (N, 2) array of x, y in the laser frame."""
        _, points, valid = self.beams(center, half_width)
        return points[valid]

    def beams(self, center, half_width):
        """Every beam in a sector, for a check that counts the beams that miss as well as
        those that hit: (angles (N,), points (N, 2) x, y in the laser frame, valid (N,)).
        An invalid beam's point is wherever its reading puts it, or NaN."""
        sector = self.in_sector(center, half_width)
        r, a = self.ranges[sector], self.angles[sector]
        with np.errstate(invalid='ignore'):
            points = np.column_stack((r * np.cos(a), r * np.sin(a)))
        return a, points, self.valid[sector]
