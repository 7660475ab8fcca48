"""How much of a world's free floor a run visited: the figure of the wander benchmark.

The floor is cut into square cells. A cell is free when the robot, standing
at its centre (heading along x), clears every obstacle, and it belongs to
the floor when it can be reached from the run's start through free cells
(so the space outside a world's outer wall does not count). A cell is
visited when the robot's axle passed through it.
"""
import math

import numpy as np

DEFAULT_CELL = 0.2   # m


def reachable_cells(course_map, start, cell=DEFAULT_CELL):
    """Boolean grid of the free cells reachable from start (x, y), and the grid's origin.

    Returns (free, (x0, y0)): free[row, col] covers x0 + col * cell, y0 + row * cell.
    """
    edges = course_map.edges.reshape(-1, 2)
    x0, y0 = edges.min(axis=0)
    x1, y1 = edges.max(axis=0)
    cols, rows = int(math.ceil((x1 - x0) / cell)), int(math.ceil((y1 - y0) / cell))
    clear = np.zeros((rows, cols), dtype=bool)
    for row in range(rows):
        for col in range(cols):
            centre = (x0 + (col + 0.5) * cell, y0 + (row + 0.5) * cell, 0.0)
            clear[row, col] = course_map.clearance(centre) > 0.0
    free = np.zeros_like(clear)
    first = (int((start[1] - y0) // cell), int((start[0] - x0) // cell))
    stack = [first] if clear[first] else []
    while stack:
        row, col = stack.pop()
        if 0 <= row < rows and 0 <= col < cols and clear[row, col] and not free[row, col]:
            free[row, col] = True
            stack.extend(((row + 1, col), (row - 1, col), (row, col + 1), (row, col - 1)))
    return free, (x0, y0)


def visited_share(course_map, trail, cell=DEFAULT_CELL):
    """Share (0..1) of the free floor's cells that the trail [(x, y, ...)] passed through."""
    if not len(trail):
        return 0.0
    free, (x0, y0) = reachable_cells(course_map, trail[0][:2], cell)
    if not free.any():
        return 0.0
    xy = np.asarray([p[:2] for p in trail], dtype=float)
    cols = ((xy[:, 0] - x0) // cell).astype(int)
    rows = ((xy[:, 1] - y0) // cell).astype(int)
    inside = (rows >= 0) & (rows < free.shape[0]) & (cols >= 0) & (cols < free.shape[1])
    visited = np.zeros_like(free)
    visited[rows[inside], cols[inside]] = True
    return float((visited & free).sum()) / float(free.sum())
