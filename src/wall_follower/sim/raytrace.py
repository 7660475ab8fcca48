"""Laser raytracing on an OccupancyGrid, vectorised over beams.

`stage_ranges` reproduces real Stage's World::Raytrace, whose quirks show in
every scan and are what the reference recordings measure:

* A beam walks whole cells from the exact laser position: each step moves one
  cell along x or along y, chosen by an integer error term of the truncated
  cell deltas (ax, ay) of the full-range ray. That walk is a fixed lattice
  path, so the state after m steps has a closed form (see stage_walk), which is
  what lets all beams be handled at once instead of cell by cell.
* The range of a hit is the travelled distance along the major axis divided
  by the cosine, so a beam along an axis reads a whole number of cells.
* The walk runs through cells only inside 32x32-cell "regions" that hold
  some block; an empty region is skipped by jumping to where the exact ray
  crosses its border. A jump re-anchors the walk on the ray, which shifts the
  later quantisation: ignoring it puts 3-6% of beams more than 2 cm off.
* The budget is the Manhattan cell distance ax + ay, decremented by each step
  and each jump's Manhattan length, so walls just inside range_max can read
  range_max.
* Cell lookups truncate towards zero (C's double -> int), not floor.

`exact_ranges` is plain geometry: the distance to the boundary of the first
occupied cell along the exact ray, for scoring.
"""
import math

import numpy as np

from .stage_walk import Walks

__all__ = ['stage_ranges', 'exact_ranges', 'stage_beam_angles', 'REGION_WIDTH']

REGION_BITS = 5
REGION_WIDTH = 1 << REGION_BITS


def stage_beam_angles(start, increment, samples):
    """World angles of a Stage ranger's beams.

    Stage stores the running beam angle in a float32 between beams, so the angles are
    a float32 running sum; its rounding drift moves some 1081-beam ranges by a cell.
    """
    steps = np.full(samples, increment, dtype=np.float32)
    steps[0] = start
    return np.cumsum(steps, dtype=np.float32).astype(np.float64)


