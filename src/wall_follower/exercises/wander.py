"""Wander without touching anything: the lab's experiment 3 (the book's wander.py) done right.

The book's wander takes min() of every range, so an LDS-01's 0.0 readings
(no return) look like a wall at 0 m and the robot spins for ever; it turns
for a fixed time whatever it sees and drives at 1 m/s. Here:

    FORWARD: drive while the nearest valid reading in a cone ahead is at
             least `obstacle_distance` away;
    TURN:    pivot toward the more open side, chosen once when the turn
             starts, until the cone is clear by `clear_distance` (more
             than obstacle_distance, so that the robot does not dither on
             the edge), then FORWARD again.

A cone with no valid reading and no proven free beam (an LDS-01 facing
open space beyond its range, or a blind laser) counts as blocked: the
robot turns until it sees something ahead.
"""
import math

import numpy as np

from wall_follower.control.motion import Command
from wall_follower.params import checked
from wall_follower.params.exercises.wander import RULES, WANDER

FORWARD = 'FORWARD'
TURN = 'TURN'


class Wanderer(object):
    """FORWARD / TURN, one ScanView at a time.

    Its parameters (keyword arguments; their defaults, ranges and meanings
    are the WANDER table, what they must satisfy together its RULES) are
    the defaults overridden by those given.
    """

    def __init__(self, **params):
        self.reconfigure(**params)
        self.state = FORWARD
        self.turn_sign = 1.0

    def reconfigure(self, **params):
        """Go on under these parameters (the defaults, overridden) from the next update on."""
        self.p = checked(WANDER, params, RULES)

    def update(self, view):
        """The command for one ScanView; sets self.state."""
        p = self.p
        nearest = nearest_in_cone(view, p['cone_half_width'])
        if self.state == FORWARD and nearest < p['obstacle_distance']:
            self.state = TURN
            self.turn_sign = 1.0 if openness(view, 1.0, p['side_reach']) >= \
                openness(view, -1.0, p['side_reach']) else -1.0
        elif self.state == TURN and nearest >= p['clear_distance']:
            self.state = FORWARD
        if self.state == TURN:
            return Command(0.0, self.turn_sign * p['turn_rate'])
        return Command(p['speed'], 0.0)


def nearest_in_cone(view, half_width):
    """Nearest valid reading within half_width of straight ahead.

    inf when the cone holds proven no-returns only (open space); 0.0 when
    it holds nothing known at all, which must be treated as blocked.
    """
    cone = view.in_sector(0.0, half_width)
    hits = view.ranges[cone & view.valid]
    if hits.size:
        return float(hits.min())
    return math.inf if (cone & view.free).any() else 0.0


def openness(view, sign, reach):
    """How open one side is: the mean range, capped at reach, of its known beams.

    sign +1 is the left (0 to 180 deg), -1 the right. No-returns count as
    reach; readings that prove nothing are left out. 0 when nothing is known.
    """
    side = (np.sign(view.angles) == sign) & view.known
    if not side.any():
        return 0.0
    return float(np.minimum(np.where(view.free[side], reach, view.ranges[side]), reach).mean())
