"""Maps on disk in map_server's format: NAME.pgm + NAME.yaml.

save_map writes byte for byte what map_server's `map_saver -f NAME` (Noetic)
writes: a binary PGM (P5) with the comment line map_saver puts in, the top
row of the map first, 254 for a free cell (0 <= value <= free_threshold),
0 for an occupied one (value >= occupied_threshold) and 205 for the rest
(unknown, -1, and values in between); and a YAML naming the image, with
resolution and origin printed as C's %f does and the fixed thresholds
map_server reads back. One difference: for a relative NAME map_saver
writes the image's path as given, which map_server's loader then resolves
against the YAML's folder (a second time); here the image is named
relative to the YAML's folder, so the pair loads from anywhere. load_map
reads such a pair as map_server does in its default (trinary) mode.

Neither writes nor reads a map that cannot be one (no cells, data that do
not fill width x height, a resolution that is not positive, an origin that
is not finite): a ValueError says what is wrong, naming the file read.
"""
import math
import os
from collections import namedtuple

import numpy as np
import yaml

from wall_follower.params import defaults
from wall_follower.params.mapping.map_saver import TABLE

__all__ = ['save_map', 'load_map', 'SavedMap', 'FREE', 'OCCUPIED', 'UNKNOWN']

FREE, OCCUPIED, UNKNOWN = 254, 0, 205
# The defaults of the thresholds below: the map_saver node's, map_server's map_saver's.
_DEFAULT = defaults(TABLE)

# data: int8 (rows, cols), row 0 at the bottom as nav_msgs/OccupancyGrid has it:
# 100 occupied, 0 free, -1 unknown. origin: (x, y, yaw) of the lower-left corner.
SavedMap = namedtuple('SavedMap', ['data', 'resolution', 'origin'])


def pgm_bytes(data, resolution, occupied_threshold=_DEFAULT['occupied_threshold'],
              free_threshold=_DEFAULT['free_threshold']):
    """The PGM file map_saver writes for OccupancyGrid values data (rows, cols)."""
    data = np.asarray(data, dtype=np.int16)
    rows, cols = data.shape
    pixels = np.full(data.shape, UNKNOWN, dtype=np.uint8)
    pixels[data >= occupied_threshold] = OCCUPIED
    pixels[(data >= 0) & (data <= free_threshold)] = FREE
    header = 'P5\n# CREATOR: map_saver.cpp %.3f m/pix\n%d %d\n255\n' % (
        float(np.float32(resolution)), cols, rows)
    return header.encode('ascii') + pixels[::-1].tobytes()


def yaml_text(image, resolution, origin):
    """The YAML map_saver writes beside the PGM named `image`."""
    return ('image: %s\nresolution: %f\norigin: [%f, %f, %f]\nnegate: 0\n'
            'occupied_thresh: 0.65\nfree_thresh: 0.196\n\n'
            % (image, float(np.float32(resolution)), origin[0], origin[1], origin[2]))


def map_problem(width, height, cells, resolution, origin):
    """What makes a map of width x height cells, `cells` values, resolution [m] and
    origin (x, y, yaw) unusable, in words; None for a usable one."""
    if width <= 0 or height <= 0:
        return 'the map has no cells (%d x %d)' % (width, height)
    if cells != width * height:
        return '%d values do not fill %d x %d cells' % (cells, width, height)
    return _placement_problem(resolution, origin)


def _placement_problem(resolution, origin):
    """What makes a map's resolution [m] or origin (x, y, yaw) unusable; None if nothing."""
    if not (math.isfinite(resolution) and resolution > 0.0):
        return 'resolution %r is not a positive length' % resolution
    if len(origin) != 3 or not all(math.isfinite(value) for value in origin):
        return 'origin %r is not three finite numbers (x, y, yaw)' % (list(origin),)
    return None


def save_map(name, data, resolution, origin,
             occupied_threshold=_DEFAULT['occupied_threshold'],
             free_threshold=_DEFAULT['free_threshold']):
    """Write NAME.pgm and NAME.yaml as `map_saver -f NAME` does; returns the two paths.

    Raises ValueError, writing nothing, for a map that cannot be one (map_problem)."""
    data = np.asarray(data)
    rows, cols = data.shape if data.ndim == 2 else (0, 0)
    problem = map_problem(cols, rows, data.size, resolution, tuple(origin))
    if problem:
        raise ValueError(problem)
    image, meta = name + '.pgm', name + '.yaml'
    named = image if os.path.isabs(image) else os.path.basename(image)
    _write_whole(image, pgm_bytes(data, resolution, occupied_threshold, free_threshold))
    _write_whole(meta, yaml_text(named, resolution, origin).encode('ascii'))
    return image, meta


