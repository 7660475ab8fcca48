"""Laser conventions of the platforms the package must serve, emulated on a Stage world.

The same world can be scanned as real Stage publishes it, as the real
TurtleBot3 LDS-01 driver does, or as the Gazebo TurtleBot3 model does, so the
nodes can be tested against each convention (see DESIGN.md, "Laser
conventions"). A profile fixes where the beams point (in the laser frame) and
how a reading is reported; the beams are raytraced at the profile's own angles.
"""
import math
from collections import namedtuple

import numpy as np

__all__ = ['PROFILES', 'BeamLayout', 'beam_layout', 'report']

PROFILES = ('stage', 'lds01', 'gazebo')

# Range noise of both TurtleBot3 lasers (metres, one sigma), and the LDS-01's share of
# readings that come back empty although something is in range.
SIGMA = 0.01
LDS01_DROPOUT = 0.01
# Gazebo TurtleBot3 model: 360 samples from 0 to 6.28319 rad, so the ends coincide.
_GAZEBO_ANGLE_MAX = 6.28319

BeamLayout = namedtuple('BeamLayout', ['angle_min', 'angle_max', 'angle_increment', 'count'])


def beam_layout(profile, ranger):
    """Beam angles in the laser frame for `profile` and a world's RangerSpec."""
    if profile == 'stage':
        # stageros: angle_min = -fov/2, increment = fov/(samples-1)
        count = ranger.samples
        increment = ranger.fov / (count - 1) if count > 1 else 0.0
        return BeamLayout(-ranger.fov / 2.0, ranger.fov / 2.0, increment, count)
    if profile == 'lds01':
        # hls_lfcd_lds_driver: one beam per degree, index 0 straight ahead, counter-clockwise
        increment = 2.0 * math.pi / 360.0
        return BeamLayout(0.0, 2.0 * math.pi - increment, increment, 360)
    if profile == 'gazebo':
        return BeamLayout(0.0, _GAZEBO_ANGLE_MAX, _GAZEBO_ANGLE_MAX / 359.0, 360)
    raise ValueError('unknown laser profile %r (known: %s)' % (profile, ', '.join(PROFILES)))


def report(profile, ranges, intensities, hit, ranger, rng):
    """Turn raytraced ranges into what `profile` publishes.

    ranges/intensities: raytraced values; hit: which beams hit something (the others
    read range_max). rng: a numpy RandomState, for reproducible noise.
    stage: Stage's own noise model (the world's `noise`), no-hit = range_max, readings
        below range_min kept as they are.
    lds01: gaussian noise, no return or below range_min -> 0.0, random 0.0 dropouts.
    gazebo: gaussian noise, no return or below range_min -> inf.
    """
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
    noisy = ranges + rng.normal(0.0, SIGMA, len(ranges))
    valid = hit & (ranges >= ranger.range_min)
    noisy = np.clip(noisy, ranger.range_min, ranger.range_max)
    if profile == 'lds01':
        valid &= rng.random_sample(len(ranges)) >= LDS01_DROPOUT
        empty = 0.0
    elif profile == 'gazebo':
        empty = float('inf')
    else:
        raise ValueError('unknown laser profile %r (known: %s)' % (profile, ', '.join(PROFILES)))
    return np.where(valid, noisy, empty), np.where(valid, intensities, 0.0)


def angle_noise(ranger, layout, rng):
    """Stage's per-beam angle jitter (the world's `noise` angle term), in radians."""
    return layout.angle_increment * ranger.noise[2] * (rng.randint(0, 1000, layout.count) * 0.002
                                                      - 1.0) * 0.5
