"""FOLLOW: a PD law on the distance and angle of the straight wall on the right.

The course's rule is bang-bang on one ray; a PD law on a wall fitted
through many beams holds the band without its zig-zag. Heading into the
wall, the robot slows to the arc that still turns parallel in time, and
heading away from it, to the arc that turns back parallel in time. What
stands out of the wall toward the robot just ahead (the face of the wall
it meets at its end) is held at target_distance too, unless a wall lies
across the way, which the left turn onto it is planned for.
"""
import math

from wall_follower.control.following.manoeuvre import Manoeuvre
from wall_follower.control.motion import Command
from wall_follower.control.sensing.wall_fit import from_centre


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
        proud = 0.0 if self.inner_corner.blocking(obs) else obs.proud
        gain = p.settle_gain if self.settling > 0.0 else 1.0
        turn = steer(p, distance - proud, angle, p.target_distance - dip, gain)
        speed = p.cruise_speed * (1.0 - p.turn_slowdown * min(1.0, abs(turn) / p.max_turn_rate))
        from_rotation_centre = from_centre(obs.wall, p.laser_x).distance
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
