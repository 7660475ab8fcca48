"""Laser ranges on an OccupancyGrid, as real Stage measures them, for all beams at once.

What Stage does to a beam (measured against the recordings in
test/data/stage_reference, whose every beam `stage_ranges` reproduces):

* Cell path. The beam is followed cell by cell along a stage_walk path that
  starts at the laser's exact position, in cell units, and heads for the cell
  range_max away. The cell looked at is that position truncated towards zero
  (C's double-to-int), not floored.
* Range. A hit reads the distance travelled along the path's major axis,
  divided by the direction cosine of that axis: a beam along an axis reads a
  whole number of cells, and hits lie up to about a cell behind the surface.
* Regions. The world is tiled into 32x32-cell regions and only the regions
  something was drawn into (obstacles, robot bodies) are followed cell by
  cell. Across an empty region the beam flies: from its current position,
  along a line parallel to the beam, to where that line enters the next
  region, and its cell path goes on from that point. These restarts shift the
  later quantisation; ignoring them puts 3-6 % of beams more than 2 cm off.
* Budget. A beam may spend (cells along x + cells along y) of range_max: one
  per cell step, and each flight's Manhattan length, rounded up. A wall just
  inside range_max can be out of reach, and then reads as a miss does:
  range_max exactly, intensity 0.
* Re-anchoring. Inside a region Stage follows the cell it stepped to; at every
  region border it takes the cell from the (truncated) position again. The two
  part where the path passes x = 0 or y = 0, or where rounding carries a
  position within rounding of a cell border across it: then a cell is looked
  at twice, or one is skipped.

How it is computed here: every beam alternates flights and walks, in rounds
that take all beams at once (numpy's cost is per call, not per beam). A
flight lists the region-border crossings ahead of each beam along both axes
and takes the first that lands. A walk covers up to three region borders
along each axis: where the path crosses them comes from the closed forms of
stage_walk, and inside each region only the part of the path within the
bounding box of the region's visible cells is searched, one table lookup per
line of the path's minor axis. Most beams end after a walk, a flight and a
walk; a scan takes three or four rounds. That is about a thousand numpy
calls whatever the number of beams; src/stage_raytrace.c steps the same model
cell by cell in C, over twenty times faster, and `stage_ranges` uses it where
its library is built (see compiled_raytrace.py).

`exact_ranges` is plain geometry: the distance to the boundary of the first
occupied cell along the exact ray, for scoring.
"""
import copy
import math

import numpy as np

from . import compiled_raytrace
from .stage_walk import MINOR, NEVER, CellPaths

__all__ = ['stage_ranges', 'exact_ranges', 'stage_beam_angles', 'REGION_WIDTH']

REGION_BITS = 5
REGION_WIDTH = 1 << REGION_BITS
# Region borders looked ahead along each axis by one walk, and the ring of empty
# regions around the grid's tables that this needs.
_BORDERS_AHEAD = 3
_RING = _BORDERS_AHEAD + 1
# Signed cell coordinate of the box of a region without visible cells: beyond any walk.
_NO_BOX = 1 << 40
# Directions of travel, in the order of the per-direction tables: +x, -x, +y, -y.
_PLUS_X, _PLUS_Y = 0, 2


def stage_beam_angles(start, increment, samples):
    """World angles of a Stage ranger's beams.

    Stage stores the running beam angle in a float32 between beams, so the angles are
    a float32 running sum; its rounding drift moves some 1081-beam ranges by a cell.
    """
    steps = np.full(samples, increment, dtype=np.float32)
    steps[0] = start
    return np.cumsum(steps, dtype=np.float32).astype(np.float64)


