"""Checks that a floorplan is a fair course: what every generated world must pass.

They work on the world's free-space mask (True = free) at the floorplan's
pixel size, so they judge exactly the pixels Stage will load:

- connected: one region of free space (4-connected pixels), so that no
  part of the world is out of reach;
- corridors wide enough: no two stretches of wall that face each other
  across free space come nearer than `min_width`. Walls "face" when each
  one's normal points within `CORNER_ANGLE`/2 of the other: the two legs of
  a corner of at least CORNER_ANGLE never do, so corners are not mistaken
  for narrow passages, while the sides of a corridor, or a pillar and the
  wall beside it, always do;
- the robot fits along every wall: the places where the robot's centre can
  be `follow_distance` from every wall (the middle of the band a follower
  keeps) form one region, and every wall pixel is within reach of it (a
  corner's pixels at most follow_distance / sin(CORNER_ANGLE / 2) away), so
  a follower can go all the way round any wall it finds;
- the start pose at least `start_clearance` from every wall.

Each check returns the problems it found, in words; none means the world
passes.
"""
import math

import numpy as np
from scipy.ndimage import distance_transform_edt, label
from scipy.spatial import cKDTree

# The sharpest corner of free space that is a corner and not a narrowing [rad].
CORNER_ANGLE = math.radians(60.0)
MIN_WIDTH = 0.7
START_CLEARANCE = 0.5
FOLLOW_DISTANCE = 0.25
_FOUR = np.array([[0, 1, 0], [1, 1, 1], [0, 1, 0]])


class FreeSpace(object):
    """A free-space mask and where its pixels are.

    free[row, col]: True where free; row 0 is the top (+y). The centre of
    pixel (row, col) is at (x0 + col * pixel, y0 - row * pixel) metres.
    """

    def __init__(self, free, pixel, x0, y0):
        self.free = np.asarray(free, dtype=bool)
        self.pixel = float(pixel)
        self.x0, self.y0 = float(x0), float(y0)
        padded = np.pad(self.free, 1, mode='constant', constant_values=False)
        # Distance from each free pixel's centre to the nearest wall (half a pixel
        # nearer than the nearest black pixel's centre).
        self.clearance = (distance_transform_edt(padded)[1:-1, 1:-1] - 0.5) * self.pixel
        self.clearance[~self.free] = 0.0

    def xy(self, rows, cols):
        return np.column_stack((self.x0 + cols * self.pixel, self.y0 - rows * self.pixel))

    def cell(self, x, y):
        """(row, col) of the pixel holding (x, y); None outside the mask."""
        row = int(round((self.y0 - y) / self.pixel))
        col = int(round((x - self.x0) / self.pixel))
        if 0 <= row < self.free.shape[0] and 0 <= col < self.free.shape[1]:
            return row, col
        return None

    def wall_pixels(self):
        """(rows, cols) of the free pixels that touch a wall (4-neighbours)."""
        padded = np.pad(self.free, 1, mode='constant', constant_values=False)
        touching = ~(padded[:-2, 1:-1] & padded[2:, 1:-1] & padded[1:-1, :-2] & padded[1:-1, 2:])
        return np.nonzero(self.free & touching)


def connected(space):
    """Problems: free space in more than one piece."""
    _, count = label(space.free, structure=_FOUR)
    if count == 0:
        return ['no free space']
    if count > 1:
        return ['free space is in %d separate pieces' % count]
    return []


def _segment_free(space, a, b):
    """Whether the straight line between points a and b stays in free space."""
    steps = max(2, int(math.ceil(np.hypot(*(b - a)) / (0.5 * space.pixel))) + 1)
    for t in np.linspace(0.0, 1.0, steps):
        cell = space.cell(*(a + t * (b - a)))
        if cell is None or not space.free[cell]:
            return False
    return True


