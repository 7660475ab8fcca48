"""Whether a laser scan can be driven on at all, and what is wrong with it if not.

A laser can fail in ways that still deliver well-formed messages: an LDS-01
whose motor stalls sends scans of nothing but 0.0, a driver restarting
sends an empty one. A controller fed such a scan sees "no wall anywhere"
and drives straight on. Every node that reads a scan therefore passes it
through check_scan() first, and a scan it rejects stops the robot with the
reason it names.

The rule for single readings (DESIGN.md, "Laser conventions"): a hit lies
inside [range_min, range_max); a no-return written as range_max or +inf
proves free space up to range_max; 0.0, NaN, -inf, negative and
below-range_min readings prove nothing. A scan is usable when at least
MIN_KNOWN_SHARE of its readings are hits or proven no-returns.
"""
import math
from collections import namedtuple

from wall_follower.control.sensing.scan import ScanView

ScanCheck = namedtuple('ScanCheck', ['view', 'problem'])
"""view: a ScanView of a usable scan, else None; problem: why not, else None."""

# Beam counts and angles may disagree by this many beams: drivers differ on
# whether angle_max is the last beam's angle or the end of the sweep.
COUNT_SLACK = 1.5

# A scan with fewer usable readings than this share of its beams is unusable:
# a laser that returns a beam or two out of hundreds is failing, not seeing.
# An LDS-01 that drops a beam in a hundred, or sees only the walls within its
# reach in a large hall, keeps far more than this.
MIN_KNOWN_SHARE = 0.02


def check_scan(msg):
    """A ScanCheck of a sensor_msgs/LaserScan (or anything with its fields)."""
    problem = malformation(msg)
    if problem is not None:
        return ScanCheck(None, problem)
    view = ScanView.from_msg(msg)
    known = int(view.known.sum())
    if not known:
        return ScanCheck(None, 'none of its %d readings is usable (%s)'
                         % (view.ranges.size, unusable_kinds(view)))
    if known < MIN_KNOWN_SHARE * view.ranges.size:
        return ScanCheck(None, 'only %d of its %d readings %s usable (%s)'
                         % (known, view.ranges.size, 'is' if known == 1 else 'are',
                            unusable_kinds(view)))
    return ScanCheck(view, None)


def malformation(msg):
    """Why a scan's layout cannot be trusted, or None when it can."""
    count = len(msg.ranges)
    numbers = (msg.angle_min, msg.angle_max, msg.angle_increment, msg.range_min, msg.range_max)
    if count < 2:
        return 'it has %d beam%s' % (count, '' if count == 1 else 's')
    if not all(math.isfinite(value) for value in numbers):
        return 'its angles or range limits are not finite numbers'
    if msg.angle_increment == 0.0:
        return 'its angle_increment is 0'
    if msg.range_max <= msg.range_min or msg.range_max <= 0.0:
        return ('its range_max (%g) is not above its range_min (%g)'
                % (msg.range_max, msg.range_min))
    expected = (msg.angle_max - msg.angle_min) / msg.angle_increment + 1.0
    if abs(count - expected) > COUNT_SLACK:
        return ('its %d ranges do not match its angles (%g to %g by %g: %.0f beams)'
                % (count, msg.angle_min, msg.angle_max, msg.angle_increment, expected))
    return None


def unusable_kinds(view):
    """A short list of what the unusable readings of a scan are."""
    ranges = view.ranges
    kinds = (('NaN', ranges != ranges),
             ('0.0', ranges == 0.0),
             ('negative', ranges < 0.0),
             ('below range_min', (ranges > 0.0) & (ranges < view.range_min)),
             ('-inf', ranges == -math.inf))
    return ', '.join('%d %s' % (mask.sum(), name) for name, mask in kinds if mask.any())