def stage_ranges(grid, x, y, angles, range_max, height=None, robot_cells=(), other_cells=(),
                 implementation=None):
    """Ranges and intensities of beams from (x, y) at world `angles`, as Stage computes them.

    height: beam height above the ground for Stage's block height test (None: every
        visible cell counts).
    robot_cells: [(xs, ys)] Stage cells of robot bodies; this laser never hits them but,
        as in Stage, they make their regions followed cell by cell.
    other_cells: [(xs, ys, intensity)] cells of other robots, which the laser does hit.
    A beam that hits nothing reads range_max exactly with intensity 0.
    implementation: 'compiled' (the C loop of src/stage_raytrace.c), 'numpy', or None
        for the compiled one where its library is built, else numpy. Both give the
        same beams.
    """
    angles = np.asarray(angles, dtype=np.float64)
    bodies = [c for c in robot_cells if len(c[0])]
    others = [c for c in other_cells if len(c[0])]
    tables = None
    if not others:
        static = _static_tables(grid, height)
        tables = static.with_bodies(bodies) if bodies else static
    if tables is None:
        visible = _visible(grid, height).copy()
        returns = grid.ranger_return.copy()
        nrows, ncols = visible.shape
        for cells_x, cells_y, intensity in others:
            rows = np.asarray(cells_y, dtype=np.int64) - grid.iy0
            cols = np.asarray(cells_x, dtype=np.int64) - grid.ix0
            inside = (rows >= 0) & (cols >= 0) & (rows < nrows) & (cols < ncols)
            visible[rows[inside], cols[inside]] = True
            returns[rows[inside], cols[inside]] = intensity
        bodies = bodies + [(c[0], c[1]) for c in others]
        tables = _GridTables.build(grid, visible, returns, bodies)
    beams = _Beams(angles, grid.ppm * float(range_max))
    return _tracer(implementation)(tables, grid.ppm, float(x), float(y), beams, float(range_max))


def _tracer(implementation):
    """The trace function of an implementation named as in stage_ranges."""
    if implementation == 'numpy':
        return _trace_numpy
    if implementation not in (None, 'compiled'):
        raise ValueError("raytrace implementation %r is none of 'compiled', 'numpy' or None"
                         % (implementation,))
    if compiled_raytrace.available():
        return compiled_raytrace.trace
    if implementation == 'compiled':
        raise RuntimeError(compiled_raytrace.NOT_FOUND)
    return _trace_numpy


def _trace_numpy(tables, ppm, x, y, beams, range_max):
    return _Scan(tables, ppm, x, y, beams, range_max).run()


class _Beams(object):
    """Per-beam constants both implementations start from, computed once, in numpy.

    Stage nudges a beam at exactly 0 rad, whose slope would otherwise be 0.
    cells_x, cells_y: the whole cells to range_max (`reach` cells away) along x and y.
    """

    def __init__(self, angles, reach):
        angle = angles.copy()
        angle[angles == 0.0] = 1e-12
        self.cos = np.cos(angle)
        self.sin = np.sin(angle)
        self.tana = self.sin / self.cos
        self.cells_x = np.abs(reach * self.cos).astype(np.int64)
        self.cells_y = np.abs(reach * self.sin).astype(np.int64)


def _visible(grid, height):
    return grid.visible(height) if height is not None else ~np.isnan(grid.ranger_return)


def _static_tables(grid, height):
    """The tables of the grid alone, cached on the grid per beam height."""
    key = ('stage_ranges', None if height is None else round(float(height), 9))
    tables = grid.cache.get(key)
    if tables is None:
        tables = _GridTables.build(grid, _visible(grid, height), grid.ranger_return, [])
        grid.cache[key] = tables
    return tables


