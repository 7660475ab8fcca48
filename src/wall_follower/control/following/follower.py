"""Right-hand wall following as a plain state machine: a scan in, a command out.

The course's rule is bang-bang on one ray (too far: turn right, too near:
turn left, in the band: straight, wall ahead: turn left). Here each of
those situations is a manoeuvre of its own, flown by an object that owns
what it has to remember and says when it is done (see manoeuvre.py):

- FOLLOW (follow_wall.py): a PD law on the distance and angle of the wall
  on the right, a line fitted through many beams (wall_fit.py);
- WALL_AHEAD (inner_corner.py): a wall ahead (an inner corner) is turned
  onto at the full turn rate, wide at first, nearly pivoting past the
  corner, and wide again onto parallel. Its wide end lands the robot
  nearer than target_distance on purpose, an error well above the laser's
  noise, so for settle_time after the turn FOLLOW's distance gain is raised
  by settle_gain to bring it back out sooner;
- OUTER_CORNER (outer_corner.py): a wall that ends on the right (a convex
  corner) is rounded on a wide arc, an arc round the corner's tip and a
  wide arc again; a round pillar (pillar.py), looked for at every scan, is
  circled at the full turn rate;
- SEARCH (search.py): no wall near, straight ahead until one comes up.

Corners get their own states because a wall fit cannot see them coming.
The turn rate, not the speed, is what limits a lap: a quarter turn takes
the same time at max_turn_rate whatever the speed, so corners are driven
at the largest radius that keeps the wall in the band.

Everything is in the laser frame (x ahead, y left, angles counter-clockwise,
0 = ahead, -pi/2 = right) and read by angle through ScanView, so the
laser's beam order and its way of writing "no return" do not matter.
Motion is modelled about the robot's rotation centre; the laser sits
laser_x ahead of it (on a TurtleBot3, behind it).
"""
import copy

from wall_follower.control.following.follow_wall import FollowWall
from wall_follower.control.following.inner_corner import InnerCorner
from wall_follower.control.following.manoeuvre import FOLLOW, OUTER_CORNER, SEARCH, WALL_AHEAD
from wall_follower.control.following.outer_corner import OuterCorner
from wall_follower.control.following.pillar import RoundPillar
from wall_follower.control.following.search import Search
from wall_follower.control.motion import Command
from wall_follower.control.sensing.observation import Observation
from wall_follower.control.sensing.scan import RIGHT
from wall_follower.control.stamps import elapsed
from wall_follower.params import checked
from wall_follower.params.course.wall_following import FOLLOWER
from wall_follower.rotation import wrap_angle

#: The controller's parameters: defaults, ranges, units and meanings.
PARAMETERS = FOLLOWER


class FollowerParams(object):
    """The controller's parameters, defaults from PARAMETERS, overridable by name.

    An unknown name, a value of the wrong type or one out of range is an
    error (ParameterError, a ValueError) rather than silently ignored, so
    that a typo in a configuration shows up instead of leaving a default
    in force.
    """

    def __init__(self, **overrides):
        for name, value in checked(PARAMETERS, overrides).items():
            setattr(self, name, value)


