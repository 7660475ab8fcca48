"""The planned left turn onto a wall ahead (inner corner): a wide start, then a tight arc.

Turning at the full turn rate, time is lost only where the arc is tighter
than cruise_speed / max_turn_rate (0.39 m at 0.19 m/s and 0.49 rad/s). The
start of the turn can be wide: the wall ahead is still far, and the robot
only drifts a little off the old wall (0.39 * (1 - cos 20 deg) = 23 mm for
the first 20 degrees). Past that, the arc tightens to keep the wall on the
right within the band through the middle of the corner.

A turn is planned by the angle still to turn, which is the angle of the
wall ahead: that is what each scan measures again. gap(angle) is how much
nearer to the wall ahead the rest of the turn carries the robot, so the
turn starts where the gap left equals it, and a gap that has run short
(a late start, a wall seen late) shrinks every arc of the rest of the turn
in proportion, which keeps its shape.
"""
import math


class LeftTurn(object):
    """The left turn that starts with wide_angle (rad) on wide_radius, then goes on at radius."""

    def __init__(self, radius, wide_radius, wide_angle):
        self.radius = float(radius)
        self.wide_radius = float(wide_radius)
        # The tight arc takes the turn's last angles, from here to parallel.
        self._tight_from = math.pi / 2 - float(wide_angle)

    def arc_radius(self, angle):
        """Radius planned with angle (rad) still to turn."""
        return self.wide_radius if angle > self._tight_from else self.radius

    def gap(self, angle):
        """How much nearer to the wall the turn from angle to parallel carries the robot.

        An arc of radius r turning from a to b (b < a, angles to the wall)
        comes r * (cos b - cos a) nearer to it. Angles past a right angle
        count as a right angle (see follower.as_planned).
        """
        angle = min(max(angle, 0.0), math.pi / 2)
        tight = min(angle, self._tight_from)
        gap = self.radius * (1.0 - math.cos(tight))
        if angle > tight:
            gap += self.wide_radius * (math.cos(tight) - math.cos(angle))
        return gap

    def drift(self, angle):
        """How far the wide start of a turn through angle carries the robot off the wall it leaves.

        Only the part of a turn beyond the tight arc's share is wide: a
        wall ahead at 45 degrees is turned onto on the tight arc alone.
        """
        wide_part = max(0.0, min(angle, math.pi / 2) - self._tight_from)
        return self.wide_radius * (1.0 - math.cos(wide_part))

    def radius_within(self, gap, angle):
        """Radius to fly now, with angle still to turn and gap left to the turn's end.

        The planned radius, shrunk in proportion when the gap is shorter
        than the plan needs; never widened, so a turn begun early simply
        ends early.
        """
        needed = self.gap(angle)
        scale = min(1.0, max(0.0, gap) / needed) if needed > 0.0 else 1.0
        return self.arc_radius(angle) * scale
