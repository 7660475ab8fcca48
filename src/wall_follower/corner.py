"""The arc that rounds a convex (outer) corner faster than circling its tip.

Circling the end of a wall at the band's distance (0.25 m) holds the wall
in the band, but at the turn-rate limit it allows only 0.49 * 0.25 = 0.12
m/s. Rounding the corner as if it were rounded off with a radius c and
keeping the band's distance from that rounding lets the robot drive an
arc of radius 0.25 + c, which is faster, and its distance to the tip
still stays within the band: it starts and ends at hypot(c, 0.25) and
comes to 0.25 - 0.41 c half way round.

The arc is pinned to the corner's tip as the scans see it, and carried
along with the robot's own motion between scans. Which way the corner
points, which the tip alone cannot tell, comes from the wall that ended.

Points are in the laser frame (x ahead, y left), in metres. The arc is
the path of the robot's rotation centre (-laser_x ahead of the laser),
the one point that a turn does not carry sideways.
"""
import math

import numpy as np

from wall_follower.motion import seen_after_move


class CornerArc(object):
    """The centre of the arcs round the corner at `tip`, rounded off with radius `rounding`.

    tip: (x, y) of the wall's end; along: vector along that wall in the
    direction of travel. An arc of radius r about the centre keeps
    r - rounding from the rounded-off corner. laser_x: the laser's position
    ahead of the rotation centre.
    """

    def __init__(self, tip, along, rounding, laser_x=0.0):
        self.laser_x = float(laser_x)
        self.tip = np.asarray(tip, dtype=float)
        along = np.asarray(along, dtype=float) / math.hypot(*along)
        toward_wall = np.array((along[1], -along[0]))
        # From the tip to the centre of the rounding, and the corner's
        # outward direction (from that centre through the tip).
        self._to_center = rounding * (toward_wall - along)
        self._outward = (along - toward_wall) / math.sqrt(2.0)

    @property
    def center(self):
        """(x, y) of the circle's centre."""
        return self.tip + self._to_center

    def moved(self, advance, turn):
        """Follow the robot's move (advance metres ahead, then turn rad left)."""
        self.tip = seen_after_move(self.tip[None, :], advance, turn, self.laser_x)[0]
        c, s = math.cos(turn), math.sin(turn)
        rotate = np.array(((c, s), (-s, c)))
        self._to_center = rotate.dot(self._to_center)
        self._outward = rotate.dot(self._outward)

    def observe(self, points, gate):
        """Re-pin the tip to the hits within gate of where it is expected.

        The tip is the point of the corner farthest out along its outward
        direction; the second farthest is taken, so that one spurious beam
        cannot move it. Returns whether the tip was seen.
        """
        near = points[np.hypot(*(points - self.tip).T) < gate]
        if len(near) < 2:
            return False
        reach = near.dot(self._outward)
        self.tip = near[np.argpartition(-reach, 1)[1]]
        return True

    def offset(self):
        """(distance, bearing) of the circle's centre from the robot's rotation centre."""
        x, y = self.center
        x += self.laser_x
        return float(math.hypot(x, y)), float(math.atan2(y, x))
