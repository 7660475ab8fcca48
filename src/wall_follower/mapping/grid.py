"""A log-odds occupancy grid and its update from one laser scan.

Each cell holds log(p / (1 - p)) of being occupied, 0 (p = 0.5) until a beam
has told anything about it. A scan updates each cell at most once, so that
a cell crossed by many beams of one scan is not counted free many times:
the cell a beam ends in is a hit, the cells it crossed on the way are
misses, and cells beyond its end are left alone. The last cell before a hit
is left alone too: a beam that grazes a wall crosses the wall's own cells
just before it ends, and would otherwise wear the wall away. At a slant,
one cell of the beam is not enough: a beam at an angle a from the wall's
normal is within a cell of the wall for resolution / cos(a) before its end,
and on the way crosses wall cells whose surface lies deeper in them than it
reaches (`spared`).
"""

import numpy as np

from wall_follower.params import defaults
from wall_follower.params.mapping.slam import MAPPER, grid_shape

__all__ = ['LogOddsGrid', 'probability', 'spared']

# The defaults of hit and miss below: the mapper's.
_DEFAULT = defaults(MAPPER)


def spared(origin, ends, hit, resolution, most):
    """How far short of its end each beam from origin to ends (N, 2) may clear cells:
    a cell across the surface it hit, resolution / cos(a) along the beam at an angle a
    from the surface's normal, at most `most` [m]; a free beam clears to its end (0).

    The surface is the line through the ends of the neighbouring beams that hit (one
    of them where only one did; a lone hit is taken head on). A wall seen at 84 degrees
    from 3 m away by a laser of a degree between beams has its hits 0.4 m apart, and
    each beam clears the wall cells on its way to the next: where the wall lies near a
    cell's far side, the walls of a long room were worn away by the lap's later, slanted
    views (a generated room, issue 41).
    """
    ends = np.asarray(ends, dtype=float).reshape(-1, 2)
    hit = np.asarray(hit, dtype=bool)
    before = np.roll(ends, 1, axis=0)
    after = np.roll(ends, -1, axis=0)
    hit_before = np.roll(hit, 1)
    hit_after = np.roll(hit, -1)
    if len(hit):
        hit_before[0] = hit_after[-1] = False
    tangent = (np.where(hit_after[:, None], after, ends)
               - np.where(hit_before[:, None], before, ends))
    beam = ends - np.asarray(origin, dtype=float)
    cross = np.abs(beam[:, 0] * tangent[:, 1] - beam[:, 1] * tangent[:, 0])
    norms = np.hypot(beam[:, 0], beam[:, 1]) * np.hypot(tangent[:, 0], tangent[:, 1])
    with np.errstate(divide='ignore', invalid='ignore'):
        cosine = np.where(norms > 0.0, cross / norms, 1.0)
        along = np.minimum(resolution / cosine, most)
    return np.where(hit, np.maximum(along, resolution), 0.0)


def probability(logodds):
    """p of occupancy from log-odds."""
    return 1.0 - 1.0 / (1.0 + np.exp(logodds))


