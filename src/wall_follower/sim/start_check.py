"""Whether a world's robots can start where they are put: the checks stage_sim makes before
its first step.

Real Stage runs whatever it is given: a world with no robot steps an empty
clock, and a robot whose body starts across a wall is stalled at every move
(Stage refuses each step that leaves the body touching an obstacle's cells),
so a run from there measures nothing. Neither can be meant, and each is
refused here with the world file and the robot named; so is a robot
outside every wall of the map (beyond the box the obstacles span), which
drives off into nothing, and two robots whose bodies overlap.

"Across a wall" is measured exactly: the body's polygon, taken whole,
meets one of the true outline edges that an obstacle's cells are drawn
from (touching is not meeting), so a small obstacle wholly under the body
counts too. Stage's cells are coarser (a body a centimetre clear of a wall
face can share a cell with it) and real Stage starts such a robot, so a
start is not refused for a shared cell alone; once running, the
simulator's steps are held by the cells, as Stage's are. A robot wholly
inside the interior of a wide obstacle meets none of its edges, as in
Stage, and is not told apart from one in free space.
"""
import numpy as np

from .grid import footprint_corners, footprints_overlap, obstacle_edges

__all__ = ['start_problems']


def start_problems(world, grid, starts):
    """Sentences saying why the robots of world cannot start at starts (one (x, y, yaw)
    for each of world.robots, in order); [] when they can.

    grid: the world's sim.grid.OccupancyGrid.
    """
    if not world.robots:
        return ['%s: no robot to simulate (the world has no position model)' % world.path]
    problems = []
    box = _walls_box(grid)
    for spec, start in zip(world.robots, starts):
        where = '%s: robot "%s" at (%.3f, %.3f)' % (world.path, spec.name, start[0], start[1])
        if box is not None and not _inside(box, start):
            problems.append('%s is outside the map (its walls span x %.2f .. %.2f, '
                            'y %.2f .. %.2f)' % ((where,) + box))
        elif _meets_an_obstacle(world, footprint_corners(spec, start)):
            problems.append('%s starts inside a wall (its body overlaps an obstacle)' % where)
    bodies = [footprint_corners(spec, start) for spec, start in zip(world.robots, starts)]
    for first in range(len(bodies)):
        for second in range(first + 1, len(bodies)):
            if footprints_overlap(bodies[first], bodies[second]):
                problems.append('%s: robots "%s" and "%s" start on top of each other' % (
                    world.path, world.robots[first].name, world.robots[second].name))
    return problems


def _meets_an_obstacle(world, corners):
    """Whether the convex polygon corners (N, 2) meets an outline edge of an obstacle."""
    for obstacle in world.obstacles:
        if obstacle.obstacle_return and np.any(_segments_meet(corners, *obstacle_edges(obstacle))):
            return True
    return False


def _segments_meet(corners, xs, ys):
    """For each segment (xs[i], ys[i]: its ends), whether it meets the open interior of the
    convex polygon corners: no separating axis among the polygon's edge normals and the
    segment's own normal (a segment that only touches the polygon is separated)."""
    starts = np.stack([xs[:, 0], ys[:, 0]], axis=1)
    ends = np.stack([xs[:, 1], ys[:, 1]], axis=1)
    meets = np.ones(len(starts), dtype=bool)
    sides = np.roll(corners, -1, axis=0) - corners
    for axis in np.stack([-sides[:, 1], sides[:, 0]], axis=1):
        body = corners.dot(axis)
        a, b = starts.dot(axis), ends.dot(axis)
        meets &= (np.maximum(a, b) > body.min()) & (np.minimum(a, b) < body.max())
    normals = np.stack([ys[:, 0] - ys[:, 1], xs[:, 1] - xs[:, 0]], axis=1)
    along = np.einsum('ij,ij->i', normals, starts)
    body = corners.dot(normals.T)   # (N corners, segments)
    point = ~normals.any(axis=1)    # a segment of no length has no normal of its own
    meets &= point | ((body.min(axis=0) < along) & (along < body.max(axis=0)))
    return meets


def _walls_box(grid):
    """(xmin, xmax, ymin, ymax) [m] of the cells obstacles block; None when none do."""
    rows, cols = np.nonzero(grid.occupied)
    if not len(rows):
        return None
    res = grid.resolution
    return ((grid.ix0 + cols.min()) * res, (grid.ix0 + cols.max() + 1) * res,
            (grid.iy0 + rows.min()) * res, (grid.iy0 + rows.max() + 1) * res)


def _inside(box, pose):
    return box[0] <= pose[0] <= box[1] and box[2] <= pose[1] <= box[3]
