"""OUTER_CORNER: round the end of a wall that stopped on the right (a convex corner).

A wide arc, an arc round the corner's tip and a wide arc again (see
corner.py): the middle arc is pinned to the tip at every scan, and the
last one starts where it will end at the planned distance from the next
wall: judged on that wall once it is fitted, and until then as if the
corner were square, in which case it then goes on. Where that wall is a
short side with a wall across its end, the turn onto which leaves no
room to ride nearer first, the corner lands nearer it by that turn's dip:
the wide end is planned to, and once the side is fitted the arc round
the tip is pulled toward it by as much, for a corner whose wide end
never comes (a sharp tip, ridden wide). A side too short to rejoin (the
end of a thin bar) ends at a corner of its own, and the arc is pinned to
that one in turn. A corner that comes up with no wall fitted (the end of a
box's short side, mid-turn) is circled instead.
A round pillar standing free is no corner but one curve: it is circled
at the turn rate's limit for as long as it is seen (pillar.py).
Where the next wall lies farther than farthest_distance (a tip standing out
of it toward the robot), the turn goes on round the tip past parallel to it,
until the robot heads into it as steeply as FOLLOW dives onto it.

The turn is planned as if it began and ended outer_corner_offset farther
out than target_distance. Wide arcs that meet half way round a square
corner fly nearly all of it at cruise speed, but planned from
target_distance itself they pass the tip nearer than the band allows; a
little farther out, their meeting point moves off the tip and the turn
starts a little later, and they clear it.
"""
import math

from wall_follower.control.following.corner import OFF_ARC, CornerArc, OuterTurn
from wall_follower.control.following.follow_wall import dive_angle, steer
from wall_follower.control.following.landing_track import LandingTrack
from wall_follower.control.following.manoeuvre import FOLLOW, Manoeuvre
from wall_follower.control.motion import STOP, Command
from wall_follower.control.sensing.scan import RIGHT
from wall_follower.control.sensing.wall_fit import (along_the_way, from_centre, in_laser_frame,
                                                    wall_beyond)
from wall_follower.rotation import wrap_angle

# A wall fitted this much further round than the robot has turned from the
# one that ended is another wall [rad].
OTHER_WALL_ANGLE = math.radians(15.0)
# A wall fitted along the right once the turn is this far round is the next
# side (see _round_short_side). The faces of a many-sided island come along
# the right after smaller turns, and are circled on the arc round the first
# tip [rad].
NEXT_SIDE_TURN = math.radians(60.0)
# A wide end under way goes on while it lands no more than this beyond
# where it was planned to (see _track_wide) [m].
WIDE_END_HOLD = 0.003


