"""Laser ranges on an OccupancyGrid, as real Stage measures them.

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

src/stage_raytrace.c follows each beam this way, cell by cell, through
compiled_raytrace.py; this module lays out what it reads: which cells a beam
can hit and which regions it walks.
"""
import numpy as np

from . import compiled_raytrace

__all__ = ['stage_ranges', 'stage_beam_angles']

# Stage's regions are 2^5 = 32 cells wide.
_REGION_BITS = 5


def stage_beam_angles(start, increment, samples):
    """World angles of a Stage ranger's beams.

    Stage stores the running beam angle in a float32 between beams, so the angles are
    a float32 running sum; its rounding drift moves some 1081-beam ranges by a cell.
    """
    steps = np.full(samples, increment, dtype=np.float32)
    steps[0] = start
    return np.cumsum(steps, dtype=np.float32).astype(np.float64)


def stage_ranges(grid, x, y, angles, range_max, height=None, robot_cells=(), other_cells=()):
    """Ranges and intensities of beams from (x, y) at world `angles`, as Stage computes them.

    height: beam height above the ground for Stage's block height test (None: every
        visible cell counts).
    robot_cells: [(xs, ys)] Stage cells of robot bodies; this laser never hits them but,
        as in Stage, they make their regions walked cell by cell.
    other_cells: [(xs, ys, intensity)] cells of other robots, which the laser does hit
        (where they lie on the grid).
    A beam that hits nothing reads range_max exactly with intensity 0. Raises
    compiled_raytrace.LibraryMissing when the library is not built.
    """
    static = _static_layers(grid, height)
    visible, returns = static.visible, grid.ranger_return
    others = [c for c in other_cells if len(c[0])]
    if others:
        visible, returns = visible.copy(), returns.copy()
        for cells_x, cells_y, intensity in others:
            rows, cols = _cells_on(grid, cells_x, cells_y)
            visible[rows, cols] = True
            returns[rows, cols] = intensity
    bodies = [c[:2] for c in list(robot_cells) + others if len(c[0])]
    populated, region_origin = _populated_regions(
        np.concatenate([static.region_x] + [_region(c[0]) for c in bodies]),
        np.concatenate([static.region_y] + [_region(c[1]) for c in bodies]))
    tables = compiled_raytrace.GridTables(visible, returns, (grid.ix0, grid.iy0), populated,
                                          region_origin, grid.ppm)
    beams = compiled_raytrace.Beams(angles, range_max, grid.ppm)
    return compiled_raytrace.trace(tables, beams, x, y)


class _StaticLayers(object):
    """What a scan takes from the grid alone, per beam height.

    visible [row, col]: cells a beam can hit, as the uint8 the library reads.
    region_x, region_y: the regions something was drawn into, once each.
    """

    def __init__(self, grid, height):
        visible = grid.visible(height) if height is not None else ~np.isnan(grid.ranger_return)
        self.visible = visible.astype(np.uint8)
        rows, cols = np.nonzero(grid.drawn)
        populated, (rx0, ry0) = _populated_regions(_region(cols + grid.ix0),
                                                   _region(rows + grid.iy0))
        region_rows, region_cols = np.nonzero(populated)
        self.region_x = region_cols + rx0
        self.region_y = region_rows + ry0


def _static_layers(grid, height):
    """The grid's _StaticLayers, cached on the grid per beam height."""
    key = ('stage_ranges', None if height is None else round(float(height), 9))
    layers = grid.cache.get(key)
    if layers is None:
        layers = _StaticLayers(grid, height)
        grid.cache[key] = layers
    return layers


def _region(cells):
    """Regions of Stage cell coordinates along one axis."""
    return np.asarray(cells, dtype=np.int64) >> _REGION_BITS


def _cells_on(grid, cells_x, cells_y):
    """(rows, cols) of the Stage cells that lie on the grid."""
    rows = np.asarray(cells_y, dtype=np.int64) - grid.iy0
    cols = np.asarray(cells_x, dtype=np.int64) - grid.ix0
    nrows, ncols = grid.shape
    inside = (rows >= 0) & (cols >= 0) & (rows < nrows) & (cols < ncols)
    return rows[inside], cols[inside]


def _populated_regions(region_x, region_y):
    """(populated [rows, cols], (rx0, ry0)): the box of the given regions, set where given."""
    if not len(region_x):
        return np.zeros((0, 0), dtype=bool), (0, 0)
    rx0, ry0 = int(region_x.min()), int(region_y.min())
    populated = np.zeros((int(region_y.max()) - ry0 + 1, int(region_x.max()) - rx0 + 1),
                         dtype=bool)
    populated[region_y - ry0, region_x - rx0] = True
    return populated, (rx0, ry0)
