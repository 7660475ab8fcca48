"""Stage's integer cell walk, in closed form.

Stage draws polygon edges (World::MapPoly) and casts rays (World::Raytrace)
with the same walk: from a start cell towards a cell (ax, ay) away, one unit
step at a time, an x step when the error term (2i+1)*ay - (2j+1)*ax is
negative (i, j: x and y steps made so far) and a y step otherwise, so ties go
to y. The walk is a fixed lattice path, so the state after any number of
steps can be computed directly, for many walks at once with numpy.
"""
import numpy as np

__all__ = ['y_steps_before_x', 'x_steps_before_y', 'x_count', 'steps_until_x', 'steps_until_y', 'line_cells']

_NEVER = np.iinfo(np.int64).max


def y_steps_before_x(i, ax, ay):
    """y steps made before x step number i (0-based): #{j : (2j+1)*ax <= (2i+1)*ay}."""
    return ((2 * i + 1) * ay + ax) // (2 * np.maximum(ax, 1))


def x_steps_before_y(j, ax, ay):
    """x steps made before y step number j (0-based): #{i : (2i+1)*ay < (2j+1)*ax}."""
    return np.minimum(np.maximum(-((ay - (2 * j + 1) * ax) // (2 * np.maximum(ay, 1))), 0), ax)


def x_count(m, ax, ay):
    """Number of x steps among the first m steps of the walk towards (ax, ay).

    x step number i is step i + y_steps_before_x(i) of the walk; invert that by an
    estimate from the slope and two correction rounds.
    """
    ax_safe = np.maximum(ax, 1)
    est = np.ceil(np.minimum(m, ax + ay) / (1.0 + ay / ax_safe) - 0.5).astype(np.int64)
    est = np.minimum(np.maximum(est, 0), ax)
    for _ in range(2):
        after = est + y_steps_before_x(est, ax, ay)
        est = np.where((est < ax) & (after < m), est + 1, est)
        prev = est - 1
        before = prev + y_steps_before_x(prev, ax, ay)
        est = np.where((est > 0) & (before >= m), prev, est)
    return np.where(ax == 0, 0, est)


def steps_until_x(count, ax, ay):
    """Number of steps after which the walk has made `count` >= 1 x steps (huge if never)."""
    i = count - 1
    steps = i + y_steps_before_x(i, ax, ay) + 1
    return np.where((count <= ax) & (ax > 0), steps, _NEVER)


def steps_until_y(count, ax, ay):
    """Number of steps after which the walk has made `count` >= 1 y steps (huge if never)."""
    j = count - 1
    steps = j + x_steps_before_y(j, ax, ay) + 1
    return np.where((count <= ay) & (ay > 0), steps, _NEVER)


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
    i = x_count(m, ax[edge], ay[edge])
    j = m - i
    return x0[edge] + sx[edge] * i, y0[edge] + sy[edge] * j
