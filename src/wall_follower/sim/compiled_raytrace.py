"""Stage's raytrace as a C loop (src/stage_raytrace.c), loaded through ctypes.

numpy's cost is per call, and following Stage's beam exactly takes about a
thousand numpy calls per scan, over 1 ms; the same beams stepped cell by
cell in C take a few tens of microseconds. catkin builds the library with
the workspace and puts it on LD_LIBRARY_PATH (devel/lib or lib of the
install space); where it is not there, say when the package's Python is used
from the source tree alone, raytrace.py uses its numpy implementation, which
gives the same beams.
"""
import ctypes

import numpy as np

__all__ = ['LIBRARY', 'NOT_FOUND', 'available', 'trace']

LIBRARY = 'libwall_follower_raytrace.so'
NOT_FOUND = ('%s is not on LD_LIBRARY_PATH: build the workspace and source its setup file'
             % LIBRARY)

_BYTES = np.ctypeslib.ndpointer(dtype=np.uint8, flags='C_CONTIGUOUS')
_DOUBLES = np.ctypeslib.ndpointer(dtype=np.float64, flags='C_CONTIGUOUS')
_INTS = np.ctypeslib.ndpointer(dtype=np.int64, flags='C_CONTIGUOUS')
_INT = ctypes.c_int64
_DOUBLE = ctypes.c_double


def _load():
    try:
        library = ctypes.CDLL(LIBRARY)
    except OSError:
        return None
    function = library.stage_raytrace
    function.restype = None
    function.argtypes = [_BYTES, _DOUBLES, _INT, _INT, _INT, _INT,
                         _BYTES, _INT, _INT, _INT, _INT,
                         _DOUBLE, _DOUBLE, _DOUBLE, _INT, _DOUBLES, _DOUBLES, _DOUBLES,
                         _INTS, _INTS, _DOUBLE, _DOUBLES, _DOUBLES]
    return function


_STAGE_RAYTRACE = _load()


def available():
    """True when the library was found."""
    return _STAGE_RAYTRACE is not None


def trace(tables, ppm, x, y, beams, range_max):
    """(ranges, intensities) of `beams` (raytrace._Beams) from (x, y) on raytrace's `tables`."""
    count = len(beams.cos)
    ranges = np.empty(count)
    intensities = np.empty(count)
    region_lo = tables.region_lo
    region_rows = len(tables.populated) // tables.region_stride
    _STAGE_RAYTRACE(tables.visible, tables.returns, tables.width, tables.height,
                    tables.cx0, tables.cy0, tables.populated.view(np.uint8),
                    tables.region_stride, region_rows, int(region_lo[0]), int(region_lo[1]),
                    ppm, x * ppm, y * ppm, count, beams.cos, beams.sin, beams.tana,
                    beams.cells_x, beams.cells_y, range_max, ranges, intensities)
    return ranges, intensities
