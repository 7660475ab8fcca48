"""range_ahead: straight ahead by angle in every laser convention, plain words without a reading."""
import math

import numpy as np
import pytest

from laser_conventions import CONVENTIONS, GAZEBO, LDS01, STAGE, box, cast, scan_view
from wall_follower.control.sensing.scan import ScanView
from wall_follower.exercises.range_ahead import describe, range_ahead
from wall_follower.params import defaults
from wall_follower.params.exercises.range_ahead import TABLE

ROOM = box(-2.0, -1.0, 1.0, 1.0)
HALF_WIDTH = defaults(TABLE)['half_width']


@pytest.mark.parametrize('convention', CONVENTIONS, ids=lambda c: c.name)
@pytest.mark.parametrize('pose, expected', [((0.0, 0.0, 0.0), 1.0), ((0.0, 0.0, math.pi), 2.0),
                                            ((0.0, 0.5, math.pi / 2), 0.5)])
def test_the_distance_straight_ahead_whatever_the_convention(convention, pose, expected):
    ahead = range_ahead(scan_view(ROOM, pose, convention), HALF_WIDTH)
    assert ahead.distance == pytest.approx(expected, abs=0.005)


def test_the_labs_middle_beam_is_not_ahead_on_an_lds01():
    """The lab's ranges[len / 2] reads behind the robot on an LDS-01; ours reads ahead."""
    ranges = cast(ROOM, (0.0, 0.0, 0.0), LDS01)
    assert ranges[len(ranges) // 2] == pytest.approx(2.0, abs=0.01)
    reading = range_ahead(scan_view(ROOM, (0.0, 0.0, 0.0), LDS01), HALF_WIDTH)
    assert reading.distance == pytest.approx(1.0, abs=0.005)


def test_invalid_readings_in_the_window_are_ignored():
    view = scan_view(ROOM, (0.0, 0.0, 0.0), LDS01)
    ranges = view.ranges.copy()
    ranges[0] = 0.0
    ranges[1] = float('nan')
    ahead = range_ahead(ScanView(ranges, LDS01.angle_min, LDS01.increment, 0.12, 3.5),
                        HALF_WIDTH)
    assert ahead.distance == pytest.approx(1.0, abs=0.005)
    assert ahead.unknown == 2


@pytest.mark.parametrize('convention', [STAGE, LDS01, GAZEBO], ids=lambda c: c.name)
def test_open_space_beyond_range_says_there_is_no_valid_reading(convention):
    far = box(-10.0, -10.0, 10.0, 10.0)
    ahead = range_ahead(scan_view(far, (0.0, 0.0, 0.0), convention), HALF_WIDTH)
    assert ahead.distance is None
    text = describe(ahead, HALF_WIDTH, convention.range_max)
    assert 'no valid reading within 5 deg of straight ahead' in text
    if convention.no_return == 0.0:
        assert 'prove nothing' in text
    else:
        assert 'nothing within' in text


def test_a_reading_is_printed_in_metres():
    ahead = range_ahead(scan_view(ROOM, (0.0, 0.0, 0.0), STAGE), HALF_WIDTH)
    assert describe(ahead, HALF_WIDTH, 3.5) == 'range ahead: %.3f m' % ahead.distance
    assert np.isfinite(ahead.distance)
