"""FOLLOW: a PD law on the distance and angle of the straight wall on the right.

The course's rule is bang-bang on one ray; a PD law on a wall fitted
through many beams holds the band without its zig-zag. Heading into the
wall, the robot slows to the arc that still turns parallel in time, and
heading away from it, to the arc that turns back parallel in time. What
stands out of the wall toward the robot just ahead (the face of the wall
it meets at its end) is held at target_distance too, but for the face of
a wall across the way, which the left turn onto it is planned for: what
stands out nearer than that face (a step before the corner) is still
held off. Heading away from a wall that recedes, it is held where the
present heading passes it (passing_distance), not across the wall's
line; but not while settling after a left turn. Beyond farthest_distance
from the wall, the robot dives onto it (dive_angle) instead of gliding in
on the PD law's shallow slope.
"""
import math

from wall_follower.control.following.manoeuvre import Manoeuvre
from wall_follower.control.motion import Command
from wall_follower.control.sensing.wall_fit import from_centre

# The steepest dive onto a wall beyond farthest_distance [rad] (see dive_angle):
# a bound, not a tuned value. Past a tip 0.2 m proud of the next wall, laps
# were the same with it at 45 degrees, 60 or none at all; at 30 the dive came
# down too late, and the wall read 0.33 m off as the tip fell behind. A wall
# met more steeply is one across the way, which the left turn is for.
MAX_DIVE = math.radians(45.0)


class FollowWall(Manoeuvre):
    """Follows the wall on the right until it ends where the turn round its end starts.

    inner_corner: the left turn onto a wall ahead, whose wide start the
    robot rides nearer for; outer_corner: the turn round the wall's end,
    which says where following is over. settling: seconds left of
    settle_gain on the distance after a left turn, which lands the robot
    nearer than target_distance on purpose.
    """

    def __init__(self, params, inner_corner, outer_corner):
        super().__init__(params)
        self.inner_corner = inner_corner
        self.outer_corner = outer_corner
        self.settling = 0.0

    def elapse(self, dt, turning):
        """Hold settling at settle_time while a left turn is flown; let it run down after."""
        self.settling = self.params.settle_time if turning else max(0.0, self.settling - dt)

    def done(self, obs):
        return self.outer_corner.due(obs)

    def command(self, obs):
        p = self.params
        distance, angle = obs.wall
        # The wide start of a left turn carries the robot off this wall:
        # riding that much nearer before it keeps the turn's middle in band.
        dip = self.inner_corner.dip(obs)
        standing = obs.beside if self.inner_corner.blocking(obs) else (obs.proud, obs.proud_reach)
        proud, reach = standing
        gain = p.settle_gain if self.settling > 0.0 else 1.0
        held, heading = distance - proud, angle
        if proud > 0.0 and -math.pi / 2 < angle < 0.0 and self.settling <= 0.0:
            # A wall that recedes: what stands out of it is passed where the
            # present heading passes it. Just after a left turn, the wall
            # headed away from is the one the turn left, and what stands out
            # of it the top of the step the turn was onto, which runs on
            # parallel to it: held across its line, as before.
            held, heading = passing_distance(obs.wall, proud, reach), 0.0
        turn = steer(p, held, heading, p.target_distance - dip, gain)
        from_rotation_centre = from_centre(obs.wall, p.laser_x).distance
        # Far beyond the band, the PD law heads in only k_distance / k_angle
        # radians per metre off, and glided onto a wall 0.44 m off (beyond a
        # tip standing out of it) for 2.7 s, out of the band for 1.5 s of it.
        slope = dive_angle(p, from_rotation_centre - proud, p.target_distance - dip)
        if heading >= 0.0 and slope > 0.0:
            turn = min(turn, p.k_angle * (heading - slope))
        speed = p.cruise_speed * (1.0 - p.turn_slowdown * min(1.0, abs(turn) / p.max_turn_rate))
        if angle > 0.0:
            # Heading into the wall: no faster than the arc that still turns
            # parallel before coming nearer than closest_distance.
            room, way = from_rotation_centre - p.closest_distance + dip, 1.0
        elif angle < 0.0 and turn < 0.0:
            # Heading away from it and turning back: no faster than the arc
            # that turns parallel before going farther than farthest_distance.
            # At cruise speed the full turn rate's arc is too wide to follow a
            # wall that bends away more sharply, or to catch a robot handed
            # over heading off the wall, and it drifted out of the band.
            room, way = p.farthest_distance - from_rotation_centre + proud, -1.0
        else:
            return Command(speed, turn)
        radius = max(p.min_arc_radius, arc_radius(room, abs(angle)))
        if radius * p.max_turn_rate < speed:
            # That arc is flown at the full turn rate, the way it was planned.
            speed, turn = radius * p.max_turn_rate, way * p.max_turn_rate
        return Command(speed, turn)


def passing_distance(wall, depth, reach):
    """How far to the right the present heading passes what stands depth (m) out of wall
    toward the robot, reach (m) ahead of the laser (Observation.proud and proud_reach).

    Its distance across the wall's line, wall.distance - depth, is where
    the robot passes it once turned parallel to that line. Heading away
    from a wall that recedes (angle < 0: a shallow notch, a bend away just
    before a step back in), turning parallel would carry the robot right,
    toward what stands out, since the line runs away from it and it does
    not: held across the line, the step back in ahead of a notch read as
    if beside the robot, and FOLLOW turned left at the full turn rate half
    a metre early, off the notch and out of the band. Along the present
    heading it is passed this much farther out: the line through it,
    parallel to the wall, lies reach * sin(-angle) farther right where it
    is, and across the heading that is 1 / cos(angle) more.
    """
    distance, angle = wall
    return (distance - depth - reach * math.sin(angle)) / math.cos(angle)


def steer(params, distance, angle, target, gain=1.0):
    """PD turn rate holding a wall at distance target and parallel (gain: on the distance)."""
    return -gain * params.k_distance * (distance - target) + params.k_angle * angle


def arc_radius(gap, angle):
    """Radius of the left arc that turns parallel to a wall within gap of it.

    Heading into a wall at angle needs a turn through angle; an arc of
    radius r comes r * (1 - cos(angle)) nearer the wall meanwhile, hence
    r = gap / (1 - cos(angle)). Angles past a right angle count as a
    right angle, at the same gap.
    """
    return max(0.0, gap) / max(1.0 - math.cos(min(angle, math.pi / 2)), 1e-6)


def dive_angle(params, distance, target):
    """How steeply (rad) to head into a wall whose line lies distance (m) from the rotation
    centre, to come onto it at target (m).

    Not at all within farthest_distance. Beyond it, as steeply as the
    widest arc the turn rate allows at cruise speed (cruise_speed /
    max_turn_rate) still turns parallel from at target: an arc of radius r
    turning parallel from heading in by a comes r * (1 - cos(a)) nearer the
    wall. At most MAX_DIVE.
    """
    if distance <= params.farthest_distance:
        return 0.0
    radius = params.cruise_speed / params.max_turn_rate
    return min(MAX_DIVE, math.acos(max(-1.0, 1.0 - max(0.0, distance - target) / radius)))
