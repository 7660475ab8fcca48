"""Where odometry puts the robot, how sure that is, and what a match may change of it.

Between scans the odometry's motion is nearly right: its scale errors
(Stage's `odom_error`, a real robot's wheels) are a few per cent of the
travel and the turn. So the robot's pose predicted from the last one by
that motion is uncertain by a little that grows with the motion since a
match last fixed the pose (`Prediction`, a covariance carried through each
motion as an extended Kalman filter carries it). A heading error grows into
a sideways error as the robot drives on, and the odometry may be read a
step apart from the scan (Stage's `odom` localization reports the pose
after the step its laser has not seen yet; a real robot's stamps differ
too): while the robot keeps its speed that costs nothing, but where it
speeds up, slows down or changes its turn, the scan's pose is anywhere
between the two steps, and the prediction as unsure as they differ.

The match weighs the prediction by that covariance (matcher.py: a
maximum a posteriori fit), so that a direction the scan cannot tell (a
corridor) comes from odometry and the others from the scan; and it is
believed only if the correction it then makes is likely under the
prediction's covariance (within `match_gate` standard deviations,
`surprise`) and within the search window. A match beyond is a second fit
that odometry does not support: the estimate never jumps to it.
"""
import math

import numpy as np

from .poses import between

__all__ = ['Prediction', 'in_frame', 'surprise']

# The least uncertainty of a prediction, right after a match fixed the pose: a match's own
# [m, rad]. Its covariance, computed as if the scan's points erred independently, claims
# it to be a fraction of a millimetre; but a laser's ranges err together (Stage raytraces
# on a grid of its `resolution`, 2 cm in the generated worlds, and matches jitter by up to
# that from scan to scan).
FLOOR = (0.01, math.radians(0.5))
# The most a robot's motion from one scan to the next may change [m, rad]: at a laser of
# 5 Hz (the LDS-01's), a TurtleBot3's top speed (0.22 m/s), and the turn the course's
# robot allows (0.49 rad/s), near enough. A larger change of the odometry's step is a
# slip (or a faster turn than that), not a scan a step away from its odometry.
LAG = (0.044, math.radians(6.0))


class Prediction(object):
    """The covariance (x, y, yaw in the robot's frame) of the odometry's prediction of
    the robot's pose, carried from the last pose a match fixed through each motion
    since, and grown by its errors.

    drift: the share of its travel and of its turn odometry may get wrong (one
    standard deviation).
    """

    def __init__(self, drift):
        self.drift = float(drift)
        self.fixed()

    def fixed(self, covariance=None):
        """A match fixed the pose, with this covariance (robot frame; none: FLOOR's)."""
        floor = np.diag([FLOOR[0] ** 2, FLOOR[0] ** 2, FLOOR[1] ** 2])
        self.matrix = floor if covariance is None else np.asarray(covariance) + floor

    def moved(self, step, previous):
        """The odometry moved the robot by step (x, y, yaw in its frame) since the last
        scan, after previous (the step before; None for none)."""
        c, s = math.cos(step[2]), math.sin(step[2])
        back = np.array([[c, s], [-s, c]])
        carry = np.eye(3)
        carry[:2, :2] = back
        # A heading already off turns the travel into a sideways error.
        carry[:2, 2] = back.dot([-step[1], step[0]])
        linear = self.drift * math.hypot(step[0], step[1])
        angular = self.drift * abs(step[2])
        if previous is not None:   # the scan may lie a step before or after the odometry
            linear += min(math.hypot(step[0] - previous[0], step[1] - previous[1]), LAG[0])
            angular += min(abs(step[2] - previous[2]), LAG[1])
        self.matrix = carry.dot(self.matrix).dot(carry.T) + np.diag(
            [linear ** 2, linear ** 2, angular ** 2])

    def covariance(self):
        return self.matrix

    @property
    def sigma(self):
        """(linear, angular) standard deviations along the worst directions."""
        return (float(math.sqrt(max(np.linalg.eigvalsh(self.matrix[:2, :2])))),
                float(math.sqrt(self.matrix[2, 2])))


def in_frame(covariance, yaw):
    """A map-frame covariance (x, y, yaw) seen from a pose heading yaw."""
    c, s = math.cos(yaw), math.sin(yaw)
    turn = np.array([[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]])
    return turn.dot(covariance).dot(turn.T)


def surprise(predicted, prediction, pose):
    """How far pose lies from the predicted one: (the correction (x, y, yaw) in the
    prediction's frame, in standard deviations of the Prediction)."""
    correction = np.array(between(predicted, pose))
    return correction, float(math.sqrt(correction.dot(
        np.linalg.solve(prediction.covariance(), correction))))
