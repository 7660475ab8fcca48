"""The line in a camera image: its HSV mask, the lab's slice centroid, and its pixels.

All images are OpenCV BGR arrays (rows top-down), whatever their size; the
HSV bounds are OpenCV's (hue 0-179, saturation and value 0-255).
"""
from collections import namedtuple

import cv2
import numpy as np

HsvBounds = namedtuple('HsvBounds', ['lower', 'upper'])
"""Inclusive (hue, saturation, value) bounds of the line's colour."""


def hsv_bounds(values):
    """The HsvBounds of a parameter set (name -> value: hue_low ... value_high)."""
    return HsvBounds(
        (values['hue_low'], values['saturation_low'], values['value_low']),
        (values['hue_high'], values['saturation_high'], values['value_high']))


def line_mask(bgr, bounds):
    """uint8 mask (255 on the line's colour, 0 elsewhere) of a BGR image.

    A lower hue above the upper one wraps round (red lines: 170 to 10).
    """
    hsv = cv2.cvtColor(bgr, cv2.COLOR_BGR2HSV)
    lower, upper = bounds.lower, bounds.upper
    if lower[0] <= upper[0]:
        return cv2.inRange(hsv, _bound(lower), _bound(upper))
    high_hues = cv2.inRange(hsv, _bound(lower), _bound((179, upper[1], upper[2])))
    low_hues = cv2.inRange(hsv, _bound((0, lower[1], lower[2])), _bound(upper))
    return cv2.bitwise_or(high_hues, low_hues)


def _bound(values):
    """An HSV bound as inRange takes it in every OpenCV 4 (uint8, as the image)."""
    return np.array(values, dtype=np.uint8)


def slice_rows(height, top, depth):
    """(first, end) rows of the lab's slice: from top (a share of the height, 0 = the
    image's top row) down by depth (a share of the height), at least one row."""
    first = min(height - 1, max(0, int(round(top * height))))
    end = min(height, max(first + 1, int(round((top + depth) * height))))
    return first, end


def slice_centroid(mask, top, depth):
    """(column, row) of the centroid of the mask within the lab's thin slice (slice_rows),
    in pixels; None when the slice holds no line pixel."""
    first, end = slice_rows(mask.shape[0], top, depth)
    moments = cv2.moments(mask[first:end], binaryImage=True)
    if moments['m00'] <= 0.0:
        return None
    return moments['m10'] / moments['m00'], first + moments['m01'] / moments['m00']


def line_pixels(mask, stride):
    """(N, 2) float (column, row) of the mask's line pixels, every stride-th in each
    direction (pixel centres at integer coordinates)."""
    rows, columns = np.nonzero(mask[::stride, ::stride])
    return np.column_stack((columns * stride, rows * stride)).astype(float)


def mark_centroid(bgr, centroid, radius):
    """A copy of a BGR image with the centroid (column, row), if any, marked by a red dot."""
    marked = bgr.copy()
    if centroid is not None:
        cv2.circle(marked, (int(round(centroid[0])), int(round(centroid[1]))), radius,
                   (0, 0, 255), -1)
    return marked
