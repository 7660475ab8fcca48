"""Plain geometry on the simulator's grid: the yardsticks its Stage-like readings
and collisions are measured against in the tests.

exact_ranges follows the exact ray, unlike Stage's cell walk; footprint_clearance
measures how close the robot's body box comes to the occupied cells.
"""
import math

import numpy as np

from wall_follower.sim.grid import footprint_corners, footprints_overlap

# Corners of a cell's square, in cells from its lower-left corner, in order round it.
_SQUARE = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])


def footprint_clearance(grid, spec, pose):
    """Smallest distance [m] between the body box at `pose` and any occupied cell's square.

    0 on contact or overlap; inf on a grid without occupied cells. Between two convex
    polygons apart, the smallest distance is from a corner of one to an edge of the other.
    Plain geometry, unlike the simulator's collisions, which are Stage's cell for cell.
    """
    rows, cols = np.nonzero(grid.occupied)
    if not len(rows):
        return float('inf')
    corners = footprint_corners(spec, pose)
    squares = (np.stack([cols + grid.ix0, rows + grid.iy0], axis=1)[:, None, :] + _SQUARE) * \
        grid.resolution
    near = np.all((squares.max(axis=1) >= corners.min(axis=0)) &
                  (squares.min(axis=1) <= corners.max(axis=0)), axis=1)
    if any(footprints_overlap(corners, square) for square in squares[near]):
        return 0.0
    return float(min(_corner_to_edge(corners[None], squares),
                     _corner_to_edge(squares, corners[None])))


def _corner_to_edge(points, polygons):
    """Smallest distance from any of `points` [..., P, 2] to an edge of `polygons` [..., E, 2]."""
    start = polygons[..., None, :, :]
    edge = np.roll(polygons, -1, axis=-2)[..., None, :, :] - start
    offset = points[..., :, None, :] - start
    along = np.clip((offset * edge).sum(axis=-1) / (edge * edge).sum(axis=-1), 0.0, 1.0)
    return np.hypot(*np.moveaxis(offset - along[..., None] * edge, -1, 0)).min()


def exact_ranges(grid, x, y, angles, range_max):
    """Distance from (x, y) along each angle to the first occupied cell's boundary.

    A grid-line traversal (Amanatides & Woo): the ray enters a new cell at every
    crossing of a vertical or horizontal cell border; the range is the crossing
    distance of the first occupied cell entered (0 if the start cell is occupied),
    or range_max if none is entered within range_max.
    """
    angles = np.asarray(angles, dtype=np.float64)
    res = grid.resolution
    cosa = np.cos(angles)
    sina = np.sin(angles)
    nrows, ncols = grid.occupied.shape
    start_col = math.floor(x / res) - grid.ix0
    start_row = math.floor(y / res) - grid.iy0
    ranges = np.full(len(angles), float(range_max))
    if 0 <= start_row < nrows and 0 <= start_col < ncols and grid.occupied[start_row, start_col]:
        ranges[:] = 0.0
        return ranges
    with np.errstate(divide='ignore', invalid='ignore'):
        inv_cos = np.where(np.abs(cosa) > 1e-12, 1.0 / np.abs(cosa), np.inf)
        inv_sin = np.where(np.abs(sina) > 1e-12, 1.0 / np.abs(sina), np.inf)
    # distance along the ray to the first vertical / horizontal border, then between borders
    fx = x / res - math.floor(x / res)
    fy = y / res - math.floor(y / res)
    with np.errstate(invalid='ignore'):
        first_x = np.where(np.isfinite(inv_cos), np.where(cosa > 0, 1.0 - fx, fx) * res * inv_cos,
                           np.inf)
        first_y = np.where(np.isfinite(inv_sin), np.where(sina > 0, 1.0 - fy, fy) * res * inv_sin,
                           np.inf)
    step_x = res * inv_cos
    step_y = res * inv_sin
    col_step = np.where(cosa > 0, 1, -1)
    row_step = np.where(sina > 0, 1, -1)
    active = np.arange(len(angles))
    best = np.full(len(angles), np.inf)   # nearest hit seen so far
    done = 0
    chunk = 48
    while len(active):
        a = active[:, None]
        k = done + np.arange(chunk)[None, :]
        with np.errstate(invalid='ignore'):
            tx = first_x[a] + k * step_x[a]
            ty = first_y[a] + k * step_y[a]
        # the cell entered at each x crossing and at each y crossing
        col_x = start_col + col_step[a] * (k + 1)
        row_x = _floor_cells(y, tx, sina[a], res) - grid.iy0
        row_y = start_row + row_step[a] * (k + 1)
        col_y = _floor_cells(x, ty, cosa[a], res) - grid.ix0
        t = np.concatenate([tx, ty], axis=1)
        rows = np.concatenate([row_x, row_y], axis=1)
        cols = np.concatenate([col_x, col_y], axis=1)
        inside = (rows >= 0) & (cols >= 0) & (rows < nrows) & (cols < ncols) & np.isfinite(t)
        hit = inside & grid.occupied[np.clip(rows, 0, nrows - 1), np.clip(cols, 0, ncols - 1)]
        best[active] = np.minimum(best[active], np.where(hit, t, np.inf).min(axis=1))
        # every crossing up to the nearer of the two last crossings has now been seen
        horizon = np.minimum(tx[:, -1], ty[:, -1])
        settled = best[active] <= horizon
        beyond = horizon >= range_max
        gone = _left_grid(x, y, cosa[active], sina[active], horizon, grid, nrows, ncols)
        finished = settled | beyond | gone
        ranges[active[finished]] = np.minimum(best[active[finished]], range_max)
        done += chunk
        active = active[~finished]
    return ranges


def _floor_cells(origin, t, direction, res):
    """Cell index along one axis of the points origin + t * direction (t may be inf)."""
    with np.errstate(invalid='ignore'):
        coord = np.where(np.isfinite(t), origin + t * direction, 0.0)
    return np.floor(coord / res).astype(np.int64)


def _left_grid(x, y, cosa, sina, t, grid, nrows, ncols):
    """Has the ray, at distance t, left the grid in a direction it cannot come back from?"""
    res = grid.resolution
    px = (x + t * cosa) / res - grid.ix0
    py = (y + t * sina) / res - grid.iy0
    return (((px < 0) & (cosa <= 0)) | ((px > ncols) & (cosa >= 0)) |
            ((py < 0) & (sina <= 0)) | ((py > nrows) & (sina >= 0)))
