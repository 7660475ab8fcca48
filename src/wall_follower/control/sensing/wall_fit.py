"""The follower's walls: fitted by consensus through the hits, and seen as a turn plans them.

The follower's walls are Lines (lines.py) whose angle is measured from the
right: 0 for a wall parallel on the right, > 0 when the robot heads into
it, pi/2 for a wall square across the way ahead. Every function here takes
and returns them so.

walls.py cuts the whole scan into walls for the finder, which picks one
and tracks it; the follower instead asks, at every scan, for the one
straight wall through the hits in a sector, which a consensus fit finds
even where a stray beam, an obstacle or the other leg of a corner lies in
that sector too.
"""
import math
from collections import namedtuple

import numpy as np

from wall_follower.control.sensing.lines import Line, consensus_line, fit_line
from wall_follower.control.sensing.scan import RIGHT
from wall_follower.rotation import wrap_angle


class Standing(namedtuple('Standing', ['depth', 'reach'])):
    """What stands out of a wall toward the robot ahead (proud_of).

    depth: how far, past wall_inlier_distance (m; 0 for nothing); reach:
    the x of the farthest hit ahead that stands out that far, within
    wall_inlier_distance (-inf for none): how far ahead a step's top runs.
    """

    __slots__ = ()


NOTHING_STANDS_OUT = Standing(0.0, -math.inf)


def right_wall(points, params):
    """(the Line, (x, y) of its farthest hit ahead, (x, y) of the farthest hit ahead it runs
    on to (wall_runs_to), what stands out of it toward the robot ahead (proud_of)) of the
    wall on the right, or None, None, None, NOTHING_STANDS_OUT.

    Seeded by the hits from straight right to wall_seed_ahead ahead of it:
    the wall the robot is about to drive along. Hits behind the right would
    seed the wall being left: past a bend of less than a right angle (a
    wall that turns away by 30 degrees, say) they outnumber the next wall's
    while the robot passes the bend, and a line through both, turned half
    way between them, steers the robot off both. Where those hits hold no
    wall that runs on at least rejoin_ahead ahead of the laser (the end of
    a wall beside the robot, whose next wall lies across the sector, or a
    corner's tip standing out of it), the wall is seeded by the hits within
    wall_seed either side of straight right instead. The other leg of a
    corner, or an obstacle, in the wider sector is not averaged in either
    way.
    """
    ahead_of_right = wrap_angle(np.arctan2(points[:, 1], points[:, 0]) - RIGHT)
    fit = _seeded_wall(
        points, (ahead_of_right >= 0.0) & (ahead_of_right <= params.wall_seed_ahead), params)
    if fit is None or fit.end[0] < params.rejoin_ahead:
        fit = _seeded_wall(points, np.abs(ahead_of_right) <= params.wall_seed, params) or fit
    if fit is None:
        return None, None, None, NOTHING_STANDS_OUT
    return (fit.wall, fit.end, wall_runs_to(fit.line, fit.offsets, fit.end, points, params),
            proud_of(fit.offsets, points, fit.wall.distance, params))


SeededWall = namedtuple('SeededWall', ['wall', 'line', 'offsets', 'end'])


def _seeded_wall(points, seeded, params):
    """The SeededWall (the wall's Line, its line in the laser's frame, the points' offsets
    from it, its farthest inlier ahead) of the straight wall through most of the seeded
    points, or None (also when farther than wall_lost_distance)."""
    wall = wall_through(points[seeded], points, params)
    if wall is None or wall.distance > params.wall_lost_distance:
        return None
    line = in_laser_frame(wall)
    offsets = line.offsets(points)
    inliers = points[np.abs(offsets) < params.wall_inlier_distance]
    return SeededWall(wall, line, offsets, inliers[np.argmax(inliers[:, 0])])


def proud_of(offsets, points, distance, params):
    """The Standing of the points ahead out of a wall toward the robot (offsets: theirs from
    the wall's line; distance: the wall's).

    The end of a wall can stick out of its line (the face of the wall it
    meets, a door frame): the line holds the robot at target_distance
    from the wall, and the robot passes the end nearer than that. Only
    points that also lie nearer the robot's side than the wall count, as
    far as a heading up to wall_continue_angle off the wall can tell: a
    wall turned farther away behind the right has its line run far out to
    the right ahead, and the next wall (across the end of an obtuse inner
    corner, say) stands out of that line without being any nearer. The
    second farthest hit counts, and the second farthest ahead of those
    that stand out as far, so that one stray beam cannot move the robot.
    Only points ahead of the rotation centre count (the laser sits
    laser_x ahead of it): the robot comes no nearer to a point beside or
    behind the centre on any arc at least as wide as the point is near.
    Counted, the tip of a corner just rounded, beside the robot with the
    next wall set back beyond a short side, held the robot off that wall
    and out of the band.
    """
    ahead = points[:, 0] > -params.laser_x
    nearer_than_wall = distance + points[:, 1] + points[:, 0] * math.tan(params.wall_continue_angle)
    toward = -offsets
    standing = ahead & (nearer_than_wall > params.wall_inlier_distance) & (
        toward > params.wall_inlier_distance)
    if np.count_nonzero(standing) < 2:
        return NOTHING_STANDS_OUT
    deepest = float(np.partition(toward[standing], -2)[-2])
    top = standing & (toward >= deepest - params.wall_inlier_distance)
    reach = float(np.partition(points[top, 0], -2)[-2]) if np.count_nonzero(top) > 1 else -math.inf
    return Standing(deepest - params.wall_inlier_distance, reach)


