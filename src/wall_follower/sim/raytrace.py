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

from .stage_walk import steps_until_x, steps_until_y, x_count

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
    """Which Stage regions hold any block, and the visible cells padded to whole regions."""

    def __init__(self, populated, rx0, ry0, visible, returns):
        self.populated = populated
        self.rx0, self.ry0 = rx0, ry0
        self.cx0 = rx0 * REGION_WIDTH
        self.cy0 = ry0 * REGION_WIDTH
        self.visible = visible
        self.returns = returns
        blocks = visible.reshape(populated.shape[0], REGION_WIDTH, populated.shape[1],
                                 REGION_WIDTH)
        self.has_visible = blocks.any(axis=(1, 3))

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
        populated = self.populated.copy()
        populated[r, c] = True
        out = _RegionMap.__new__(_RegionMap)
        out.__dict__.update(self.__dict__)
        out.populated = populated
        return out

    def lookup(self, table, rx, ry):
        r = ry - self.ry0
        c = rx - self.rx0
        inside = (r >= 0) & (c >= 0) & (r < table.shape[0]) & (c < table.shape[1])
        out = np.zeros(rx.shape, dtype=table.dtype)
        out[inside] = table[r[inside], c[inside]]
        return out


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
    return _trace(regions, grid.ppm, float(x), float(y), angles, float(range_max))


def _visible(grid, height):
    return grid.visible(height) if height is not None else ~np.isnan(grid.ranger_return)


def _static_regions(grid, height):
    """The region map of the grid alone, cached on the grid per beam height."""
    cache = grid.__dict__.setdefault('_stage_region_maps', {})
    key = None if height is None else round(float(height), 9)
    regions = cache.get(key)
    if regions is None:
        regions = _RegionMap.build(grid, _visible(grid, height), grid.ranger_return, [])
        cache[key] = regions
    return regions


def _trace(regions, ppm, x, y, angles, range_max):
    nbeams = len(angles)
    angle = np.where(angles == 0.0, 1e-12, angles)
    sina = np.sin(angle)
    cosa = np.cos(angle)
    tana = sina / cosa
    dx = ppm * range_max * cosa
    dy = ppm * range_max * sina
    sx = np.where(dx < 0, -1, 1)
    sy = np.where(dy < 0, -1, 1)
    ax = np.abs(dx).astype(np.int64)
    ay = np.abs(dy).astype(np.int64)
    x_major = ax > ay
    startx, starty = x * ppm, y * ppm
    xjumpx = sx * float(REGION_WIDTH)
    xjumpy = sx * REGION_WIDTH * tana
    yjumpx = sy * REGION_WIDTH / tana
    yjumpy = sy * float(REGION_WIDTH)
    xjumpdist = np.abs(xjumpx) + np.abs(xjumpy)
    yjumpdist = np.abs(yjumpx) + np.abs(yjumpy)

    ranges = np.full(nbeams, range_max)
    intensities = np.zeros(nbeams)
    # per-beam walk state
    steps = np.zeros(nbeams, dtype=np.int64)        # i + j so far
    budget = ax + ay                                 # Stage's n
    globx = np.full(nbeams, startx)
    globy = np.full(nbeams, starty)
    recalc = np.ones(nbeams, dtype=bool)
    xcx = np.zeros(nbeams)
    xcy = np.zeros(nbeams)
    ycx = np.zeros(nbeams)
    ycy = np.zeros(nbeams)
    dist_x = np.zeros(nbeams)
    dist_y = np.zeros(nbeams)
    active = np.nonzero(budget > 0)[0]
    # beams outside the populated regions and heading away can never hit anything
    rx_lo, ry_lo = regions.rx0, regions.ry0
    rx_hi = rx_lo + regions.populated.shape[1] - 1
    ry_hi = ry_lo + regions.populated.shape[0] - 1

    while len(active):
        b = active
        cell_x = np.trunc(globx[b]).astype(np.int64)
        cell_y = np.trunc(globy[b]).astype(np.int64)
        reg_x = cell_x >> REGION_BITS
        reg_y = cell_y >> REGION_BITS
        populated = regions.lookup(regions.populated, reg_x, reg_y)

        finished = np.zeros(len(b), dtype=bool)

        # -- walk cell by cell through a populated region ---------------------------------
        p = np.nonzero(populated)[0]
        if len(p):
            bp = b[p]
            pax, pay = ax[bp], ay[bp]
            psx, psy = sx[bp], sy[bp]
            m0 = steps[bp]
            i0 = x_count(m0, pax, pay)
            j0 = m0 - i0
            cx0, cy0 = cell_x[p], cell_y[p]
            # x and y steps left before the walk leaves this region
            left_x = np.where(psx > 0, ((reg_x[p] + 1) << REGION_BITS) - cx0,
                              cx0 - (reg_x[p] << REGION_BITS) + 1)
            left_y = np.where(psy > 0, ((reg_y[p] + 1) << REGION_BITS) - cy0,
                              cy0 - (reg_y[p] << REGION_BITS) + 1)
            exit_steps = np.minimum(steps_until_x(i0 + left_x, pax, pay),
                                    steps_until_y(j0 + left_y, pax, pay)) - m0
            limit = np.minimum(exit_steps, budget[bp])
            hit_q = np.full(len(p), -1, dtype=np.int64)
            has_visible = regions.lookup(regions.has_visible, reg_x[p], reg_y[p])
            v = np.nonzero(has_visible)[0]
            if len(v):
                hit_q[v] = _first_hit_in_window(
                    regions, m0[v], i0[v], j0[v], cx0[v], cy0[v], limit[v], pax[v], pay[v],
                    psx[v], psy[v])
            hit = hit_q >= 0
            q = np.where(hit, hit_q, exit_steps)
            m_new = m0 + q
            i_new = x_count(m_new, pax, pay)
            j_new = m_new - i_new
            gx = globx[bp] + psx * (i_new - i0)
            gy = globy[bp] + psy * (j_new - j0)
            hb = bp[hit]
            if len(hb):
                along_x = np.abs((gx[hit] - startx) / cosa[hb]) / ppm
                along_y = np.abs((gy[hit] - starty) / sina[hb]) / ppm
                ranges[hb] = np.where(x_major[hb], along_x, along_y)
                hx = cx0[hit] + psx[hit] * (i_new[hit] - i0[hit]) - regions.cx0
                hy = cy0[hit] + psy[hit] * (j_new[hit] - j0[hit]) - regions.cy0
                intensities[hb] = regions.returns[hy, hx]
            out_of_budget = ~hit & (exit_steps >= budget[bp])
            finished[p] = hit | out_of_budget
            moving = ~hit & ~out_of_budget
            bm = bp[moving]
            steps[bm] = m_new[moving]
            budget[bm] -= exit_steps[moving]
            globx[bm] = gx[moving]
            globy[bm] = gy[moving]
            recalc[bm] = True

        # -- jump over an empty region --------------------------------------------------
        e = np.nonzero(~populated)[0]
        if len(e):
            be = b[e]
            fresh = be[recalc[be]]
            if len(fresh):
                _region_crossings(fresh, globx, globy, sx, sy, tana, xcx, xcy, ycx, ycy,
                                  dist_x, dist_y)
                recalc[fresh] = False
            along_x = dist_x[be] < dist_y[be]
            jx, jy = be[along_x], be[~along_x]
            globx[jx], globy[jx] = xcx[jx], xcy[jx]
            budget[jx] = np.trunc(budget[jx] - dist_x[jx]).astype(np.int64)
            xcx[jx] += xjumpx[jx]
            xcy[jx] += xjumpy[jx]
            dist_y[jx] -= dist_x[jx]
            dist_x[jx] = xjumpdist[jx]
            globx[jy], globy[jy] = ycx[jy], ycy[jy]
            budget[jy] = np.trunc(budget[jy] - dist_y[jy]).astype(np.int64)
            ycx[jy] += yjumpx[jy]
            ycy[jy] += yjumpy[jy]
            dist_x[jy] -= dist_y[jy]
            dist_y[jy] = yjumpdist[jy]
            nrx = np.trunc(globx[be]).astype(np.int64) >> REGION_BITS
            nry = np.trunc(globy[be]).astype(np.int64) >> REGION_BITS
            gone = (((nrx > rx_hi) & (sx[be] > 0)) | ((nrx < rx_lo) & (sx[be] < 0)) |
                    ((nry > ry_hi) & (sy[be] > 0)) | ((nry < ry_lo) & (sy[be] < 0)))
            finished[e] = (budget[be] <= 0) | gone

        active = b[~finished]
    return ranges, intensities


