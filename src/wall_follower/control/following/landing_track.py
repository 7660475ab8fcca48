"""The wall a left turn lands on, tracked from scan to scan by the robot's own motion.

A wall square to the beams is placed by every one of them alike, so the
laser's range resolution moves its fit in steps: Stage's grid reads each
range as a whole number of cells (2 cm at the worlds' resolution) along
the beam's major axis, and while the robot creeps through the middle of a
left turn the wall ahead reads the same for several scans, then jumps by a
cell. Planned from the raw fit, the turn slowed down at every jump and
sped up again at every freeze: a pivot of one scan, a few times a turn.
The wall does not move, though, and the robot knows how it moved: its
distance is predicted from the last command and pulled toward each new
fit by GAIN, never farther from the fit than TOLERANCE. A fit farther than
JUMP from the prediction, or turned by more than TURN_JUMP from it, is
another wall (or the robot did not move as commanded), and is taken as it
is.
"""
import math

from wall_follower.control.sensing.lines import Line
from wall_follower.rotation import wrap_angle

# Of the difference between the fit and the prediction, the share the
# estimate takes at each scan: about the inverse of the number of scans
# a range stays on one cell while the robot creeps through a pivot.
GAIN = 0.3
# The estimate stays within this of the fit [m]: half a cell of the
# worlds' grid, about the largest error its steps put in a fit.
TOLERANCE = 0.01
# A fit this far from the prediction starts the track afresh [m] ...
JUMP = 0.04
# ... as does one turned this far from it [rad].
TURN_JUMP = math.radians(15.0)


class LandingTrack(object):
    """The distance of the wall a turn lands on, filtered: update() once per scan.

    wall: the estimate, a Line (distance from the rotation centre, angle
    still to turn onto it), or None while there is none.
    """

    def __init__(self):
        self.wall = None

    def update(self, fitted, motion, dt):
        """The estimate on this scan, from fitted (the Line measured now, or None), given
        motion, the Command driven for the dt seconds since the last scan.

        The robot's arc through dt brings it nearer the wall by its length
        times the sine of the angle still to turn, taken half way along.
        The angle is the fit's own: a line through many beams turns
        smoothly.
        """
        if fitted is None or self.wall is None:
            self.wall = fitted
            return fitted
        turned = motion.angular * dt
        predicted = self.wall.distance - motion.linear * dt * math.sin(
            self.wall.angle - 0.5 * turned)
        error = fitted.distance - predicted
        turn_error = wrap_angle(fitted.angle - (self.wall.angle - turned))
        if abs(error) > JUMP or abs(turn_error) > TURN_JUMP:
            self.wall = fitted
            return fitted
        distance = min(max(predicted + GAIN * error, fitted.distance - TOLERANCE),
                       fitted.distance + TOLERANCE)
        self.wall = Line(distance, fitted.angle)
        return self.wall
