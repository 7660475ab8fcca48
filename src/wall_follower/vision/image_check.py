"""Whether a raw or compressed camera frame can be read, and what is wrong with it if not.

A frame that cannot be read is named in words (never a traceback) so that
a node can warn and stop the robot. The raw encodings are
sensor_msgs/image_encodings' (those cv_bridge reads): a size, a step and
a length of data that do not agree are caught before any conversion. A
row step may pad a row, as drivers align rows in memory, but by less than
the alignment the step itself shows (at most ROW_ALIGNMENT bytes): a step
of 1280 bytes for 320 bgr8 pixels (960 bytes) is rgba8 data under the
wrong name, not padding. A compressed frame must hold the whole image:
OpenCV decodes a JPEG cut short into an image whose lower part is grey,
without a word, so a JPEG must end with its end-of-image marker and a PNG
with its IEND chunk.
"""
import re

import cv2
import numpy as np

_CHANNELS = {'rgb8': (3, 1), 'bgr8': (3, 1), 'rgba8': (4, 1), 'bgra8': (4, 1),
             'rgb16': (3, 2), 'bgr16': (3, 2), 'rgba16': (4, 2), 'bgra16': (4, 2),
             'mono8': (1, 1), 'mono16': (1, 2), 'yuv422': (2, 1), 'yuv422_yuy2': (2, 1)}
_BAYER = re.compile(r'^bayer_(rggb|bggr|gbrg|grbg)(8|16)$')
_GENERIC = re.compile(r'^(8|16|32|64)(U|S|F)C([1-4])$')
ROW_ALIGNMENT = 64       # bytes: the widest row alignment a row step may pad to
JPEG_START, JPEG_END = b'\xff\xd8', b'\xff\xd9'
PNG_START, PNG_END = b'\x89PNG\r\n\x1a\n', b'IEND\xaeB`\x82'


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
    row = width * size
    if step < row:
        return 'a row step of %d bytes is too short for %d %s pixels' % (step, width, encoding)
    if step - row >= min(ROW_ALIGNMENT, step & -step):
        return ('a row step of %d bytes does not fit %d %s pixels (%d bytes and a padding '
                'to align rows): another encoding?' % (step, width, encoding, row))
    if length < step * height:
        return '%d bytes of data, %d x %d %s needs %d' % (
            length, width, height, encoding, step * height)
    return None


def decode_compressed(data):
    """(BGR image, None) of a compressed frame (JPEG, PNG, ...: sensor_msgs/CompressedImage's
    data, bytes), or (None, what is wrong)."""
    if len(data) == 0:
        return None, 'an empty compressed image'
    problem = cut_short(data)
    if problem is not None:
        return None, problem
    image = cv2.imdecode(np.frombuffer(data, np.uint8), cv2.IMREAD_COLOR)
    if image is None or image.size == 0:
        return None, 'a compressed image that cannot be decoded (%d bytes)' % len(data)
    return image, None


def cut_short(data):
    """What shows that a compressed frame (bytes) is cut short, or None: a JPEG (trailing zero
    padding aside) must end with its end-of-image marker, a PNG with its IEND chunk."""
    if data.startswith(JPEG_START) and not data.rstrip(b'\x00').endswith(JPEG_END):
        return 'a JPEG cut short (it does not end with an end-of-image marker)'
    if data.startswith(PNG_START) and not data.endswith(PNG_END):
        return 'a PNG cut short (it does not end with an IEND chunk)'
    return None


def size_problem(image, width, height):
    """What is wrong with an image (an array, rows first) that camera_info says is width x
    height pixels, or None if it is that size."""
    rows, columns = image.shape[:2]
    if (columns, rows) != (width, height):
        return 'the image is %dx%d but camera_info says %dx%d' % (columns, rows, width, height)
    return None
