"""WALL_AHEAD: the left turn onto a wall across the way (an inner corner).

The turn is flown at the full turn rate: wide at first, nearly pivoting
past the corner, and wide again onto parallel (see left_turn.py). Its
speed is re-planned from the wall ahead at every scan, so the turn is
closed-loop, not timed; that wall is tracked from scan to scan by the
robot's own motion (landing_track.py), as a grid's ranges move its fit in
steps. Its wide end is planned on the new wall to the last: once that
wall has come round to the right and left the lane ahead, it is the wall
on the right the robot still heads into, and the turn goes on until the
lane's edges are clear of it. While such a wall comes up,
the robot rides a little nearer the old wall, by as much as the wide start
will carry it off beyond wide_allowance; a turn begun without that room
(after a short wall) flies short_turn instead: a shorter wide start and a
tight arc rather than a pivot. Whatever else stands ahead on the right (the
foot of a step the turn passes) it passes no nearer than closest_distance.
"""
import math

import numpy as np

from wall_follower.control.following.body import Body
from wall_follower.control.following.landing_track import LandingTrack
from wall_follower.control.following.left_turn import LeftTurn
from wall_follower.control.following.manoeuvre import Manoeuvre
from wall_follower.control.following.reach_track import ReachTrack
from wall_follower.control.following.turn_reading import peak_reading
from wall_follower.control.motion import Command
from wall_follower.control.sensing.lines import Line
from wall_follower.control.sensing.observation import second_smallest
from wall_follower.control.sensing.wall_fit import (along_the_way, as_planned, from_centre,
                                                    in_laser_frame, same_line, wall_runs_to)

# How far beyond reach (see InnerCorner.due) the wall ahead must be for a turn
# onto it to end [m]. All through the turn's wide start that wall stays at the
# edge of reach, its distance and the gap the rest of the turn needs
# shrinking alike, and a scan places it only to a few millimetres. More
# (1 cm) held on turns that a noisy laser's early start had begun too far
# from the wall being left, and their crossover left the band.
OUT_OF_REACH = 0.005
# How much farther out than planned the turn lands [m]. It lands on the
# wall as tracked (landing_track.py), which runs through the middle of the
# fit's grid steps, while the turn's start (due) is judged on the fit
# itself. Landed on the track as planned, turns came out nearer than those
# landed on the fit, whose steps down slowed them to a near pivot, and
# FOLLOW spent twice the time nearer than the band after them.
LANDING_MARGIN = 0.005
# How many times the range of tight radii is halved in search of the widest one
# whose plan keeps the reading within turn_farthest (InnerCorner._within_reading):
# to within 1/32 of the planned radius, 5 mm of the short-wall turn's 16 cm.
TIGHTENING_STEPS = 5


