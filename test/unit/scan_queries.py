"""Queries on a ScanView that only the tests ask: one direction's range, the nearest hit.

Shared by the unit tests (not itself a test module). They read a scan the
way the controllers do, by angle and through ScanView's masks, so that a
test can say "the wall on the right is 0.3 m away" whatever the laser's
conventions.
"""
import math
import warnings

import numpy as np

from wall_follower.control.sensing.lines import fit_line


def sector_ranges(view, center, half_width):
    """The valid readings within half_width of the angle center."""
    return view.ranges[view.in_sector(center, half_width) & view.valid]


def range_at(view, angle, half_width=math.radians(5.0)):
    """Median of the valid readings within half_width of angle, or inf."""
    values = sector_ranges(view, angle, half_width)
    return float(np.median(values)) if values.size else math.inf


def min_range(view, center, half_width):
    """Closest valid reading in a sector, or inf."""
    values = sector_ranges(view, center, half_width)
    return float(values.min()) if values.size else math.inf


def fit_wall(view, center, half_width, min_points=5):
    """(distance, normal angle) of a straight line through a sector's hits, or None."""
    return fit_line(view.points(center, half_width), min_points)


def nearest(view, half_width=math.radians(3.0), min_hits=3):
    """(distance, angle) of the nearest direction that min_hits valid beams support, or None.

    Each beam's range is replaced by the median of its neighbours within
    half_width, so that a lone beam does not count.
    """
    if not view.valid.any():
        return None
    order = np.argsort(view.angles)
    angles = view.angles[order]
    ranges = np.where(view.valid[order], view.ranges[order], np.nan)
    k = max(1, int(round(half_width / max(view.half_step * 2.0, 1e-9))))
    padded = np.concatenate((ranges[-k:], ranges, ranges[:k]))
    windows = np.array([padded[i:i + 2 * k + 1] for i in range(ranges.size)])
    hits = np.sum(np.isfinite(windows), axis=1)
    with warnings.catch_warnings():
        warnings.simplefilter('ignore', RuntimeWarning)
        smooth = np.where(hits >= min_hits, np.nanmedian(windows, axis=1), np.nan)
    smooth = np.where(np.isfinite(ranges), smooth, np.nan)
    if not np.isfinite(smooth).any():
        return None
    best = int(np.nanargmin(smooth))
    return float(smooth[best]), float(angles[best])
