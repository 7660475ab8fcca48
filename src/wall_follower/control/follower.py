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

import numpy as np

from wall_follower.control.corner import CornerArc, OuterTurn
from wall_follower.control.left_turn import LeftTurn
from wall_follower.control.motion import Command, seen_after_move
from wall_follower.control.scan import RIGHT, fit_line, wrap_angle
from wall_follower.params import checked
from wall_follower.params.wall_following import FOLLOWER

FOLLOW = 'FOLLOW'
WALL_AHEAD = 'WALL_AHEAD'
OUTER_CORNER = 'OUTER_CORNER'
SEARCH = 'SEARCH'

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


class Observation(object):
    """What one scan tells the controller, measured once per update.

    wall: (distance, angle) of the straight wall on the right, angle > 0
    when the robot heads into it, or None. wall_end: (x, y) of that wall's
    farthest hit ahead, and wall_ahead its x: how far ahead of the laser
    the wall is still seen (-inf without a wall). right: every hit on the
    right side. front: distance to the nearest hit in the
    lane the robot is about to drive through. ahead: (distance, angle) of
    the straight wall across that lane, angle measured like the right
    wall's (pi/2 for a wall square ahead), or None. nearest: (distance,
    bearing) of the closest hit on the right side, or None.
    """

    def __init__(self, view, params, motion=(0.0, 0.0)):
        # A command takes effect a scan period or so after the scan it
        # answers: judging the scan where the robot will be by then, under
        # the command still running, keeps the loop from overshooting.
        hits = seen_after_move(unbiased(view.points(), params.range_bias),
                               motion[0] * params.latency, motion[1] * params.latency,
                               params.laser_x)
        off_right = np.abs(wrap_angle(np.arctan2(hits[:, 1], hits[:, 0]) - RIGHT))
        near = np.hypot(hits[:, 0], hits[:, 1]) < params.wall_fit_range
        sector = hits[(off_right <= params.wall_sector) & near]
        self.wall, self.wall_end = right_wall(sector, params)
        self.wall_ahead = self.wall_end[0] if self.wall_end is not None else -math.inf
        self.right = hits[off_right <= math.pi / 2]
        front = hits[hits[:, 0] > 0.0]
        lane = front[np.abs(front[:, 1]) <= params.corridor_half_width]
        self.front = second_smallest(lane[:, 0])
        self.ahead = wall_through(lane[lane[:, 0] < params.ahead_range], front, params)
        self.nearest = nearest_in(self.right)


def unbiased(points, bias):
    """Hits moved bias metres nearer the laser along their beams.

    Stage raytraces in whole grid cells and so reads a wall long, by about
    0.008 m on average at its default 0.02 m resolution; a laser that reads
    true wants bias 0.
    """
    ranges = np.hypot(points[:, 0], points[:, 1])
    scale = np.maximum(ranges - bias, 0.0) / np.maximum(ranges, 1e-9)
    return points * scale[:, None]


def right_wall(points, params):
    """((distance, angle), (x, y) of its farthest hit ahead) of the wall on the right, or None, None.

    Seeded by the hits straight to the right only, so that the other leg of
    a corner, or an obstacle, in the wider sector is not averaged into it.
    """
    bearings = np.arctan2(points[:, 1], points[:, 0])
    seed = points[np.abs(bearings - RIGHT) <= params.wall_seed]
    wall = wall_through(seed, points, params)
    if wall is None or wall[0] > params.wall_lost_distance:
        return None, None
    line = (wall[0], wall[1] + RIGHT)
    inliers = points[np.abs(offsets_from(points, line)) < params.wall_inlier_distance]
    return wall, inliers[np.argmax(inliers[:, 0])]


def wall_through(seed, points, params):
    """(distance, angle) of the straight wall through most of the seed hits, or None.

    The line through most of the seed is refitted through every hit of
    points that lies near it, and must then be straight (small residual)
    and still pass through most of the seed. angle is that of the wall's
    normal measured from the right: 0 for a wall parallel on the right,
    > 0 when the robot heads into it.
    """
    first = consensus_line(seed, params.wall_inlier_distance, params.wall_min_points)
    if first is None:
        return None
    inliers = points[np.abs(offsets_from(points, first)) < params.wall_inlier_distance]
    fit = fit_line(inliers, params.wall_min_points)
    if fit is None:
        return None
    residual = float(np.sqrt(np.mean(offsets_from(inliers, fit) ** 2)))
    kept = np.abs(offsets_from(seed, fit)) < params.wall_inlier_distance
    if residual > params.wall_max_residual or kept.mean() < params.wall_seed_support:
        return None
    return fit[0], float(wrap_angle(fit[1] - RIGHT))


def consensus_line(points, tolerance, min_points, max_pairs_points=40):
    """Line through points that the most of them lie near (within tolerance), or None.

    Every line through two of the points is a candidate (of at most
    max_pairs_points points spread evenly, to bound the work); the one with
    the most points near it wins and is refitted through them. Unlike a
    plain least-squares fit, a few stray hits (a beam grazing an obstacle's
    side, the other leg of a corner) cannot tilt it.
    """
    if len(points) < max(2, min_points):
        return None
    step = max(1, int(math.ceil(len(points) / float(max_pairs_points))))
    first, second = np.triu_indices(len(points[::step]), 1)
    ends = points[::step]
    along = ends[second] - ends[first]
    length = np.hypot(along[:, 0], along[:, 1])
    usable = length > 1e-9
    normals = np.column_stack((-along[usable, 1], along[usable, 0])) / length[usable, None]
    offsets = points.dot(normals.T) - np.sum(normals * ends[first][usable], axis=1)
    near = np.abs(offsets) < tolerance
    if not near.size:
        return None
    best = int(np.argmax(near.sum(axis=0)))
    return fit_line(points[near[:, best]], min_points)


