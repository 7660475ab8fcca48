"""Stage's integer cell walk, in closed form.

Stage draws polygon edges (World::MapPoly) and casts rays (World::Raytrace)
with the same walk: from a start cell towards a cell (ax, ay) away, one unit
step at a time, an x step when the error term (2i+1)*ay - (2j+1)*ax is
negative (i, j: x and y steps made so far) and a y step otherwise, so ties go
to y. The walk is a fixed lattice path, so the state after any number of
steps can be computed directly, for many walks at once with numpy.
"""
import numpy as np

__all__ = ['Walks', 'line_cells', 'NEVER']

NEVER = np.iinfo(np.int64).max


class Walks(object):
    """Many walks at once: arrays ax, ay >= 0 of cell distances along x and y."""

    def __init__(self, ax, ay):
        self.ax = np.asarray(ax, dtype=np.int64)
        self.ay = np.asarray(ay, dtype=np.int64)
        self._two_ax = 2 * self.ax
        self._two_ay = 2 * self.ay
        self._div_x = 2 * np.maximum(self.ax, 1)
        self._div_y = 2 * np.maximum(self.ay, 1)
        self._ax_plus_ay = self.ax + self.ay
        self._ay_minus_ax = self.ay - self.ax
        self._slope = self.ay / np.maximum(self.ax, 1)

    def subset(self, index):
        """The walks selected by `index`."""
        return Walks(self.ax[index], self.ay[index])

    def column(self):
        """These walks with their constants shaped (n, 1), to broadcast over a row."""
        return Walks(self.ax[:, None], self.ay[:, None])

    def y_before_x(self, i):
        """y steps made before x step number i (0-based): #{j : (2j+1)*ax <= (2i+1)*ay}."""
        return (i * self._two_ay + self._ax_plus_ay) // self._div_x

    def x_before_y(self, j):
        """x steps made before y step number j (0-based): #{i : (2i+1)*ay < (2j+1)*ax}."""
        return np.minimum(np.maximum(-((self._ay_minus_ax - j * self._two_ax) // self._div_y),
                                     0), self.ax)

    def x_count(self, m):
        """Number of x steps among the first m steps.

        x step number i is step i + y_before_x(i), within half a step of
        (i + 1/2) * (1 + ay/ax); so the estimate below is off by at most one, and one
        check in each direction settles it.
        """
        ax = self.ax
        est = np.ceil(np.minimum(m, self._ax_plus_ay) / (1.0 + self._slope) - 0.5)
        est = np.minimum(np.maximum(est.astype(np.int64), 0), ax)
        est = np.where((est < ax) & (est + self.y_before_x(est) < m), est + 1, est)
        prev = est - 1
        est = np.where((est > 0) & (prev + self.y_before_x(prev) >= m), prev, est)
        return np.where(ax == 0, 0, est)

    def steps_until_x(self, count):
        """Steps after which `count` >= 1 x steps are made (NEVER if the walk has fewer)."""
        return np.where(count <= self.ax, count + self.y_before_x(count - 1), NEVER)

    def steps_until_y(self, count):
        """Steps after which `count` >= 1 y steps are made (NEVER if the walk has fewer)."""
        return np.where(count <= self.ay, count + self.x_before_y(count - 1), NEVER)


def line_cells(x0, y0, x1, y1):
    """Cells Stage marks for edges from integer cells (x0, y0) to (x1, y1), arrays of edges.

    The cell before every step is marked, so an edge's end cell is left to the next
    edge of its polygon. Returns (xs, ys) of all edges' cells, concatenated.
    """
    x0, y0, x1, y1 = (np.atleast_1d(np.asarray(v, dtype=np.int64)) for v in (x0, y0, x1, y1))
    ax = np.abs(x1 - x0)
    ay = np.abs(y1 - y0)
    n = ax + ay
    if not len(n) or n.max() == 0:
        return np.zeros(0, dtype=np.int64), np.zeros(0, dtype=np.int64)
    sx = np.where(x1 < x0, -1, 1)
    sy = np.where(y1 < y0, -1, 1)
    edge = np.repeat(np.arange(len(n)), n)
    m = np.arange(n.sum()) - np.repeat(np.cumsum(n) - n, n)
    i = Walks(ax[edge], ay[edge]).x_count(m)
    return x0[edge] + sx[edge] * i, y0[edge] + sy[edge] * (m - i)
