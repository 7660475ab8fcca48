"""Right-hand wall following as a plain state machine: a scan in, a command out.

The course's rule is bang-bang on one ray (too far: turn right, too near:
turn left, in the band: straight, wall ahead: turn left). Here the same
behaviour comes from a PD law on the wall's distance and angle, the wall
being a line fitted through many beams, which holds the band without the
zig-zag of the bang-bang rule. Corners get their own states because a wall
fit cannot see them coming:

- a wall ahead (inner corner) is turned onto at the full turn rate: wide
  at first, nearly pivoting past the corner, and wide again onto parallel
  (see left_turn.py). Time is lost only in proportion to how much tighter
  than the wide arc the robot turns, so a short pivot costs less than a
  long tight arc. The speed is re-planned from the wall ahead at every
  scan, so the turn is closed-loop, not timed; its wide end, once the new
  wall is on the right, is flown by FOLLOW's rule for heading into a
  wall: at cruise speed as far as closest_distance allows. That lands it
  nearer than target_distance on purpose, an error well above the laser's
  noise, so for settle_time after the turn the distance gain is raised by
  settle_gain to bring it back out sooner. While such a
  wall comes up, the robot rides a little nearer the old wall, by as much
  as the wide start will carry it off beyond wide_allowance. A turn begun
  without that room (after a short wall) flies short_turn instead: a
  shorter wide start and a tight arc rather than a pivot;
- a wall that ends on the right (outer, convex corner) is rounded on a
  wide arc, an arc round the corner's tip and a wide arc again (see
  corner.py); the middle arc is pinned to the tip at every scan, and the
  last one starts where it will end at the planned distance from the next
  wall (nearer, by the dip, when that wall is a short side with a wall
  across its end), and then goes on. A corner that comes up with no wall
  fitted (the end of a box's short side, mid-turn) is circled instead.

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

from wall_follower.control.corner import CornerArc, OuterTurn
from wall_follower.control.left_turn import LeftTurn
from wall_follower.control.motion import Command
from wall_follower.control.observation import Observation
from wall_follower.control.scan import RIGHT, wrap_angle
from wall_follower.control.wall_fit import along_the_way, as_planned, from_centre, same_line

FOLLOW = 'FOLLOW'
WALL_AHEAD = 'WALL_AHEAD'
OUTER_CORNER = 'OUTER_CORNER'
SEARCH = 'SEARCH'

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
    right). The last command is kept, to judge the next scan where the
    robot will be when that command takes effect; arc is the CornerArc
    being driven round an outer corner, or None, and starting_wide whether
    that corner's turn is still in its wide start (only a turn begun from
    following the wall has one, and once over it does not come back),
    ending_wide whether it has begun its wide end (which, once begun, goes
    on: the tip's position jitters by a grid cell from scan to scan).
    left_turn is the turn onto a wall ahead as configured, and turn the
    one in force: planned afresh at each scan from the distance to the
    right wall, and kept while it is flown.
    """

    def __init__(self, params=None):
        self.params = params or FollowerParams()
        self.state = SEARCH
        self.command = Command(0.0, 0.0)
        self.arc = None
        self.starting_wide = False
        self.ending_wide = False
        p = self.params
        wide_radius = p.cruise_speed / p.max_turn_rate
        self.left_turn = LeftTurn(p.inner_corner_radius, wide_radius, math.radians(p.wide_start_deg),
                                  math.radians(p.wide_end_deg))
        self.short_turn = LeftTurn(p.short_turn_radius, wide_radius,
                                   math.radians(p.short_wide_start_deg),
                                   math.radians(p.short_wide_end_deg))
        self.right_turn = OuterTurn(p.outer_corner_radius, wide_radius,
                                    math.radians(p.outer_wide_start_deg),
                                    math.radians(p.outer_wide_end_deg), p.target_distance,
                                    p.outer_wide_tolerance)
        self.turn = self.left_turn
        self.settling = 0.0   # seconds left of settle_gain after a turn onto a wall ahead
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
            self.turn = self._turn_from(obs)
        previous, self.state = self.state, self._next_state(obs)
        self.settling = p.settle_time if self.state == WALL_AHEAD else max(0.0, self.settling - dt)
        self._track_corner(obs, previous, dt)
        speed, turn = getattr(self, '_cmd_' + self.state.lower())(obs)
        self.command = Command(min(max(speed, 0.0), p.cruise_speed),
                               min(max(turn, -p.max_turn_rate), p.max_turn_rate))
        return self.command

    def _next_state(self, obs):
        p = self.params
        near = obs.nearest is not None and obs.nearest[0] < p.wall_lost_distance
        if obs.front < p.front_turn_distance or self._turn_due(obs):
            return WALL_AHEAD
        if self.state == WALL_AHEAD:
            # Turn on until the wall ahead has come round to the right. Only
            # the end of a wall beside the robot (a short wall, a box) can
            # end the turn otherwise: anything near behind it only means the
            # turn is not over yet.
            if self._rejoined(obs, p.rejoin_angle_deg) and not self._blocking(obs):
                return FOLLOW
            if obs.ahead is not None or obs.front < p.front_clear_distance:
                return WALL_AHEAD
            if near and self._beside(obs.nearest):
                return OUTER_CORNER
            if near:
                return WALL_AHEAD
        elif self.state == OUTER_CORNER:
            # An arc ends where it was planned to, nearly parallel to the next
            # wall; circling a hit has no such end, and takes any wall.
            exit_deg = p.arc_exit_angle_deg if self.arc is not None else p.rejoin_angle_deg
            if self._rejoined(obs, exit_deg):
                return FOLLOW
        elif (obs.wall is not None
              and obs.wall_ahead + p.laser_x > self.right_turn.lead + p.outer_turn_lead):
            # The wall goes on past where the arc round its end starts.
            return FOLLOW
        if near and self.state != SEARCH:
            return OUTER_CORNER
        if obs.wall is not None:
            return FOLLOW
        return SEARCH

    def _beside(self, hit):
        """True when a (distance, bearing) hit is within corner_bearing_deg of the right."""
        off_right = abs(float(wrap_angle(hit[1] - RIGHT)))
        return off_right <= math.radians(self.params.corner_bearing_deg)

    def _turn_due(self, obs):
        """True once the planned left turn would end on the wall ahead."""
        p = self.params
        if not self._blocking(obs):
            return False
        distance, angle = self._ahead_as_planned(obs)
        return self.turn.gap(angle) >= distance - p.turn_lead - p.inner_corner_distance

    def _ahead_as_planned(self, obs):
        """The wall ahead as the left turn is planned for it: see as_planned and from_centre."""
        return from_centre(self._ahead_square_to_right(obs), self.params.laser_x)

    def _ahead_square_to_right(self, obs):
        """as_planned of the wall ahead, squared to the wall on the right if that is along the way.

        A right wall fitted farther off parallel is mid-corner, not the
        wall the one ahead meets.
        """
        wall = obs.wall if along_the_way(obs.wall, self.params.rejoin_angle_deg) else None
        return as_planned(obs.ahead, wall)

    def _turn_from(self, obs):
        """The left turn to fly from here: its wide start ends at most wide_allowance past target.

        A robot that has not ridden nearer first (a short wall left no
        room) would cut the wide start of left_turn short, and then fly
        its near pivot for most of the turn: short_turn, tight but not a
        pivot, is faster there.
        """
        if obs.wall is None:
            return self.left_turn
        p = self.params
        allowed = p.target_distance + p.wide_allowance - from_centre(obs.wall, p.laser_x)[0]
        turn = self.left_turn.drifting_at_most(allowed)
        if turn.wide_start < self.left_turn.wide_start - math.radians(p.short_turn_cut_deg):
            turn = self.short_turn.drifting_at_most(allowed)
        return turn

    def _approach_dip(self, obs, still_turning=0.0):
        """How much nearer to ride while a wall across the way is within approach_range.

        As much as the wide start of the turn onto that wall will drift,
        less what it may drift past target_distance (wide_allowance).
        still_turning: how far (rad) the robot turns right before that turn
        starts, which adds to the wall's angle.
        """
        if not self._blocking(obs):
            return 0.0
        distance, angle = self._ahead_square_to_right(obs)
        if distance >= self.params.approach_range:
            return 0.0
        return max(0.0, self.left_turn.drift(angle + still_turning) - self.params.wide_allowance)

    def _blocking(self, obs):
        """True when a wall lies across the way ahead (not the right wall seen ahead)."""
        steep = math.radians(self.params.ahead_min_angle_deg)
        if obs.ahead is None or not steep <= obs.ahead[1] <= math.pi - steep:
            return False  # none, or one nearly along the way (beside the lane)
        return obs.wall is None or not same_line(obs.ahead, obs.wall)

    @staticmethod
    def _arc_radius(gap, angle):
        """Radius of the left arc that turns parallel to a wall within gap of it.

        Heading into a wall at angle needs a turn through angle; an arc of
        radius r comes r * (1 - cos(angle)) nearer the wall meanwhile, hence
        r = gap / (1 - cos(angle)). Angles past a right angle count as a
        right angle, at the same gap.
        """
        return max(0.0, gap) / max(1.0 - math.cos(min(angle, math.pi / 2)), 1e-6)

    def _rejoined(self, obs, max_angle_deg):
        """True when a corner is over: a straight wall on the right, nearly parallel."""
        return along_the_way(obs.wall, max_angle_deg) and obs.wall_ahead > self.params.rejoin_ahead

    def _steer(self, distance, angle, target, gain=1.0):
        """PD turn rate holding a wall at distance target and parallel (gain: on the distance)."""
        p = self.params
        return -gain * p.k_distance * (distance - target) + p.k_angle * angle

    def _cmd_follow(self, obs):
        p = self.params
        distance, angle = obs.wall
        # The wide start of a left turn carries the robot off this wall:
        # riding that much nearer before it keeps the turn's middle in band.
        dip = self._approach_dip(obs)
        gain = p.settle_gain if self.settling > 0.0 else 1.0
        turn = self._steer(distance, angle, p.target_distance - dip, gain)
        speed = p.cruise_speed * (1.0 - p.turn_slowdown * min(1.0, abs(turn) / p.max_turn_rate))
        if angle > 0.0:
            # Heading into the wall: no faster than the arc that still turns
            # parallel before coming nearer than closest_distance.
            room = from_centre(obs.wall, p.laser_x)[0] - p.closest_distance + dip
            radius = max(p.min_arc_radius, self._arc_radius(room, angle))
            if radius * p.max_turn_rate < speed:
                # That arc is flown at the full turn rate, the way it was planned.
                speed, turn = radius * p.max_turn_rate, p.max_turn_rate
        return Command(speed, turn)

    def _cmd_wall_ahead(self, obs):
        """Turn left at full rate, on the planned turn that ends parallel to the wall ahead.

        Closed loop on the wall ahead: the speed is set each update to the
        radius still needed, so a late start slows the robot down instead of
        carrying it too close, and a wall too near is turned from on the spot.
        """
        p = self.params
        radius = p.inner_corner_radius
        if obs.ahead is not None:
            distance, angle = self._ahead_as_planned(obs)
            radius = self.turn.radius_within(distance - p.inner_corner_distance, angle)
        if obs.front < p.front_stop_distance:
            radius = 0.0
        return Command(radius * p.max_turn_rate, p.max_turn_rate)

    def _track_corner(self, obs, previous, dt):
        """Start the arc round an outer corner, or move it on, or drop it after the corner.

        The wide start, once over, stays over, and the wide end, once begun,
        goes on (see starting_wide and ending_wide).
        """
        if self.state != OUTER_CORNER:
            self.arc = None
        elif previous != OUTER_CORNER:
            self.arc = self._corner_arc(obs)
            self.starting_wide = previous == FOLLOW
            self.ending_wide = False
        elif self.arc is not None:
            self.arc.moved(self.command.linear * dt, self.command.angular * dt)
            self.arc.observe(obs.right, self.params.corner_gate)
        if self.arc is not None:
            self.starting_wide = self.starting_wide and self.right_turn.starts_wide(
                self.arc.turned(), self.arc.offset()[0])
            # A wall across the way just past the corner (beyond a pillar's
            # short side) leaves no room to ride nearer before the turn onto
            # it: the corner lands that much nearer the side instead.
            nearer = self._approach_dip(obs, math.pi / 2 - self.arc.turned())
            self.ending_wide = self.ending_wide or self.right_turn.ends_wide(
                self.arc.turned(), self.arc.past_tip(), nearer)

    def _corner_arc(self, obs):
        """The arc round the end of the wall that just ended; None without such a wall.

        Without it (the corner comes up in the middle of a left turn, at
        the end of a short wall or a box's side) which way the corner points
        is unknown, and the robot circles the nearest hit instead. A wall
        fitted far off parallel (beyond rejoin_angle_deg) is not the one
        that ended either: mid-turn onto a box's short side, it is the wall
        the turn left behind, and an arc pinned to its end would circle a
        point nowhere near the corner.
        """
        if not along_the_way(obs.wall, self.params.rejoin_angle_deg):
            return None
        angle = obs.wall[1]
        return CornerArc(obs.wall_end, (math.cos(angle), math.sin(angle)), self.right_turn.center,
                         self.params.laser_x)

    def _cmd_outer_corner(self, obs):
        p = self.params
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
        turn = -speed / radius + self._steer(distance, float(wrap_angle(bearing - RIGHT)), radius)
        return Command(speed, turn)

    def _cmd_search(self, obs):
        return Command(self.params.search_speed, 0.0)
