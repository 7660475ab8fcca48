"""The arm's joints as the built-in controller moves them: each follows the position
desired of it, but never faster than its speed limit nor out of its range.

Where the trajectory asks for no more than the limits allow the joints are exactly
where it says (the built-in stand-in for ros_control's position controllers on a
perfectly stiff arm); where it asks for more, a joint moves at its speed limit
towards the desired position, and arrives late.
"""
import numpy as np


class ArmJoints(object):
    """Joint positions [rad] and velocities [rad/s], stepped towards desired ones.

    lower, upper: position limits; velocity: speed limits (arrays over the joints).
    """

    def __init__(self, positions, lower, upper, velocity):
        self.lower, self.upper = np.asarray(lower, float), np.asarray(upper, float)
        self.limit = np.asarray(velocity, float)
        self.positions = np.clip(np.asarray(positions, float), self.lower, self.upper)
        self.velocities = np.zeros_like(self.positions)

    def step(self, desired, desired_velocity, elapsed):
        """Move towards desired (positions, velocities) over elapsed [s]; returns nothing."""
        target = np.clip(np.asarray(desired, float), self.lower, self.upper)
        reach = self.limit * max(elapsed, 0.0)
        change = target - self.positions
        on_track = np.abs(change) <= reach + 1e-12
        moved = np.where(on_track, target, self.positions + np.sign(change) * reach)
        self.velocities = np.where(
            on_track, np.clip(np.asarray(desired_velocity, float), -self.limit, self.limit),
            np.sign(change) * self.limit)
        at_limit = ((moved <= self.lower) & (self.velocities < 0.0)) | \
            ((moved >= self.upper) & (self.velocities > 0.0))
        self.velocities[at_limit] = 0.0
        self.positions = np.clip(moved, self.lower, self.upper)
