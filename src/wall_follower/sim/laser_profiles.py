"""Laser conventions of the platforms the package must serve, emulated on a Stage world.

The same world can be scanned as real Stage publishes it, as the real
TurtleBot3 lasers' drivers do (LDS-01, LDS-02), as the Gazebo TurtleBot3
model does, or as the course's own 720-beam simulation does, so the nodes can
be tested against each convention (see DESIGN.md, "Laser conventions"). A
profile fixes where the beams point (in the laser frame), how far the laser
reaches and how a reading is reported; the beams are raytraced at the
profile's own angles.
"""
import math
from collections import namedtuple

import numpy as np

__all__ = ['PROFILES', 'BeamLayout', 'Reach', 'beam_layout', 'reach', 'report']

PROFILES = ('stage', 'lds01', 'lds02', 'gazebo', 'course720')

# Range noise of the TurtleBot3 lasers (metres, one sigma), and the share of
# readings that come back empty although something is in range (LDS-01, LDS-02).
SIGMA = 0.01
DROPOUT = 0.01
# Gazebo TurtleBot3 model: 360 samples from 0 to 6.28319 rad, so the ends coincide.
_GAZEBO_ANGLE_MAX = 6.28319
# The course's simulation: 720 beams, one every half degree, from -pi (backwards).
_COURSE_BEAMS = 720
# LDS-02 (LD08, ld08_driver): a revolution yields a different number of points
# every time, and the driver publishes them as they came: range_min 0 and
# range_max 100 whatever the laser can see, its specified 0.16-8 m reach.
LDS02_BEAMS = (230, 260)
_LDS02_PUBLISHED = (0.0, 100.0)
_LDS02_REACH = (0.16, 8.0)

BeamLayout = namedtuple('BeamLayout', ['angle_min', 'angle_max', 'angle_increment', 'count'])
# What a profile sees (raytraced up to `max`, nothing nearer than `min`) and what its
# scans say in range_min and range_max.
Reach = namedtuple('Reach', ['min', 'max', 'published_min', 'published_max'])


def _check(profile):
    if profile not in PROFILES:
        raise ValueError('unknown laser profile %r (known: %s)' % (profile, ', '.join(PROFILES)))


def beam_layout(profile, ranger, rng=None):
    """Beam angles in the laser frame for `profile` and a world's RangerSpec.

    rng (a numpy RandomState) draws lds02's beam count, which changes from
    scan to scan; the other profiles do not use it.
    """
    _check(profile)
    if profile == 'stage':
        # stageros: angle_min = -fov/2, increment = fov/(samples-1)
        count = ranger.samples
        increment = ranger.fov / (count - 1) if count > 1 else 0.0
        return BeamLayout(-ranger.fov / 2.0, ranger.fov / 2.0, increment, count)
    if profile == 'lds01':
        # hls_lfcd_lds_driver: one beam per degree, index 0 straight ahead, counter-clockwise
        increment = 2.0 * math.pi / 360.0
        return BeamLayout(0.0, 2.0 * math.pi - increment, increment, 360)
    if profile == 'lds02':
        # ld08_driver: from ahead, counter-clockwise; angle_max is the last point's
        # angle and the increment (angle_max - angle_min) / count, so that
        # angle_min + count * increment, not + (count - 1), reaches angle_max.
        count = (rng if rng is not None else np.random).randint(LDS02_BEAMS[0],
                                                                LDS02_BEAMS[1] + 1)
        angle_max = 2.0 * math.pi * (count - 1) / count
        return BeamLayout(0.0, angle_max, angle_max / count, count)
    if profile == 'gazebo':
        return BeamLayout(0.0, _GAZEBO_ANGLE_MAX, _GAZEBO_ANGLE_MAX / 359.0, 360)
    increment = 2.0 * math.pi / _COURSE_BEAMS
    return BeamLayout(-math.pi, math.pi - increment, increment, _COURSE_BEAMS)


def reach(profile, ranger):
    """The profile's Reach: the world's ranger's, but for lds02, which has its own."""
    _check(profile)
    if profile == 'lds02':
        return Reach(_LDS02_REACH[0], _LDS02_REACH[1], *_LDS02_PUBLISHED)
    return Reach(ranger.range_min, ranger.range_max, ranger.range_min, ranger.range_max)


def report(profile, ranges, intensities, hit, ranger, rng):
    """Turn raytraced ranges into what `profile` publishes.

    ranges/intensities: raytraced values (up to the profile's reach); hit: which
    beams hit something (the others read the reach). rng: a numpy RandomState,
    for reproducible noise.
    stage: Stage's own noise model (the world's `noise`), no-hit = range_max, readings
        below range_min kept as they are.
    lds01, lds02: gaussian noise, no return or nearer than the reach -> 0.0, random
        0.0 dropouts.
    gazebo, course720: gaussian noise, no return or below range_min -> inf.
    """
    _check(profile)
    ranges = np.array(ranges, dtype=np.float64)
    intensities = np.array(intensities, dtype=np.float64)
    if profile == 'stage':
        const_variance, proportional, _ = ranger.noise
        if const_variance > 0.0 or proportional > 0.0:
            uniform = rng.randint(0, 1000, len(ranges)) * 0.002 - 1.0
            noisy = ranges + ranges * proportional * uniform + \
                rng.normal(0.0, math.sqrt(const_variance), len(ranges))
            ranges = np.where(hit, noisy, ranges)
        return ranges, intensities
    limits = reach(profile, ranger)
    noisy = ranges + rng.normal(0.0, SIGMA, len(ranges))
    valid = hit & (ranges >= limits.min)
    noisy = np.clip(noisy, limits.min, limits.max)
    if profile in ('lds01', 'lds02'):
        valid &= rng.random_sample(len(ranges)) >= DROPOUT
        empty = 0.0
    else:
        empty = float('inf')
    return np.where(valid, noisy, empty), np.where(valid, intensities, 0.0)


def angle_noise(ranger, layout, rng):
    """Stage's per-beam angle jitter (the world's `noise` angle term), in radians."""
    spread = rng.randint(0, 1000, layout.count) * 0.002 - 1.0
    return layout.angle_increment * ranger.noise[2] * spread * 0.5
