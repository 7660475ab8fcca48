"""The world rasterised the way Stage rasterises it, and robot footprint geometry.

Stage does not fill obstacles: it draws each block's outline edges into square
cells of `resolution` with an integer line walk between the floored vertex
cells (Stage's World::MapPoly). Ranges and collisions then come from those
cells, so the grid here reproduces exactly that set of cells. Cell (ix, iy)
covers [ix, ix+1) x [iy, iy+1) * resolution in the world.
"""
import math

import numpy as np

from .stage_walk import line_cells

__all__ = ['OccupancyGrid', 'obstacle_edges', 'footprint_corners', 'footprint_cells',
           'footprint_collides', 'footprints_overlap']

# Empty cells kept around the obstacles, so that every lookup near them stays inside.
_MARGIN_CELLS = 2


class OccupancyGrid(object):
    """Stage's cells of a World.

    occupied[row, col]: a cell an obstacle (obstacle_return) was drawn into.
    drawn[row, col]: a cell any model was drawn into (Stage walks such regions cell by cell).
    ranger_return[row, col]: intensity a ranger reads on hitting the cell; NaN where
        nothing visible to rangers was drawn.
    ranger_zmin/zmax[row, col]: height span of the visible blocks in the cell (Stage only
        lets a beam hit a block whose z span contains the beam's height).
    Row r, column c is Stage cell (ix0 + c, iy0 + r); `origin` is that cell's corner.
    """

    def __init__(self, resolution, ix0, iy0, occupied, drawn, ranger_return, ranger_zmin,
                 ranger_zmax):
        self.resolution = float(resolution)
        self.ppm = 1.0 / self.resolution  # as Stage computes it, for identical rounding
        self.ix0 = int(ix0)
        self.iy0 = int(iy0)
        self.occupied = occupied
        self.drawn = drawn
        self.ranger_return = ranger_return
        self.ranger_zmin = ranger_zmin
        self.ranger_zmax = ranger_zmax
        self.origin = (self.ix0 * self.resolution, self.iy0 * self.resolution)
        self._visible = {}
        # Derived lookup structures other modules build once per grid (e.g. raytrace).
        self.cache = {}

    @property
    def shape(self):
        return self.occupied.shape

    @classmethod
    def from_world(cls, world):
        ppm = 1.0 / world.resolution
        drawn = []  # (xs, ys, obstacle)
        for obstacle in world.obstacles:
            xs, ys = _obstacle_cells(obstacle, ppm)
            drawn.append((xs, ys, obstacle))
        all_x = np.concatenate([d[0] for d in drawn] + [np.zeros(1, dtype=np.int64)])
        all_y = np.concatenate([d[1] for d in drawn] + [np.zeros(1, dtype=np.int64)])
        ix0 = int(all_x.min()) - _MARGIN_CELLS
        iy0 = int(all_y.min()) - _MARGIN_CELLS
        shape = (int(all_y.max()) - iy0 + 1 + _MARGIN_CELLS,
                 int(all_x.max()) - ix0 + 1 + _MARGIN_CELLS)
        occupied = np.zeros(shape, dtype=bool)
        drawn_cells = np.zeros(shape, dtype=bool)
        ranger_return = np.full(shape, np.nan)
        zmin = np.full(shape, np.inf)
        zmax = np.full(shape, -np.inf)
        for xs, ys, obstacle in drawn:
            rows, cols = ys - iy0, xs - ix0
            drawn_cells[rows, cols] = True
            if obstacle.obstacle_return:
                occupied[rows, cols] = True
            if obstacle.ranger_return >= 0.0:
                # Stage reports the first model drawn into a cell.
                fresh = np.isnan(ranger_return[rows, cols])
                ranger_return[rows[fresh], cols[fresh]] = obstacle.ranger_return
                zmin[rows, cols] = np.minimum(zmin[rows, cols], obstacle.z_range[0])
                zmax[rows, cols] = np.maximum(zmax[rows, cols], obstacle.z_range[1])
        return cls(world.resolution, ix0, iy0, occupied, drawn_cells, ranger_return, zmin, zmax)

    def visible(self, height):
        """Cells a beam at `height` above the ground can hit (cached per height)."""
        key = round(float(height), 9)
        mask = self._visible.get(key)
        if mask is None:
            mask = (~np.isnan(self.ranger_return) & (self.ranger_zmin <= height) &
                    (height <= self.ranger_zmax))
            self._visible[key] = mask
        return mask

    def world_to_cell(self, x, y):
        """(row, col) indices of the cell containing world point(s) (x, y)."""
        col = np.floor(np.asarray(x) * self.ppm).astype(np.int64) - self.ix0
        row = np.floor(np.asarray(y) * self.ppm).astype(np.int64) - self.iy0
        return row, col


