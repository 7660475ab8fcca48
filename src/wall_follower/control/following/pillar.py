"""Circling a round pillar at the turn rate's limit (part of OUTER_CORNER).

Any lap takes at least a full turn at max_turn_rate, and round a pillar
that is nearly all it takes: the fastest lap circles it at the full turn
rate, as fast as the band's radius allows. So the turn is held at the
limit and the path corrected by the speed instead (motion.along_curvature):
the PD law asks for a curvature, the curve of the pillar's radius plus
target_distance less what the distance and heading are off by.

The pillar is fitted afresh at every scan (circles.round_pillar) and
taken for one once its hits have looked round on pillar_confirm scans
running: one scan's hits of a small box's corner can fit a circle too,
but not for long, nor with the arc and the shape of a round one. It is
then circled for as long as a circle fits at all.

A disc a few cells across on Stage's grid fits to a centimetre or two
either way from scan to scan. So its centre is carried along with the
robot and each new fit pulled in by CENTER_GAIN, and its radius, which
only feeds the curve forward, averaged in by RADIUS_GAIN. The distance
steered on is the scan's own fit's, from the rotation centre to the
pillar's near side, which the laser measures directly.
"""
import math

from wall_follower.control.following.follow_wall import steer
from wall_follower.control.motion import along_curvature, seen_after_move
from wall_follower.control.sensing.circles import round_pillar
from wall_follower.control.sensing.scan import RIGHT
from wall_follower.rotation import wrap_angle

# How much of a new fit's centre, and of its radius, each scan takes in.
CENTER_GAIN = 0.5
RADIUS_GAIN = 0.1


class RoundPillar(object):
    """The round pillar being circled, carried with the robot from scan to scan.

    found: whether a pillar is being circled; center: its (x, y) in the
    laser frame, radius: its radius, both averaged over the scans since it
    was first found; gap: the rotation centre's distance from its near side
    on the last scan.
    """

    def __init__(self, params):
        self.params = params
        self.forget()

    def forget(self):
        """Lose the pillar: the next one is fitted anew."""
        self.found = False
        self.center = self.radius = self.gap = None
        self._round_scans = 0

    def observe(self, obs, motion, dt):
        """Fit the pillar on a new Observation; motion: the Command driven for the last dt
        seconds, which carries the pillar known so far into this scan's frame."""
        p = self.params
        fit = round_pillar(obs.right, obs.nearest, p)
        if fit is None:
            self.forget()
            return
        self._round_scans = self._round_scans + 1 if fit.round else 0
        self.found = self.found or self._round_scans >= p.pillar_confirm
        circle = fit.circle
        self.gap = math.hypot(circle.center[0] + p.laser_x, circle.center[1]) - circle.radius
        if self.center is None:
            self.center, self.radius = circle.center, circle.radius
            return
        self.center = seen_after_move(self.center[None, :], motion.linear * dt,
                                      motion.angular * dt, p.laser_x)[0]
        self.center = self.center + CENTER_GAIN * (circle.center - self.center)
        self.radius += RADIUS_GAIN * (circle.radius - self.radius)

    def command(self):
        """Round the pillar at pillar_nearer inside target_distance, turning at the limit."""
        p = self.params
        distance = p.target_distance - p.pillar_nearer
        radius = self.radius + distance
        # The PD law's turn at the speed that flies that curve at max_turn_rate.
        speed = radius * p.max_turn_rate
        x, y = self.center[0] + p.laser_x, self.center[1]
        heading = float(wrap_angle(math.atan2(y, x) - RIGHT))
        turn = -p.max_turn_rate + steer(p, self.gap, heading, distance)
        return along_curvature(turn / speed, p.cruise_speed, p.max_turn_rate)
