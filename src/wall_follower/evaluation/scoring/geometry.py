"""Exact 2-D geometry of a world's obstacles: their edges as line segments.

The simulator, like Stage, works on a grid whose cells make obstacles look
up to a cell fatter; scores must not inherit that, so they are measured
against the segments the world file actually describes.
"""
import math

import numpy as np


def obstacle_edges(obstacle):
    """World-frame outline edges (M, 2, 2) of a worldfile.Obstacle."""
    gx, gy, _, ga = obstacle.pose
    ox, oy, _, oa = obstacle.origin
    cx = gx + ox * math.cos(ga) - oy * math.sin(ga)
    cy = gy + ox * math.sin(ga) + oy * math.cos(ga)
    ca = ga + oa
    local = np.asarray(obstacle.edges, dtype=float)
    wx = cx + local[..., 0] * math.cos(ca) - local[..., 1] * math.sin(ca)
    wy = cy + local[..., 0] * math.sin(ca) + local[..., 1] * math.cos(ca)
    return np.stack([wx, wy], axis=-1)


def solid_edges(world):
    """Edges (K, 2, 2) of every obstacle a robot collides with."""
    edges = [obstacle_edges(o) for o in world.obstacles if o.obstacle_return]
    return np.concatenate(edges) if edges else np.zeros((0, 2, 2))


def _cross(a, b):
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def cast_rays(edges, x, y, angles):
    """Distance along each ray from (x, y) to the first edge it meets (inf if none)."""
    angles = np.asarray(angles, dtype=float)
    d = np.stack([np.cos(angles), np.sin(angles)], axis=-1)[:, None, :]
    a = edges[None, :, 0, :]
    e = edges[None, :, 1, :] - a
    ap = a - np.array([x, y])
    denom = _cross(d, e)
    with np.errstate(divide='ignore', invalid='ignore'):
        t = _cross(ap, e) / denom
        u = _cross(ap, d) / denom
    hit = (denom != 0.0) & (t >= 0.0) & (u >= 0.0) & (u <= 1.0)
    t = np.where(hit, t, np.inf)
    return t.min(axis=1) if t.shape[1] else np.full(len(angles), np.inf)


def segment_distance(p, a, b):
    """Distances from points p (..., 2) to segments a->b (..., 2), broadcast against each
    other."""
    ab = b - a
    length2 = np.maximum((ab ** 2).sum(axis=-1), 1e-18)
    s = np.clip(((p - a) * ab).sum(axis=-1) / length2, 0.0, 1.0)
    offset = p - a - s[..., None] * ab
    return np.hypot(offset[..., 0], offset[..., 1])


def point_segment_distance(p, a, b):
    """Distances (N, M) from points p (N, 2) to segments a->b (M, 2)."""
    return segment_distance(p[:, None, :], a[None], b[None])


def _segments_cross(a1, b1, a2, b2):
    """(N, M) whether segments a1->b1 (N) and a2->b2 (M) intersect."""
    def side(p, q, r):
        return _cross(q - p, r - p)
    p, q = a1[:, None, :], b1[:, None, :]
    r, s = a2[None, :, :], b2[None, :, :]
    d1, d2 = side(r, s, p), side(r, s, q)
    d3, d4 = side(p, q, r), side(p, q, s)
    return (d1 * d2 <= 0.0) & (d3 * d4 <= 0.0)


def _inside_convex(points, polygon):
    """Whether each point lies inside a convex polygon given counter-clockwise."""
    edges = np.roll(polygon, -1, axis=0) - polygon
    rel = points[:, None, :] - polygon[None, :, :]
    return (_cross(edges[None], rel) >= 0.0).all(axis=1)


def polygon_clearance(polygon, edges):
    """Smallest distance between a convex polygon (counter-clockwise) and any edge; 0 on contact."""
    if len(edges) == 0:
        return math.inf
    a2, b2 = edges[:, 0], edges[:, 1]
    a1, b1 = polygon, np.roll(polygon, -1, axis=0)
    if _segments_cross(a1, b1, a2, b2).any() or _inside_convex(a2, polygon).any():
        return 0.0
    return float(min(point_segment_distance(polygon, a2, b2).min(),
                     point_segment_distance(edges.reshape(-1, 2), a1, b1).min()))
