"""What one scan tells the wall follower, measured once per update for every manoeuvre."""
import math

import numpy as np

from wall_follower.control.motion import seen_after_move
from wall_follower.control.sensing.lines import Line
from wall_follower.control.sensing.scan import RIGHT
from wall_follower.control.sensing.wall_fit import along_the_way, right_wall, wall_through
from wall_follower.rotation import wrap_angle


class Observation(object):
    """What one scan tells the controller.

    wall: the straight wall on the right (a Line, angle from the right, > 0
    when the robot heads into it), or None. wall_end: (x, y) of that wall's
    farthest hit ahead, and wall_ahead its x: how far ahead of the laser
    the wall is still seen (-inf without a wall). right: every hit on the
    right side. front: distance to the nearest hit in the lane the robot is
    about to drive through; front_wide: the same in that lane widened by
    clear_margin each side. ahead: the straight wall across that lane (a
    Line measured like the right wall: pi/2 for a wall square ahead), or
    None. nearest: (distance, bearing) of the closest hit on the right
    side, or None. protrusion: how far the tip of the corner at the wall's
    end stands out of the wall towards the robot (a stub or a box there;
    see corner_tip), 0 if it does not; wall_end is then that tip.
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
        self.right = hits[off_right <= math.pi / 2]
        front = hits[hits[:, 0] > 0.0]
        across = np.abs(front[:, 1])
        lane = front[across <= params.corridor_half_width]
        self.front = second_smallest(lane[:, 0])
        self.front_wide = second_smallest(
            front[across <= params.corridor_half_width + params.clear_margin][:, 0])
        self.ahead = wall_through(lane[lane[:, 0] < params.ahead_range], front, params)
        self.nearest = nearest_in(self.right)
        self.wall_end, self.protrusion = corner_tip(
            off_the_walls(self.right, self.ahead, params), self.wall, self.wall_end, params)
        self.wall_ahead = self.wall_end[0] if self.wall_end is not None else -math.inf

    def rejoined(self, max_angle, min_ahead):
        """True when a corner is over: a straight wall on the right, nearly parallel.

        Nearly: within max_angle (rad); and seen at least min_ahead ahead of the laser.
        """
        return along_the_way(self.wall, max_angle) and self.wall_ahead > min_ahead


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


def second_smallest(values):
    """The second-smallest value (inf if fewer than two).

    The second, not the first, so that one spurious beam does not count.
    """
    if values.size < 2:
        return math.inf
    return float(np.partition(values, 1)[1])


def off_the_walls(right, ahead, params):
    """The hits ahead on the right that are neither in the lane nor on the wall across it.

    Only hits within pass_lookahead ahead count. Whatever is in the lane
    starts a left turn instead.
    """
    hits = right[(right[:, 0] > 0.0) & (right[:, 0] <= params.pass_lookahead)
                 & (-right[:, 1] > params.corridor_half_width)]
    if ahead is None:
        return hits
    return hits[np.abs(Line(ahead.distance, ahead.angle + RIGHT).offsets(hits))
                >= params.wall_inlier_distance]


def corner_tip(hits, wall, end, params):
    """(tip, protrusion) of the corner at the wall's end: where it is, and how far out of the
    wall towards the robot it stands [m].

    A stub or a box just where the wall ends makes the corner the robot
    has to round, and has to pass: the tip is the hit within tip_reach of
    the wall's end that lies farthest on along the wall and out of it. It
    counts only if it stands out beyond wall_inlier_distance (nearer, it is
    the wall itself), and only if nothing farther from the end stands out
    more (the next wall bending in, or a step in this one: the robot
    follows that as it comes). Otherwise the tip is the wall's end and the
    protrusion 0. The second-farthest hit each time, so that one spurious
    beam does not count.
    """
    if wall is None:
        return end, 0.0
    line = Line(wall.distance, wall.angle + RIGHT)
    along = np.array((-line.normal[1], line.normal[0]))
    out = -line.offsets(hits)
    near = np.hypot(*(hits - end).T) < params.tip_reach
    reach = (hits[near] - end).dot(along - line.normal)
    if reach.size < 2:
        return end, 0.0
    tip = np.argpartition(reach, -2)[-2]
    standing = out[near][tip]
    if reach[tip] <= 0.0 or standing <= params.wall_inlier_distance \
            or second_largest(out[~near]) > standing:
        return end, 0.0
    return hits[near][tip], float(standing)


def second_largest(values):
    """The second-largest value (-inf if fewer than two)."""
    return -second_smallest(-values)


def nearest_in(points):
    """(distance, bearing) of the second-closest hit, or None.

    The second, so that one spurious beam cannot pull the robot off.
    """
    if len(points) < 2:
        return None
    dist = np.hypot(points[:, 0], points[:, 1])
    x, y = points[np.argpartition(dist, 1)[1]]
    return float(math.hypot(x, y)), float(math.atan2(y, x))
