"""Rounding a convex (outer) corner: the arc round its tip, and the turn that flies it.

Circling the end of a wall at target_distance holds the wall in the band,
but at the turn-rate limit it allows only max_turn_rate * target_distance
of forward speed, well below cruise_speed. Two things make the corner
faster while its tip stays in the band:

- the arc round the tip is centred a little off the tip (CornerArc's
  centre), as if the corner were rounded off: an arc of radius
  target_distance + c round a corner rounded off by c starts and ends at
  the band's distance and comes only (sqrt 2 - 1) c nearer half way round;
- the turn starts and ends on the widest arc the turn rate allows at cruise
  speed (cruise_speed / max_turn_rate, OuterTurn), and circles the tip on
  the tighter arc only in between. Begun before the tip is reached, a
  wide arc keeps the tip about as near as circling it would, and only the
  tight middle part of the turn loses time to the turn-rate limit.

The arc is pinned to the corner's tip as the scans see it, and carried
along with the robot's own motion between scans. Which way the corner
points, which the tip alone cannot tell, comes from the wall that ended.

Points are in the laser frame (x ahead, y left), in metres. The arcs are
the path of the robot's rotation centre (-laser_x ahead of the laser),
the one point that a turn does not carry sideways.
"""
import math

import numpy as np

from wall_follower.control.motion import seen_after_move
from wall_follower.rotation import wrap_angle


class CornerArc(object):
    """The centre of the arcs round the corner at `tip`, carried along with the robot.

    tip: (x, y) of the wall's end; along: vector along that wall in the
    direction of travel. center: where the arcs' centre lies from the tip,
    as (ahead, off): metres ahead along the wall and off it, away from it
    (toward the robot); a corner rounded off with radius r has its centre
    at (-r, -r). laser_x: the laser's position ahead of the rotation centre.
    """

    def __init__(self, tip, along, center, laser_x=0.0):
        self.laser_x = float(laser_x)
        self.tip = np.asarray(tip, dtype=float)
        # Where the tip was first pinned, carried along like it: see observe.
        self._pinned = self.tip.copy()
        along = np.asarray(along, dtype=float) / math.hypot(*along)
        away = np.array((-along[1], along[0]))
        self._to_center = center[0] * along + center[1] * away
        self._along = along
        self._pulled = np.zeros(2)

    @property
    def center(self):
        """(x, y) of the circle's centre."""
        return self.tip + self._to_center + self._pulled

    def pull(self, amount, toward):
        """Move the centre amount metres along the unit vector toward (a wall's normal), so
        that an arc that ends along that wall ends that much nearer it; each call replaces
        the last, from where the centre was planned."""
        self._pulled = amount * np.asarray(toward, dtype=float)

    def moved(self, advance, turn):
        """Follow the robot's move (advance metres ahead, then turn rad left)."""
        self.tip, self._pinned = seen_after_move(np.array((self.tip, self._pinned)), advance, turn,
                                                 self.laser_x)
        c, s = math.cos(turn), math.sin(turn)
        rotate = np.array(((c, s), (-s, c)))
        self._to_center = rotate.dot(self._to_center)
        self._along = rotate.dot(self._along)
        self._pulled = rotate.dot(self._pulled)

    @property
    def along(self):
        """The direction of travel along the wall that ended, as (x, y)."""
        return self._along

    def past_tip(self):
        """How far the rotation centre is past the tip, along the wall that ended.

        Round a square corner, that is its distance from the next wall.
        """
        return float((np.array((-self.laser_x, 0.0)) - self.tip).dot(self._along))

    def turned(self):
        """How far (rad) the robot is turned right from the direction of the wall that ended."""
        return float(wrap_angle(math.atan2(self._along[1], self._along[0])))

    def observe(self, points, gate):
        """Re-pin the tip to the hits within gate of where it is expected, and no more than
        gate farther along the wall that ended than where it was first pinned.

        The tip is the point of the corner farthest out along its outward
        direction, the diagonal half way between a square corner's two
        walls; the second farthest is taken, so that one spurious beam
        cannot move it. The next wall of a corner that turns by less than
        half a right angle runs out along that diagonal itself: re-pinned
        scan after scan, the tip crept along it, and the arc round that
        moving tip carried the robot in onto the next wall (round a tooth
        standing out of a slanted wall, whose wall runs on 18 degrees
        further round, 0.16 m from it for two seconds). What a re-pin is
        for moves the tip no farther along the wall that ended than one
        gate: from an end first seen short of the true one on Stage's
        saw-tooth, or from the foot of a step's face up to its top. Returns
        whether the tip was seen.
        """
        near = points[np.hypot(*(points - self.tip).T) < gate]
        near = near[(near - self._pinned).dot(self._along) <= gate]
        if len(near) < 2:
            return False
        # Out along the corner's diagonal, halfway between the two walls.
        along_x, along_y = self._along
        reach = near.dot((along_x - along_y, along_y + along_x))
        self.tip = near[np.argpartition(-reach, 1)[1]]
        return True

    def offset(self):
        """(distance, bearing) of the circle's centre from the robot's rotation centre."""
        x, y = self.center
        x += self.laser_x
        return float(math.hypot(x, y)), float(math.atan2(y, x))