def wall_runs_to(line, offsets, end, points, params):
    """The farthest of points ahead that the wall along line (in the laser's frame; offsets:
    the points' from it) runs on to from end, its farthest inlier ahead.

    On a wall slanted to Stage's grid the hits form a saw-tooth, a whole
    cell deep, and the line fitted through a few teeth is tilted off the
    wall: its inliers stop short of the wall's end. The hits ahead of end
    still follow the wall, each within wall_continue_gap of the one
    before, and never farther beyond the line than wall_inlier_distance
    and wall_continue_angle allow; the wall runs on over them. Past a
    wall's real end the next hits lie on a wall farther away or beyond a
    bend sharper than that angle, or there are none.
    """
    tangent = np.array((-line.normal[1], line.normal[0]))
    if tangent[0] < 0.0:
        tangent = -tangent
    along = points.dot(tangent)
    start = float(np.dot(end, tangent))
    slope = math.tan(params.wall_continue_angle)
    for index in sorted(np.flatnonzero(along > start), key=lambda index: along[index]):
        hit = points[index]
        if (math.hypot(*(hit - end)) > params.wall_continue_gap
                or offsets[index] > params.wall_inlier_distance + (along[index] - start) * slope):
            break
        end = hit
    return end


def wall_beyond(points, tip, along, params):
    """The Line (angle from the right) of the straight wall through the points beyond the
    end of a wall, from its tip on, or None.

    tip: (x, y) of that wall's end; along: its direction of travel. Round
    an outer corner the wall fitted on the right stays the one that ended
    until the robot has turned most of the way: the hits straight to the
    right that seed it are that wall's, and its saw-tooth outnumbers the
    next one's. The next wall already shows among the hits farther than
    wall_inlier_distance beyond the ended wall's line, and it meets that
    wall at the tip: its line passes within corner_gate of it.
    """
    along = np.asarray(along, dtype=float) / math.hypot(*along)
    toward = np.array((-along[1], along[0]))
    beyond = points[(points - tip).dot(toward) < -params.wall_inlier_distance]
    wall = wall_through(beyond, beyond, params)
    if wall is None:
        return None
    line = in_laser_frame(wall)
    return wall if abs(line.offsets(np.asarray(tip)[None, :])[0]) <= params.corner_gate else None


def wall_through(seed, points, params):
    """The Line of the straight wall through most of the seed hits, or None.

    The line through most of the seed is refitted through every hit of
    points that lies near it, and must then be straight (small residual)
    and still pass through most of the seed.
    """
    first = consensus_line(seed, params.wall_inlier_distance, params.wall_min_points)
    if first is None:
        return None
    inliers = points[np.abs(first.offsets(points)) < params.wall_inlier_distance]
    fit = fit_line(inliers, params.wall_min_points)
    if fit is None:
        return None
    residual = float(np.sqrt(np.mean(fit.offsets(inliers) ** 2)))
    kept = np.abs(fit.offsets(seed)) < params.wall_inlier_distance
    if residual > params.wall_max_residual or kept.mean() < params.wall_seed_support:
        return None
    return Line(fit.distance, float(wrap_angle(fit.angle - RIGHT)))


def same_line(first, second, max_angle=math.radians(15.0), max_distance=0.05):
    """True when two walls are one and the same, within fit error."""
    return (abs(float(wrap_angle(first.angle - second.angle))) < max_angle
            and abs(first.distance - second.distance) < max_distance)


def in_laser_frame(wall):
    """The Line of a wall measured from the right as the laser frame has it: its normal's
    angle from ahead, the normal pointing from the laser toward the wall."""
    return Line(wall.distance, wall.angle + RIGHT)


def along_the_way(wall, max_angle):
    """True for a wall within max_angle (rad) of parallel; False for None."""
    return wall is not None and abs(wall.angle) < max_angle


def from_centre(wall, laser_x):
    """The wall seen by the laser, as the rotation centre has it.

    A turn is an arc of the rotation centre, so that is the distance it must
    be planned by. Heading into a wall at angle, the centre is nearer it
    than the laser by -laser_x * sin(angle): on a Burger (laser 32 mm
    behind the centre) 32 mm when heading square at a wall ahead, nothing
    once parallel. Angles past a right angle count as a right angle.
    """
    return Line(wall.distance + laser_x * math.sin(min(wall.angle, math.pi / 2)), wall.angle)


def as_planned(ahead, wall=None):
    """The wall ahead that a left turn is planned for.

    A wall ahead at more than a right angle is rare in rooms, but common in
    the fit of a short wall's few hits, a box's side say, whose angle is
    the uncertain part: the hits pin down where the wall crosses the way
    ahead, while a tilted fit brings its foot (the perpendicular distance)
    nearer, and would start the turn early. Such a wall counts as a square
    wall where its line crosses the way: square to the way itself, or, when
    the robot heads into the wall on its right, square to that wall. That
    is common while riding nearer before the turn, and after an outer
    corner, whose arc hands over still turning right: the turn then has
    those degrees more to go, and flown at its start, wide, they carry the
    robot nearer the wall ahead (see LeftTurn.gap).
    """
    if ahead.angle <= math.pi / 2:
        return ahead
    into = max(0.0, wall.angle) if wall is not None else 0.0
    return Line(ahead.distance / max(math.sin(ahead.angle), 1e-6) * math.cos(into),
                math.pi / 2 + into)
