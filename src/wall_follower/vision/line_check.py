"""Whether the line colour in a camera frame looks like a line on the floor.

The line follower acts only on a mask that does: a yellow floor, a yellow
wall or a frame of noise whose pixels happen to fall in the line's colour
must stop the robot, not steer it. The mask, within the floor the camera
sees up to the projection's max_distance, is judged by three properties a
painted line has whatever the camera:

- it is connected: the line shows in a few pieces (one; more where it
  leaves the view and comes back, or where its stepped edges break off a
  pixel: at most 9 in the line worlds, at any camera size, JPEG or not);
  noise falls in hundreds. More than MAX_PIECES is not a line.
- it covers a plausible share of the floor in view: at most what a band of
  the widest line could cover, twice as long as the view's longest chord
  (a bending line is longer than a straight one).
- its width on the floor lies within bounds of the course's line. The mask
  is put on a grid over the floor (FloorGrid), where the width of a piece
  is the diameter of the widest disc inside it (a distance transform). A
  pixel spans more floor the farther it looks, and a piece's edges are only
  known to within a pixel: the bounds are widened by that span, so that far
  and coarse views pass. A piece wider than max_width (a patch, a wall)
  fails the frame. A piece narrower than min_width that lies wholly inside
  the view (not cut by the image's border, the horizon or max_distance, as a
  line the camera sees only the edge of is) is a thread or a speck, not the
  line: it fails nothing, but is left out of what is acted on.

A frame that fails is NOT_A_LINE, with the reason in words (stable words,
so that a repeated warning can be throttled); one with no line colour left
on a floor in view is EMPTY (clear floor: a search may turn to look for
the line); else LINE, with the mask of the pieces to act on.
"""
from collections import namedtuple

import cv2
import numpy as np

LINE = 'line'
EMPTY = 'empty'
NOT_A_LINE = 'not a line'

MAX_PIECES = 20
CELLS_ACROSS = 4            # grid cells across the narrowest line accepted
MAX_CELLS = 250000          # at most this many grid cells: a far-seeing camera gets coarser ones
LENGTH_SHARE = 2.0          # a line in view is at most this many of the view's longest chords

Verdict = namedtuple('Verdict', ['kind', 'mask', 'problem'])
"""What a frame's line colour is (LINE, EMPTY or NOT_A_LINE), the uint8 mask to act on (the
pieces of line; zeros unless LINE) and, for NOT_A_LINE, why in words."""


class FloorGrid(object):
    """The floor a camera sees, as square cells: what judging a mask on the floor needs,
    worked out once for a projection (vision.floor.FloorProjection) and a cell size [m].

    view: (height, width) bool, the pixels that see the floor within max_distance; edge:
    the pixels on or next to the border of that view; in_view: (rows, columns) bool, the
    cells seen; span: (rows, columns) float, the floor one pixel spans at each cell [m].
    """

    def __init__(self, projection, cell):
        self.view = projection.floor_view()
        beyond = ~self.view
        beyond[[0, -1], :] = True
        beyond[:, [0, -1]] = True
        self.edge = cv2.dilate(beyond.astype(np.uint8), np.ones((3, 3), np.uint8)) > 0
        rows, columns = np.nonzero(self.view)
        points = projection.to_floor(np.column_stack((columns, rows)))
        self.cells_in_view = 0
        if len(points) == 0:
            return
        lower = points.min(axis=0) - cell
        extent = points.max(axis=0) + cell - lower
        cell = max(cell, float(np.sqrt(extent[0] * extent[1] / MAX_CELLS)))
        self.cell = cell
        size = np.ceil(extent / cell).astype(int) + 1
        self.size = (int(size[0]), int(size[1]))       # (columns, rows), as OpenCV takes it
        # Grid (column, row, 1) -> pixel (column, row, 1): x along columns, y along rows.
        self.to_image = projection.homography().dot(
            np.array([[cell, 0.0, lower[0]], [0.0, cell, lower[1]], [0.0, 0.0, 1.0]]))
        grid_columns, grid_rows = np.meshgrid(np.arange(self.size[0]), np.arange(self.size[1]))
        ahead = (self.to_image[2, 0] * grid_columns + self.to_image[2, 1] * grid_rows
                 + self.to_image[2, 2]) > 0.0
        self.in_view = ahead & (self._sample(self.view.astype(np.uint8)) > 0)
        self.cells_in_view = int(self.in_view.sum())
        self.span = self._pixel_span(projection, lower, grid_columns, grid_rows)
        seen = np.column_stack((grid_columns[self.in_view], grid_rows[self.in_view])) * cell
        hull = cv2.convexHull(seen.astype(np.float32)).reshape(-1, 2)
        self.area = self.cells_in_view * cell * cell
        self.diameter = float(np.max(np.hypot(*(hull[:, None, :] - hull[None, :, :]).T)))

    def on_floor(self, image):
        """A uint8 image (labels, a mask) on the grid: at each cell in view, the value of the
        pixel its centre lies in; 0 out of view."""
        return np.where(self.in_view, self._sample(image), 0)

    def _sample(self, image):
        return cv2.warpPerspective(image, self.to_image, self.size,
                                   flags=cv2.INTER_NEAREST | cv2.WARP_INVERSE_MAP)

    def share_bound(self, max_width):
        """The largest share of the floor in view that a line max_width [m] wide covers."""
        return min(1.0, LENGTH_SHARE * max_width * self.diameter / self.area)

    def _pixel_span(self, projection, lower, grid_columns, grid_rows):
        """(rows, columns) floor distance [m] a step of one pixel makes at each cell in view
        (the larger of a step along a row and along a column); 0 out of view."""
        span = np.zeros(self.in_view.shape)
        centres = lower + self.cell * np.column_stack((grid_columns[self.in_view],
                                                       grid_rows[self.in_view]))
        pixels, _ = projection.to_pixels(centres)
        for step in ((1.0, 0.0), (0.0, 1.0)):
            moved, on_floor = projection.floor_points(pixels + step)
            reach = np.where(on_floor, np.hypot(*(moved - centres).T), projection.max_distance)
            span[self.in_view] = np.maximum(span[self.in_view], reach)
        return span


