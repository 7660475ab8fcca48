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

from wall_follower.sim.compiled_library import (ADDRESS, DOUBLE, INT, address, load_function,
                                                missing_message)

__all__ = ['LIBRARY', 'MISSING', 'LibraryMissing', 'available', 'require', 'GridTables',
           'Beams', 'trace']

LIBRARY = 'libwall_follower_raytrace.so'
MISSING = missing_message(LIBRARY, "the simulator's laser", 'src/stage_raytrace.c')


class LibraryMissing(RuntimeError):
    """The raytrace library is not where the dynamic loader looks; MISSING says how to build it."""


class GridTables(ctypes.Structure):
    """struct grid_tables: which cells a beam can hit, and which regions it walks.

    visible [rows, cols] (bool) and returns [rows, cols] (the intensity of a visible
    cell) cover Stage cells from cell_origin (x, y); populated [rows, cols] (bool)
    covers the 32x32-cell regions from region_origin (x, y), the regions a beam walks
    cell by cell. Outside them nothing is visible and no region populated.
    """

    _fields_ = [('visible', ADDRESS), ('returns', ADDRESS),
                ('width', INT), ('height', INT), ('cx0', INT), ('cy0', INT),
                ('populated', ADDRESS),
                ('region_cols', INT), ('region_rows', INT), ('rx0', INT), ('ry0', INT),
                ('ppm', DOUBLE)]

    def __init__(self, visible, returns, cell_origin, populated, region_origin, ppm):
        visible, visible_pointer = address(visible, np.uint8)
        returns, returns_pointer = address(returns, np.float64)
        populated, populated_pointer = address(populated, np.uint8)
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

    _fields_ = [('count', INT),
                ('cosa', ADDRESS), ('sina', ADDRESS), ('tana', ADDRESS),
                ('ax', ADDRESS), ('ay', ADDRESS),
                ('range_max', DOUBLE),
                ('ranges', ADDRESS), ('intensities', ADDRESS)]

    def __init__(self, angles, range_max, ppm):
        angle = np.array(angles, dtype=np.float64)
        angle[angle == 0.0] = 1e-12
        reach = ppm * float(range_max)
        cos, cos_pointer = address(np.cos(angle), np.float64)
        sin, sin_pointer = address(np.sin(angle), np.float64)
        tan, tan_pointer = address(sin / cos, np.float64)
        ax, ax_pointer = address(np.abs(reach * cos).astype(np.int64), np.int64)
        ay, ay_pointer = address(np.abs(reach * sin).astype(np.int64), np.int64)
        ranges, ranges_pointer = address(np.empty(len(angle)), np.float64)
        intensities, intensities_pointer = address(np.empty(len(angle)), np.float64)
        super(Beams, self).__init__(len(angle), cos_pointer, sin_pointer, tan_pointer,
                                    ax_pointer, ay_pointer, float(range_max),
                                    ranges_pointer, intensities_pointer)
        self.arrays = (cos, sin, tan, ax, ay)
        self.readings = (ranges, intensities)


_STAGE_RAYTRACE = load_function(LIBRARY, 'stage_raytrace',
                                [ctypes.POINTER(GridTables), ctypes.POINTER(Beams), DOUBLE, DOUBLE])


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
