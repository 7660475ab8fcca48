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
path can therefore be looked at anywhere without stepping along it, for many
paths at once with numpy.
"""
import numpy as np

__all__ = ['CellPaths', 'line_cells', 'NEVER', 'MAJOR', 'MINOR']

# A state beyond any path.
NEVER = float(1 << 40)
# The kinds of step, indexing the first dimension of stacked queries.
MAJOR, MINOR = 0, 1


class CellPaths(object):
    """Many paths at once, given arrays a, b >= 0 of their x and y cell distances.

    long / short: the number of major / minor steps (major is x when a > b, else y).
    State m of a path is the cell after its first m steps, 0 <= m <= long + short.
    Step counts and states are float64 holding whole numbers (exact far beyond any
    path), because numpy divides floats several times faster than integers; each
    floor division below is exact, as its quotient is a fraction with a small
    denominator, far from the rounding error. Queries that take `kind` accept MAJOR,
    MINOR, or None for arrays stacked as [major queries, minor queries] along their
    first dimension.
    """

    def __init__(self, a, b):
        a = np.asarray(a, dtype=np.float64)
        b = np.asarray(b, dtype=np.float64)
        table = np.empty((14,) + a.shape)
        long, short = table[0], table[1]
        np.maximum(a, b, out=long)
        np.minimum(a, b, out=short)
        # The x-before-y rule is strict: seen from a major x axis a minor step waits
        # for a tie, seen from a major y axis it does not.
        tie = table[11]
        np.greater(a, b, out=tie)
        # Steps of the other kind taken before step number c (0-based) of one kind:
        #   ceil(((2c+1) * other + offset) / twice_own)
        #   = floor((c * 2 other + other + offset + twice_own - 1) / twice_own),
        # where the offset carries the tie rule: tie - long for major steps (other =
        # short) and 1 - tie - short for minor ones (other = long), or, for a path
        # without minor steps, long, which puts them all after its end.
        twice_own = table[6:8]
        np.maximum(table[0:2], 1.0, out=twice_own)
        twice_own *= 2.0
        np.multiply(short, 2.0, out=table[2])
        np.multiply(long, 2.0, out=table[3])
        table[4] = short + tie - long + twice_own[0] - 1.0
        table[5] = np.where(short == 0, 2.0 * long, long + 1.0 - tie - short) + twice_own[1] - 1.0
        # the same for step number count - 1, for state_after
        np.subtract(table[4:6], table[2:4], out=table[12:14])
        # minor steps within the first m steps: floor((m * 2 short + c) / d)
        table[8] = table[2]
        np.maximum(long + short + tie - 1.0, 0.0, out=table[9])
        np.maximum(long + short, 1.0, out=table[10])
        table[10] *= 2.0
        self._table = table
        self._unpack()

    def _unpack(self):
        table = self._table
        self.long, self.short = table[0], table[1]
        self._twice_other = table[2:4]
        self._before = table[4:6]
        self._twice_own = table[6:8]
        self._within = table[8:11]
        self.major_is_x = table[11]
        self._after = table[12:14]

    def select(self, index):
        """The paths at `index` (an index array or a boolean mask)."""
        out = CellPaths.__new__(CellPaths)
        out._table = self._table[:, index]
        out._unpack()
        return out

    def others_before(self, c, kind):
        """Steps of the other kind taken before step number c (0-based) of `kind`.

        Beyond the path this carries on as if the path went on; for c = -1 it is <= 0.
        """
        return np.floor((c * self._twice_other[kind] + self._before[kind]) /
                        self._twice_own[kind])

    def state_after(self, count, kind=None):
        """State at which `count` >= 1 steps of `kind` are done.

        Beyond the path this is a state beyond its end (and it is <= 0 for count <= 0),
        so that comparisons with states within the path need no special case.
        """
        if kind is None:
            shape = (2,) + (1,) * (np.ndim(count) - 2) + (-1,)
            twice_other = self._twice_other.reshape(shape)
            after = self._after.reshape(shape)
            twice_own = self._twice_own.reshape(shape)
        else:
            twice_other = self._twice_other[kind]
            after = self._after[kind]
            twice_own = self._twice_own[kind]
        # count steps of this kind, and the others taken before the last of them
        return count + np.floor((count * twice_other + after) / twice_own)

    def minors_within(self, m):
        """Minor steps among the first m steps, 0 <= m <= long + short.

        Minor step k is step number k + others_before(k, MINOR); solving that for k
        gives one floor division.
        """
        return _minor_steps_within(m, *self._within)


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