def narrowest_passage(space, min_width=MIN_WIDTH, corner_angle=CORNER_ANGLE):
    """(width m, (x, y) of its middle) of the narrowest passage under min_width; None if none.

    Pairs of wall pixels nearer than min_width whose walls face each other
    (see the module's rule) with free space between them.
    """
    rows, cols = space.wall_pixels()
    if not len(rows):
        return None
    gy, gx = np.gradient(space.clearance)
    # Inward normals (away from the wall), in world axes (rows run to -y).
    normals = np.column_stack((gx[rows, cols], -gy[rows, cols]))
    lengths = np.hypot(normals[:, 0], normals[:, 1])
    usable = lengths > 1e-9
    normals[usable] /= lengths[usable, None]
    points = space.xy(rows, cols)
    # Pixel centres lie half a pixel off their walls on either side.
    reach = min_width - space.pixel
    pairs = cKDTree(points).query_pairs(reach, output_type='ndarray')
    if not len(pairs):
        return None
    a, b = pairs[:, 0], pairs[:, 1]
    gap = points[b] - points[a]
    distance = np.hypot(gap[:, 0], gap[:, 1])
    direction = gap / np.maximum(distance, 1e-12)[:, None]
    facing = math.cos(corner_angle / 2.0)
    across = (usable[a] & usable[b] & (distance > 0.0)
              & ((normals[a] * direction).sum(axis=1) > facing)
              & ((normals[b] * -direction).sum(axis=1) > facing))
    for index in np.flatnonzero(across)[np.argsort(distance[across])]:
        first, second = points[a[index]], points[b[index]]
        if _segment_free(space, first, second):
            middle = (first + second) / 2.0
            return distance[index] + space.pixel, (float(middle[0]), float(middle[1]))
    return None


def corridors_wide_enough(space, min_width=MIN_WIDTH, corner_angle=CORNER_ANGLE):
    """Problems: a passage narrower than min_width."""
    narrowest = narrowest_passage(space, min_width, corner_angle)
    if narrowest is None:
        return []
    width, (x, y) = narrowest
    return ['a passage only %.2f m wide (under %.2f m) at (%.2f, %.2f)'
            % (width, min_width, x, y)]


def robot_fits_along_walls(space, follow_distance=FOLLOW_DISTANCE, corner_angle=CORNER_ANGLE):
    """Problems: the band's middle in pieces, or a wall a follower cannot come near."""
    centres = space.clearance >= follow_distance
    _, count = label(centres, structure=_FOUR)
    if count != 1:
        return ['the places %.2f m from every wall are in %d pieces: a follower cannot go '
                'all the way round' % (follow_distance, count)]
    rows, cols = space.wall_pixels()
    to_centres = distance_transform_edt(~centres)[rows, cols] * space.pixel
    reach = follow_distance / math.sin(corner_angle / 2.0) + space.pixel
    far = to_centres > reach
    if far.any():
        worst = int(np.argmax(to_centres))
        x, y = space.xy(rows[worst:worst + 1], cols[worst:worst + 1])[0]
        return ['%d wall pixels a follower cannot come within %.2f m of, e.g. at (%.2f, %.2f)'
                % (int(far.sum()), follow_distance, x, y)]
    return []


def start_clear(space, start, start_clearance=START_CLEARANCE):
    """Problems: the start (x, y, yaw) nearer than start_clearance to a wall, or not free."""
    cell = space.cell(start[0], start[1])
    if cell is None or not space.free[cell]:
        return ['the start (%.2f, %.2f) is not in free space' % start[:2]]
    if space.clearance[cell] < start_clearance:
        return ['the start (%.2f, %.2f) is %.2f m from a wall (under %.2f m)'
                % (start[0], start[1], space.clearance[cell], start_clearance)]
    return []


def world_problems(space, start, min_width=MIN_WIDTH, start_clearance=START_CLEARANCE,
                   follow_distance=FOLLOW_DISTANCE):
    """Every problem of a floorplan and its start pose; [] for a fair course."""
    problems = connected(space)
    if problems:
        return problems
    return (corridors_wide_enough(space, min_width) + robot_fits_along_walls(space, follow_distance)
            + start_clear(space, start, start_clearance))
