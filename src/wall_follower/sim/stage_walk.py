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
        a = np.asarray(a, dtype=np.int64)
        b = np.asarray(b, dtype=np.int64)
        long = np.maximum(a, b)
        short = np.minimum(a, b)
        # The x-before-y rule is strict: seen from a major x axis a minor step waits
        # for a tie, seen from a major y axis it does not.
        tie = (a > b).astype(np.int64)
        own = np.stack([long, short])
        other = own[::-1]
        twice_own = 2 * np.maximum(own, 1)
        # Steps of the other kind taken before step number c (0-based) of one kind:
        #   ceil(((2c+1) * other + offset) / twice_own)
        #   = floor((c * 2 other + other + offset + twice_own - 1) / twice_own),
        # where the offset carries the tie rule (and, for a path without minor steps,
        # puts them all after its end).
        offset = np.stack([tie - long, np.where(short == 0, long, 1 - tie - short)])
        self._table = np.concatenate([
            own, 2 * other, other + offset + twice_own - 1, twice_own,
            # minor steps within the first m steps: floor((m * 2 short + c) / d)
            [2 * short, np.maximum(long + short + tie - 1, 0), 2 * np.maximum(long + short, 1),
             tie]]).astype(np.float64)
        self._unpack()

    def _unpack(self):
        table = self._table
        self.long, self.short = table[0], table[1]
        self._twice_other = table[2:4]
        self._before = table[4:6]
        self._twice_own = table[6:8]
        self._within = table[8:11]
        self.major_is_x = table[11]

    def select(self, index):
        """The paths at `index` (an index array or a boolean mask)."""
        out = CellPaths.__new__(CellPaths)
        out._table = self._table[:, index]
        out._unpack()
        return out

    def others_before(self, c, kind):
        """Steps of the other kind taken before step number c (0-based) of `kind`.

        Beyond the path this carries on as if the path went on (c >= 0 only).
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
            before = self._before.reshape(shape) - twice_other
            twice_own = self._twice_own.reshape(shape)
        else:
            twice_other = self._twice_other[kind]
            before = self._before[kind] - twice_other
            twice_own = self._twice_own[kind]
        return count + np.floor((count * twice_other + before) / twice_own)

    def majors_before_minor(self, k):
        """Major steps taken before minor step number k (all of them if there is none)."""
        return np.minimum(np.maximum(self.others_before(k, MINOR), 0.0), self.long)

    def minors_within(self, m):
        """Minor steps among the first m steps, 0 <= m <= long + short.

        Minor step k is step number k + majors_before_minor(k); solving that for k
        gives one floor division.
        """
        twice_short, const, div = self._within
        return np.floor((m * twice_short + const) / div)

    def x_steps_within(self, m):
        """x steps among the first m steps, 0 <= m <= long + short."""
        minors = self.minors_within(m)
        return np.where(self.major_is_x > 0, m - minors, minors)


def line_cells(x0, y0, x1, y1):
    """Cells Stage marks for edges from integer cells (x0, y0) to (x1, y1), arrays of edges.

    The cell before every step is marked, so an edge's end cell is left to the next
    edge of its polygon. Returns (xs, ys) of all edges' cells, concatenated.
    """
    x0, y0, x1, y1 = (np.atleast_1d(np.asarray(v, dtype=np.int64)) for v in (x0, y0, x1, y1))
    a = np.abs(x1 - x0)
    b = np.abs(y1 - y0)
    steps = a + b
    if not len(steps) or steps.max() == 0:
        return np.zeros(0, dtype=np.int64), np.zeros(0, dtype=np.int64)
    sx = np.where(x1 < x0, -1, 1)
    sy = np.where(y1 < y0, -1, 1)
    edge = np.repeat(np.arange(len(steps)), steps)
    m = np.arange(steps.sum()) - np.repeat(np.cumsum(steps) - steps, steps)
    i = CellPaths(a[edge], b[edge]).x_steps_within(m).astype(np.int64)
    return x0[edge] + sx[edge] * i, y0[edge] + sy[edge] * (m - i)
