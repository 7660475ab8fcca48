"""How good a saved map is, judged against the world it was made in.

precision: the share of the map's occupied cells that lie within one map
cell (the 8 around it, or itself) of a cell a true wall surface passes
through. recall: the share of the true wall cells the laser could see from
the robot's true path (noise-free beams up to the mapper's range limit)
that have an occupied map cell within one cell. worst_distance: how far the
centre of the occupied cell farthest from any true wall lies from it [m]
(a cell a wall passes through is at most half its diagonal away; a wall
drawn beside the true one, or a ghost, is farther). The map frame is placed in
the world by the robot's true start pose: the mapper's map frame starts on
the odometry's, and odometry starts at zero there.
"""
import math
from collections import namedtuple

import numpy as np

from wall_follower.evaluation.scoring.course import CourseMap
from wall_follower.evaluation.scoring.geometry import cast_rays, point_segment_distance
from wall_follower.rotation import wrap_angle

__all__ = ['MapQuality', 'map_quality']

MapQuality = namedtuple('MapQuality', ['precision', 'recall', 'occupied', 'seen_walls',
                                       'worst_distance'])

_BEAMS = 360
# The path is sampled every path_step metres, or this much turning [rad].
_PATH_TURN = 0.2
# Cells: how near a cell boundary a point counts as on it.
_ON_BOUNDARY = 1e-6
# Occupied cells measured against the walls at once (bounds the distance matrix's memory).
_CHUNK = 2000


def _to_map(points, map_in_world):
    """World points (N, 2) in the map frame whose origin sits at map_in_world."""
    x, y, yaw = map_in_world
    c, s = math.cos(yaw), math.sin(yaw)
    dx, dy = points[:, 0] - x, points[:, 1] - y
    return np.column_stack((c * dx + s * dy, -s * dx + c * dy))


def _cell_mask(points, saved_map):
    """The map's cells that hold points (N, 2), as a boolean mask of its shape.

    A point within rounding of a cell boundary goes to the cell above it
    (the larger index), so that a wall lying along a boundary marks one row
    of cells whichever float noise the map's origin brings: else that row
    came out once or twice by the origin, and with it the count of seen
    wall cells.
    """
    rows, cols = saved_map.data.shape
    res = saved_map.resolution
    c = np.floor((points[:, 0] - saved_map.origin[0]) / res + _ON_BOUNDARY).astype(np.int64)
    r = np.floor((points[:, 1] - saved_map.origin[1]) / res + _ON_BOUNDARY).astype(np.int64)
    inside = (r >= 0) & (r < rows) & (c >= 0) & (c < cols)
    mask = np.zeros((rows, cols), dtype=bool)
    mask[r[inside], c[inside]] = True
    return mask


def _dilate(mask):
    out = mask.copy()
    padded = np.pad(mask, 1)
    for dr in (0, 1, 2):
        for dc in (0, 1, 2):
            out |= padded[dr:dr + mask.shape[0], dc:dc + mask.shape[1]]
    return out


def _wall_points(edges, spacing):
    points = []
    for a, b in edges:
        count = max(2, int(math.ceil(np.hypot(*(b - a)) / spacing)) + 1)
        t = np.linspace(0.0, 1.0, count)[:, None]
        points.append(a + t * (b - a))
    return np.concatenate(points) if points else np.zeros((0, 2))


def _worst_distance(saved_map, occupied, edges, start_pose):
    """The largest distance [m] from an occupied cell's centre to the nearest true wall."""
    rows, cols = np.nonzero(occupied)
    if not len(rows) or not len(edges):
        return 0.0 if not len(rows) else float('inf')
    res = saved_map.resolution
    centres = np.column_stack((saved_map.origin[0] + (cols + 0.5) * res,
                               saved_map.origin[1] + (rows + 0.5) * res))
    a, b = _to_map(edges[:, 0], start_pose), _to_map(edges[:, 1], start_pose)
    return max(float(point_segment_distance(centres[i:i + _CHUNK], a, b).min(axis=1).max())
               for i in range(0, len(centres), _CHUNK))


def map_quality(saved_map, world_path, start_pose, path, max_range, path_step=0.1):
    """MapQuality of a SavedMap made in world_path by a robot that started at the true
    start_pose (x, y, yaw) and went along the true path [(x, y, yaw), ...]."""
    course = CourseMap(world_path)
    res = saved_map.resolution
    occupied = saved_map.data == 100
    walls = _to_map(_wall_points(course.edges, res / 4.0), start_pose)
    true_walls = _cell_mask(walls, saved_map)
    angles = np.linspace(-math.pi, math.pi, _BEAMS, endpoint=False)
    seen_points, last = [], None
    reach = min(max_range, course.range_max)
    for pose in path:
        if last is not None and math.hypot(pose[0] - last[0], pose[1] - last[1]) < path_step \
                and abs(wrap_angle(pose[2] - last[2])) < _PATH_TURN:
            continue
        last = pose
        lx, ly, lyaw = course.laser_pose(pose)
        ranges = cast_rays(course.edges, lx, ly, lyaw + angles)
        hit = ranges < reach
        seen_points.append(np.column_stack((lx + ranges[hit] * np.cos(lyaw + angles[hit]),
                                            ly + ranges[hit] * np.sin(lyaw + angles[hit]))))
    seen_points = np.concatenate(seen_points) if seen_points else np.zeros((0, 2))
    seen = _cell_mask(_to_map(seen_points, start_pose), saved_map)
    seen_count = int(seen.sum())
    precision = float((occupied & _dilate(true_walls)).sum()) / max(int(occupied.sum()), 1)
    recall = float((seen & _dilate(occupied)).sum()) / max(seen_count, 1)
    return MapQuality(precision, recall, int(occupied.sum()), seen_count,
                      _worst_distance(saved_map, occupied, course.edges, start_pose))
