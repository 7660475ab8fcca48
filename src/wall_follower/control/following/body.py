"""The robot's body, and how far its tail swings towards the wall it leaves on a left turn.

Turns are planned for the rotation centre; the body around it is what
touches walls. A Burger's body barely reaches past a circle of 0.14 m, so
at the following distance any turn is clear of the wall. A Waffle's rear
corners reach 0.26 m from its rotation centre, more than the distance the
wall is followed at: turning left off a wall on the right swings its tail
towards that wall, the more so the tighter the arc. The body is a
rectangle in the base frame, as TurtleBot3 bodies are.
"""
import math


class Body(object):
    """The rectangle rear (> 0) behind the rotation centre and half_width to each side [m]."""

    def __init__(self, rear, half_width):
        self.rear, self.half_width = float(rear), float(half_width)

    def swing(self, radius):
        """How near the wall on the right the tail comes, from where the rotation centre
        was, when the robot turns left off that wall on an arc of radius (0: on the spot).

        The arc's centre lies radius to the left; the rear right corner
        circles it at its distance and passes straight between it and the
        wall once the robot has turned far enough.
        """
        return math.hypot(self.rear, self.half_width + radius) - radius
