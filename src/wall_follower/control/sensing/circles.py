"""Circles through laser hits: the fit, and the round pillar standing free on the right.

A wall fit sees a round pillar as a string of short chords, each ending
where it began, so the follower would round the pillar as a run of outer
corners, slowing for each. Fitted as a circle, the pillar is one curve
to fly round at the turn rate's limit.

Pure geometry on (N, 2) arrays of hits in the laser frame.
"""
import math
from collections import namedtuple

import numpy as np

from wall_follower.rotation import wrap_angle

Circle = namedtuple('Circle', 'center radius rms')
Circle.__doc__ = """center: (x, y) as an array; radius [m]; rms: the RMS distance [m] of the
points it was fitted to from it."""


def fit_circle(points, min_points=3):
    """The least-squares circle through (N, 2) points: a Circle, or None.

    None below min_points, or for points on one straight line. The
    algebraic fit (x^2 + y^2 = a x + b y + c, linear in a, b, c) needs no
    starting guess; on the short arc a laser sees of a pillar it is close
    to the geometric one.
    """
    if len(points) < max(3, min_points):
        return None
    x, y = points[:, 0], points[:, 1]
    design = np.column_stack((x, y, np.ones(len(points))))
    solution, _, rank, _ = np.linalg.lstsq(design, x * x + y * y, rcond=None)
    if rank < 3:
        return None
    center = solution[:2] / 2.0
    squared = solution[2] + center.dot(center)
    if squared <= 0.0:
        return None
    radius = math.sqrt(squared)
    rms = float(np.sqrt(np.mean((np.hypot(x - center[0], y - center[1]) - radius) ** 2)))
    return Circle(center, radius, rms)


def arc_span(points, center):
    """The angle [rad] that (N, 2) points span round center (less than a full turn)."""
    angles = np.sort(np.arctan2(points[:, 1] - center[1], points[:, 0] - center[0]))
    gaps = np.diff(np.concatenate((angles, angles[:1] + 2.0 * math.pi)))
    return float(2.0 * math.pi - gaps.max())


def bulge(points, circle):
    """How much the points' distance from circle bends along the arc they span [m].

    The curvature term c of offset = a + b u + c u^2, u running from -1 to 1
    over the span round the centre. Two straight legs meeting at a corner,
    fitted with one circle, stand out of it at the corner and fall inside it
    at their ends: |c| is about a centimetre or more. A round thing's offsets
    are only its outline's grid and the laser's noise, with no such shape.
    """
    offsets = points - circle.center
    angles = np.arctan2(offsets[:, 1], offsets[:, 0])
    # Measured from the middle of the arc, so that it does not wrap.
    middle = math.atan2(np.sin(angles).sum(), np.cos(angles).sum())
    along = wrap_angle(angles - middle)
    half = max(1e-9, float(np.abs(along).max()))
    u = along / half
    design = np.column_stack((np.ones(len(u)), u, u * u))
    radial = np.hypot(offsets[:, 0], offsets[:, 1]) - circle.radius
    return float(np.linalg.lstsq(design, radial, rcond=None)[0][2])


class PillarFit(namedtuple('PillarFit', 'circle round')):
    """A free-standing circle on the right (round_pillar): the Circle, and whether its hits
    look round (they span pillar_min_arc and do not bulge by pillar_max_bulge)."""

    __slots__ = ()


def round_pillar(points, nearest, params):
    """The PillarFit of what stands free on the right with the nearest hit on its near side,
    or None.

    points: the hits on the right; nearest: (distance, bearing) of the
    nearest of them. The pillar's hits are those within pillar_window of the
    nearest; it stands free when no hit lies farther from it by up to
    pillar_clearance more (a wall's corner, a long box or a pillar beside a
    wall runs on past the window). Its circle is at most pillar_max_radius,
    fits its hits to pillar_fit_tolerance, and has the laser outside it.
    Whether its hits look round is the fit's round; the caller confirms it
    over several scans, as one scan's hits of a small box's corner can
    look round too.
    """
    if nearest is None:
        return None
    distance, bearing = nearest
    spread = np.hypot(*(points - (distance * math.cos(bearing),
                                  distance * math.sin(bearing))).T)
    window = params.pillar_window
    if np.any((spread >= window) & (spread < window + params.pillar_clearance)):
        return None
    near = points[spread < window]
    circle = fit_circle(near, params.wall_min_points)
    if (circle is None or circle.radius > params.pillar_max_radius
            or circle.rms > params.pillar_fit_tolerance
            or math.hypot(*circle.center) <= circle.radius):
        return None
    looks_round = (arc_span(near, circle.center) >= params.pillar_min_arc
                   and abs(bulge(near, circle)) <= params.pillar_max_bulge)
    return PillarFit(circle, looks_round)
