"""What one scan tells the wall follower, measured once per update for every manoeuvre."""
import math

import numpy as np

from wall_follower.control.motion import seen_after_move
from wall_follower.control.sensing.scan import RIGHT
from wall_follower.control.sensing.wall_fit import (in_laser_frame, proud_of, right_wall,
                                                    wall_through)
from wall_follower.rotation import wrap_angle


class Observation(object):
    """What one scan tells the controller.

    wall: the straight wall on the right (a Line, angle from the right, > 0
    when the robot heads into it), or None. wall_end: (x, y) of that wall's
    farthest hit ahead, and wall_ahead its x: how far ahead of the laser
    the wall is still seen (-inf without a wall). wall_tip: (x, y) of the
    farthest hit ahead it runs on to, past a saw-tooth that the line
    misses (wall_fit.wall_runs_to), where a turn round its end would
    begin; wall_runs its x (-inf without a wall). proud: how far the hits
    ahead in the wall's sector stand out of it toward the robot, and
    proud_reach the x of the farthest that stand out as far
    (wall_fit.proud_of; 0 and -inf without). beside: the Standing
    (depth, reach) of the same, but only of the hits that stand more than
    clear_margin out and lie clearly nearer than the wall across the way
    (ahead), whose face stands out of the right wall's line where the two
    meet (standing_beside; proud and proud_reach without a wall ahead).
    right: every hit on the right side. front: distance to the nearest hit
    in the lane the robot is about to drive through; front_wide: the same
    in that lane widened by clear_margin each side; front_wide_off_wall:
    the same, leaving out the hits at that lane's right edge that are the
    right wall's own (on_wall_at_lane_edge); front_on_arc: the same of the
    hits in the lane that the arc of motion sweeps as well (in_arc_lane).
    ahead: the straight wall across that lane (a Line measured like the
    right wall: pi/2 for a wall square ahead), or None. nearest:
    (distance, bearing) of the closest hit on the right side, or None.
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
        self.wall, self.wall_end, self.wall_tip, standing = right_wall(sector, params)
        self.proud, self.proud_reach = standing
        self.wall_ahead = self.wall_end[0] if self.wall_end is not None else -math.inf
        self.wall_runs = self.wall_tip[0] if self.wall_tip is not None else -math.inf
        self.right = hits[off_right <= math.pi / 2]
        front = hits[hits[:, 0] > 0.0]
        across = np.abs(front[:, 1])
        lane = front[across <= params.corridor_half_width]
        self.front = second_smallest(lane[:, 0])
        self.front_on_arc = second_smallest(
            lane[in_arc_lane(lane, motion, params.laser_x, params.corridor_half_width)][:, 0])
        wide = front[across <= params.corridor_half_width + params.clear_margin]
        self.front_wide = second_smallest(wide[:, 0])
        self.front_wide_off_wall = self.front_wide if self.wall is None else second_smallest(
            wide[~on_wall_at_lane_edge(wide, self.wall, params)][:, 0])
        self.ahead = wall_through(lane[lane[:, 0] < params.ahead_range], front, params)
        self.beside = standing if self.wall is None or self.ahead is None else standing_beside(
            sector, self.wall, self.ahead, params)
        self.nearest = nearest_in(self.right)

    def rejoined(self, max_angle, min_ahead, heading_in=0.0):
        """True when a corner is over: a straight wall on the right, nearly parallel (or heading
        into it by heading_in, rad).

        Nearly: within max_angle (rad); and seen at least min_ahead ahead of the laser.
        """
        return (self.wall is not None and abs(self.wall.angle - heading_in) < max_angle
                and self.wall_ahead > min_ahead)


def unbiased(points, bias):
    """Hits moved bias metres nearer the laser along their beams.

    Stage raytraces in whole grid cells and so reads a wall long, on
    average by a fraction of its map resolution (the range_bias parameter's
    default is that average at Stage's default resolution); a laser that
    reads true wants bias 0.
    """
    ranges = np.hypot(points[:, 0], points[:, 1])
    scale = np.maximum(ranges - bias, 0.0) / np.maximum(ranges, 1e-9)
    return points * scale[:, None]


def on_wall_at_lane_edge(points, wall, params):
    """Which laser-frame points lie at the lane's right edge (farther right than
    corridor_half_width) and on the right wall (a Line), beyond it, or less than clear_margin
    nearer than it.

    The near side of a wall reads a few centimetres out of its fitted
    line where Stage's grid draws it slanted, or where the wall is rough;
    nearer than that, a hit is something else beside the way.
    """
    return ((points[:, 1] < -params.corridor_half_width)
            & (in_laser_frame(wall).offsets(points) >= -params.clear_margin))


def standing_beside(points, wall, ahead, params):
    """The Standing (wall_fit.proud_of) out of wall toward the robot of those laser-frame
    points that stand more than clear_margin out of it and lie more than
    wall_inlier_distance nearer than the wall across the way (ahead, a Line).

    Where the right wall meets a wall across the way, that wall's face
    stands out of the right wall's line, and the left turn onto it is
    planned for it; so is riding into the few centimetres the right wall's
    own near side reads out of its fitted line (on_wall_at_lane_edge). A
    step, a box or a door frame on the right before the corner stands out
    farther, nearer than that face, and is passed like anything else:
    left out with the face, it held nothing off, and FOLLOW steered the
    robot toward the step's top to hold the wall beyond it.
    """
    offsets = in_laser_frame(wall).offsets(points)
    beside = (offsets < -params.clear_margin) & (
        in_laser_frame(ahead).offsets(points) < -params.wall_inlier_distance)
    return proud_of(offsets[beside], points[beside], wall.distance, params)


def in_arc_lane(points, motion, laser_x, half_width):
    """Which laser-frame points lie within half_width of the arc the rotation centre flies
    under motion (linear [m/s], angular [rad/s]); all of them on an arc no wider than
    half_width, or a straight way.

    The lane straight ahead holds things that a turn carries the robot away
    from: rounding the end of a wall, the robot passed the corner of a
    block ahead on its left a few centimetres outside the lane, but
    Stage drew that corner a grid cell fatter, a noisy beam put it inside,
    and the robot turned left onto the block instead of on round the end.
    On an arc too tight to hold the lane (a pivot) nothing is left out:
    which way the robot goes next is open.
    """
    linear, angular = motion
    if angular == 0.0 or abs(linear) <= half_width * abs(angular):
        return np.ones(len(points), dtype=bool)
    radius = linear / angular
    off_arc = np.hypot(points[:, 0] + laser_x, points[:, 1] - radius) - abs(radius)
    return np.abs(off_arc) <= half_width


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
