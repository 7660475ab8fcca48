"""The LDS-02 and course720 laser profiles: beam layout, reach and how "no return" reads.

Each scan is also read back through ScanView, as the nodes read it, so a
profile that put its beams somewhere else than its header says would fail.
"""
import math
import os
import textwrap

import numpy as np
import pytest

from wall_follower.control.sensing.scan import FRONT, LEFT, RIGHT, ScanView
from wall_follower.control.sensing.scan_check import check_scan
from wall_follower.sim.engine import Simulation
from wall_follower.sim.laser_profiles import LDS02_BEAMS, PROFILES, beam_layout
from wall_follower.sim.worldfile import load_world

REFERENCE = os.path.join(os.path.dirname(__file__), '..', 'data', 'stage_reference')
# In ref_room (walls at +-1.9 m), a robot at (0.9, 0, 0) has its laser 32 mm
# behind it: the wall ahead is 1.032 m away, those to the sides 1.9 m.
AHEAD, SIDE = 1.032, 1.9
NOISY = 0.05


def room_scans(profile, steps=1, seed=0, pose=(0.9, 0.0, 0.0)):
    sim = Simulation(load_world(os.path.join(REFERENCE, 'ref_room.world')),
                     laser_profile=profile, seed=seed, poses={0: pose})
    return [sim.step().robots[0].scan for _ in range(steps)]


def one_wall_scan(tmp_path, profile, distance):
    """A robot `distance` m from one wall ahead, with nothing else in any direction."""
    path = os.path.join(str(tmp_path), 'one_wall.world')
    with open(path, 'w') as stream:
        stream.write(textwrap.dedent('''
            define bot position ( size [ 0.1 0.1 0.2 ]
                                  ranger ( sensor ( range [ 0.12 3.5 ] fov 360 samples 360 ) ) )
            model ( size [ 0.1 4 0.5 ] pose [ %f 0 0 0 ] )
            bot ( name "robot" pose [ 0 0 0 0 ] )
        ''' % (distance + 0.05)))
    sim = Simulation(load_world(path), laser_profile=profile, seed=1)
    return sim.step().robots[0].scan


def range_towards(scan, angle, half_width=math.radians(3.0)):
    """Median range of the hits within half_width of angle, read as the nodes read a scan."""
    hits = ScanView.from_msg(scan).points(angle, half_width)
    return float(np.median(np.hypot(hits[:, 0], hits[:, 1])))


def test_every_profile_is_known_to_the_simulator():
    assert set(PROFILES) == {'stage', 'lds01', 'lds02', 'gazebo', 'course720'}
    with pytest.raises(ValueError):
        Simulation(load_world(os.path.join(REFERENCE, 'ref_room.world')), laser_profile='lds03')


def test_lds02_beam_count_changes_from_scan_to_scan_within_the_ld08s():
    counts = [len(scan.ranges) for scan in room_scans('lds02', steps=40)]
    assert min(counts) >= LDS02_BEAMS[0] and max(counts) <= LDS02_BEAMS[1]
    assert len(set(counts)) > 10


@pytest.mark.parametrize('profile', PROFILES)
def test_every_profiles_scans_pass_the_nodes_scan_check(profile):
    for scan in room_scans(profile, steps=20, seed=6):
        assert check_scan(scan).problem is None


def test_lds02_header_as_ld08_driver_writes_it():
    for scan in room_scans('lds02', steps=5):
        count = len(scan.ranges)
        assert len(scan.intensities) == count
        assert scan.angle_min == 0.0
        # the increment is the span over the count, not over the gaps between beams
        assert scan.angle_increment == pytest.approx((scan.angle_max - scan.angle_min) / count)
        assert scan.angle_max == pytest.approx(2 * math.pi * (count - 1) / count)
        assert (scan.range_min, scan.range_max) == (0.0, 100.0)


@pytest.mark.parametrize('profile', ['lds02', 'course720'])
def test_beams_point_where_the_header_says(profile):
    for scan in room_scans(profile, steps=3, seed=2):
        assert range_towards(scan, FRONT) == pytest.approx(AHEAD, abs=NOISY)
        assert range_towards(scan, LEFT) == pytest.approx(SIDE, abs=NOISY)
        assert range_towards(scan, RIGHT) == pytest.approx(SIDE, abs=NOISY)
        assert range_towards(scan, math.pi) == pytest.approx(1.9 + 0.868, abs=NOISY)