def _obstacle_cells(obstacle, ppm):
    """Stage cells of an obstacle's outline edges (Model::LocalToPixels + World::MapPoly)."""
    wx, wy = obstacle_edges(obstacle)
    px = np.floor(wx * ppm).astype(np.int64)
    py = np.floor(wy * ppm).astype(np.int64)
    return line_cells(px[:, 0], py[:, 0], px[:, 1], py[:, 1])


def obstacle_edges(obstacle):
    """World x and y (each (M, 2): start, end) of an obstacle's outline edges, the true
    lines its cells are drawn from."""
    gx, gy, _, ga = obstacle.pose
    ox, oy, _, oa = obstacle.origin
    # GetGlobalPose() + geom.pose, in Stage's order of floating-point operations.
    cosg, sing = math.cos(ga), math.sin(ga)
    cx = gx + ox * cosg - oy * sing
    cy = gy + ox * sing + oy * cosg
    ca = ga + oa
    cosa, sina = math.cos(ca), math.sin(ca)
    local = obstacle.edges
    wx = cx + local[..., 0] * cosa - local[..., 1] * sina
    wy = cy + local[..., 0] * sina + local[..., 1] * cosa
    return wx, wy


def footprint_corners(spec, pose):
    """World corners (4, 2) of the robot body box: `size` centred at `origin` in base_link.

    Order: rear-right, front-right, front-left, rear-left (Stage's default block).
    """
    length, width = spec.size[0], spec.size[1]
    ox, oy, oa = spec.origin
    local = np.array([[-0.5, -0.5], [0.5, -0.5], [0.5, 0.5], [-0.5, 0.5]]) * [length, width]
    cos_o, sin_o = math.cos(oa), math.sin(oa)
    bx = ox + local[:, 0] * cos_o - local[:, 1] * sin_o
    by = oy + local[:, 0] * sin_o + local[:, 1] * cos_o
    x, y, yaw = pose
    cosa, sina = math.cos(yaw), math.sin(yaw)
    return np.stack([x + bx * cosa - by * sina, y + bx * sina + by * cosa], axis=1)


def footprint_cells(spec, pose, ppm):
    """Stage cells (xs, ys) of the body box outline at `pose`, drawn as Stage draws it."""
    corners = footprint_corners(spec, pose)
    px = np.floor(corners[:, 0] * ppm).astype(np.int64)
    py = np.floor(corners[:, 1] * ppm).astype(np.int64)
    return line_cells(px, py, np.roll(px, -1), np.roll(py, -1))


def _rect_frame(corners):
    """Centre, unit axes and half extents of a rectangle given by its 4 corners in order."""
    centre = corners.mean(axis=0)
    edge_u = corners[1] - corners[0]
    edge_v = corners[3] - corners[0]
    half = np.array([np.hypot(*edge_u), np.hypot(*edge_v)]) / 2.0
    axes = np.stack([edge_u / (2.0 * half[0]), edge_v / (2.0 * half[1])])
    return centre, axes, half


def footprint_collides(grid, spec, pose):
    """True when the body outline at `pose`, drawn into Stage's cells, shares a cell
    with an obstacle: Stage's Block::TestCollision, cell for cell."""
    xs, ys = footprint_cells(spec, pose, grid.ppm)
    rows, cols = ys - grid.iy0, xs - grid.ix0
    nrows, ncols = grid.occupied.shape
    inside = (rows >= 0) & (rows < nrows) & (cols >= 0) & (cols < ncols)
    return bool(np.any(grid.occupied[rows[inside], cols[inside]]))


def footprints_overlap(corners_a, corners_b):
    """Separating-axis test of two rectangles given by their corners (touching = apart)."""
    for corners in (corners_a, corners_b):
        _, axes, _ = _rect_frame(corners)
        for axis in axes:
            pa = corners_a.dot(axis)
            pb = corners_b.dot(axis)
            if pa.max() <= pb.min() or pb.max() <= pa.min():
                return False
    return True
