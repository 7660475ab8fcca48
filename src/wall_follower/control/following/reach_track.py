"""How far beyond the reach of the planned left turn the wall ahead lies, tracked scan to scan.

A left turn is due once the wall across the way comes within reach of
the turn as planned, and goes on while it stays there (InnerCorner.due).
That slack, the wall's distance less the gap the turn needs, does not
change while the robot flies the plan: each of the turn's arcs brings the
robot as much nearer the wall as it takes off the gap the rest of the
turn needs (left_turn.py). On one scan it carries that scan's errors,
though: Stage's grid moves a wall's fit in whole cells, and a noisy
laser tilts it by a degree or two, which moves the gap of a turn begun
square to the wall by wide_radius * sin(angle) per radian of tilt. Judged
on each scan alone, a turn began on one low reading, ended on the next
high one, the robot steered back toward the wall it was leaving, and the
turn began again a scan or two later, short of room. So the slack is
predicted from the last command and pulled toward each new measurement by
GAIN. A measurement farther than JUMP from the prediction (another wall
across the way, or a robot that did not move as commanded) is taken as it
is.
"""

# Of the difference between the measurement and the prediction, the share
# the estimate takes at each scan.
GAIN = 0.3
# A measurement this far from the prediction starts the track afresh [m].
JUMP = 0.04


class ReachTrack(object):
    """The slack of the wall across the way, filtered: update() once per scan.

    slack: the estimate [m], > 0 where the wall is out of reach, or None
    while there is no wall across the way.
    """

    def __init__(self):
        self.slack = None

    def update(self, measured, change):
        """The estimate on this scan, from measured (the slack this scan shows, or None) and
        change: how much the command driven since the last scan changed it."""
        if measured is None or self.slack is None:
            self.slack = measured
            return measured
        predicted = self.slack + change
        error = measured - predicted
        self.slack = measured if abs(error) > JUMP else predicted + GAIN * error
        return self.slack