def test_lds02_starts_ahead_and_turns_counter_clockwise():
    scan = room_scans('lds02', seed=4, pose=(0.0, 1.5, 0.0))[0]
    quarter = int(round(math.pi / 2 / scan.angle_increment))
    left = [r for r in scan.ranges[quarter - 2:quarter + 3] if r > 0.0]
    assert np.median(left) == pytest.approx(0.4, abs=NOISY)      # the wall at y = +1.9
    ahead = [r for r in scan.ranges[:3] if r > 0.0]
    assert np.median(ahead) == pytest.approx(1.932, abs=NOISY)


def test_lds02_writes_no_return_and_too_near_as_zero(tmp_path):
    far = one_wall_scan(tmp_path, 'lds02', 1.0)
    ranges, intensities = np.asarray(far.ranges), np.asarray(far.intensities)
    angles = far.angle_min + far.angle_increment * np.arange(len(ranges))
    behind = np.cos(angles) < 0.0
    assert np.all(ranges[behind] == 0.0), 'nothing behind: every beam reads 0.0'
    assert np.all(intensities[ranges == 0.0] == 0.0)
    assert np.all(np.isfinite(ranges))
    returned = ranges[ranges > 0.0]
    assert returned.size > 0 and np.all((returned >= 0.16) & (returned <= 8.0))
    near = one_wall_scan(tmp_path, 'lds02', 0.1)
    assert near.ranges[0] == 0.0, 'nearer than the LD08 measures reads 0.0'


def test_lds02_reaches_beyond_the_lds01():
    # ref_room's far corner, 4.6 m away diagonally, is out of the LDS-01's 3.5 m
    lds02 = room_scans('lds02', pose=(-1.5, -1.5, math.pi / 4))[0]
    lds01 = room_scans('lds01', pose=(-1.5, -1.5, math.pi / 4))[0]
    assert lds01.ranges[0] == 0.0
    assert lds02.ranges[0] == pytest.approx(math.hypot(3.4, 3.4) + 0.032, abs=NOISY)


def test_lds02_noise_and_dropouts_as_lds01():
    a, b = (room_scans('lds02', seed=seed, pose=(0.0, 0.0, 0.0))[0] for seed in (11, 11))
    assert np.array_equal(a.ranges, b.ranges)
    scans = room_scans('lds02', steps=40, seed=5, pose=(0.0, 0.0, 0.0))
    dropped = np.mean([np.mean(scan.ranges == 0.0) for scan in scans])
    assert 0.005 < dropped < 0.02
    # the wall 1.9 m to the left, over a few beams of many scans: sigma about 1 cm
    left = np.concatenate([s.ranges[np.abs(s.angle_min + s.angle_increment
                                           * np.arange(len(s.ranges)) - LEFT) < 0.02]
                           for s in scans])
    left = left[left > 0.0]
    assert np.std(left) == pytest.approx(0.01, rel=0.4)


def test_course720_header_index_zero_backwards():
    scan = room_scans('course720')[0]
    assert len(scan.ranges) == len(scan.intensities) == 720
    assert scan.angle_min == pytest.approx(-math.pi)
    assert scan.angle_increment == pytest.approx(2 * math.pi / 720)
    assert scan.angle_max == pytest.approx(math.pi - 2 * math.pi / 720)
    assert (scan.range_min, scan.range_max) == (0.12, 3.5)
    assert scan.ranges[0] == pytest.approx(1.9 + 0.868, abs=NOISY)    # behind
    assert scan.ranges[360] == pytest.approx(AHEAD, abs=NOISY)         # ahead


def test_course720_writes_no_return_as_inf(tmp_path):
    scan = one_wall_scan(tmp_path, 'course720', 1.0)
    ranges = np.asarray(scan.ranges)
    assert np.isinf(ranges[0]), 'nothing behind reads inf'
    assert not np.any(ranges == 0.0) and not np.any(np.isnan(ranges))
    assert ranges[360] == pytest.approx(1.0, abs=NOISY)


def test_layouts_other_than_lds02_need_no_random_draw():
    ranger = load_world(os.path.join(REFERENCE, 'ref_room.world')).robots[0].ranger
    for profile in ('stage', 'lds01', 'gazebo', 'course720'):
        assert beam_layout(profile, ranger) == beam_layout(profile, ranger)