class OuterCorner(Manoeuvre):
    """The right turn round a wall's end, until the next wall is along the right.

    turn: the OuterTurn as configured. arc: the CornerArc being driven
    round, or None while circling the nearest hit instead. starting_wide:
    whether the turn is still in its wide start (only a turn begun from
    following the wall has one, and once over it does not come back; nor
    has a turn round a tip standing out of the wall toward the robot,
    which lies nearer than the wide start is planned for).
    ending_wide: whether it has begun its wide end (which, once begun, goes
    on: the tip's position jitters by a grid cell from scan to scan).
    heading_in: how far (rad) the robot headed into the wall as the arc was
    pinned to its end.
    inner_corner: the left turn, whose approach dip a wall across the way
    just past the corner leaves no room for. pillar: the RoundPillar, the
    follower's, circled instead while one is found.
    """

    def __init__(self, params, inner_corner, pillar):
        super().__init__(params)
        self.configure()
        self.inner_corner = inner_corner
        self.pillar = pillar
        self.arc = None
        self.starting_wide = False
        self.ending_wide = False
        self.heading_in = 0.0
        self.landing = LandingTrack()

    def configure(self):
        """Plan the turn from the parameters, again after they have changed."""
        p = self.params
        self.turn = OuterTurn(p.outer_corner_radius, p.cruise_speed / p.max_turn_rate,
                              p.outer_wide_start, p.outer_wide_end,
                              p.target_distance + p.outer_corner_offset, p.outer_wide_tolerance)

    def due(self, obs):
        """True unless the wall on the right goes on past where the arc round its end starts,
        or a nearer wall does.

        Where a wall steps up toward the robot by less than the lane is
        wide, the wall ends at the foot of the step's face, which the robot
        passes beside; the step's top stands out of the wall and runs on
        past its end (more than wall_continue_gap): there is no corner to
        round, and FOLLOW keeps clear of the step. The top of the next wall
        at a corner can stand out too, but the wall beyond it falls away. A
        wall fitted on a round pillar is one of its chords: the pillar is
        rounded.
        """
        return obs.wall is None or self.pillar.found or self.due_within(obs, 0.0)

    def due_within(self, obs, travel):
        """True when a fitted wall on the right (no pillar found) ends where the turn round
        its end is due (see due) within travel (m) more of the way.

        Only an end actually seen counts for a turn still to come: a wall
        runs on to the edge of the sector it is looked for in
        (wall_sector, and no farther than wall_fit_range), and may run on
        past it, unseen.
        """
        p = self.params
        if obs.wall is None or self.pillar.found:
            return False
        if travel > 0.0 and obs.wall_runs + p.wall_continue_gap >= self._seen_to(obs.wall):
            return False
        ends = obs.wall_runs + p.laser_x <= self._turn_starts(obs) + travel
        return ends and obs.proud_reach <= obs.wall_runs + p.wall_continue_gap

    def _seen_to(self, wall):
        """How far ahead of the laser [m] the sector the wall on the right is looked for in
        reaches along that wall."""
        p = self.params
        edge = RIGHT + p.wall_sector
        line = in_laser_frame(wall)
        towards = math.cos(edge - line.angle)
        reach = p.wall_fit_range
        if towards > 0.0:
            reach = min(reach, line.distance / towards)
        return reach * math.cos(edge)

    def _turn_starts(self, obs):
        """How far ahead of the rotation centre the end of the wall on the right lies where
        the turn round it starts [m], from where the robot is off that wall (taken
        outer_corner_offset farther out, as the whole turn is planned) and how it heads."""
        wall = from_centre(obs.wall, self.params.laser_x)
        return (self.turn.lead_from(wall.distance + self.params.outer_corner_offset, wall.angle)
                + self.params.outer_turn_lead)

    def begin(self, obs, previous):
        self._pin(obs, wide_start=previous == FOLLOW)
        self.landing = LandingTrack()
        self._track_wide(obs, STOP, 0.0)

    def carry_on(self, obs, motion, dt):
        if self.arc is not None:
            self.arc.moved(motion.linear * dt, motion.angular * dt)
            self.arc.observe(obs.right, self.params.corner_gate)
            if self._round_short_side(obs):
                self._pin(obs, wide_start=self._before_wide_start(obs))
        self._track_wide(obs, motion, dt)

    def _before_wide_start(self, obs):
        """True when the end of the wall on the right is no more than outer_wide_tolerance
        nearer than where the wide start round it begins.

        A wide start begun farther on circles a centre beyond the tip, and
        carries the robot outside the arc round it: past the short faces of
        a small pillar not yet found, out of the band.
        """
        p = self.params
        return obs.wall_runs + p.laser_x >= self._turn_starts(obs) - p.outer_wide_tolerance

    def _pin(self, obs, wide_start):
        """Pin a new arc to the end of the wall on the right, to be flown from its wide start
        if wide_start (unless round a tip standing out toward the robot), noting how far the
        robot heads into that wall as it begins (see OuterTurn.starts_wide)."""
        self.arc = self._corner_arc(obs)
        self.starting_wide = wide_start and not obs.proud
        self.ending_wide = False
        self.heading_in = max(0.0, obs.wall.angle) if self.arc is not None else 0.0

    def _round_short_side(self, obs):
        """True when the turn has come round onto a side too short to rejoin, and the turn
        round that side's own end is due: the end of a thin bar, say.

        Fitted along the right once the turn is NEXT_SIDE_TURN round, the
        side is the next wall, not the one that ended; not done(), it is too
        short to follow. Taken for the next wall of a square corner, it
        held the wide end on, past parallel to it and far outside the arc
        round the first tip, until the robot crawled back onto that arc,
        and came round the side's far end cutting inside it. That end is a
        corner of its own, rounded as one come up from FOLLOW: from its wide
        start, unless the robot is already past where that begins
        (_before_wide_start). On the tight arc alone, circling each face of
        a many-sided island cost up to 9 % of the lap.
        """
        p = self.params
        return (not self.pillar.found and along_the_way(obs.wall, p.arc_exit_angle)
                and self.arc.turned() >= NEXT_SIDE_TURN and self.due(obs))

    def end(self):
        self.arc = None

    def done(self, obs):
        """True on a wall along the right: an arc ends nearly parallel to it, where it was planned
        to; circling a hit has no such end, and takes any wall. A pillar's chord is no such
        wall.

        Onto a wall farther than farthest_distance, an arc ends heading into it at the
        dive FOLLOW takes onto it (dive_angle). Ended parallel to it, round a
        tip standing 0.2 m out of it, the robot was 0.44 m off the wall as
        the tip fell behind, and out of the band until it had dived in.
        """
        p = self.params
        if self.pillar.found:
            return False
        if self.arc is None:
            return obs.rejoined(p.rejoin_angle, p.rejoin_ahead)
        dive = 0.0
        if obs.wall is not None:
            dive = dive_angle(p, from_centre(obs.wall, p.laser_x).distance, p.target_distance)
        return obs.rejoined(p.arc_exit_angle, p.rejoin_ahead, dive)

    def command(self, obs):
        """Fly the wide arcs at cruise speed, else hold the arc round the tip (or the nearest hit).

        The arc round the tip is flown at the full turn rate, which leaves no
        turn to spare for the PD law: a robot carried outside it (by a wide
        end begun before the next wall was seen and then cut short, round a
        sharp tip) would drift on outward. Farther outside than OFF_ARC, it
        slows down so that the turn rate allowed turns it as sharply as the
        law asks, and comes back onto the arc.
        """
        p = self.params
        if self.pillar.found:
            return self.pillar.command()
        if self.arc is not None:
            if self.starting_wide or self.ending_wide:
                return Command(p.cruise_speed, -p.max_turn_rate)
            distance, bearing = self.arc.offset()
            radius, share = p.outer_corner_radius, 1.0
        else:
            distance, bearing = obs.nearest
            radius, share = p.target_distance, p.circling_speed_share
        speed = min(p.cruise_speed, share * radius * p.max_turn_rate)
        # The arc's curvature as a feed-forward, and the PD law on its
        # centre as if that were a wall tangent to the arc.
        turn = -speed / radius + steer(p, distance, float(wrap_angle(bearing - RIGHT)), radius)
        if abs(turn) > p.max_turn_rate and distance > radius + OFF_ARC:
            speed *= p.max_turn_rate / abs(turn)
        return Command(speed, turn)

    def _track_wide(self, obs, motion, dt):
        """End the wide start, or begin the wide end, where the arc has got to; motion is the
        Command driven for the dt seconds since the last update.

        The next wall, once fitted, is tracked (landing_track.py): its fit
        steps by a grid cell as the robot turns, and judged on the steps
        alone the wide end began, stopped and began again, scan after scan.
        Along the wide arc, where it lands is the same at every point (the
        arc turns it off the wall as much as it nears it), so a wide end
        begun sits on its threshold: a wide end under way goes on while it
        lands within WIDE_END_HOLD of it. Stopped by a millimetre's jitter,
        it left the robot outside the arc round the tip, crawling back.
        A wide end begins only where it does not cut inside that arc
        (OuterTurn.end_clears); until then the tight arc turns the robot
        along it.
        """
        next_wall = self._next_wall(obs) if self.arc is not None else None
        landing = self.landing.update(
            None if next_wall is None else from_centre(next_wall, self.params.laser_x),
            motion, dt)
        if self.arc is None:
            return
        self.starting_wide = self.starting_wide and self.turn.starts_wide(
            self.arc.turned(), self.arc.offset(), self.heading_in)
        # A wall across the way just past the corner (beyond a pillar's
        # short side) leaves no room to ride nearer before the turn onto
        # it: the corner lands that much nearer the side instead. The turn
        # onto that wall starts once this one is over: the rest of this
        # one adds to its angle.
        if next_wall is not None:
            nearer = self.inner_corner.dip(obs, -next_wall.angle)
            self.arc.pull(nearer, in_laser_frame(next_wall).normal)
            hold = WIDE_END_HOLD if self.ending_wide else 0.0
            self.ending_wide = self.turn.lands_within(landing.distance, -landing.angle,
                                                      nearer - hold) and (
                self.ending_wide or self.turn.end_clears(self.arc.offset(), -landing.angle))
        else:
            still = math.pi / 2 - self.arc.turned()
            nearer = self.inner_corner.dip(obs, still)
            self.ending_wide = self.ending_wide or (
                self.turn.ends_wide(self.arc.turned(), self.arc.past_tip(), nearer)
                and self.turn.end_clears(self.arc.offset(), still))

    def _next_wall(self, obs):
        """The wall on the right the turn is coming round onto, once it is fitted; else None.

        Until then the corner is taken for a square one. Not every corner
        is: round the tip of a wall that meets the next at a sharp angle,
        the wide end begun where a square corner's would have begun carries
        the robot far off the next wall, and round an obtuse one (45 or 60
        degrees of turn) it begins too late, and the robot turns on past
        parallel into the next wall. The wall that ended lies across the
        heading as far as the robot has turned; the next one, not yet
        reached, lies the other way (the robot heads away from it). It is
        the wall fitted on the right once the robot has turned most of the
        way, and before that the wall fitted beyond the tip (wall_beyond).
        A wall fitted farther than farthest_distance is the next one even once the robot
        heads along it or into it, since the turn goes on round the tip
        until it dives onto it (done): taken for a square corner's instead,
        round a tip standing out of it, it began the wide end that carried
        the robot off the tip and higher above the wall.
        """
        other = self.arc.turned() - OTHER_WALL_ANGLE
        wall = obs.wall
        ended = wall is not None and self._the_wall_that_ended(obs)
        if wall is not None and not ended and wall.angle < other and \
                from_centre(wall, self.params.laser_x).distance > self.params.farthest_distance:
            return wall
        heading_away = min(0.0, other)
        if wall is None or wall.angle >= heading_away or ended:
            wall = wall_beyond(obs.right, self.arc.tip, self.arc.along, self.params)
        return wall if wall is not None and wall.angle < heading_away else None

    def _the_wall_that_ended(self, obs):
        """True when the wall fitted on the right is the one whose end the turn goes round,
        however far its fit has turned: it runs up to the tip (its farthest hit ahead within
        corner_gate of it), within a right angle of the way that wall ran.

        The arc takes that wall's way from its fit as the turn begins. Where
        the tip stands out of the wall toward the robot (a hook at the end of
        a slanted wall, on Stage's grid), that fit was turned 9 degrees toward
        the tip; fitted clear of it scans later, the same wall seemed turned
        away by more than OTHER_WALL_ANGLE, was taken for the next wall, and
        the robot flew the wide end along it, out of the band round the tip.
        The next wall runs on from the tip, its farthest hit ahead beyond it;
        the far side of a thin bar, which ends there too, runs back the
        other way.
        """
        near_tip = math.hypot(*(obs.wall_end - self.arc.tip)) < self.params.corner_gate
        return near_tip and abs(float(wrap_angle(obs.wall.angle - self.arc.turned()))) < math.pi / 2

    def _corner_arc(self, obs):
        """The arc round the end of the wall that just ended; None without such a wall.

        Without it (the corner comes up in the middle of a left turn, at
        the end of a short wall or a box's side) which way the corner points
        is unknown, and the robot circles the nearest hit instead. A wall
        fitted turned away far off parallel (beyond rejoin_angle) is not the
        one that ended either: mid-turn onto a box's short side, it is the
        wall the turn left behind, and an arc pinned to its end would circle
        a point nowhere near the corner. A wall the robot still heads into,
        however steeply, is the one that ended: the corner came up before
        FOLLOW had turned the robot parallel (just after a turn onto a
        slanted wall), and circling the nearest hit instead drifted the
        robot out of the band. Nor is a wall whose end meets hits
        standing out of it toward the robot by more than corner_gate (the
        face of a step up, turned onto): its end is the foot of that face,
        the corner to round is the face's top.
        """
        if obs.wall is None or obs.wall.angle <= -self.params.rejoin_angle or \
                obs.proud > self.params.corner_gate:
            return None
        angle = obs.wall.angle
        return CornerArc(obs.wall_tip, (math.cos(angle), math.sin(angle)), self.turn.center,
                         self.params.laser_x)