class WallFollower(object):
    """Follows the wall on the right; update() once per scan.

    States: FOLLOW (PD on the fitted right wall), WALL_AHEAD (turn left,
    still moving, until the wall ahead has come round to the right),
    OUTER_CORNER (round the end of a wall that stopped on the right),
    SEARCH (no wall near: drive straight until one appears ahead or on the
    right). manoeuvres holds the one that flies each state. A wall ahead
    within reach interrupts any of them; otherwise each state has its own
    transition. The last command is kept, to judge the next scan where the
    robot will be when that command takes effect.
    """

    def __init__(self, params=None):
        # A copy: reconfigure() changes it in place, for every manoeuvre to read.
        self.params = copy.copy(params or FollowerParams())
        self.state = SEARCH
        self.command = Command(0.0, 0.0)
        self.inner_corner = InnerCorner(self.params)
        self.pillar = RoundPillar(self.params)
        self.outer_corner = OuterCorner(self.params, self.inner_corner, self.pillar)
        self.follow_wall = FollowWall(self.params, self.inner_corner, self.outer_corner)
        self.manoeuvres = {
            FOLLOW: self.follow_wall,
            WALL_AHEAD: self.inner_corner,
            OUTER_CORNER: self.outer_corner,
            SEARCH: Search(self.params),
        }
        self._transitions = {
            FOLLOW: self._from_follow,
            WALL_AHEAD: self._from_wall_ahead,
            OUTER_CORNER: self._from_outer_corner,
            SEARCH: self._from_search,
        }
        self._stamp = None

    def reconfigure(self, params):
        """Go on under new FollowerParams from the next update on.

        Every manoeuvre reads the one params object, so it takes the new
        values in place; the corner turns are planned again from them (a
        turn being flown keeps its plan). The state is kept.
        """
        vars(self.params).update(vars(params))
        self.inner_corner.configure()
        self.outer_corner.configure()

    def update(self, view, stamp=None):
        """Advance the state machine on a ScanView; returns the next Command.

        stamp: the scan's time [s]. The time since the last scan tells how
        far the robot has turned round a corner; without stamps the scans
        are taken to be latency apart. The command stays within
        cruise_speed and max_turn_rate; the node still clamps it to the
        robot's limits.
        """
        p = self.params
        dt = p.latency if stamp is None or self._stamp is None else elapsed(stamp, self._stamp)
        self._stamp = stamp
        obs = Observation(view, p, self.command)
        if self.state != WALL_AHEAD:
            # Until it is flown, the turn onto a wall ahead is planned afresh at every scan,
            # and how far out of its reach the wall is, is tracked against that plan.
            self.inner_corner.plan(obs)
        self.pillar.observe(obs, self.command, dt)
        self.inner_corner.observe(obs, self.command, dt)
        previous, self.state = self.state, self._next_state(obs)
        self.follow_wall.elapse(dt, turning=self.state == WALL_AHEAD)
        self._hand_over(previous, obs, dt)
        speed, turn = self.manoeuvres[self.state].command(obs)
        self.command = Command(min(max(speed, 0.0), p.cruise_speed),
                               min(max(turn, -p.max_turn_rate), p.max_turn_rate))
        return self.command

    def _hand_over(self, previous, obs, dt):
        """Carry the manoeuvre in force on, or end the one left and begin the one entered."""
        manoeuvre = self.manoeuvres[self.state]
        if self.state == previous:
            manoeuvre.carry_on(obs, self.command, dt)
        else:
            self.manoeuvres[previous].end()
            manoeuvre.begin(obs, previous)

    def _next_state(self, obs):
        """A wall ahead within reach interrupts any manoeuvre; else the state's own transition.

        Round an outer corner, or from FOLLOW into one at the end of a
        fitted wall, only something near in the lane is within reach: the
        right turn carries the robot away from anything farther across its
        present heading. A wall on the right that ends short of a wall
        across the way leaves an opening between them, and the way on is
        through it; where the turn onto the wall across was due as well,
        and taken first, it carried the robot away from the opening and off
        the wall it had followed. So it was where that turn came due a few
        centimetres before the end: it swung the robot toward the opening's
        far side, and the robot dithered there between the two turns. The
        turn round the end comes first wherever it is due before anything
        in the lane comes within front_turn_distance. An opening too narrow
        to turn into has the wall across nearer than that by the time the
        end is due, and the left turn is taken as before.
        """
        following = self._transitions[self.state](obs)
        turning_right = self.state == OUTER_CORNER or (
            self.state == FOLLOW and self.outer_corner.due_within(
                obs, max(0.0, obs.front - self.params.front_turn_distance)))
        if self.inner_corner.needed(obs, turning_right=turning_right):
            return WALL_AHEAD
        return following

    def _from_follow(self, obs):
        """Follow on until the wall ends where the turn round its end starts, then round it."""
        if not self.follow_wall.done(obs):
            return FOLLOW
        if self._near(obs):
            return OUTER_CORNER
        return self._wall_or_search(obs)

    def _from_wall_ahead(self, obs):
        """Turn on until the wall ahead has come round to the right and the lane's edges
        are clear.

        Only the end of a wall beside the robot (a short wall, a box), or
        one behind it with no wall along the right (_to_round), can end the
        turn otherwise: anything near in the lane, or a wall across
        it nearer than front_clear_distance, only means the turn is not
        over yet. A wall farther across the way is turned onto when it
        comes within reach, from FOLLOW, like any other. A turn held on by
        nothing but the wall it is leaving, or by the near side of the wall
        it has come round parallel to, is over, and FOLLOW steers along
        that wall.
        """
        if not self.inner_corner.clear_of_lane_edges(obs):
            over = (self.inner_corner.leaving_its_wall(obs)
                    or self.inner_corner.landed_past_parallel(obs))
            return FOLLOW if over else WALL_AHEAD
        if self.inner_corner.done(obs):
            return FOLLOW
        if obs.front < self.params.front_clear_distance or (
                obs.ahead is not None and obs.ahead.distance < self.params.front_clear_distance):
            return WALL_AHEAD
        if self._near(obs):
            return OUTER_CORNER if self._to_round(obs) else WALL_AHEAD
        return self._wall_or_search(obs)

    def _to_round(self, obs):
        """True when the nearest hit on the right is the end of a wall for the left turn to
        round: beside the robot, or behind it while no wall is along the right.

        With no wall fitted, a hit behind the right is the end of the wall
        the turn has left: held on for it, the turn carried the robot away
        until that wall was lost. With one fitted, it is the old wall of an
        ordinary turn, which goes on until the new wall is rejoined.
        """
        ahead_of_right = float(wrap_angle(obs.nearest[1] - RIGHT))
        if ahead_of_right > self.params.corner_bearing:
            return False
        return ahead_of_right >= -self.params.corner_bearing or obs.wall is None

    def _from_outer_corner(self, obs):
        """Round the corner until the next wall is along the right, while anything is near."""
        if self.outer_corner.done(obs):
            return FOLLOW
        if self._near(obs):
            return OUTER_CORNER
        return self._wall_or_search(obs)

    def _from_search(self, obs):
        """Drive on until a wall comes up on the right."""
        return FOLLOW if self.manoeuvres[SEARCH].done(obs) else SEARCH

    @staticmethod
    def _wall_or_search(obs):
        """With nothing near to round: follow the wall on the right if there is one."""
        return FOLLOW if obs.wall is not None else SEARCH

    def _near(self, obs):
        """True when the nearest hit on the right is near enough to be a wall to follow."""
        return obs.nearest is not None and obs.nearest[0] < self.params.wall_lost_distance