class _RegionMap(object):
    """What the walk needs to know about the grid, on arrays padded to whole regions.

    populated[region row, region col]: the region holds some block (so it is walked).
    visible / returns [cell row, cell col]: cells a beam can hit, and what it reads there.
    next_visible: for each cell, the nearest visible cell at or beyond it along its row
    (+x, -x) and along its column (+y, -y), flattened into one array so that a beam
    looks up its own direction's table by offset and stride.
    """

    def __init__(self, populated, rx0, ry0, visible, returns):
        self.populated = populated
        self.rx0, self.ry0 = rx0, ry0
        self.cx0 = rx0 * REGION_WIDTH
        self.cy0 = ry0 * REGION_WIDTH
        self.visible = visible
        self.returns = returns
        height, width = visible.shape
        blocks = visible.reshape(populated.shape[0], REGION_WIDTH, populated.shape[1],
                                 REGION_WIDTH)
        self.has_visible = blocks.any(axis=(1, 3))
        self.has_visible_flags = self.flags(self.has_visible)
        self.populated_flags = self.flags(populated)
        # bounding box of each region's visible cells, in cells of the padded arrays
        in_cols = blocks.any(axis=1)   # [region row, region col, cell col within]
        in_rows = blocks.any(axis=3)   # [region row, cell row within, region col]
        col_base = (np.arange(populated.shape[1]) * REGION_WIDTH)[None, :]
        row_base = (np.arange(populated.shape[0]) * REGION_WIDTH)[:, None]
        self.box_x_lo = col_base + np.argmax(in_cols, axis=2)
        self.box_x_hi = col_base + REGION_WIDTH - 1 - np.argmax(in_cols[:, :, ::-1], axis=2)
        self.box_y_lo = row_base + np.argmax(in_rows, axis=1)
        self.box_y_hi = row_base + REGION_WIDTH - 1 - np.argmax(in_rows[:, ::-1, :], axis=1)
        far = np.int64(1 << 40)
        cols = np.where(visible, np.arange(width)[None, :], far)
        rows = np.where(visible, np.arange(height)[:, None], far)
        plus_x = np.minimum.accumulate(cols[:, ::-1], axis=1)[:, ::-1]
        minus_x = np.maximum.accumulate(np.where(visible, cols, -far), axis=1)
        plus_y = np.minimum.accumulate(rows[::-1, :], axis=0)[::-1, :]
        minus_y = np.maximum.accumulate(np.where(visible, rows, -far), axis=0)
        # row tables are indexed [y, x]; column tables transposed to [x, y]
        self.next_visible = np.concatenate([plus_x.ravel(), minus_x.ravel(),
                                            plus_y.T.ravel(), minus_y.T.ravel()])
        self.table_size = height * width
        self.height, self.width = height, width

    @classmethod
    def build(cls, grid, visible, ranger_return, extra_cells):
        """Regions of the grid's drawn cells plus `extra_cells` [(xs, ys)] (robot bodies)."""
        rows, cols = np.nonzero(grid.drawn)
        xs = [cols + grid.ix0] + [np.asarray(c[0], dtype=np.int64) for c in extra_cells]
        ys = [rows + grid.iy0] + [np.asarray(c[1], dtype=np.int64) for c in extra_cells]
        rx = np.concatenate(xs) >> REGION_BITS
        ry = np.concatenate(ys) >> REGION_BITS
        if len(rx):
            rx0, ry0 = int(rx.min()), int(ry.min())
            populated = np.zeros((int(ry.max()) - ry0 + 1, int(rx.max()) - rx0 + 1), dtype=bool)
            populated[ry - ry0, rx - rx0] = True
        else:
            rx0 = ry0 = 0
            populated = np.zeros((1, 1), dtype=bool)
        shape = (populated.shape[0] * REGION_WIDTH, populated.shape[1] * REGION_WIDTH)
        padded_visible = np.zeros(shape, dtype=bool)
        padded_returns = np.zeros(shape)
        vr, vc = np.nonzero(visible)
        vx, vy = vc + grid.ix0 - rx0 * REGION_WIDTH, vr + grid.iy0 - ry0 * REGION_WIDTH
        padded_visible[vy, vx] = True
        padded_returns[vy, vx] = ranger_return[vr, vc]
        return cls(populated, rx0, ry0, padded_visible, padded_returns)

    def with_cells(self, extra_cells):
        """This map with the regions of `extra_cells` marked populated (None if outside)."""
        xs = np.concatenate([np.asarray(c[0], dtype=np.int64) for c in extra_cells])
        ys = np.concatenate([np.asarray(c[1], dtype=np.int64) for c in extra_cells])
        r = (ys >> REGION_BITS) - self.ry0
        c = (xs >> REGION_BITS) - self.rx0
        if r.min() < 0 or c.min() < 0 or r.max() >= self.populated.shape[0] or \
                c.max() >= self.populated.shape[1]:
            return None
        out = _RegionMap.__new__(_RegionMap)
        out.__dict__.update(self.__dict__)
        out.populated = self.populated.copy()
        out.populated[r, c] = True
        out.populated_flags = out.flags(out.populated)
        return out

    def region_ids(self, rx, ry):
        """Index of regions (rx, ry) into the flat flag tables; outside ones hit the border."""
        rows, cols = self.populated.shape
        r = np.minimum(np.maximum(ry - (self.ry0 - 1), 0), rows + 1)
        c = np.minimum(np.maximum(rx - (self.rx0 - 1), 0), cols + 1)
        return r * (cols + 2) + c

    def flags(self, table):
        """`table` flattened with a border of False regions, for region_ids()."""
        return np.pad(table, 1, mode='constant', constant_values=False).ravel()


