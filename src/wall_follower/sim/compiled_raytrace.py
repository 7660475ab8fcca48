"""The simulator's raytrace, src/stage_raytrace.c, loaded through ctypes.

catkin builds the library with the workspace and puts it on LD_LIBRARY_PATH
(devel/lib, or lib of the install space) when the workspace's setup file is
sourced. There is no other implementation: without the library the simulator
cannot scan, and says so (LibraryMissing, MISSING) instead of failing later.

GridTables and Beams mirror the C structs `grid_tables` and `beams` field for
field, so that a call passes two pointers rather than a long row of
positional arguments, and keep alive the numpy arrays their fields point into.
"""
import ctypes

import numpy as np

__all__ = ['LIBRARY', 'MISSING', 'LibraryMissing', 'available', 'require', 'GridTables',
           'Beams', 'trace']

LIBRARY = 'libwall_follower_raytrace.so'
MISSING = ("the simulator's laser needs %s (built from src/stage_raytrace.c by catkin_make), "
           "which is not on LD_LIBRARY_PATH: run catkin_make in the catkin workspace, then "
           "source its devel/setup.bash" % LIBRARY)

_INT = ctypes.c_int64
_DOUBLE = ctypes.c_double
# A pointer field, set from a numpy array's address (cheaper per scan than a typed pointer).
_ADDRESS = ctypes.c_void_p


class LibraryMissing(RuntimeError):
    """The raytrace library is not where the dynamic loader looks; MISSING says how to build it."""


def _address(array, dtype):
    """`array` as the C-contiguous `dtype` array a field points into, and its address."""
    array = np.ascontiguousarray(array, dtype=dtype)
    return array, array.ctypes.data


class GridTables(ctypes.Structure):
    """struct grid_tables: which cells a beam can hit, and which regions it walks.

    visible [rows, cols] (bool) and returns [rows, cols] (the intensity of a visible
    cell) cover Stage cells from cell_origin (x, y); populated [rows, cols] (bool)
    covers the 32x32-cell regions from region_origin (x, y), the regions a beam walks
    cell by cell. Outside them nothing is visible and no region populated.
    """

    _fields_ = [('visible', _ADDRESS), ('returns', _ADDRESS),
                ('width', _INT), ('height', _INT), ('cx0', _INT), ('cy0', _INT),
                ('populated', _ADDRESS),
                ('region_cols', _INT), ('region_rows', _INT), ('rx0', _INT), ('ry0', _INT),
                ('ppm', _DOUBLE)]

    def __init__(self, visible, returns, cell_origin, populated, region_origin, ppm):
        visible, visible_pointer = _address(visible, np.uint8)
        returns, returns_pointer = _address(returns, np.float64)
        populated, populated_pointer = _address(populated, np.uint8)
        if returns.shape != visible.shape:
            raise ValueError('returns %s and visible %s differ in shape'
                             % (returns.shape, visible.shape))
        height, width = visible.shape
        region_rows, region_cols = populated.shape
        super(GridTables, self).__init__(
            visible_pointer, returns_pointer, width, height,
            int(cell_origin[0]), int(cell_origin[1]), populated_pointer,
            region_cols, region_rows, int(region_origin[0]), int(region_origin[1]), float(ppm))
        self.arrays = (visible, returns, populated)


class Beams(ctypes.Structure):
    """struct beams: a scan's beams at world `angles` out to `range_max` metres, and their
    readings once traced (`readings`: ranges and intensities).

    Stage nudges a beam at exactly 0 rad, whose slope would otherwise be 0; ax, ay are
    the whole cells to range_max (`ppm` cells a metre) along x and y.
    """

    _fields_ = [('count', _INT),
                ('cosa', _ADDRESS), ('sina', _ADDRESS), ('tana', _ADDRESS),
                ('ax', _ADDRESS), ('ay', _ADDRESS),
                ('range_max', _DOUBLE),
                ('ranges', _ADDRESS), ('intensities', _ADDRESS)]

    def __init__(self, angles, range_max, ppm):
        angle = np.array(angles, dtype=np.float64)
        angle[angle == 0.0] = 1e-12
        reach = ppm * float(range_max)
        cos, cos_pointer = _address(np.cos(angle), np.float64)
        sin, sin_pointer = _address(np.sin(angle), np.float64)
        tan, tan_pointer = _address(sin / cos, np.float64)
        ax, ax_pointer = _address(np.abs(reach * cos).astype(np.int64), np.int64)
        ay, ay_pointer = _address(np.abs(reach * sin).astype(np.int64), np.int64)
        ranges, ranges_pointer = _address(np.empty(len(angle)), np.float64)
        intensities, intensities_pointer = _address(np.empty(len(angle)), np.float64)
        super(Beams, self).__init__(len(angle), cos_pointer, sin_pointer, tan_pointer,
                                    ax_pointer, ay_pointer, float(range_max),
                                    ranges_pointer, intensities_pointer)
        self.arrays = (cos, sin, tan, ax, ay)
        self.readings = (ranges, intensities)


def _load():
    try:
        library = ctypes.CDLL(LIBRARY)
    except OSError:
        return None
    function = library.stage_raytrace
    function.restype = None
    function.argtypes = [ctypes.POINTER(GridTables), ctypes.POINTER(Beams), _DOUBLE, _DOUBLE]
    return function


_STAGE_RAYTRACE = _load()


def available():
    """True when the library was found."""
    return _STAGE_RAYTRACE is not None


def require():
    """Raise LibraryMissing unless the library was found."""
    if _STAGE_RAYTRACE is None:
        raise LibraryMissing(MISSING)


def trace(tables, beams, x, y):
    """(ranges, intensities) of `beams` (Beams) from (x, y) metres on `tables` (GridTables)."""
    require()
    _STAGE_RAYTRACE(ctypes.byref(tables), ctypes.byref(beams), float(x), float(y))
    return beams.readings
