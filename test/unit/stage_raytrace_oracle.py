"""src/stage_raytrace.c transliterated into scalar Python: the oracle the library is held to.

Line for line the same loop, on the same compiled_raytrace.GridTables and Beams
(read through the numpy arrays they keep), with the same floating-point
operations in the same order: Python floats are the same doubles, int() truncates
towards zero as C's conversion does, and >> floors as region_of does, so every
beam must come out bit for bit as the library traces it. Change the two together.
"""
import numpy as np

REGION_BITS = 5
REGION_WIDTH = 1 << REGION_BITS


class _Crossing(object):
    """A region border ahead of a flying beam along one axis (struct crossing)."""

    def __init__(self, gx, gy, dx, dy, hop_x, hop_y):
        self.x, self.y = gx + dx, gy + dy
        self.hop_x, self.hop_y = hop_x, hop_y
        self.hop_length = abs(hop_x) + abs(hop_y)
        self.distance = abs(dx) + abs(dy)


class _Grid(object):
    """The tables of a GridTables, as numpy arrays and ints."""

    def __init__(self, tables):
        visible, returns, populated = tables.arrays
        self.visible, self.returns, self.populated = visible, returns, populated
        self.cx0, self.cy0, self.rx0, self.ry0 = tables.cx0, tables.cy0, tables.rx0, tables.ry0
        self.ppm = tables.ppm

    def populated_at(self, rx, ry):
        row, col = ry - self.ry0, rx - self.rx0
        rows, cols = self.populated.shape
        return 0 <= row < rows and 0 <= col < cols and bool(self.populated[row, col])

    def visible_at(self, x, y):
        row, col = y - self.cy0, x - self.cx0
        rows, cols = self.visible.shape
        return 0 <= row < rows and 0 <= col < cols and bool(self.visible[row, col])


def trace(tables, beams, x, y):
    """(ranges, intensities) as compiled_raytrace.trace(tables, beams, x, y) gives them."""
    grid = _Grid(tables)
    cos, sin, tan, ax, ay = beams.arrays
    startx, starty = x * grid.ppm, y * grid.ppm
    ranges = np.full(len(cos), beams.range_max)
    intensities = np.zeros(len(cos))
    for beam in range(len(cos)):
        hit = _trace_beam(grid, startx, starty, float(cos[beam]), float(sin[beam]),
                          float(tan[beam]), int(ax[beam]), int(ay[beam]))
        if hit is not None:
            ranges[beam] = hit[0] / grid.ppm
            intensities[beam] = hit[1]
    return ranges, intensities


def _trace_beam(grid, startx, starty, cosa, sina, tana, ax, ay):
    """(range in cells, intensity) of one beam, or None when it hits nothing."""
    sx = -1 if cosa < 0.0 else 1
    sy = -1 if sina < 0.0 else 1
    region_x, region_y = float(sx * REGION_WIDTH), float(sy * REGION_WIDTH)
    gx, gy = startx, starty
    error = ay - ax
    budget = ax + ay
    along_x = along_y = None
    while budget > 0:
        ix, iy = int(gx), int(gy)
        rx, ry = ix >> REGION_BITS, iy >> REGION_BITS
        if grid.populated_at(rx, ry):
            cx, cy = ix, iy
            along_x = None
            while cx >> REGION_BITS == rx and cy >> REGION_BITS == ry and budget > 0:
                if grid.visible_at(cx, cy):
                    cells = abs((gx - startx) / cosa) if ax > ay else abs((gy - starty) / sina)
                    return cells, float(grid.returns[cy - grid.cy0, cx - grid.cx0])
                if error < 0:
                    gx += float(sx)
                    error += 2 * ay
                    cx += sx
                else:
                    gy += float(sy)
                    error -= 2 * ax
                    cy += sy
                budget -= 1
            continue
        if along_x is None:
            left, bottom = float(rx * REGION_WIDTH), float(ry * REGION_WIDTH)
            dx = left - gx - 1.0 if sx < 0 else left + REGION_WIDTH - gx
            dy = bottom - gy - 1.0 if sy < 0 else bottom + REGION_WIDTH - gy
            along_x = _Crossing(gx, gy, dx, dx * tana, region_x, region_x * tana)
            along_y = _Crossing(gx, gy, dy / tana, dy, region_y / tana, region_y)
        taken, other = (along_x, along_y) if along_x.distance < along_y.distance else \
            (along_y, along_x)
        gx, gy = taken.x, taken.y
        budget = int(float(budget) - taken.distance)
        taken.x += taken.hop_x
        taken.y += taken.hop_y
        other.distance -= taken.distance
        taken.distance = taken.hop_length
    return None
