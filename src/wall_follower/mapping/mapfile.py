"""Maps on disk in map_server's format: NAME.pgm + NAME.yaml.

save_map writes byte for byte what map_server's `map_saver -f NAME` (Noetic)
writes: a binary PGM (P5) with the comment line map_saver puts in, the top
row of the map first, 254 for a free cell (0 <= value <= free_threshold),
0 for an occupied one (value >= occupied_threshold) and 205 for the rest
(unknown, -1, and values in between); and a YAML naming the image as
given, with resolution and origin printed as C's %f does and the fixed
thresholds map_server reads back. load_map reads such a pair as map_server
does in its default (trinary) mode.
"""
import os
from collections import namedtuple

import numpy as np
import yaml

from wall_follower.params import defaults
from wall_follower.params.map_saver import TABLE

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


def save_map(name, data, resolution, origin,
             occupied_threshold=_DEFAULT['occupied_threshold'],
             free_threshold=_DEFAULT['free_threshold']):
    """Write NAME.pgm and NAME.yaml as `map_saver -f NAME` does; returns the two paths."""
    image, meta = name + '.pgm', name + '.yaml'
    _write_whole(image, pgm_bytes(data, resolution, occupied_threshold, free_threshold))
    _write_whole(meta, yaml_text(image, resolution, origin).encode('ascii'))
    return image, meta


def _write_whole(path, content):
    """Write through a temporary file, so a reader never sees half a map."""
    partial = path + '.partial'
    with open(partial, 'wb') as stream:
        stream.write(content)
    os.replace(partial, path)


def _read_pgm(path):
    with open(path, 'rb') as stream:
        content = stream.read()
    fields, position = [], 0
    while len(fields) < 4:
        while content[position:position + 1].isspace():
            position += 1
        if content[position:position + 1] == b'#':
            position = content.index(b'\n', position) + 1
            continue
        end = position
        while not content[end:end + 1].isspace():
            end += 1
        fields.append(content[position:end])
        position = end
    magic, cols, rows, maxval = fields[0], int(fields[1]), int(fields[2]), int(fields[3])
    if magic != b'P5' or maxval != 255:
        raise ValueError('%s: not an 8-bit binary PGM (P5)' % path)
    pixels = np.frombuffer(content[position + 1:position + 1 + rows * cols], dtype=np.uint8)
    if pixels.size != rows * cols:
        raise ValueError('%s: %d pixels, expected %d x %d' % (path, pixels.size, cols, rows))
    return pixels.reshape(rows, cols)


def load_map(yaml_path):
    """A SavedMap from a map_server YAML and its image, read as map_server's trinary mode.

    A pixel's occupancy is (255 - value) / 255 (value / 255 with negate);
    above occupied_thresh it is occupied, below free_thresh free, else unknown.
    """
    with open(yaml_path) as stream:
        meta = yaml.safe_load(stream)
    try:
        image = meta['image']
        resolution = float(meta['resolution'])
        origin = tuple(float(v) for v in meta['origin'])
        occupied, free = float(meta['occupied_thresh']), float(meta['free_thresh'])
        negate = int(meta.get('negate', 0))
    except (KeyError, TypeError, ValueError) as err:
        raise ValueError('%s: not a map_server map description (%s)' % (yaml_path, err))
    if not os.path.isabs(image):
        image = os.path.join(os.path.dirname(os.path.abspath(yaml_path)), image)
    pixels = _read_pgm(image).astype(float)
    occupancy = pixels / 255.0 if negate else (255.0 - pixels) / 255.0
    data = np.full(pixels.shape, -1, dtype=np.int8)
    data[occupancy > occupied] = 100
    data[occupancy < free] = 0
    return SavedMap(data[::-1].copy(), resolution, origin)