def stage_ranges(grid, x, y, angles, range_max, height=None, robot_cells=(), other_cells=()):
    """Ranges and intensities of beams from (x, y) at world `angles`, as Stage computes them.

    height: beam height above the ground for Stage's block height test (None: every
        visible cell counts).
    robot_cells: [(xs, ys)] Stage cells of robot bodies; this laser never hits them but,
        as in Stage, they make their regions walked cell by cell.
    other_cells: [(xs, ys, intensity)] cells of other robots, which the laser does hit.
    A beam that hits nothing reads range_max exactly with intensity 0.
    """
    angles = np.asarray(angles, dtype=np.float64)
    bodies = [c for c in robot_cells if len(c[0])]
    others = [c for c in other_cells if len(c[0])]
    regions = None
    if not others:
        static = _static_regions(grid, height)
        regions = static.with_cells(bodies) if bodies else static
    if regions is None:
        visible = _visible(grid, height).copy()
        returns = grid.ranger_return.copy()
        nrows, ncols = visible.shape
        for cells_x, cells_y, intensity in others:
            rows = np.asarray(cells_y, dtype=np.int64) - grid.iy0
            cols = np.asarray(cells_x, dtype=np.int64) - grid.ix0
            ok = (rows >= 0) & (cols >= 0) & (rows < nrows) & (cols < ncols)
            visible[rows[ok], cols[ok]] = True
            returns[rows[ok], cols[ok]] = intensity
        bodies = bodies + [(c[0], c[1]) for c in others]
        regions = _RegionMap.build(grid, visible, returns, bodies)
    return _StageTrace(regions, grid.ppm, float(x), float(y), angles, float(range_max)).run()


def _visible(grid, height):
    return grid.visible(height) if height is not None else ~np.isnan(grid.ranger_return)


def _static_regions(grid, height):
    """The region map of the grid alone, cached on the grid per beam height."""
    key = ('stage_regions', None if height is None else round(float(height), 9))
    regions = grid.cache.get(key)
    if regions is None:
        regions = _RegionMap.build(grid, _visible(grid, height), grid.ranger_return, [])
        grid.cache[key] = regions
    return regions


