"""The cell path Stage takes between two cells, in closed form.

Stage rasterises polygon edges and casts laser beams along the same kind of
path: from a start cell towards a cell `a` columns and `b` rows away, one
unit step at a time, each step along x or along y. The path steps along x
while (2i+1)*b < (2j+1)*a, where i and j count the x and y steps taken so
far, and along y otherwise: it takes whichever step keeps it closer to the
straight line, and a tie goes to y.

Seen from the longer ("major") axis, the steps along the shorter ("minor")
axis are spread evenly among the major ones, so how many steps of one kind
come before a given step of the other kind is a single floor division. A
path's cells can therefore be listed without stepping along it, for many
paths at once with numpy. (The laser follows the same path, stepped cell by
cell in src/stage_raytrace.c.)
"""
import numpy as np

__all__ = ['line_cells']


def _minor_steps_within(m, twice_short, offset, twice_total):
    """floor((m * 2 short + offset) / (2 (long + short))), with offset long + short + tie - 1.

    (Exact in float64, and for integer arguments too: a quotient of whole numbers this
    small is never within rounding of the next whole number.)
    """
    return np.floor((m * twice_short + offset) / twice_total)


def line_cells(x0, y0, x1, y1):
    """Cells Stage marks for edges from integer cells (x0, y0) to (x1, y1), arrays of edges.

    The cell before every step is marked, so an edge's end cell is left to the next
    edge of its polygon. Returns (xs, ys) of all edges' cells, concatenated.
    """
    x0, y0, x1, y1 = (np.asarray(v, dtype=np.int64).ravel() for v in (x0, y0, x1, y1))
    dx = x1 - x0
    dy = y1 - y0
    a = np.abs(dx)
    b = np.abs(dy)
    steps = a + b
    total = int(steps.sum())
    if not total:
        return np.zeros(0, dtype=np.int64), np.zeros(0, dtype=np.int64)
    along_x = a > b
    # per edge, repeated for each of its cells: the constants of minor steps within m
    # steps (of edges with steps), whether x is major, the start, the signs
    per_cell = np.stack([2 * np.minimum(a, b), steps + along_x - 1, 2 * steps, along_x, x0, y0,
                         1 - 2 * (dx < 0), 1 - 2 * (dy < 0)]).repeat(steps, axis=1)
    m = np.arange(total) - np.repeat(np.cumsum(steps) - steps, steps)
    minors = _minor_steps_within(m, per_cell[0], per_cell[1], per_cell[2]).astype(np.int64)
    i = np.where(per_cell[3] > 0, m - minors, minors)
    return per_cell[4] + per_cell[6] * i, per_cell[5] + per_cell[7] * (m - i)