class LogOddsGrid(object):
    """Cells of `resolution` metres over [xmin, xmax) x [ymin, ymax) of the map frame.

    logodds[row, col] is the cell whose lower-left corner is
    (xmin + col * resolution, ymin + row * resolution), row 0 at the bottom,
    as nav_msgs/OccupancyGrid orders its data. `observed` marks the cells a
    beam has updated. step: how far apart a beam is sampled for the cells it
    crosses, in cells: half a cell finds every one; a whole cell misses some
    that it only clips at a corner, and costs half as much (the fine grid
    scans are matched against: every scan crosses its cells hundreds of
    thousands of times, and its neighbours' beams clear what one misses).
    """

    def __init__(self, resolution, xmin, ymin, xmax, ymax, hit=_DEFAULT['hit_logodds'],
                 miss=_DEFAULT['miss_logodds'], bounds=(-4.0, 4.0), step=0.5):
        if resolution <= 0.0 or xmax <= xmin or ymax <= ymin:
            raise ValueError('a grid needs resolution > 0 and xmax > xmin, ymax > ymin '
                             '(got %r, x %r..%r, y %r..%r)' % (resolution, xmin, xmax, ymin, ymax))
        self.resolution = float(resolution)
        self.origin = (float(xmin), float(ymin))
        rows, cols = grid_shape(resolution, xmin, ymin, xmax, ymax)
        self.logodds = np.zeros((rows, cols), dtype=np.float32)
        self.observed = np.zeros((rows, cols), dtype=bool)
        self.hit = float(hit)
        self.miss = float(miss)
        self.bounds = (float(bounds[0]), float(bounds[1]))
        self.step = float(step)
        self._mark = np.zeros(rows * cols, dtype=bool)   # all False between uses

    @property
    def shape(self):
        return self.logodds.shape

    def cells(self, points):
        """(rows, cols) integer indices of (N, 2) map-frame points, and which lie inside."""
        points = np.asarray(points, dtype=float).reshape(-1, 2)
        cols = np.floor((points[:, 0] - self.origin[0]) / self.resolution).astype(np.int64)
        rows = np.floor((points[:, 1] - self.origin[1]) / self.resolution).astype(np.int64)
        inside = (rows >= 0) & (rows < self.shape[0]) & (cols >= 0) & (cols < self.shape[1])
        return rows, cols, inside

    def centre(self, rows, cols):
        """Map-frame (x, y) of cell centres."""
        return (self.origin[0] + (np.asarray(cols) + 0.5) * self.resolution,
                self.origin[1] + (np.asarray(rows) + 0.5) * self.resolution)

    def _flat(self, points):
        rows, cols, inside = self.cells(points)
        return rows[inside] * self.shape[1] + cols[inside]

    def _distinct(self, flat, less=()):
        """The distinct flat indices of flat that are not in less, ascending: np.unique
        and np.setdiff1d, by marking cells instead of sorting (a scan's beams cross a
        fine grid's cells a few hundred thousand times)."""
        if not len(flat):
            return np.zeros(0, dtype=np.int64)
        mark = self._mark
        mark[flat] = True
        mark[np.asarray(less, dtype=np.int64)] = False
        low = int(flat.min())
        cells = low + np.flatnonzero(mark[low:int(flat.max()) + 1])
        mark[flat] = False
        return cells

    def _add(self, cells, amount):
        flat = self.logodds.reshape(-1)
        flat[cells] = np.clip(flat[cells] + amount, self.bounds[0], self.bounds[1])
        self.observed.reshape(-1)[cells] = True

    def integrate(self, origin, ends, hit, spare=None):
        """One scan: beams from the map-frame point `origin` to `ends` (N, 2).

        hit[i] says whether beam i ended on an obstacle (its end cell is
        occupied) or is free all the way to its end (no return, or cut at the
        range limit). spare[i]: how far short of its end a hit beam stops
        clearing (see `spared`); a cell if not given. Returns the flat indices
        of the cells marked occupied.
        """
        ends = np.asarray(ends, dtype=float).reshape(-1, 2)
        hit = np.asarray(hit, dtype=bool)
        origin = np.asarray(origin, dtype=float)
        delta = ends - origin
        length = np.hypot(delta[:, 0], delta[:, 1])
        # Free stretch: to the end for a free beam, `short` of it for a hit.
        short = self.resolution if spare is None else np.asarray(spare, dtype=float)
        free_length = np.where(hit, np.maximum(length - short, 0.0), length)
        step = self.step * self.resolution
        samples = int(np.ceil(free_length.max() / step)) + 1 if len(length) else 0
        hit_cells = self._distinct(self._flat(ends[hit]))
        if samples > 0:
            t = np.arange(samples) * step
            keep = t[None, :] <= free_length[:, None]
            direction = delta / np.maximum(length, 1e-12)[:, None]
            points = origin + direction[:, None, :] * t[None, :, None]
            free_cells = self._distinct(self._flat(points[keep]), less=hit_cells)
        else:
            free_cells = np.zeros(0, dtype=np.int64)
        self._add(free_cells, self.miss)
        self._add(hit_cells, self.hit)
        return hit_cells

    def mark_hits(self, points, skip=()):
        """A hit for each cell holding one of the map-frame points (N, 2), once per cell,
        except the flat indices in skip (the cells this scan has already hit)."""
        self._add(self._distinct(self._flat(points), less=skip), self.hit)

    def clear(self):
        """Back to nothing observed (to be drawn anew)."""
        self.logodds.fill(0.0)
        self.observed.fill(False)

    def occupancy(self):
        """nav_msgs/OccupancyGrid values: -1 never observed, else round(100 p)."""
        values = np.rint(100.0 * probability(self.logodds)).astype(np.int8)
        values[~self.observed] = -1
        return values

    def observed_box(self, margin=0):
        """(row0, row1, col0, col1) bounding the observed cells, widened by margin cells;
        None while nothing has been observed."""
        rows = np.flatnonzero(self.observed.any(axis=1))
        if not len(rows):
            return None
        cols = np.flatnonzero(self.observed.any(axis=0))
        return (max(rows[0] - margin, 0), min(rows[-1] + 1 + margin, self.shape[0]),
                max(cols[0] - margin, 0), min(cols[-1] + 1 + margin, self.shape[1]))
