"""The planned left turn onto a wall ahead (inner corner): wide, then tight, then wide again.

Turning at the full turn rate, time is lost only where the arc is tighter
than cruise_speed / max_turn_rate, the tightest arc flown at full speed.
Both ends of the turn can be wide. At the start the wall ahead is still
far, and the robot only drifts off the old wall by wide_radius * (1 - cos
wide_start), a few centimetres at the defaults. At the end the old wall
is behind, and the last degrees only come nearer the new one (by as
little, over wide_end). Only the middle, where the robot passes the
corner itself, needs the tight arc that keeps both walls within the
band; as time is lost in proportion to how much tighter than the wide arc
it is, a short near pivot there costs less than a longer arc of middling
radius.

A turn is planned by the angle still to turn, which is the angle of the
wall ahead: that is what each scan measures again. gap(angle) is how much
nearer to the wall ahead the rest of the turn carries the robot, so the
turn starts where the gap left equals it. A gap that has run short (a late
start, a wall seen late) scales every arc of the rest of the turn down in
proportion, which keeps its shape and where it ends; one that has run long
(an early start) brings the wide end forward (radius_within).
"""
import math


class LeftTurn(object):
    """Starts with wide_start (rad) and ends with wide_end (rad) on wide_radius, on radius between.

    A turn through less than a right angle (onto a wall ahead at 45
    degrees, say) goes without its wide start first, then without part of
    its tight arc; the wide end is always flown.
    """

    def __init__(self, radius, wide_radius, wide_start, wide_end=0.0):
        self.radius = float(radius)
        self.wide_radius = float(wide_radius)
        self.wide_start, self.wide_end = float(wide_start), float(wide_end)
        # The tight arc takes the angles still to turn from here ...
        self._tight_from = math.pi / 2 - float(wide_start)
        # ... down to here.
        self._tight_to = min(float(wide_end), self._tight_from)

    def drifting_at_most(self, drift):
        """This turn with its wide start cut short, to carry the robot at most drift off the wall.

        A wide start through angle a drifts wide_radius * (1 - cos a) off
        the wall it leaves; the tight arc takes over the angles cut off.
        """
        cosine = 1.0 - max(0.0, drift) / self.wide_radius
        wide_start = min(self.wide_start, math.acos(max(-1.0, cosine)))
        return LeftTurn(self.radius, self.wide_radius, wide_start, self.wide_end)

    def tightened(self, scale):
        """This turn with its tight arc's radius scaled by scale (0 for a pivot)."""
        return LeftTurn(self.radius * scale, self.wide_radius, self.wide_start, self.wide_end)

    def arc_radius(self, angle):
        """Radius planned with angle (rad) still to turn."""
        return self.radius if self._on_tight_arc(angle) else self.wide_radius

    def _on_tight_arc(self, angle):
        """True when the plan flies the tight arc with angle (rad) still to turn."""
        return self._tight_to < angle <= self._tight_from

    def gap(self, angle):
        """How much nearer to the wall the turn from angle to parallel carries the robot.

        An arc of radius r turning from a to b (b < a, angles to the wall)
        comes r * (cos b - cos a) nearer to it. An angle past a right angle
        (the robot heading into the wall it leaves) is turned through on the
        first arc too, which then comes nearer by more than its radius.
        """
        angle = min(max(angle, 0.0), math.pi)
        arcs = ((self._tight_from, self.wide_radius), (self._tight_to, self.radius),
                (0.0, self.wide_radius))
        gap = 0.0
        for end, radius in arcs:
            if angle > end:
                gap += radius * (math.cos(end) - math.cos(angle))
                angle = end
        return gap

    def drift(self, angle):
        """How far the wide start of a turn through angle carries the robot off the wall it leaves.

        Only the part of a turn beyond the tight arc's share is wide: a
        wall ahead at 45 degrees is turned onto on the tight arc (and the
        wide end) alone.
        """
        wide_part = max(0.0, min(angle, math.pi / 2) - self._tight_from)
        return self.wide_radius * (1.0 - math.cos(wide_part))

    def radius_within(self, gap, angle):
        """Radius to fly now, with angle still to turn and gap left to the turn's end.

        A gap shorter than the plan needs (a late start) scales the planned
        radius down in proportion, so that the turn still ends where planned.
        A longer one (an early start) is spent on the wide end instead: the
        tight arc goes on until a wide arc from here would end the turn
        where planned. A wider tight arc would spend it where the robot
        passes the corner, swinging it farther off the wall it leaves, and
        an arc turning from angle a covers r * sin a of the gap per radian,
        so the last degrees carry the robot farthest on along the new wall
        for the same room. A turn planned without a wide end scales its
        tight arc up instead. Never wider than wide_radius, which cruise
        speed allows.
        """
        needed = self.gap(angle)
        if gap > needed and self._tight_to > 0.0 and self._on_tight_arc(angle):
            wide_from_here = self.wide_radius * (1.0 - math.cos(angle))
            return self.wide_radius if gap >= wide_from_here else self.radius
        scale = max(0.0, gap) / needed if needed > 0.0 else 1.0
        return min(self.wide_radius, self.arc_radius(angle) * scale)
