"""The camera's per-pixel loop, src/stage_camera.c, loaded through ctypes.

catkin builds the library with the workspace and puts it on LD_LIBRARY_PATH
when the workspace's setup file is sourced, as it does the raytrace's
(compiled_raytrace). SceneTables and ViewTables mirror the C structs
`camera_scene` and `camera_view` field for field and keep alive the numpy
arrays their fields point into.
"""
import ctypes

import numpy as np

from wall_follower.sim.compiled_library import (ADDRESS, DOUBLE, INT, address, load_function,
                                                missing_message)

__all__ = ['LIBRARY', 'MISSING', 'available', 'SceneTables', 'render']

LIBRARY = 'libwall_follower_camera.so'
# A raster cell's bits (src/stage_camera.c): inside the outline; a neighbour is not.
RASTER_FILLED = 1
RASTER_BORDER = 2
MISSING = missing_message(LIBRARY, "the simulator's camera", 'src/stage_camera.c')


class SceneTables(ctypes.Structure):
    """struct camera_scene: a list of camera.Solid packed into flat arrays."""

    _fields_ = [('solid_count', INT), ('edges', ADDRESS), ('edge_start', ADDRESS),
                ('zspan', ADDRESS), ('bounds', ADDRESS), ('colors', ADDRESS),
                ('walk_sides', ADDRESS), ('convex', ADDRESS), ('raster', ADDRESS),
                ('raster_start', ADDRESS), ('raster_shape', ADDRESS), ('raster_origin', ADDRESS),
                ('raster_cell', DOUBLE)]

    def __init__(self, solids, raster_cell):
        count = len(solids)
        edges = [solid.edges.reshape(-1, 4) for solid in solids]
        starts = np.concatenate([[0], np.cumsum([len(e) for e in edges])]).astype(np.int64)
        rasters, raster_start, raster_shape, raster_origin = [], [], [], []
        offset = 0
        for solid in solids:
            if solid.raster is None:
                raster_start.append(-1)
                raster_shape.append((0, 0))
                raster_origin.append((0.0, 0.0))
            else:
                mask, origin = solid.raster
                raster_start.append(offset)
                raster_shape.append(mask.shape)
                raster_origin.append(origin)
                rasters.append(raster_codes(mask).ravel())
                offset += mask.size
        arrays = [
            (np.concatenate(edges) if edges else np.zeros((0, 4)), np.float64),
            (starts, np.int64),
            ([(solid.zmin, solid.zmax) for solid in solids], np.float64),
            ([tuple(solid.lower) + tuple(solid.upper) for solid in solids], np.float64),
            ([np.round(np.array(solid.color) * 255.0) for solid in solids], np.uint8),
            ([solid.walk_sides for solid in solids], np.uint8),
            ([solid.convex for solid in solids], np.uint8),
            (np.concatenate(rasters) if rasters else np.zeros(1), np.uint8),
            (raster_start, np.int64), (raster_shape, np.int64), (raster_origin, np.float64)]
        kept, pointers = [], []
        for values, dtype in arrays:
            array, pointer = address(np.asarray(values, dtype=dtype).reshape(-1)
                                     if len(values) else np.zeros(1, dtype), dtype)
            kept.append(array)
            pointers.append(pointer)
        super(SceneTables, self).__init__(count, *(pointers + [float(raster_cell)]))
        self.arrays = kept


def raster_codes(mask):
    """A filled raster's cells as the C side reads them: RASTER_FILLED where filled,
    RASTER_BORDER where one of the eight neighbours (outside the raster: empty) differs."""
    padded = np.pad(mask, 1, mode='constant')
    rows, cols = mask.shape
    border = np.zeros(mask.shape, dtype=bool)
    for drow in (0, 1, 2):
        for dcol in (0, 1, 2):
            border |= padded[drow:drow + rows, dcol:dcol + cols] != mask
    return (mask * RASTER_FILLED + border * RASTER_BORDER).astype(np.uint8)


class ViewTables(ctypes.Structure):
    """struct camera_view: the pixel grid, the camera's axes, the eye, the clip range,
    the floor, and the output arrays."""

    _fields_ = [('width', INT), ('height', INT), ('u', ADDRESS), ('v', ADDRESS),
                ('basis', DOUBLE * 9), ('eye', DOUBLE * 3),
                ('near_clip', DOUBLE), ('far_clip', DOUBLE), ('floor_bounds', DOUBLE * 4),
                ('floor_color', ctypes.c_uint8 * 3), ('background', ctypes.c_uint8 * 3),
                ('rgba', ADDRESS), ('depth', ADDRESS)]


_CAMERA_RENDER = load_function(LIBRARY, 'camera_render',
                               [ctypes.POINTER(SceneTables), INT, ctypes.POINTER(ViewTables),
                                ADDRESS, ADDRESS])


def available():
    """True when the library was found."""
    return _CAMERA_RENDER is not None


def render(scenes, u, v, basis, eye, clip, floor_bounds, floor_color, background):
    """(rgba (H*W, 4) uint8, depth (H*W,) float32, rows top-down) of the pixels whose rays
    are forward + u[column] right + v[row] down (basis: forward, right, down in the world),
    from `eye` over the SceneTables in `scenes`; RuntimeError (MISSING) without the library.
    """
    if _CAMERA_RENDER is None:
        raise RuntimeError(MISSING)
    u, u_pointer = address(u, np.float64)
    v, v_pointer = address(v, np.float64)
    count = len(u) * len(v)
    rgba = np.empty((count, 4), dtype=np.uint8)
    depth = np.empty(count, dtype=np.float32)
    solids = sum(scene.solid_count for scene in scenes)
    reach = np.empty(max(solids, 1), dtype=np.float64)
    hidden = np.empty(max(solids, 1), dtype=np.uint8)
    view = ViewTables(len(u), len(v), u_pointer, v_pointer,
                      tuple(np.asarray(basis, dtype=float).ravel()), tuple(eye), clip[0], clip[1],
                      tuple(floor_bounds),
                      tuple(floor_color), tuple(background), rgba.ctypes.data, depth.ctypes.data)
    packed = (SceneTables * len(scenes))(*scenes)
    _CAMERA_RENDER(packed, len(scenes), ctypes.byref(view), reach.ctypes.data,
                   hidden.ctypes.data)
    return rgba, depth
