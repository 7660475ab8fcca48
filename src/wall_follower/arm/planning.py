"""A planned move of the arm to a named state or to a point for the `hand` origin: inverse
kinematics, the collision check of the joint-space line, and its timing.

How the redundant last joint (the wrist, which turns the hand about its own
origin) is chosen for a point goal: it stays where it is, so the hand keeps its
angle to the lower arm; only if every arm pose then touches something are other
wrist angles tried, nearest first.
"""
import collections
import math

import numpy as np

from wall_follower.arm.collision import CollisionChecker
from wall_follower.arm.kinematics import inverse, planar_dimensions
from wall_follower.arm.timing import TimedMove

Plan = collections.namedtuple('Plan', 'goal move')
"""goal: the joint positions to reach (model.names' order); move: its TimedMove."""

# Wrist angles tried, as fractions of its range, when keeping it collides.
WRIST_TRIES = 9

# The least velocity scaling a goal may ask for (0 asks for full speed): at it the longest
# move of cougarbot (the hip across its whole range) takes about ten minutes. Less is
# refused rather than planned as a move that would not end in any useful time.
MIN_VELOCITY_SCALING = 0.01


class PlanningError(ValueError):
    """No move: the reason in words (unreachable, colliding, unknown state, bad goal)."""


def velocity_factor(scaling):
    """The share of the speed limits a goal's velocity_scaling asks for: 0 means 1 (full
    speed), else it must lie within MIN_VELOCITY_SCALING and 1; PlanningError otherwise."""
    if scaling == 0.0:
        return 1.0
    if 0.0 < scaling < MIN_VELOCITY_SCALING:
        raise PlanningError('velocity_scaling %r is below the least allowed, %g: the move '
                            'would not end in any useful time' % (scaling, MIN_VELOCITY_SCALING))
    if not 0.0 < scaling <= 1.0:
        raise PlanningError('velocity_scaling %r is not within 0 to 1 (the share of the '
                            'joints\' speed limits; 0 means 1)' % scaling)
    return float(scaling)


class Planner(object):
    """Plans moves of one arm.

    model: the ArmModel; semantics: its SRDF's (states, disabled pairs); acceleration:
    limits [rad/s^2] over the joints; velocity: speed limits [rad/s] (default the URDF's);
    floor_margin, self_margin [m] and collision_step [rad]: as CollisionChecker's.
    """

    def __init__(self, model, semantics, acceleration, velocity=None, floor_margin=0.0,
                 self_margin=0.0, collision_step=0.02):
        self.model = model
        self.states = semantics.states
        self.acceleration = np.asarray(acceleration, dtype=float)
        self.velocity = model.velocity if velocity is None else np.asarray(velocity, float)
        self.dimensions = planar_dimensions(model)
        self.checker = CollisionChecker(model, semantics.disabled, floor_margin, self_margin)
        self.collision_step = collision_step

    def to_state(self, name, current, scaling=1.0):
        """The Plan to the SRDF group state name."""
        factor = velocity_factor(scaling)
        if name not in self.states:
            raise PlanningError('no named target %r (the SRDF has %s)' % (
                name, ', '.join(sorted(self.states)) or 'none'))
        goal = np.array([self.states[name][joint] for joint in self.model.names])
        problem = self._path_problem(current, goal)
        if problem:
            raise PlanningError('named target %s: %s' % (name, problem))
        return self._timed(current, goal, factor)

    def to_point(self, point, current, scaling=1.0):
        """The Plan that puts the hand origin on point (x, y, z in the root's frame [m])."""
        factor = velocity_factor(scaling)
        current = np.asarray(current, dtype=float)
        if not all(math.isfinite(value) for value in point):
            raise PlanningError('point (%s) is not finite: every coordinate must be a number'
                                % ', '.join(repr(float(value)) for value in point))
        if point[2] < 0.0:
            raise PlanningError('point (%.3f, %.3f, %.3f) is below the floor (z = 0)'
                                % tuple(point))
        solutions, reason = inverse(self.model, self.dimensions, point, current)
        if not solutions:
            raise PlanningError('point (%.3f, %.3f, %.3f) unreachable: %s' % (
                tuple(point) + (reason,)))
        problems = []
        for goal in self._with_wrists(solutions, current):
            problem = self._path_problem(current, goal)
            if problem is None:
                return self._timed(current, goal, factor)
            problems.append(problem)
        raise PlanningError('point (%.3f, %.3f, %.3f) reachable only in collision: %s' % (
            tuple(point) + (problems[0],)))

    def _with_wrists(self, solutions, current):
        """The solutions (current wrist kept), then each with the other wrist angles."""
        for goal in solutions:
            yield goal
        low, high = self.model.lower[3], self.model.upper[3]
        wrists = sorted(np.linspace(low, high, WRIST_TRIES), key=lambda w: abs(w - current[3]))
        for goal in solutions:
            for wrist in wrists:
                yield np.concatenate([goal[:3], [wrist]])

    def _path_problem(self, start, goal):
        """Why the straight line from start to goal cannot be taken, or None."""
        outside = self.model.outside_limits(goal)
        if outside:
            return '; '.join(outside)
        found = self.checker.path_contacts(start, goal, self.collision_step)
        if found is None:
            return None
        fraction, contacts = found
        where = 'at the goal' if fraction >= 1.0 else (
            'at the start' if fraction <= 0.0 else '%.0f%% of the way' % (100.0 * fraction))
        return 'in collision %s (%s)' % (where, ', '.join(contacts))

    def _timed(self, current, goal, factor):
        return Plan(goal, TimedMove(current, goal, self.velocity * factor, self.acceleration))
