"""Whether a raw or compressed camera frame can be read, and what is wrong with it if not.

A frame that cannot be read is named in words (never a traceback) so that
a node can warn and stop the robot. The raw encodings are
sensor_msgs/image_encodings' (those cv_bridge reads): a size, a step and
a length of data that do not agree are caught before any conversion.
"""
import re

import cv2
import numpy as np

_CHANNELS = {'rgb8': (3, 1), 'bgr8': (3, 1), 'rgba8': (4, 1), 'bgra8': (4, 1),
             'rgb16': (3, 2), 'bgr16': (3, 2), 'rgba16': (4, 2), 'bgra16': (4, 2),
             'mono8': (1, 1), 'mono16': (1, 2), 'yuv422': (2, 1), 'yuv422_yuy2': (2, 1)}
_BAYER = re.compile(r'^bayer_(rggb|bggr|gbrg|grbg)(8|16)$')
_GENERIC = re.compile(r'^(8|16|32|64)(U|S|F)C([1-4])$')


def pixel_bytes(encoding):
    """Bytes per pixel of a sensor_msgs/Image encoding; None for one not known."""
    if encoding in _CHANNELS:
        channels, depth = _CHANNELS[encoding]
        return channels * depth
    bayer = _BAYER.match(encoding)
    if bayer:
        return int(bayer.group(2)) // 8
    generic = _GENERIC.match(encoding)
    if generic:
        return int(generic.group(1)) // 8 * int(generic.group(3))
    return None


def raw_image_problem(encoding, height, width, step, length):
    """What makes a raw frame unreadable (sensor_msgs/Image's encoding, height, width,
    step and the length of its data, in bytes), or None if it can be read."""
    if height <= 0 or width <= 0:
        return 'an empty image (%d x %d)' % (width, height)
    size = pixel_bytes(encoding)
    if size is None:
        return 'unknown encoding %r' % (encoding,)
    if step < width * size:
        return 'a row step of %d bytes is too short for %d %s pixels' % (step, width, encoding)
    if length < step * height:
        return '%d bytes of data, %d x %d %s needs %d' % (
            length, width, height, encoding, step * height)
    return None


def decode_compressed(data):
    """(BGR image, None) of a compressed frame (JPEG, PNG, ...: sensor_msgs/CompressedImage's
    data, bytes), or (None, what is wrong)."""
    if len(data) == 0:
        return None, 'an empty compressed image'
    image = cv2.imdecode(np.frombuffer(data, np.uint8), cv2.IMREAD_COLOR)
    if image is None or image.size == 0:
        return None, 'a compressed image that cannot be decoded (%d bytes)' % len(data)
    return image, None


def size_problem(image, width, height):
    """What is wrong with an image (an array, rows first) that camera_info says is width x
    height pixels, or None if it is that size."""
    rows, columns = image.shape[:2]
    if (columns, rows) != (width, height):
        return 'the image is %dx%d but camera_info says %dx%d' % (columns, rows, width, height)
    return None