class _GridTables(object):
    """Lookup tables of one grid, on cell arrays padded to whole regions.

    Per-region tables cover the regions of the grid plus a ring of _RING empty regions
    all round (further regions are clamped onto the ring where needed); region (rx, ry)
    is entry (ry - ry0 + _RING) * region_stride + (rx - rx0 + _RING).
    populated[region]: something was drawn into the region (its cells are followed).
    box [(side * 4 + direction) * regions + region]: bounding box of the region's
        visible cells along a direction of travel, in signed coordinates (see `ahead`):
        side 0 its first coordinate, side 1 the first beyond it (one no walk enters for a
        region without visible cells); box_sides: offsets of the two sides.
    ahead[direction * cells + cell]: for every cell and direction (+x, -x along its row,
        +y, -y along its column), the nearest visible cell at or beyond it, as its
        coordinate times the direction's sign, so that along every direction "no further
        than c" reads `ahead <= c`; NEVER if there is none. The column tables are stored
        transposed, so that a walk along y reads consecutive entries too.
    returns[cell]: intensity of a visible cell; cells are (y - cy0) * width + (x - cx0).
    visible[cell]: 1 for a visible cell, as uint8 (what the compiled raytrace reads).
    """

    def __init__(self, populated, rx0, ry0, visible, returns):
        self.rx0, self.ry0 = rx0, ry0
        rows, cols = populated.shape
        self.region_rows, self.region_cols = rows, cols
        self.region_stride = cols + 2 * _RING
        self.region_origin = -((ry0 - _RING) * self.region_stride + (rx0 - _RING))
        self.cx0, self.cy0 = rx0 * REGION_WIDTH, ry0 * REGION_WIDTH
        self.height, self.width = visible.shape
        self.cells = self.height * self.width
        self.populated_lo = np.array([rx0, ry0])
        self.populated_hi = np.array([rx0 + cols - 1, ry0 + rows - 1])
        self.region_lo = np.array([rx0 - _RING, ry0 - _RING])
        self.region_hi = np.array([rx0 + cols + _RING - 1, ry0 + rows + _RING - 1])
        self.returns_origin = -(self.cy0 * self.width + self.cx0)
        self.populated = _with_ring(populated)
        self.returns = returns.ravel()
        self.visible = visible.astype(np.uint8).ravel()
        self._build_boxes(visible.reshape(rows, REGION_WIDTH, cols, REGION_WIDTH))
        self._build_ahead(visible)
        # _Scan.frame for each kind of beam: 4 * (major axis is x) + 2 * (going up x)
        # + (going up y)
        kind = np.arange(8)
        self.frames = _frame_rows(self, kind >= 4, (kind & 2) > 0, (kind & 1) > 0)

    def _build_boxes(self, blocks):
        by_col = blocks.any(axis=1)   # [region row, region col, column within]
        by_row = blocks.any(axis=3)   # [region row, row within, region col]
        col_base = self.cx0 + REGION_WIDTH * np.arange(self.region_cols)[None, :]
        row_base = self.cy0 + REGION_WIDTH * np.arange(self.region_rows)[:, None]
        x_lo = col_base + np.argmax(by_col, axis=2)
        x_hi = col_base + REGION_WIDTH - 1 - np.argmax(by_col[:, :, ::-1], axis=2)
        y_lo = row_base + np.argmax(by_row, axis=1)
        y_hi = row_base + REGION_WIDTH - 1 - np.argmax(by_row[:, ::-1, :], axis=1)
        empty = ~blocks.any(axis=(1, 3))
        near = [np.where(empty, _NO_BOX, b) for b in (x_lo, -x_hi, y_lo, -y_hi)]
        beyond = [np.where(empty, -_NO_BOX, b + 1) for b in (x_hi, -x_lo, y_hi, -y_lo)]
        self.box = np.concatenate([_with_ring(b, _NO_BOX) for b in near] +
                                  [_with_ring(b, -_NO_BOX) for b in beyond])
        self.box_sides = np.array([0, len(self.box) // 2]).reshape(2, 1, 1)

    def _build_ahead(self, visible):
        xs = self.cx0 + np.arange(self.width)[None, :]
        ys = self.cy0 + np.arange(self.height)[:, None]
        plus_x = np.where(visible, xs, NEVER)
        minus_x = np.where(visible, -xs, NEVER)
        plus_y = np.where(visible, ys, NEVER)
        minus_y = np.where(visible, -ys, NEVER)
        self.ahead = np.concatenate([
            np.minimum.accumulate(plus_x[:, ::-1], axis=1)[:, ::-1].ravel(),
            np.minimum.accumulate(minus_x, axis=1).ravel(),
            np.minimum.accumulate(plus_y[::-1, :], axis=0)[::-1, :].T.ravel(),
            np.minimum.accumulate(minus_y, axis=0).T.ravel()])

    @classmethod
    def build(cls, grid, visible, ranger_return, extra_cells):
        """Tables of the grid's drawn cells plus `extra_cells` [(xs, ys)] (robot bodies)."""
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
        vx = vc + grid.ix0 - rx0 * REGION_WIDTH
        vy = vr + grid.iy0 - ry0 * REGION_WIDTH
        padded_visible[vy, vx] = True
        padded_returns[vy, vx] = ranger_return[vr, vc]
        return cls(populated, rx0, ry0, padded_visible, padded_returns)

    def with_bodies(self, bodies):
        """These tables with the regions of `bodies` [(xs, ys)] populated (None if outside).

        Only `populated` differs, so the bodies' regions are set on a copy of it: much
        cheaper, once per scan, than building the tables with the bodies drawn in.
        """
        rx = np.concatenate([np.asarray(c[0], dtype=np.int64) for c in bodies]) >> REGION_BITS
        ry = np.concatenate([np.asarray(c[1], dtype=np.int64) for c in bodies]) >> REGION_BITS
        if rx.min() < self.rx0 or ry.min() < self.ry0 or \
                rx.max() >= self.rx0 + self.region_cols or ry.max() >= self.ry0 + self.region_rows:
            return None
        out = copy.copy(self)
        out.populated = self.populated.copy()
        out.populated[ry * self.region_stride + rx + self.region_origin] = True
        return out

    def populated_at(self, point):
        """Is the region of `point` [x; y] (cell units) populated?"""
        region = np.minimum(np.maximum(np.asarray(point).astype(np.int64) >> REGION_BITS,
                                       self.region_lo), self.region_hi)
        return bool(self.populated[region[1] * self.region_stride + region[0] +
                                   self.region_origin])


# Rows of _Scan.frame: per beam, [major axis; minor axis] pairs, then single rows.
_SIGN = slice(0, 2)             # +1 or -1: direction of travel
_BACK = slice(2, 4)             # 1 when travelling down the axis, else 0
_REGION_STRIDE = slice(4, 6)    # region entry step per region along the axis
_RETURNS_STRIDE = slice(6, 8)   # `returns` step per cell along the axis
_BOX = slice(8, 10)             # offset of the direction's box tables
_AHEAD_BASE = 10                # `ahead` entry of cell (major 0, minor 0)
_AHEAD_LINE = 11                # `ahead` step per signed minor cell
# Borders looked ahead along an axis: the first, second, ...: steps beyond the first.
_FURTHER = REGION_WIDTH * np.arange(_BORDERS_AHEAD, dtype=np.float64)[:, None]
_FURTHER_CELLS = _FURTHER.astype(np.int64)
_BORDER_NUMBER = np.arange(1, _BORDERS_AHEAD + 1)[:, None]
# Rows of _Scan.flight: per beam, what a flight needs.
_HOPS = slice(0, 4)             # how the crossing of an x border, of a y border move on: x, y
_HOP_LENGTH = slice(4, 6)       # their Manhattan lengths
_FLIGHT_AHEAD = slice(6, 8)     # the next border along x, y: a region up or 0 going down
_FLIGHT_BACK = slice(8, 10)     # and 1 cell back when going down
_FLIGHT_TANA = 10
_FLIGHT_START = slice(11, 13)   # (filled in per flight) the position flown from
# Crossings along each axis tried first.
_FIRST_CROSSINGS = 4
# Lines of a search window tried first.
_FIRST_LINES = 2


class _Scan(object):
    """One scan: per-beam constants, then rounds of flights and walks until all beams end.

    A traced beam's state is its position g in cell units, the steps its cell path has
    made and the budget n left, the first two as [major axis; minor axis] of the beam's
    own frame, in which signed cells (cell times the direction's sign) grow along the
    path.
    """

    def __init__(self, tables, ppm, x, y, beams, range_max):
        self.tables = tables
        self.ppm = ppm
        self.start = np.array([x * ppm, y * ppm])
        count = len(beams.cos)
        cos = beams.cos
        sin = beams.sin
        self.tana = beams.tana
        self.paths = CellPaths(beams.cells_x, beams.cells_y)
        self.budget = self.paths.long + self.paths.short
        major_is_x = self.paths.major_is_x > 0
        up_x = cos >= 0
        up_y = sin >= 0
        sx = 2 * up_x - 1
        sy = 2 * up_y - 1
        # frame axis f is axis swap[f] of [x; y], and the other way round
        self.swap = np.empty((2, count), dtype=np.int64)
        self.swap[1] = major_is_x
        self.swap[0] = 1 - self.swap[1]
        self.frame = tables.frames.take(4 * major_is_x + 2 * up_x + up_y, axis=1)
        self.major_trig = np.where(major_is_x, cos, sin)
        self.major_start = np.where(major_is_x, self.start[0], self.start[1])
        # flights: aim at the region border ahead, one cell past it going down
        self.flight = np.empty((13, count))
        hops = self.flight[_HOPS]
        hops[0] = sx * float(REGION_WIDTH)
        np.multiply(hops[0], self.tana, out=hops[1])
        hops[3] = sy * float(REGION_WIDTH)
        np.divide(hops[3], self.tana, out=hops[2])
        np.abs(hops, out=self.flight[_HOP_LENGTH.start:_HOP_LENGTH.start + 4])
        self.flight[4] = self.flight[4] + self.flight[5]
        self.flight[5] = self.flight[6] + self.flight[7]
        self.flight[6] = REGION_WIDTH * up_x
        self.flight[7] = REGION_WIDTH * up_y
        self.flight[8] = ~up_x
        self.flight[9] = ~up_y
        self.flight[_FLIGHT_TANA] = self.tana
        self.ranges = np.full(count, range_max)
        self.intensities = np.zeros(count)

    def run(self):
        beam = np.nonzero(self.budget > 0)[0]
        g = self.start[self.swap[:, beam]]
        steps = np.zeros((2, len(beam)))
        n = self.budget[beam]
        flying = np.full(len(beam), not self.tables.populated_at(self.start))
        while len(beam):
            if flying.any():
                fly = np.nonzero(flying)[0]
                landed, g[:, fly], n[fly] = self._fly(beam[fly], g[:, fly], n[fly])
                if not landed.all():
                    keep = np.ones(len(beam), dtype=bool)
                    keep[fly[~landed]] = False
                    beam, g, steps, n = beam[keep], g[:, keep], steps[:, keep], n[keep]
            if len(beam):
                beam, g, steps, n, flying = self._walk(beam, g, steps, n)
        return self.ranges, self.intensities

    # -- flights -------------------------------------------------------------------------
    def _fly(self, beam, g, n):
        """Fly beams out of empty regions, over the region borders ahead, until each lands.

        Stage aims at the region border ahead along x and along y (one cell past it when
        going down), flies to the nearer of the two crossings, and from then on moves
        the crossing it used one region further, paying each flight's Manhattan length,
        rounded up, from the budget. A flight lands at the first crossing into a
        populated region, unless its budget runs out first. g: frame positions.
        Returns (landed, g, n): whether each beam landed with budget left, and where,
        with what budget.
        """
        count = len(beam)
        every = np.arange(count)
        swap = self.swap.take(beam, axis=1)
        flight = self.flight.take(beam, axis=1)
        flight[_FLIGHT_START] = g[swap, every]
        # Most flights land within a few crossings: try those first, then all that
        # are needed for the rest.
        landed, out, left = self._crossings(flight, n, _FIRST_CROSSINGS)
        again = np.nonzero(landed < 0)[0]
        if len(again):
            landed[again], out[:, again], left[again] = self._crossings(
                flight.take(again, axis=1), n.take(again), None)
        return landed > 0, out[swap, every], left

    def _crossings(self, flight, n, hops):
        """Flights of `hops` crossings along each axis (None: as many as needed).

        The crossings along an axis are the same repeated additions as Stage's. Stage
        keeps the distances to the next crossing along x and along y as running
        differences; here both come from the Manhattan distances along the line, which
        are the same up to rounding (that could only tell for a crossing within
        rounding of a region's corner). Merged in that order (a tie goes to the y
        crossing, as in Stage), the first crossing that lands or runs out of budget
        ends the flight. Returns (landed, x y, n): landed 1, 0, or -1 where `hops` did
        not reach far enough to tell.
        """
        tables = self.tables
        count = flight.shape[1]
        every = np.arange(count)
        pos = flight[_FLIGHT_START]
        up = flight[_FLIGHT_AHEAD] > 0
        to = ((pos.astype(np.int64) & -REGION_WIDTH) + flight[_FLIGHT_AHEAD] - pos) - \
            flight[_FLIGHT_BACK]
        tana = flight[_FLIGHT_TANA]
        rise = to[0] * tana
        run = to[1] / tana
        # crossings needed along each axis to leave the populated regions behind
        region = pos.astype(np.int64) >> REGION_BITS
        needed = np.where(up, tables.populated_hi[:, None] - region,
                          region - tables.populated_lo[:, None]).max(axis=0) + 2
        if hops is None:
            hops = max(int(needed.max()), 1)
        # [axis of the border crossed, crossing number, x / y, beam]
        crossing = np.empty((2, hops, 2, count))
        crossing[0, 0, 0] = pos[0] + to[0]
        crossing[0, 0, 1] = pos[1] + rise
        crossing[1, 0, 0] = pos[0] + run
        crossing[1, 0, 1] = pos[1] + to[1]
        crossing[:, 1:] = flight[_HOPS].reshape(2, 1, 2, count)
        np.cumsum(crossing, axis=1, out=crossing)
        # their Manhattan distances along the flight, in flight order (y crossings first,
        # so that a stable sort puts them first in a tie)
        length = flight[_HOP_LENGTH].reshape(2, 1, count)
        distance = np.empty((2, 1, count))
        distance[1, 0] = np.abs(to[0]) + np.abs(rise)
        distance[0, 0] = np.abs(run) + np.abs(to[1])
        distance = (distance + length[::-1] * np.arange(hops)[:, None]).reshape(2 * hops, count)
        horizon = np.minimum(distance[hops - 1], distance[-1])
        order = np.argsort(distance, axis=0, kind='stable')
        on_x = order >= hops
        flat = order * count + every
        distance = distance.take(flat)
        # Each flight pays its length: after a flight along the same axis the full hop,
        # otherwise what is left of the distance to the crossing. Stage truncates the
        # budget left after each, in double precision, so a length a hair over a whole
        # number (a beam along an axis) may cost that number or one more, depending on
        # the budget's magnitude.
        paid = np.empty((2 * hops, count))
        paid[0] = distance[0]
        np.subtract(distance[1:], distance[:-1], out=paid[1:])
        np.copyto(paid[1:], np.where(on_x[1:], length[0], length[1]),
                  where=on_x[1:] == on_x[:-1])
        budget = paid
        left = n
        for number in range(2 * hops):
            left = np.trunc(left - paid[number])
            budget[number] = left
        points = crossing[::-1].reshape(2 * hops, 2, count)
        land_x = points[:, 0].take(flat)
        land_y = points[:, 1].take(flat)
        regions = np.minimum(np.maximum(land_x.astype(np.int64) >> REGION_BITS,
                                        tables.region_lo[0]), tables.region_hi[0]) + \
            np.minimum(np.maximum(land_y.astype(np.int64) >> REGION_BITS, tables.region_lo[1]),
                       tables.region_hi[1]) * tables.region_stride + tables.region_origin
        alive = budget > 0
        landed = tables.populated.take(regions) & alive
        ends = np.where(landed | ~alive, np.arange(2 * hops)[:, None], 2 * hops).min(axis=0)
        at = np.minimum(ends, 2 * hops - 1) * count + every
        out = np.empty((2, count))
        out[0] = land_x.take(at)
        out[1] = land_y.take(at)
        outcome = (landed.take(at) & (ends < 2 * hops)).astype(np.int64)
        outcome[(needed > hops) & ~((ends < 2 * hops) & (distance.take(at) <= horizon))] = -1
        return outcome, out, budget.take(at)

    # -- walks ---------------------------------------------------------------------------
    def _walk(self, beam, g, steps, n):
        """Walk beams from populated regions on through the populated regions that follow.

        A walk ends at a hit, at the end of its budget, or at a region border where it
        has to stop: into an empty region, at the last border looked ahead, or where
        Stage's cell, taken from the position again at every border, is not the cell
        the walk followed. Returns the state (beam, g, steps, n) of the walks that go
        on, and whether each flies next.
        """
        tables = self.tables
        count = len(beam)
        frame = self.frame.take(beam, axis=1)
        paths = self.paths.select(beam)
        sign = frame[_SIGN]
        region_stride = frame[_REGION_STRIDE]
        cell = g.astype(np.int64)          # truncated, as Stage does
        m0 = steps[0] + steps[1]
        budget_end = m0 + n
        # The region borders ahead along each axis (one kind of border per axis), as
        # states of the path, and the regions entered there.
        to_border = REGION_WIDTH - ((sign * cell - frame[_BACK]) & (REGION_WIDTH - 1))
        counts = (steps + to_border)[:, None, :] + _FURTHER
        states = paths.state_after(counts)
        own_shift = sign[:, None, :] * (to_border[:, None, :] + _FURTHER_CELLS)
        across_shift = sign[::-1, None, :] * (states - counts - steps[::-1, None, :]).astype(
            np.int64)
        across = cell[::-1, None, :] + across_shift
        region = (cell >> REGION_BITS) * region_stride
        here = region[0] + region[1] + tables.region_origin
        entered = ((cell >> REGION_BITS)[:, None, :] + sign[:, None, :] * _BORDER_NUMBER) * \
            region_stride[:, None, :] + (across >> REGION_BITS) * region_stride[::-1, None, :] + \
            tables.region_origin
        # Stage takes the cell from the position again at every border; a walk goes on
        # only where that is the cell it followed (it is not after passing zero, or when
        # rounding moves a position within rounding of a cell border across it).
        goes_on = tables.populated.take(entered, mode='clip')
        goes_on &= (g[:, None, :] + own_shift).astype(np.int64) == cell[:, None, :] + own_shift
        goes_on &= (g[::-1, None, :] + across_shift).astype(np.int64) == across
        goes_on[:, -1] = False
        states = states.reshape(2 * _BORDERS_AHEAD, count)
        end = np.minimum(np.where(goes_on.reshape(2 * _BORDERS_AHEAD, count), NEVER,
                                  states).min(axis=0), budget_end)
        # The walk's stretch in each region it enters, narrowed to the bounding box of the
        # region's visible cells; the first such window along the walk is where it hits,
        # if anywhere before its end (when it passes the window without a hit, later).
        visits = 2 * _BORDERS_AHEAD + 1
        regions = np.empty((visits, count), dtype=np.int64)
        regions[0] = here
        regions[1:] = entered.reshape(visits - 1, count)
        entry = np.empty((visits, count))
        entry[0] = m0
        entry[1:] = states
        shift = sign * cell - steps    # signed cell = shift + steps made, per axis
        box = frame[_BOX][:, None, :] + regions
        into, beyond = paths.state_after(
            tables.box.take(box[:, None] + tables.box_sides, mode='clip') -
            shift[:, None, None, :]).swapaxes(0, 1)
        start = np.maximum(np.maximum(entry, into[0]), into[1])
        stop = np.minimum(np.minimum(end, beyond[0]), beyond[1])
        start[start >= stop] = NEVER
        first = start.min(axis=0)
        b = np.nonzero(first < NEVER)[0]
        hit = np.zeros(count, dtype=bool)
        if len(b):
            first = first.take(b)
            stop = stop.take(b, axis=1)
            until = np.where(start.take(b, axis=1) == first, stop, NEVER).min(axis=0)
            found, majors, state = self._first_hit(b, first, until, paths, frame, shift)
            hits = b[found]
            hit[hits] = True
            moved = np.empty((2, len(hits)))
            moved[0] = majors - steps[0].take(hits)
            moved[1] = state - majors - steps[1].take(hits)
            self._record(beam[hits], g[0].take(hits), cell.take(hits, axis=1),
                         frame.take(hits, axis=1), moved)
            # A walk that passes its window without a hit goes on from the border that
            # ends the window's region, if that comes before its end.
            passed = np.ones(len(b), dtype=bool)
            passed[found] = False
            missed = b[passed]
            after = states.take(missed, axis=1)
            after = np.where(after >= until[passed], after, NEVER).min(axis=0)
            end[missed] = np.minimum(end[missed], after)
        going_on = np.nonzero(~hit & (end < budget_end))[0]
        done = np.empty((2, count))
        done[1] = paths.minors_within(end)
        done[0] = end - done[1]
        done = done.take(going_on, axis=1)
        end = end.take(going_on)
        frame = frame.take(going_on, axis=1)
        g = g.take(going_on, axis=1) + frame[_SIGN] * (done - steps.take(going_on, axis=1))
        # Stage goes on from the cell of the position, which need not be the one entered
        region = (g.astype(np.int64) >> REGION_BITS) * frame[_REGION_STRIDE]
        flies = ~tables.populated.take(region[0] + region[1] + tables.region_origin,
                                       mode='clip')
        return beam.take(going_on), g, done, budget_end.take(going_on) - end, flies

    def _first_hit(self, b, start, stop, paths, frame, shift):
        """First visible cell of walks b among their states start .. stop-1.

        The states lie on lines of the minor axis, each a run along the major axis, and
        one `ahead` lookup per run says whether and where it meets a visible cell. Most
        walks hit on their first line or two; those are searched for every walk, the
        rest only for walks without a hit there. Returns (hit, majors, state): which
        walks hit (indices into b), and for those the major steps made and the state.
        """
        path = paths.select(b)
        frame = frame.take(b, axis=1)
        shift = shift.take(b, axis=1)
        # per window: its first line and its last, its first state and its last, the
        # `ahead` entry of line 0 at major step 0, its step per line and per major step,
        # and the signed major cell at major step 0
        window = np.empty((8, len(b)))
        window[0] = start
        np.subtract(stop, 1.0, out=window[1])
        window[2:4] = window[0:2]
        window[0:2] = path.minors_within(window[0:2])
        window[5] = frame[_AHEAD_LINE]
        window[6] = frame[_SIGN.start]
        window[7] = shift[0]
        window[4] = frame[_AHEAD_BASE] + window[5] * shift[1] + window[6] * shift[0]
        hit, majors, state = self._lines(path, window, _FIRST_LINES)
        rest = np.nonzero(~hit & (window[1] - window[0] >= _FIRST_LINES))[0]
        if len(rest):
            window = window.take(rest, axis=1)
            window[0] += _FIRST_LINES
            found, rest_majors, rest_state = self._lines(
                path.select(rest), window, int((window[1] - window[0]).max()) + 1)
            rest = rest[found]
            hit[rest] = True
            majors[rest] = rest_majors[found]
            state[rest] = rest_state[found]
        found = np.nonzero(hit)[0]
        return found, majors.take(found), state.take(found)

    def _lines(self, path, window, lines):
        """Search the first `lines` lines of each window (see _first_hit) for a visible cell.

        Returns (hit, majors, state) per window; majors and state only mean something
        where it hits.
        """
        first, _, start, last, base, step, sign, shift_major = window
        count = len(first)
        # the line before the first, then the lines searched
        line = first + np.arange(-1.0, lines)[:, None]
        # major steps made before each line's first and after its last state (beyond
        # the path these run on, but the window's own bounds then take over)
        bounds = path.others_before(line, MINOR)
        line = line[1:]
        lo = np.maximum(bounds[:-1], start - line)
        hi = np.minimum(bounds[1:], last - line)
        nearest = self.tables.ahead.take((base + step * line + sign * lo).astype(np.int64),
                                         mode='clip')
        hits = (lo <= hi) & (nearest <= hi + shift_major)
        at = hits.argmax(axis=0) * count + np.arange(count)
        majors = nearest.take(at) - shift_major
        return hits.take(at), majors, majors + line.take(at)

    def _record(self, beam, g_major, cell, frame, moved):
        """Range and intensity of beams that hit after `moved` [major; minor] steps."""
        sign = frame[_SIGN]
        self.ranges[beam] = np.abs((g_major + sign[0] * moved[0] - self.major_start[beam]) /
                                   self.major_trig[beam]) / self.ppm
        tables = self.tables
        hit_cell = (cell + sign * moved.astype(np.int64)) * frame[_RETURNS_STRIDE]
        self.intensities[beam] = tables.returns.take(hit_cell[0] + hit_cell[1] +
                                                     tables.returns_origin)


def _frame_rows(tables, major_is_x, up_x, up_y):
    """The rows of _Scan.frame of beams with these axes and directions, on `tables`."""
    sx = 2 * up_x - 1
    sy = 2 * up_y - 1
    dir_x = _PLUS_X + ~up_x
    dir_y = _PLUS_Y + ~up_y
    regions = len(tables.populated)
    along = np.empty((2, 12, len(up_x)), dtype=np.int64)
    for major, (s_major, s_minor, d_major, d_minor, stride, origin, r, w) in enumerate((
            (sx, sy, dir_x, dir_y, tables.width, tables.cy0 * tables.width + tables.cx0,
             (1, tables.region_stride), (1, tables.width)),
            (sy, sx, dir_y, dir_x, tables.height, tables.cx0 * tables.height + tables.cy0,
             (tables.region_stride, 1), (tables.width, 1)))):
        rows = along[major]
        rows[0] = s_major
        rows[1] = s_minor
        rows[2:4] = rows[0:2] < 0
        rows[_REGION_STRIDE] = np.array(r)[:, None]
        rows[_RETURNS_STRIDE] = np.array(w)[:, None]
        rows[8] = d_major * regions
        rows[9] = d_minor * regions
        rows[_AHEAD_BASE] = d_major * tables.cells - origin
        rows[_AHEAD_LINE] = stride * s_minor
    return np.where(major_is_x, along[0], along[1])


def _with_ring(table, empty=False):
    """`table` [region row, region col] with _RING empty regions all round, flattened."""
    return np.pad(table, _RING, mode='constant', constant_values=empty).ravel()


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
