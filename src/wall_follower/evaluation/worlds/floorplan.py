"""Floorplan bitmaps in the package's world conventions, drawn exactly.

A world's free space is drawn at METRES_PER_PIXEL with everything outside
it black, and the image is the free space's bounding box plus WALL of
black on every side, so its black pixels reach all four edges: Stage then
scales the whole image to the floorplan `size` (pixels x METRES_PER_PIXEL)
and centres it on the floorplan `pose` (the box's centre), which puts every
wall exactly where the geometry says.

Pixels are decided in integer centimetres (pixel centres are odd, vertices
even), so the same geometry gives the same pixels on every machine. Used by
tools/make_world_bitmaps.py for the shipped worlds and by the world
generator for random ones.
"""
import io

import numpy as np
from PIL import Image

METRES_PER_PIXEL = 0.02
WALL = 0.10


def to_centimetres(value):
    return int(round(value * 100))


def inside(points_x, points_y, outline):
    """Even-odd point-in-polygon test, exact on integer coordinates."""
    result = np.zeros(points_x.shape, dtype=bool)
    for (x0, y0), (x1, y1) in zip(outline, outline[1:] + outline[:1]):
        if y0 == y1:
            continue
        spans = (y0 > points_y) != (y1 > points_y)
        # x of the edge at points_y, compared without division:
        # points_x < x0 + (points_y - y0) * (x1 - x0) / (y1 - y0)
        lhs = (points_x - x0) * (y1 - y0)
        rhs = (points_y - y0) * (x1 - x0)
        left = np.where(y1 > y0, lhs < rhs, lhs > rhs)
        result ^= spans & left
    return result


class Canvas(object):
    """Pixel centres (integer cm) of a box [left, right] x [bottom, top] in cm.

    Row 0 is the top (+y) edge, as in Stage's bitmaps.
    """

    def __init__(self, left, bottom, right, top):
        pixel = to_centimetres(METRES_PER_PIXEL)
        self.left, self.top = left, top
        self.width, self.height = (right - left) // pixel, (top - bottom) // pixel
        columns, rows = np.meshgrid(np.arange(self.width), np.arange(self.height))
        self.x = left + pixel * columns + pixel // 2
        self.y = top - pixel * rows - pixel // 2

    def polygon(self, outline_m):
        """Which pixel centres lie inside a polygon given in metres."""
        return inside(self.x, self.y, [(to_centimetres(x), to_centimetres(y))
                                       for x, y in outline_m])

    def disc(self, x, y, radius):
        """Which pixel centres lie inside a disc given in metres, its rim included."""
        cx, cy, r = to_centimetres(x), to_centimetres(y), to_centimetres(radius)
        return (self.x - cx) ** 2 + (self.y - cy) ** 2 <= r * r


def crop_to_free(canvas, free):
    """The floorplan image of a free-space mask drawn on canvas, and its size [m] and centre [m].

    The image is cropped to the free pixels' bounding box plus WALL on every side.
    """
    margin = to_centimetres(WALL) // to_centimetres(METRES_PER_PIXEL)
    rows = np.flatnonzero(free.any(axis=1))
    columns = np.flatnonzero(free.any(axis=0))
    top, bottom = rows[0] - margin, rows[-1] + margin + 1
    left, right = columns[0] - margin, columns[-1] + margin + 1
    padded = np.pad(free, margin, mode='constant', constant_values=False)
    cropped = padded[top + margin:bottom + margin, left + margin:right + margin]
    image = Image.fromarray(np.where(cropped, 255, 0).astype(np.uint8), mode='L')
    size = (cropped.shape[1] * METRES_PER_PIXEL, cropped.shape[0] * METRES_PER_PIXEL)
    pixel = to_centimetres(METRES_PER_PIXEL)
    x0 = canvas.left + pixel * left
    y1 = canvas.top - pixel * top
    centre = ((2 * x0 + pixel * cropped.shape[1]) / 200.0,
              (2 * y1 - pixel * cropped.shape[0]) / 200.0)
    return image, size, centre


def render(outline_m, pillars_m=()):
    """The floorplan image of one outline and its round pillars, and its size [m] and centre [m]."""
    outline = [(to_centimetres(x), to_centimetres(y)) for x, y in outline_m]
    wall = to_centimetres(WALL)
    xs, ys = zip(*outline)
    left, right = min(xs) - wall, max(xs) + wall
    bottom, top = min(ys) - wall, max(ys) + wall
    canvas = Canvas(left, bottom, right, top)
    free = canvas.polygon(outline_m)
    for x, y, radius in pillars_m:
        free &= ~canvas.disc(x, y, radius)
    image = Image.fromarray(np.where(free, 255, 0).astype(np.uint8), mode='L')
    size = (canvas.width * METRES_PER_PIXEL, canvas.height * METRES_PER_PIXEL)
    return image, size, ((left + right) / 200.0, (bottom + top) / 200.0)


def png_bytes(image):
    buffer = io.BytesIO()
    image.save(buffer, format='PNG', optimize=False)
    return buffer.getvalue()