class LineCheck(object):
    """Judges masks (uint8, nonzero on the line's colour) against a line of line_width [m]:
    widths from line_width / tolerance to line_width * tolerance pass (see the module)."""

    def __init__(self, line_width, tolerance):
        self.reconfigure(line_width, tolerance)
        self._grid = None
        self._grid_key = None

    def reconfigure(self, line_width, tolerance):
        self.min_width = line_width / tolerance
        self.max_width = line_width * tolerance

    def grid(self, projection):
        """The FloorGrid of a projection (kept while the projection and the bounds stay)."""
        key = (projection.key(), self.min_width)
        if key != self._grid_key:
            self._grid = FloorGrid(projection, self.min_width / CELLS_ACROSS)
            self._grid_key = key
        return self._grid

    def judge(self, mask, projection):
        """The Verdict on a mask seen through a projection of the same image size."""
        grid = self.grid(projection)
        nothing = np.zeros_like(mask)
        if grid.cells_in_view == 0:
            return Verdict(NOT_A_LINE, nothing, 'the camera sees no floor within %.1f m'
                           % projection.max_distance)
        inside = ((mask > 0) & grid.view).astype(np.uint8)
        count, labels = cv2.connectedComponents(inside, connectivity=8)
        if count == 1:
            return Verdict(EMPTY, nothing, None)
        if count - 1 > MAX_PIECES:
            return Verdict(NOT_A_LINE, nothing, 'line colour scattered in more than %d pieces, '
                           'not one line' % MAX_PIECES)
        labels = labels.astype(np.uint8)
        cells = grid.on_floor(labels)
        if np.count_nonzero(cells) > grid.share_bound(self.max_width) * grid.cells_in_view:
            return Verdict(NOT_A_LINE, nothing, 'line colour covers more of the floor in view '
                           'than a line %.1f cm wide can' % (100.0 * self.max_width))
        narrowest, widest = self._widths(grid, cells, count)
        if np.any(narrowest > self.max_width):
            return Verdict(NOT_A_LINE, nothing, 'a patch of line colour wider than the line '
                           '(over %.1f cm on the floor)' % (100.0 * self.max_width))
        keep = widest >= self.min_width
        keep[np.unique(labels[grid.edge & (inside > 0)])] = True
        keep[0] = False
        if not keep.any():
            return Verdict(EMPTY, nothing, None)
        if keep[1:].all():
            return Verdict(LINE, inside * np.uint8(255), None)
        kept = np.zeros(256, np.uint8)          # label -> 255 for the pieces kept
        kept[:count] = np.where(keep, 255, 0)
        return Verdict(LINE, cv2.LUT(labels, kept), None)

    def _widths(self, grid, cells, count):
        """(count,) the least and the most width [m] each piece (label) may have, from the
        widest disc inside it (measured to the cell) and the floor a pixel spans there; 0 for
        a piece on no cell. A colour edge may be off by up to a pixel each side (JPEG
        blurs colour over two): the least width allows for that; the most width need only
        allow for a pixel in all, as a line is far wider than a thread."""
        line = cells > 0
        inside = cv2.distanceTransform(line.astype(np.uint8), cv2.DIST_L2, cv2.DIST_MASK_5)
        width = (2.0 * inside[line] - 1.0) * grid.cell
        least = width - 2.0 * grid.span[line] - grid.cell
        most = width + grid.span[line] + grid.cell
        labels = cells[line]
        narrowest, widest = np.zeros(count), np.zeros(count)
        for label in np.unique(labels):
            piece = labels == label
            narrowest[label] = max(0.0, np.max(least[piece]))
            widest[label] = np.max(most[piece])
        return narrowest, widest
