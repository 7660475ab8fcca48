"""Whether a world's robots can start where they are put: the checks stage_sim makes before
its first step.

Real Stage runs whatever it is given: a world with no robot steps an empty
clock, and a robot whose body starts across a wall is stalled at every move
(Stage refuses each step that leaves the body touching an obstacle's cells),
so a run from there measures nothing. Neither can be meant, and each is
refused here with the world file and the robot named; so is a robot
outside every wall of the map (beyond the box the obstacles span), which
drives off into nothing, and two robots whose bodies overlap.

A wall is what Stage draws: an obstacle's outline cells (sim.grid). A
robot wholly inside the interior of a wide obstacle touches none of them,
as in Stage, and is not told apart from one in free space.
"""
import numpy as np

from .grid import footprint_collides, footprint_corners, footprints_overlap

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
        elif footprint_collides(grid, spec, start):
            problems.append('%s starts inside a wall (its body overlaps an obstacle)' % where)
    bodies = [footprint_corners(spec, start) for spec, start in zip(world.robots, starts)]
    for first in range(len(bodies)):
        for second in range(first + 1, len(bodies)):
            if footprints_overlap(bodies[first], bodies[second]):
                problems.append('%s: robots "%s" and "%s" start on top of each other' % (
                    world.path, world.robots[first].name, world.robots[second].name))
    return problems


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