def _region_crossings(b, globx, globy, sx, sy, tana, xcx, xcy, ycx, ycy, dist_x, dist_y):
    """Where the ray from the current point leaves its region along x and along y.

    Stage aims one cell past the border when going left or down.
    """
    gx, gy = globx[b], globy[b]
    ix = np.trunc(gx).astype(np.int64)
    iy = np.trunc(gy).astype(np.int64)
    # C integer division truncates; floor it for negative coordinates off a border
    region_x = (np.fix(ix / REGION_WIDTH) * REGION_WIDTH).astype(np.float64)
    region_y = (np.fix(iy / REGION_WIDTH) * REGION_WIDTH).astype(np.float64)
    region_x -= np.where((gx < 0) & (ix % REGION_WIDTH != 0), REGION_WIDTH, 0)
    region_y -= np.where((gy < 0) & (iy % REGION_WIDTH != 0), REGION_WIDTH, 0)
    xdx = np.where(sx[b] < 0, region_x - gx - 1.0, region_x + REGION_WIDTH - gx)
    xdy = xdx * tana[b]
    ydy = np.where(sy[b] < 0, region_y - gy - 1.0, region_y + REGION_WIDTH - gy)
    ydx = ydy / tana[b]
    xcx[b] = gx + xdx
    xcy[b] = gy + xdy
    ycx[b] = gx + ydx
    ycy[b] = gy + ydy
    dist_x[b] = np.abs(xdx) + np.abs(xdy)
    dist_y[b] = np.abs(ydx) + np.abs(ydy)


def _first_hit_in_window(regions, m0, i0, j0, cx0, cy0, limit, ax, ay, sx, sy):
    """Index of the first tested state (< limit) whose cell is visible, else -1."""
    width = int(limit.max()) if len(limit) else 0
    if width <= 0:
        return np.full(len(m0), -1, dtype=np.int64)
    q = np.arange(width, dtype=np.int64)[None, :]
    m = m0[:, None] + q
    i = x_count(m, ax[:, None], ay[:, None])
    j = m - i
    cells_x = cx0[:, None] + sx[:, None] * (i - i0[:, None]) - regions.cx0
    cells_y = cy0[:, None] + sy[:, None] * (j - j0[:, None]) - regions.cy0
    tested = q < limit[:, None]
    rows = np.clip(cells_y, 0, regions.visible.shape[0] - 1)
    cols = np.clip(cells_x, 0, regions.visible.shape[1] - 1)
    hits = tested & regions.visible[rows, cols]
    first = np.argmax(hits, axis=1)
    return np.where(hits.any(axis=1), first, -1)


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