# Round a tip, a robot this far outside its arc is off it [m]: it slows
# down to turn back onto it (OuterCorner.command), and a wide start that
# would carry it farther out ends (OuterTurn.starts_wide). A noisy laser's
# fit moves the tip by about as much: slowed for less, the robot cut inside
# the arc, near the tip, and wide starts ended early. Held back until 3 cm
# out, it drifted out that far first, round a sharp tip before a short side,
# and rode wide into the turn across that side's end.
OFF_ARC = 0.01
# A wide start begun heading into the wall this much or more is flown without
# OuterTurn's tolerance [rad]: see starts_wide. It shrinks in proportion up to
# there: a wall fit's angle is good only to a degree or so on a noisy laser,
# and a tolerance dropped at 1 degree of heading in slowed the arena's laps on
# lasers with noise by up to 0.5 %.
TOLERANCE_HEADING = math.radians(8.0)


class OuterTurn(object):
    """The right turn round a square corner: wide at first, round the tip, wide at the end.

    The wide arcs (wide_radius: cruise speed at the full turn rate) take
    the first wide_start and the last wide_end (rad) of the turn; between
    them the robot circles the corner's tip on a tighter arc of `radius`.
    The tight arc's centre (`center`, for a CornerArc) is placed so that
    the turn starts and ends at `distance` from the walls, each wide arc
    meeting the tight one tangentially; `lead` is how far ahead of the
    rotation centre the tip is where the turn starts. tolerance: how far
    inside the tight arc a wide start may still begin (see starts_wide).
    """

    def __init__(self, radius, wide_radius, wide_start, wide_end, distance, tolerance=0.0):
        self.radius = float(radius)
        self.tolerance = float(tolerance)
        self.distance = float(distance)
        self.wide_radius = float(wide_radius)
        self.wide_start = float(wide_start)
        self.wide_end = float(wide_end)
        shift = self.wide_radius - self.radius
        # A wide arc through angle a from parallel to a wall at `distance`,
        # tangent to the tight arc, puts the tight arc's centre
        # wide_radius - shift * cos(a) nearer that wall: the old wall for the
        # wide start, the next wall (its offset ahead) for the wide end.
        self.center = (distance - self.wide_radius + shift * math.cos(self.wide_end),
                       distance - self.wide_radius + shift * math.cos(self.wide_start))

    @property
    def lead(self):
        """How far ahead of the rotation centre the tip lies where the turn starts as planned:
        from `distance`, parallel to the wall."""
        return self.lead_from(self.distance)

    def lead_from(self, distance, heading_in=0.0):
        """How far ahead of the rotation centre (along its heading) the tip lies where a turn
        begun from distance (m, off the wall that ends) heading into it by heading_in (rad)
        starts.

        That is where the wide start meets the tight arc tangentially, as it
        does from the planned distance, parallel, at `lead`. Nearer the wall,
        or heading into it, a wide start begun there crossed into the tight
        arc and cut in toward the tip; begun later, it meets the arc.
        So near that the wide arc cannot meet it, the turn starts with the
        two centres abreast.
        """
        wide, across = self.wide_radius, self.wide_radius - self.radius
        off = distance - wide * math.cos(heading_in) - self.center[1]
        behind = math.sqrt(max(0.0, across * across - off * off))
        along = behind - self.center[0] - wide * math.sin(heading_in)
        return along * math.cos(heading_in) + distance * math.sin(heading_in)

    def starts_wide(self, turned, centre, heading_in=0.0):
        """True while the wide start goes on: turned (rad) short of wide_start.

        centre: (distance, bearing) of the tight arc's centre from the
        rotation centre, as CornerArc.offset gives it. The wide start ends
        on meeting the tight arc, so a start well nearer the wall than
        planned tightens early. Within tolerance
        of it, a start goes on wide: the tip is seen only to a cell or so of
        Stage's grid, and a start that much nearer than planned only passes
        the tip that much nearer. That holds for a turn begun parallel to
        the wall, whose wide arc meets the tight one tangentially. One begun
        heading into the wall by heading_in (rad: FOLLOW still turning onto
        a short wall just turned onto) crosses into the tight arc instead;
        flown on wide while within the tolerance, it cut inside the arc round
        the tip and out of the band. The tolerance shrinks with that angle,
        and is gone at TOLERANCE_HEADING.

        As planned, the wide start meets the tight arc tangentially, where
        that arc's centre comes abeam. One begun late, or heading away from
        the wall (a corner come up as a left turn onto a short wall ended
        past parallel), is more than OFF_ARC outside the tight arc with its
        centre abeam or behind already, and the wide arc, which turns less
        sharply, carries it farther out: flown on, it left the band round
        the tip. It ends there, and the tight arc turns the robot back onto
        it.
        """
        off_centre, bearing = centre
        tolerance = self.tolerance * max(0.0, 1.0 - heading_in / TOLERANCE_HEADING)
        moving_out = off_centre > self.radius + OFF_ARC and bearing <= -math.pi / 2
        return (0.0 < self.wide_start and turned < self.wide_start
                and off_centre > self.radius - tolerance and not moving_out)

    def ends_wide(self, turned, past_tip, nearer=0.0):
        """True where the wide end goes on, turned (rad) so far and past_tip from the next wall.

        It starts no earlier than planned, and only where it will end at
        `distance` (less nearer) from the next wall, so an arc flown wide of
        the tight one turns out later.
        """
        return self.lands_within(past_tip, math.pi / 2 - turned, nearer)

    def end_clears(self, centre, angle):
        """True where a wide end begun now, angle (rad) short of the next wall, brings the robot
        no more than OFF_ARC nearer the tight arc's centre than it is, or than that arc.

        centre: (distance, bearing) of the tight arc's centre from the
        rotation centre, as CornerArc.offset gives it. Begun heading along
        the tight arc, on it or inside it, the wide arc turns less sharply
        and leaves it outward at once. Begun heading in toward the tip, it
        crosses into the tight arc first: round a sharp tip met still
        turning onto the wall that ends there, a wide end begun where a
        square corner's would begin passed the tip 0.16-0.18 m off.
        """
        off, bearing = centre
        x, y = off * math.cos(bearing), off * math.sin(bearing)
        wide = self.wide_radius
        # Turned t along the wide arc (its centre wide_radius to the right),
        # the rotation centre is at (wide sin t, wide (cos t - 1)); nearest
        # the tight arc's centre where t points the arc at it.
        turn = min(max(math.atan2(x, y + wide), 0.0), max(angle, 0.0))
        nearest = math.hypot(x - wide * math.sin(turn), y - wide * (math.cos(turn) - 1.0))
        return nearest >= min(off, self.radius) - OFF_ARC

    def lands_within(self, distance, angle, nearer=0.0):
        """True where a wide end begun now ends at `distance` (less nearer) or nearer.

        distance: the rotation centre's from the next wall; angle (rad): the
        turn still to go onto it, at most wide_end. The wide arc carries the
        robot wide_radius * (1 - cos angle) off that wall as it turns.
        """
        if not self.wide_end or abs(angle) > self.wide_end:
            return False
        landing = distance + self.wide_radius * (1.0 - math.cos(angle))
        return landing <= self.distance - nearer