class InnerCorner(Manoeuvre):
    """The left turn onto a wall ahead, until that wall has come round to the right.

    left_turn is the turn as configured, short_turn the one after a short
    wall, and turn the one in force: planned afresh from every scan until
    it is flown (plan()), and kept while it is.
    """

    def __init__(self, params):
        super().__init__(params)
        self.configure()
        self.turn = self.left_turn
        self.track = LandingTrack()
        self.reach = ReachTrack()
        self._observed = None

    def observe(self, obs, motion, dt):
        """Track the wall a left turn lands on (landing_track.py) and how far beyond the turn's
        reach the wall across the way lies (reach_track.py) through this update's
        Observation: motion is the Command driven for the dt seconds since the last."""
        self._observed = obs
        self.track.update(self._fitted_landing_wall(obs), motion, dt)
        if self.blocking(obs):
            ahead = self._ahead_as_planned(obs)
            self.reach.update(self._slack(ahead), self._slack_change(ahead, motion, dt))
        else:
            self.reach.update(None, 0.0)

    def configure(self):
        """Plan the turns from the parameters, again after they have changed.

        A turn being flown keeps its plan; the next one is planned anew.
        """
        p = self.params
        wide_radius = p.cruise_speed / p.max_turn_rate
        self.left_turn = LeftTurn(p.inner_corner_radius, wide_radius, p.wide_start, p.wide_end)
        # The nearest the robot may ride before the turn, for its tail to keep
        # body_clearance from the wall as the wide start swings it round.
        self._deepest_dip = p.target_distance - p.body_clearance - \
            Body(p.body_rear, p.body_half_width).swing(wide_radius)
        self.short_turn = LeftTurn(p.short_turn_radius, wide_radius, p.short_wide_start,
                                   p.short_wide_end)

    def plan(self, obs):
        """Choose the turn to fly from here: its wide start ends at most wide_allowance past target.

        A robot that has not ridden nearer first (a short wall left no
        room) would cut the wide start of left_turn short, and then fly
        its near pivot for most of the turn: short_turn, tight but not a
        pivot, is faster there.
        """
        if obs.wall is None:
            self.turn = self.left_turn
            return
        p = self.params
        allowed = p.target_distance + p.wide_allowance - from_centre(obs.wall, p.laser_x).distance
        turn = self.left_turn.drifting_at_most(allowed)
        if turn.wide_start < self.left_turn.wide_start - p.short_turn_cut:
            turn = self.short_turn.drifting_at_most(allowed)
        self.turn = self._within_reading(turn, obs) if self.blocking(obs) else turn

    def _within_reading(self, turn, obs):
        """turn, its tight arc tightened no more than it takes to keep the wall on the right
        reading no farther than turn_farthest through an ideal corner (turn_reading.py); a
        pivot where nothing else will.

        Riding nearer first (dip) keeps a turn's widest reading at the
        band's edge; a robot that could not (after a short wall, or from
        find_wall's end) starts the turn farther out, and its tight arc,
        swinging the laser round behind the rotation centre, carries it off
        the band before the wall ahead comes near enough to read. Only a
        plan that reads more than turn_tolerance past turn_farthest is
        tightened: tightened too, the turns that read about the edge cost
        2 % of lap time for scans a few millimetres out. The widest arc that
        keeps within turn_farthest is found by halving the range of radii
        TIGHTENING_STEPS times.
        """
        p = self.params
        angle = self._ahead_as_planned(obs).angle
        right = from_centre(obs.wall, p.laser_x)
        landing = p.inner_corner_distance + LANDING_MARGIN

        def within(scale, farthest=p.turn_farthest):
            candidate = turn.tightened(scale)
            ahead = Line(candidate.gap(angle) + landing, angle)
            return peak_reading(candidate, right, ahead, landing, p.laser_x,
                                p.right_sector) <= farthest

        if within(1.0, p.turn_farthest + p.turn_tolerance):
            return turn
        low, high = 0.0, 1.0
        for _ in range(TIGHTENING_STEPS):
            middle = 0.5 * (low + high)
            if within(middle):
                low = middle
            else:
                high = middle
        return turn.tightened(low)

    def needed(self, obs, turning_right=False):
        """True when anything is near in the lane ahead, or a wall across the way is near
        enough that the planned turn, begun now, ends inner_corner_distance from it.

        turning_right: the robot is rounding an outer corner, which turns it
        away from a wall across its present heading (a pillar or an island
        beyond the corner, say): only something near in the lane counts then,
        and only in the part of it that the arc being flown sweeps as well
        (Observation.front_on_arc).
        """
        front = obs.front_on_arc if turning_right else obs.front
        if front < self.params.front_turn_distance:
            return True
        return not turning_right and self.due(obs)

    def due(self, obs, beyond=0.0):
        """True when a wall across the way is near enough that the planned turn, begun now,
        ends inner_corner_distance from it; or, given beyond (m), when it is no more than that
        out of reach. For the Observation last observed, judged on how far out of reach the
        wall is as tracked through the scans (reach_track.py), not on that one scan's fit."""
        if not self.blocking(obs):
            return False
        if obs is self._observed:
            return self.reach.slack <= beyond
        return self._slack(self._ahead_as_planned(obs)) <= beyond

    def _slack(self, ahead):
        """How far [m] the wall across the way (ahead, as _ahead_as_planned gives it) lies
        beyond the reach of the planned turn begun now (< 0 within it)."""
        p = self.params
        return ahead.distance - self.turn.gap(ahead.angle) - p.turn_lead - p.inner_corner_distance

    def _slack_change(self, ahead, motion, dt):
        """How much the command driven for dt seconds (motion) changed the slack of the wall
        across the way (_slack; ahead as there), by the turn as planned.

        The robot came nearer the wall by its arc's length times the sine
        of the angle, taken half way along, and turned by as much less to go.
        """
        turned = motion.angular * dt
        nearer = motion.linear * dt * math.sin(ahead.angle + 0.5 * turned)
        return self.turn.gap(ahead.angle + turned) - self.turn.gap(ahead.angle) - nearer

    def done(self, obs):
        """True once a straight wall is along the right again, not one the turn is leaving,
        and no turn onto a wall across the way is due yet.

        The wall the turn leaves swings away behind the right as the robot
        turns (its angle goes negative): turning onto a short step, it is
        the only long wall on the right for a while, and taken for the next
        one it handed the turn to FOLLOW, which steered back at it, mid-turn.
        A wall farther across the way (the next one of a room whose walls
        meet at wide angles) is turned onto when it comes within reach, from
        FOLLOW: a turn held on until it was gone would carry the robot round
        off the wall it has just reached. The wall the turn is onto must be
        out of reach by OUT_OF_REACH: ended whenever a scan put it a few
        millimetres beyond, the turn handed over to FOLLOW, which steered back
        at the wall the turn was leaving, and began again at the next scan.
        """
        p = self.params
        return (obs.rejoined(p.rejoin_angle, p.rejoin_ahead) and obs.wall.angle > -p.rejoin_behind
                and not self.due(obs, beyond=OUT_OF_REACH))

    def clear_of_lane_edges(self, obs):
        """True when nothing is nearer than front_turn_distance in the lane widened by
        clear_margin each side.

        Something at the lane's edge (a step in the wall, a stub at a
        corner's tip) leaves the lane after a few degrees of left turn; a
        turn handed back to FOLLOW then is steered straight back into it,
        and begun again, scan after scan.
        """
        return obs.front_wide >= self.params.front_turn_distance

    def leaving_its_wall(self, obs):
        """True when what holds the widened lane's edges (not clear_of_lane_edges) can only
        be the wall on the right that the turn is leaving.

        A robot nearer that wall than the widened lane's half-width
        (corridor_half_width + clear_margin) finds the wall itself, or the
        saw-tooth of a slanted one, at the widened lane's edge, and
        clear_of_lane_edges would hold the turn on until the wall lay behind
        and was lost. Turned away from it by more than rejoin_behind, with
        the lane itself clear and no wall across it, the turn is over.
        """
        p = self.params
        return (obs.wall is not None and obs.wall.angle < -p.rejoin_behind
                and obs.wall.distance < p.corridor_half_width + p.clear_margin
                and obs.front >= p.front_turn_distance and obs.ahead is None)

    def landed_past_parallel(self, obs):
        """True when the turn is over (done), has come round parallel to the wall it landed on
        or past, and nothing but that wall's own near side holds the widened lane's edges
        (not clear_of_lane_edges).

        Ridden nearer than the widened lane's half-width, a wall whose near
        side reads a few centimetres out of its fitted line keeps hits at
        the lane's edge however far the robot turns from it: held on for
        them, the turn went on past parallel and handed over to
        OUTER_CORNER, which circled 0.41 m out from the wall for 2.7 s.
        Still heading into the wall, the turn's last degrees are flown as
        planned instead.
        """
        return (self.done(obs) and obs.wall.angle <= 0.0
                and obs.front_wide_off_wall >= self.params.front_turn_distance)

    def command(self, obs):
        """Turn left at full rate, on the planned turn that ends parallel to the wall ahead.

        Closed loop on the wall ahead: the speed is set each update to the
        radius still needed, so a late start slows the robot down instead of
        carrying it too close, and a wall too near is turned from on the spot.
        """
        p = self.params
        radius = p.inner_corner_radius
        landing = self._landing(obs)
        if landing is not None:
            radius = self.turn.radius_within(*landing)
        radius = min(radius, self._clear_radius(obs))
        if obs.front < p.front_stop_distance:
            radius = 0.0
        return Command(radius * p.max_turn_rate, p.max_turn_rate)

    def _clear_radius(self, obs):
        """The widest left arc that passes every hit ahead on the right, but those of the wall
        it lands on, no nearer than closest_distance (inf when none is in the way).

        The turn is planned on the wall it lands on alone. The foot of a
        step or the tip of a stub beside the way, which the robot passes on
        its right while it turns left, is not in that plan, and the wide
        start, flown at cruise speed, cut inside it. An arc of radius r,
        centred r to the left of the rotation centre, passes a point x ahead
        of that centre and y to its right (y < closest_distance) at least
        closest_distance away while r <= (x^2 + y^2 - closest_distance^2) /
        (2 (closest_distance - y)). Only hits within 45 degrees of ahead
        count: one abeam is being passed already, at whatever radius. The
        wall landed on is the plan's to keep clear of (its hits bounded the
        wide start, and turns landed wide of their walls); the second
        tightest bound is kept, so that one spurious beam does not slow the
        turn.
        """
        p = self.params
        clear = p.closest_distance
        points = obs.right
        landed_on = self._wall_landed_on(obs)
        if landed_on is not None:
            points = points[in_laser_frame(landed_on).offsets(points) < -p.wall_inlier_distance]
        x, across = points[:, 0] + p.laser_x, -points[:, 1]
        near = (x >= across) & (across < clear)
        x, across = x[near], across[near]
        return second_smallest(np.maximum(
            0.0, (x * x + across * across - clear * clear) / (2.0 * (clear - across))))

    def _landing(self, obs):
        """(gap, angle): how much nearer the wall the turn lands on the rest of the turn may
        carry the rotation centre, and the angle (rad) still to turn onto it; or None.

        That wall is the wall ahead while there is one. Past the corner the
        new wall leaves the lane ahead, but it is still at the widened lane's
        edge while the robot heads into it, which holds the turn on: the
        wall on the right is then the one it lands on. Flown on the tight
        arc for want of a wall ahead, those last degrees cost a pivot's time
        where the wide end had room for cruise speed. The turn lands
        inner_corner_distance from a wall, nearer than target_distance, for
        FOLLOW to steer back out along it; a short side that runs on less
        than landing_run leaves no room for that before the turn round its
        end, which is planned from target_distance, and a landing nearer
        would carry the robot past that end's tip nearer still. On such a
        side the turn lands at target_distance, or, where the side shows
        itself short only once the turn is under way (as the wall ahead
        comes round to the right), where the turn flown as planned lands,
        if that is nearer but no nearer than inner_corner_distance: planned
        afresh for target_distance there, the gap ran out at once and the
        robot pivoted through the whole wide end. Either wall is the one
        tracked (observe), and the landing LANDING_MARGIN farther out.
        """
        p = self.params
        short_side = False
        if obs.ahead is None:
            if not self._onto_right_wall(obs):
                return None
            line = in_laser_frame(obs.wall)
            runs = wall_runs_to(line, line.offsets(obs.right), obs.wall_tip, obs.right, p)[0]
            short_side = runs < p.landing_run
        distance, angle = self._landing_wall(obs)
        landing = p.inner_corner_distance
        if short_side:
            landed_as_planned = distance - LANDING_MARGIN - self.turn.gap(angle)
            landing = min(p.target_distance, max(landing, landed_as_planned))
        return distance - landing - LANDING_MARGIN, angle

    def dip(self, obs, still_turning=0.0):
        """How much nearer to ride while a wall across the way is within approach_range.

        As much as the wide start of the turn onto that wall will drift,
        less what it may drift past target_distance (wide_allowance), but
        never so near that the start of the turn swings the robot's tail
        within body_clearance of the wall. still_turning: how far (rad) the
        robot turns right before that turn starts, which adds to the wall's
        angle.
        """
        if not self.blocking(obs):
            return 0.0
        distance, angle = self._ahead_square_to_right(obs)
        if distance >= self.params.approach_range:
            return 0.0
        drift = self.left_turn.drift(angle + still_turning) - self.params.wide_allowance
        return max(0.0, min(drift, self._deepest_dip))

    def blocking(self, obs):
        """True when a wall lies across the way ahead (not the right wall seen ahead)."""
        steep = self.params.ahead_min_angle
        if obs.ahead is None or not steep <= obs.ahead.angle <= math.pi - steep:
            return False  # none, or one nearly along the way (beside the lane)
        return obs.wall is None or not same_line(obs.ahead, obs.wall)

    def _ahead_as_planned(self, obs):
        """The wall ahead as fitted, as the left turn is planned for it: see as_planned and
        from_centre."""
        return from_centre(self._ahead_square_to_right(obs), self.params.laser_x)

    def _landing_wall(self, obs):
        """The wall a left turn lands on, as tracked through obs (observe), or as fitted on
        an Observation that was not."""
        if obs is self._observed:
            return self.track.wall
        return self._fitted_landing_wall(obs)

    def _fitted_landing_wall(self, obs):
        """The wall a left turn lands on (_wall_landed_on), as fitted on obs and seen from the
        rotation centre (from_centre); None if there is none.

        The wall ahead is taken as the turn is planned for it (as_planned).
        """
        wall = self._wall_landed_on(obs)
        if wall is None:
            return None
        if wall is obs.ahead:
            return self._ahead_as_planned(obs)
        return from_centre(wall, self.params.laser_x)

    def _wall_landed_on(self, obs):
        """The wall a left turn lands on, as obs fits it: the wall ahead while there is one;
        past the corner, the wall on the right while the robot still heads into it (a positive
        angle, within rejoin_angle of parallel); else None."""
        if obs.ahead is not None:
            return obs.ahead
        return obs.wall if self._onto_right_wall(obs) else None

    def _onto_right_wall(self, obs):
        """True when the wall on the right is one the robot still turns onto: within
        rejoin_angle of parallel, heading into it."""
        return along_the_way(obs.wall, self.params.rejoin_angle) and obs.wall.angle > 0.0

    def _ahead_square_to_right(self, obs):
        """as_planned of the wall ahead, squared to the wall on the right if that is along the way.

        A right wall fitted farther off parallel is mid-corner, not the
        wall the one ahead meets.
        """
        wall = obs.wall if along_the_way(obs.wall, self.params.rejoin_angle) else None
        return as_planned(obs.ahead, wall)