def offsets_from(points, line):
    """Signed distances of points from line = (distance, normal angle)."""
    distance, angle = line
    return points.dot((math.cos(angle), math.sin(angle))) - distance


def same_line(first, second, max_angle=math.radians(15.0), max_distance=0.05):
    """True when two (distance, angle) walls are one and the same, within fit error."""
    return (abs(float(wrap_angle(first[1] - second[1]))) < max_angle
            and abs(first[0] - second[0]) < max_distance)


def along_the_way(wall, max_angle):
    """True for a (distance, angle) wall within max_angle (rad) of parallel; False for None."""
    return wall is not None and abs(wall[1]) < max_angle


def from_centre(wall, laser_x):
    """The (distance, angle) of a wall seen by the laser, as the rotation centre has it.

    A turn is an arc of the rotation centre, so that is the distance it must
    be planned by. Heading into a wall at angle, the centre is nearer it
    than the laser by -laser_x * sin(angle): on a Burger (laser 32 mm
    behind the centre) 32 mm when heading square at a wall ahead, nothing
    once parallel. Angles past a right angle count as a right angle.
    """
    distance, angle = wall
    return distance + laser_x * math.sin(min(angle, math.pi / 2)), angle


def as_planned(ahead, wall=None):
    """The (distance, angle) of a wall ahead that a left turn is planned for.

    A wall ahead at more than a right angle is rare in rooms, but common in
    the fit of a short wall's few hits, a box's side say, whose angle is
    the uncertain part: the hits pin down where the wall crosses the way
    ahead, while a tilted fit brings its foot (the perpendicular distance)
    nearer, and would start the turn early. Such a wall counts as a square
    wall where its line crosses the way: square to the way itself, or, when
    the robot heads into the (distance, angle) wall on its right, square to
    that wall. That is common while riding nearer before the turn, and
    after an outer corner, whose arc hands over still turning right: the
    turn then has those degrees more to go, and flown at its start, wide,
    they carry the robot nearer the wall ahead (see LeftTurn.gap).
    """
    distance, angle = ahead
    if angle <= math.pi / 2:
        return distance, angle
    into = max(0.0, wall[1]) if wall is not None else 0.0
    return distance / max(math.sin(angle), 1e-6) * math.cos(into), math.pi / 2 + into


def second_smallest(values):
    """The second-smallest value (inf if fewer than two).

    The second, not the first, so that one spurious beam does not count.
    """
    if values.size < 2:
        return math.inf
    return float(np.partition(values, 1)[1])


def nearest_in(points):
    """(distance, bearing) of the second-closest hit, or None.

    The second, so that one spurious beam cannot pull the robot off.
    """
    if len(points) < 2:
        return None
    dist = np.hypot(points[:, 0], points[:, 1])
    x, y = points[np.argpartition(dist, 1)[1]]
    return float(math.hypot(x, y)), float(math.atan2(y, x))


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
        self.state = SEARCH
        self.command = Command(0.0, 0.0)
        self.arc = None
        self.starting_wide = False
        self.ending_wide = False
        self.reconfigure(params or FollowerParams())
        self.turn = self.left_turn
        self.settling = 0.0   # seconds left of settle_gain after a turn onto a wall ahead
        self._stamp = None

    def reconfigure(self, params):
        """Go on under new FollowerParams from the next update on.

        The state is kept; a turn already being flown keeps its plan, and
        the next one is planned with the new parameters.
        """
        self.params = p = params
        wide_radius = p.cruise_speed / p.max_turn_rate
        self.left_turn = LeftTurn(p.inner_corner_radius, wide_radius, p.wide_start, p.wide_end)
        self.short_turn = LeftTurn(p.short_turn_radius, wide_radius, p.short_wide_start,
                                   p.short_wide_end)
        self.right_turn = OuterTurn(p.outer_corner_radius, wide_radius, p.outer_wide_start,
                                    p.outer_wide_end, p.target_distance, p.outer_wide_tolerance)

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
            if self._rejoined(obs, p.rejoin_angle) and not self._blocking(obs):
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
            exit_angle = p.arc_exit_angle if self.arc is not None else p.rejoin_angle
            if self._rejoined(obs, exit_angle):
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
        """True when a (distance, bearing) hit is within corner_bearing of the right."""
        off_right = abs(float(wrap_angle(hit[1] - RIGHT)))
        return off_right <= self.params.corner_bearing

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
        wall = obs.wall if along_the_way(obs.wall, self.params.rejoin_angle) else None
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
        if turn.wide_start < self.left_turn.wide_start - p.short_turn_cut:
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
        steep = self.params.ahead_min_angle
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

    def _rejoined(self, obs, max_angle):
        """True when a corner is over: a straight wall on the right, nearly parallel."""
        return along_the_way(obs.wall, max_angle) and obs.wall_ahead > self.params.rejoin_ahead

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
        fitted far off parallel (beyond rejoin_angle) is not the one
        that ended either: mid-turn onto a box's short side, it is the wall
        the turn left behind, and an arc pinned to its end would circle a
        point nowhere near the corner.
        """
        if not along_the_way(obs.wall, self.params.rejoin_angle):
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