def _write_whole(path, content):
    """Write through a temporary file, so a reader never sees half a map."""
    partial = path + '.partial'
    with open(partial, 'wb') as stream:
        stream.write(content)
    os.replace(partial, path)


def _read_pgm(path):
    """The pixels (rows, cols) of an 8-bit binary PGM; ValueError naming path if it is not
    one, or is cut short."""
    try:
        with open(path, 'rb') as stream:
            content = stream.read()
    except (IOError, OSError) as err:
        raise ValueError('%s: cannot read the image (%s)' % (path, err.strerror or err))
    fields, position = [], 0
    while len(fields) < 4:
        while content[position:position + 1].isspace():
            position += 1
        if position >= len(content):
            raise ValueError('%s: the PGM header is cut short' % path)
        if content[position:position + 1] == b'#':
            position = content.find(b'\n', position) + 1 or len(content)
            continue
        end = position
        while end < len(content) and not content[end:end + 1].isspace():
            end += 1
        if end == len(content):     # each field ends in a whitespace
            raise ValueError('%s: the PGM header is cut short' % path)
        fields.append(content[position:end])
        position = end
    if fields[0] != b'P5' or not all(field.isdigit() for field in fields[1:]):
        raise ValueError('%s: not a binary PGM (P5) image' % path)
    cols, rows, maxval = (int(field) for field in fields[1:])
    if maxval != 255:
        raise ValueError('%s: not an 8-bit PGM (maxval %d)' % (path, maxval))
    if rows == 0 or cols == 0:
        raise ValueError('%s: the image has no pixels (%d x %d)' % (path, cols, rows))
    pixels = np.frombuffer(content[position + 1:position + 1 + rows * cols], dtype=np.uint8)
    if pixels.size != rows * cols:
        raise ValueError('%s: cut short: %d of the %d x %d pixels' % (
            path, pixels.size, cols, rows))
    return pixels.reshape(rows, cols)


def _read_description(yaml_path):
    """The map description (image, resolution, origin, thresholds, negate) of a map_server
    YAML, each checked; ValueError naming yaml_path and what is wrong."""
    try:
        with open(yaml_path) as stream:
            meta = yaml.safe_load(stream)
    except (IOError, OSError) as err:
        raise ValueError('%s: cannot read the map description (%s)' % (
            yaml_path, err.strerror or err))
    except UnicodeDecodeError as err:
        raise ValueError('%s: not a map description: not text (%s)' % (yaml_path, err.reason))
    except yaml.YAMLError as err:
        mark = getattr(err, 'problem_mark', None)
        raise ValueError('%s:%s not YAML (%s)' % (
            yaml_path, '%d:' % (mark.line + 1) if mark else '',
            getattr(err, 'problem', None) or str(err).splitlines()[0]))
    try:
        image = meta['image']
        resolution = float(meta['resolution'])
        origin = tuple(float(v) for v in meta['origin'])
        occupied, free = float(meta['occupied_thresh']), float(meta['free_thresh'])
        negate = int(meta.get('negate', 0))
    except (KeyError, TypeError, ValueError, AttributeError) as err:
        raise ValueError('%s: not a map_server map description (%s)' % (yaml_path, err))
    if not isinstance(image, str) or not image:
        raise ValueError('%s: image must name a file' % yaml_path)
    problem = _placement_problem(resolution, origin)
    if problem:
        raise ValueError('%s: %s' % (yaml_path, problem))
    if not os.path.isabs(image):
        image = os.path.join(os.path.dirname(os.path.abspath(yaml_path)), image)
    if not os.path.isfile(image):
        raise ValueError('%s: its image %s does not exist' % (yaml_path, image))
    return image, resolution, origin, occupied, free, negate


def load_map(yaml_path):
    """A SavedMap from a map_server YAML and its image, read as map_server's trinary mode.

    A pixel's occupancy is (255 - value) / 255 (value / 255 with negate);
    above occupied_thresh it is occupied, below free_thresh free, else unknown.
    Raises ValueError naming the file and what is wrong for anything that is not such a
    pair.
    """
    image, resolution, origin, occupied, free, negate = _read_description(yaml_path)
    pixels = _read_pgm(image).astype(float)
    occupancy = pixels / 255.0 if negate else (255.0 - pixels) / 255.0
    data = np.full(pixels.shape, -1, dtype=np.int8)
    data[occupancy > occupied] = 100
    data[occupancy < free] = 0
    return SavedMap(data[::-1].copy(), resolution, origin)