class _StageTrace(object):
    """All beams of one scan walked together, region by region, as World::Raytrace does.

    Per beam the walk state is (i, j), the x and y steps made, the floating position
    `glob` in cell units (re-anchored on the ray by every jump) and Stage's budget n.
    Beams in empty regions jump until they reach a populated one; then every live beam
    walks its populated region to a hit, out of the region, or out of budget. The
    arithmetic runs masked over all beams, because numpy's per-call cost, not the
    element count, dominates at a few hundred beams.
    """

    def __init__(self, regions, ppm, x, y, angles, range_max):
        self.regions = regions
        self.ppm = ppm
        angle = np.where(angles == 0.0, 1e-12, angles)
        self.sina = np.sin(angle)
        self.cosa = np.cos(angle)
        self.tana = self.sina / self.cosa
        dx = ppm * range_max * self.cosa
        dy = ppm * range_max * self.sina
        self.forward_x = dx >= 0
        self.forward_y = dy >= 0
        self.sx = np.where(self.forward_x, 1, -1)
        self.sy = np.where(self.forward_y, 1, -1)
        ax = np.abs(dx).astype(np.int64)
        ay = np.abs(dy).astype(np.int64)
        self.ax, self.ay = ax, ay
        self.x_major = ax > ay
        self.walks = Walks(ax, ay)
        # steps to leave a region from cell offset c within it: 32 - c ahead, c + 1 back
        self.exit_base_x = np.where(self.forward_x, REGION_WIDTH, 1)
        self.exit_base_y = np.where(self.forward_y, REGION_WIDTH, 1)
        self.startx, self.starty = x * ppm, y * ppm
        self.xjumpx = self.sx * float(REGION_WIDTH)
        self.xjumpy = self.sx * REGION_WIDTH * self.tana
        self.yjumpx = self.sy * REGION_WIDTH / self.tana
        self.yjumpy = self.sy * float(REGION_WIDTH)
        self.xjumpdist = np.abs(self.xjumpx) + np.abs(self.xjumpy)
        self.yjumpdist = np.abs(self.yjumpx) + np.abs(self.yjumpy)
        count = len(angles)
        self.ranges = np.full(count, range_max)
        self.intensities = np.zeros(count)
        self.i = np.zeros(count, dtype=np.int64)
        self.j = np.zeros(count, dtype=np.int64)
        self.n = ax + ay
        self.live = self.n > 0
        self.globx = np.full(count, self.startx)
        self.globy = np.full(count, self.starty)
        self.recalc = np.ones(count, dtype=bool)
        # next region crossing along x (point, Manhattan distance) and along y
        self.xcx = np.zeros(count)
        self.xcy = np.zeros(count)
        self.ycx = np.zeros(count)
        self.ycy = np.zeros(count)
        self.dist_x = np.zeros(count)
        self.dist_y = np.zeros(count)
        self.reg_lo = (regions.rx0, regions.ry0)
        self.reg_hi = (regions.rx0 + regions.populated.shape[1] - 1,
                       regions.ry0 + regions.populated.shape[0] - 1)

    # -- rounds --------------------------------------------------------------------------
    def run(self):
        regions = self.regions
        while True:
            # jump the beams in empty regions until each reaches a populated one
            while True:
                cell_x = self.globx.astype(np.int64)   # C's truncation towards zero
                cell_y = self.globy.astype(np.int64)
                reg_x = cell_x >> REGION_BITS
                reg_y = cell_y >> REGION_BITS
                region = regions.region_ids(reg_x, reg_y)
                populated = regions.populated_flags[region]
                jumping = self.live & ~populated
                if not jumping.any():
                    break
                self._jump(jumping)
            walking = self.live & populated
            if not walking.any():
                return self.ranges, self.intensities
            self._walk_regions(walking, cell_x, cell_y, reg_x, reg_y,
                               regions.has_visible_flags[region])

    def _walk_regions(self, walking, cell_x, cell_y, reg_x, reg_y, has_visible):
        """Walk the `walking` beams through their current region."""
        i0, j0 = self.i, self.j
        m0 = i0 + j0
        left_x = self.exit_base_x - self.sx * (cell_x - (reg_x << REGION_BITS))
        left_y = self.exit_base_y - self.sy * (cell_y - (reg_y << REGION_BITS))
        walks = self.walks
        exit_x = walks.steps_until_x(i0 + left_x)
        exit_y = walks.steps_until_y(j0 + left_y)
        exit_m = np.minimum(exit_x, exit_y)
        budget_m = m0 + self.n
        end_m = np.minimum(exit_m, budget_m)   # the states m0 .. end_m-1 are tested
        hit = np.zeros(len(walking), dtype=bool)
        look = np.nonzero(walking & has_visible & (end_m > m0))[0]
        if len(look):
            start, stop = self._box_window(look, m0[look], end_m[look], cell_x[look],
                                           cell_y[look], reg_x[look], reg_y[look])
            keep = start < stop
            look, start, stop = look[keep], start[keep], stop[keep]
        if len(look):
            found, hit_i, hit_j = self._first_hit(look, start, stop, cell_x[look],
                                                  cell_y[look])
            hits = look[found]
            hit[hits] = True
            self._record_hits(hits, hit_i[found], hit_j[found], cell_x[hits], cell_y[hits])
        leaving = walking & ~hit & (exit_m < budget_m)
        self.live &= ~walking | leaving
        by_x = exit_x < exit_y
        new_i = np.where(by_x, i0 + left_x, walks.x_before_y(j0 + left_y - 1))
        new_j = np.where(by_x, walks.y_before_x(new_i - 1), j0 + left_y)
        moved_i = (new_i - i0) * leaving
        moved_j = (new_j - j0) * leaving
        self.globx = self.globx + self.sx * moved_i
        self.globy = self.globy + self.sy * moved_j
        self.n = self.n - (moved_i + moved_j)
        self.i = i0 + moved_i
        self.j = j0 + moved_j
        self.recalc |= leaving

    def _box_window(self, b, m0, end_m, cell_x, cell_y, reg_x, reg_y):
        """Steps [start, stop) of the walk that lie in the box around the region's targets.

        Only there can the walk hit anything, and for a region crossed by a straight wall
        that box is one cell wide, which keeps the hit search short.
        """
        regions = self.regions
        r = reg_y - regions.ry0
        c = reg_x - regions.rx0
        box_x = (regions.box_x_lo[r, c] + regions.cx0, regions.box_x_hi[r, c] + regions.cx0)
        box_y = (regions.box_y_lo[r, c] + regions.cy0, regions.box_y_hi[r, c] + regions.cy0)
        walks = self.walks.subset(b)
        i0, j0 = self.i[b], self.j[b]
        forward_x, forward_y = self.forward_x[b], self.forward_y[b]
        # steps along each axis to reach the box and to pass beyond it
        into_x = np.maximum(np.where(forward_x, box_x[0] - cell_x, cell_x - box_x[1]), 0)
        past_x = np.where(forward_x, box_x[1] - cell_x, cell_x - box_x[0]) + 1
        into_y = np.maximum(np.where(forward_y, box_y[0] - cell_y, cell_y - box_y[1]), 0)
        past_y = np.where(forward_y, box_y[1] - cell_y, cell_y - box_y[0]) + 1
        start = np.maximum(np.where(into_x > 0, walks.steps_until_x(i0 + into_x), m0),
                           np.where(into_y > 0, walks.steps_until_y(j0 + into_y), m0))
        stop = np.minimum(np.minimum(walks.steps_until_x(i0 + np.maximum(past_x, 1)),
                                     walks.steps_until_y(j0 + np.maximum(past_y, 1))), end_m)
        stop = np.where((past_x <= 0) | (past_y <= 0), start, stop)
        return start, stop

    def _first_hit(self, b, start, stop, cell_x, cell_y):
        """First visible cell among the walk's states start .. stop-1.

        (cell_x, cell_y) is the cell of the beams' current state (i, j). The states form
        runs along the beam's major axis, one per minor-axis line; the next-visible
        table answers each run with one lookup. Returns (found, i, j) of the hit state.
        """
        regions = self.regions
        x_major = self.x_major[b]
        sx, sy = self.sx[b], self.sy[b]
        i0, j0 = self.i[b], self.j[b]
        major0 = np.where(x_major, i0, j0)
        minor0 = np.where(x_major, j0, i0)
        s_major = np.where(x_major, sx, sy)
        cell_major0 = np.where(x_major, cell_x - regions.cx0, cell_y - regions.cy0)
        cell_minor0 = np.where(x_major, cell_y - regions.cy0, cell_x - regions.cx0)
        last = stop - 1
        walks = self.walks.subset(b)
        x_first = walks.x_count(start)
        x_last = walks.x_count(last)
        minor_first = np.where(x_major, start - x_first, x_first)
        minor_last = np.where(x_major, last - x_last, x_last)
        width = int((minor_last - minor_first).max()) + 1
        k = minor_first[:, None] + np.arange(-1, width)[None, :]
        bounds = _major_before_minor(walks.column(), x_major[:, None], k)
        k = k[:, 1:]
        lo = np.maximum(bounds[:, :-1], start[:, None] - k)
        hi = np.minimum(bounds[:, 1:], last[:, None] - k)
        usable = (k <= minor_last[:, None]) & (lo <= hi)
        minor_cell = cell_minor0[:, None] + np.where(x_major, sy, sx)[:, None] * (
            k - minor0[:, None])
        lo_cell = cell_major0[:, None] + s_major[:, None] * (lo - major0[:, None])
        hi_cell = cell_major0[:, None] + s_major[:, None] * (hi - major0[:, None])
        table = np.where(x_major, np.where(sx > 0, 0, 1), np.where(sy > 0, 2, 3)) * \
            regions.table_size
        stride = np.where(x_major, regions.width, regions.height)
        index = table[:, None] + np.where(usable, minor_cell * stride[:, None] + lo_cell, 0)
        nearest = regions.next_visible[index]
        hits = usable & np.where(s_major[:, None] > 0, nearest <= hi_cell, nearest >= hi_cell)
        found = hits.any(axis=1)
        line = np.argmax(hits, axis=1)
        rows = np.arange(len(b))
        hit_major = major0 + s_major * (nearest[rows, line] - cell_major0)
        hit_minor = k[rows, line]
        return (found, np.where(x_major, hit_major, hit_minor),
                np.where(x_major, hit_minor, hit_major))

    def _record_hits(self, b, hit_i, hit_j, cell_x, cell_y):
        i0, j0 = self.i[b], self.j[b]
        sx, sy = self.sx[b], self.sy[b]
        gx = self.globx[b] + sx * (hit_i - i0)
        gy = self.globy[b] + sy * (hit_j - j0)
        along_x = np.abs((gx - self.startx) / self.cosa[b]) / self.ppm
        along_y = np.abs((gy - self.starty) / self.sina[b]) / self.ppm
        self.ranges[b] = np.where(self.x_major[b], along_x, along_y)
        regions = self.regions
        self.intensities[b] = regions.returns[cell_y + sy * (hit_j - j0) - regions.cy0,
                                              cell_x + sx * (hit_i - i0) - regions.cx0]

    def _jump(self, jumping):
        """Jump the `jumping` beams over one empty region each."""
        fresh = jumping & self.recalc
        if fresh.any():
            self._region_crossings(fresh)
            self.recalc &= ~fresh
        by_x = self.dist_x < self.dist_y
        jump_x = jumping & by_x
        jump_y = jumping & ~by_x
        self.globx = np.where(jump_x, self.xcx, np.where(jump_y, self.ycx, self.globx))
        self.globy = np.where(jump_x, self.xcy, np.where(jump_y, self.ycy, self.globy))
        travelled = np.where(by_x, self.dist_x, self.dist_y)
        self.n = np.where(jumping, (self.n - travelled).astype(np.int64), self.n)
        self.xcx = self.xcx + self.xjumpx * jump_x
        self.xcy = self.xcy + self.xjumpy * jump_x
        self.ycx = self.ycx + self.yjumpx * jump_y
        self.ycy = self.ycy + self.yjumpy * jump_y
        self.dist_x, self.dist_y = (
            np.where(jump_x, self.xjumpdist, self.dist_x - travelled * jump_y),
            np.where(jump_y, self.yjumpdist, self.dist_y - travelled * jump_x))
        # a beam beyond every populated region, heading away, will never hit anything
        reg_x = self.globx.astype(np.int64) >> REGION_BITS
        reg_y = self.globy.astype(np.int64) >> REGION_BITS
        gone = (((reg_x > self.reg_hi[0]) & self.forward_x) |
                ((reg_x < self.reg_lo[0]) & ~self.forward_x) |
                ((reg_y > self.reg_hi[1]) & self.forward_y) |
                ((reg_y < self.reg_lo[1]) & ~self.forward_y))
        self.live &= ~(jumping & ((self.n <= 0) | gone))

    def _region_crossings(self, fresh):
        """Where the ray from each `fresh` beam's point leaves its region along x and y.

        Stage aims one cell past the border when going left or down.
        """
        gx, gy = self.globx, self.globy
        ix = gx.astype(np.int64)
        iy = gy.astype(np.int64)
        # C's integer division truncates; Stage then floors it off a border when negative
        region_x = ((np.abs(ix) >> REGION_BITS) * np.sign(ix)) << REGION_BITS
        region_y = ((np.abs(iy) >> REGION_BITS) * np.sign(iy)) << REGION_BITS
        region_x = region_x - np.where((gx < 0) & (ix != region_x), REGION_WIDTH, 0)
        region_y = region_y - np.where((gy < 0) & (iy != region_y), REGION_WIDTH, 0)
        xdx = np.where(self.sx < 0, region_x - gx - 1.0, region_x + REGION_WIDTH - gx)
        xdy = xdx * self.tana
        ydy = np.where(self.sy < 0, region_y - gy - 1.0, region_y + REGION_WIDTH - gy)
        ydx = ydy / self.tana
        self.xcx = np.where(fresh, gx + xdx, self.xcx)
        self.xcy = np.where(fresh, gy + xdy, self.xcy)
        self.ycx = np.where(fresh, gx + ydx, self.ycx)
        self.ycy = np.where(fresh, gy + ydy, self.ycy)
        self.dist_x = np.where(fresh, np.abs(xdx) + np.abs(xdy), self.dist_x)
        self.dist_y = np.where(fresh, np.abs(ydx) + np.abs(ydy), self.dist_y)


def _major_before_minor(walks, x_major, k):
    """Major-axis steps made before minor step k (all of them when there is no step k)."""
    after_start = k >= 0
    # a walk along an axis has a single minor line holding every major step
    along_x = np.where(walks.ay == 0, walks.ax * after_start, walks.x_before_y(k))
    along_y = np.where(walks.ax == 0, walks.ay * after_start,
                       np.minimum(np.maximum(walks.y_before_x(k), 0), walks.ay))
    return np.where(x_major, along_x, along_y)


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
