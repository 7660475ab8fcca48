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
  wide arc again;
- SEARCH (search.py): no wall near, straight ahead until one comes up.

Corners get their own states because a wall fit cannot see them coming.
The turn rate, not the speed, is what limits a lap: a 90 degree corner
takes 3.2 s at 0.49 rad/s whatever the speed, so corners are driven at the
largest radius that keeps the wall in the band.

Everything is in the laser frame (x ahead, y left, angles counter-clockwise,
0 = ahead, -pi/2 = right) and read by angle through ScanView, so the
laser's beam order and its way of writing "no return" do not matter.
Motion is modelled about the robot's rotation centre; the laser sits
laser_x ahead of it (on a Burger, 32 mm behind it).
"""
import math

from wall_follower.control.follow_wall import FollowWall
from wall_follower.control.inner_corner import InnerCorner
from wall_follower.control.manoeuvre import FOLLOW, OUTER_CORNER, SEARCH, WALL_AHEAD
from wall_follower.control.motion import Command
from wall_follower.control.observation import Observation
from wall_follower.control.outer_corner import OuterCorner
from wall_follower.control.scan import RIGHT, wrap_angle
from wall_follower.control.search import Search

#: Every tunable number of the controller: name -> (default, meaning).
#: Distances from the laser in metres, speeds in m/s and rad/s, angles in degrees.
PARAMETERS = {
    # The robot
    'laser_x': (-0.032, 'laser position ahead of the rotation centre (Burger: 32 mm behind)'),
    # Following a straight wall
    'target_distance': (0.25, 'wanted distance to the wall on the right'),
    'range_bias': (0.008, 'how much longer than true the laser reads (Stage ~0.008, LDS-01 0)'),
    'cruise_speed': (0.19, 'forward speed on a straight wall'),
    'max_turn_rate': (0.49, 'largest turn rate the controller asks for'),
    'k_distance': (11.0, 'turn rate per metre of distance error (rad/s/m)'),
    'k_angle': (3.0, 'turn rate per radian of heading into the wall (rad/s/rad)'),
    'latency': (0.1, 'scan-to-motion delay (s): each scan is judged where the robot will be'),
    'turn_slowdown': (0.0, 'share of cruise speed given up at the largest turn rate'),
    'closest_distance': (0.215, 'heading into the wall, slow so as to turn parallel no nearer'),
    'min_arc_radius': (0.2, '... but never onto an arc tighter than this (no pivot on the spot)'),
    # Finding the wall on the right
    'wall_sector_deg': (60.0, 'half width of the sector around the right searched for the wall'),
    'wall_seed_deg': (20.0, 'half width of the sector around the right that seeds the fit'),
    'wall_fit_range': (0.8, 'hits farther than this are not taken for the wall on the right'),
    'wall_inlier_distance': (0.025, 'hits this near the seed line belong to the wall'),
    'wall_min_points': (6, 'fewest hits that make a wall'),
    'wall_max_residual': (0.025, 'RMS misfit above which the hits are no straight wall'),
    'wall_seed_support': (0.6, 'share of the seed hits the wall line must still pass through'),
    'wall_lost_distance': (0.45, 'a wall farther than this is not followed'),
    # Inner corners: a wall ahead
    'corridor_half_width': (0.14, 'half width of the lane ahead searched for a wall ahead'),
    'ahead_range': (1.0, 'walls ahead are looked for up to this far'),
    'ahead_min_angle_deg': (30.0, 'a wall ahead must cross the heading at least this steeply'),
    'inner_corner_radius': (0.09, 'radius of the left turn onto a wall ahead, between its wide arcs'),
    'wide_start_deg': (30.0, 'first part of that turn, flown at cruise speed on its widest arc'),
    'wide_end_deg': (30.0, 'last part of that turn, flown the same way'),
    'wide_allowance': (0.015, 'the wide start may carry the robot this far past target_distance'),
    'short_turn_cut_deg': (5.0, 'a wide start cut by more than this: fly the short-wall turn below'),
    'short_turn_radius': (0.16, 'radius of that turn (after a short wall), between its wide arcs'),
    'short_wide_start_deg': (20.0, 'first part of the short-wall turn, on its widest arc'),
    'short_wide_end_deg': (25.0, 'last part of the short-wall turn, the same way'),
    'approach_range': (0.8, 'a wall ahead this near: ride nearer by the wide start\'s drift'),
    'inner_corner_distance': (0.22, 'distance from the wall ahead at which that turn ends'),
    'turn_lead': (0.015, 'start the turn this much early, for the scan and command delay'),
    'settle_time': (3.0, 'after that turn, the distance gain is raised for this long (s) ...'),
    'settle_gain': (1.5, '... by this factor, to bring the robot back out to target_distance'),
    'front_turn_distance': (0.38, 'anything nearer in the lane ahead starts the left turn'),
    'front_clear_distance': (0.6, 'the turn goes on while anything in the lane is nearer'),
    'front_stop_distance': (0.2, 'anything nearer in the lane ahead: turn on the spot'),
    # Outer corners: the right wall ends
    'outer_corner_radius': (0.27, 'radius of the arc round a corner\'s tip, between wide arcs'),
    'outer_wide_start_deg': (25.0, 'first part of that turn, flown at cruise speed on its widest arc'),
    'outer_wide_end_deg': (40.0, 'last part of that turn as planned, flown the same way'),
    'outer_turn_lead': (-0.005, 'start the turn round a wall\'s end this much early (negative: late)'),
    'outer_wide_tolerance': (0.03, 'the wide start is flown even this far inside the tip\'s arc'),
    'circling_speed_share': (0.9, 'circling a hit: share of the speed at max_turn_rate (turn headroom)'),
    'corner_gate': (0.1, 'the corner tip is looked for this near where it is expected'),
    'corner_bearing_deg': (30.0, 'after a left turn, circle a wall end only this near the right'),
    'rejoin_ahead': (0.15, 'after a corner, follow a wall seen at least this far ahead ...'),
    'rejoin_angle_deg': (40.0, '... and within this angle of the heading'),
    'arc_exit_angle_deg': (5.0, 'an outer corner arc ends this near parallel to the next wall'),
    # No wall near
    'search_speed': (0.15, 'forward speed while no wall is near'),
}


class FollowerParams(object):
    """The controller's parameters, defaults from PARAMETERS, overridable by name.

    An unknown name is an error rather than silently ignored, so that a typo
    in a YAML file shows up instead of leaving a default in force.
    """

    def __init__(self, **overrides):
        unknown = set(overrides) - set(PARAMETERS)
        if unknown:
            raise ValueError('unknown follower parameter(s): %s' % ', '.join(sorted(unknown)))
        for name, (default, _) in PARAMETERS.items():
            setattr(self, name, type(default)(overrides.get(name, default)))

    @staticmethod
    def defaults():
        """name -> default, e.g. for reading them as ROS private parameters."""
        return dict((name, default) for name, (default, _) in PARAMETERS.items())


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
        self.params = params or FollowerParams()
        self.state = SEARCH
        self.command = Command(0.0, 0.0)
        self.inner_corner = InnerCorner(self.params)
        self.outer_corner = OuterCorner(self.params, self.inner_corner)
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

    def update(self, view, stamp=None):
        """Advance the state machine on a ScanView; returns the next Command.

        stamp: the scan's time [s]. The time since the last scan tells how
        far the robot has turned round a corner; without stamps the scans
        are taken to be latency apart. The command stays within
        cruise_speed and max_turn_rate; the node still clamps it to the
        robot's limits.
        """
        p = self.params
        dt = p.latency if stamp is None or self._stamp is None else stamp - self._stamp
        self._stamp = stamp
        obs = Observation(view, p, self.command)
        if self.state != WALL_AHEAD:
            # Until it is flown, the turn onto a wall ahead is planned afresh at every scan.
            self.inner_corner.plan(obs)
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
        """A wall ahead within reach interrupts any manoeuvre; else the state's own transition."""
        if self.inner_corner.needed(obs):
            return WALL_AHEAD
        return self._transitions[self.state](obs)

    def _from_follow(self, obs):
        """Follow on until the wall ends where the turn round its end starts, then round it."""
        if not self.follow_wall.done(obs):
            return FOLLOW
        if self._near(obs):
            return OUTER_CORNER
        return self._wall_or_search(obs)

    def _from_wall_ahead(self, obs):
        """Turn on until the wall ahead has come round to the right.

        Only the end of a wall beside the robot (a short wall, a box) can
        end the turn otherwise: anything near behind it only means the
        turn is not over yet.
        """
        if self.inner_corner.done(obs):
            return FOLLOW
        if obs.ahead is not None or obs.front < self.params.front_clear_distance:
            return WALL_AHEAD
        if self._near(obs):
            return OUTER_CORNER if self._beside(obs.nearest) else WALL_AHEAD
        return self._wall_or_search(obs)

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

    def _beside(self, hit):
        """True when a (distance, bearing) hit is within corner_bearing_deg of the right."""
        off_right = abs(float(wrap_angle(hit[1] - RIGHT)))
        return off_right <= math.radians(self.params.corner_bearing_deg)
