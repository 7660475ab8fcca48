"""check_scan: which scans can be driven on, and the reason given for each that cannot."""
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from laser_conventions import CONVENTIONS, LDS01, STAGE, box, cast
from wall_follower.control.sensing.scan_check import check_scan


class Scan(object):
    """The fields of a sensor_msgs/LaserScan that check_scan reads."""

    def __init__(self, ranges, angle_min, angle_increment, range_min, range_max,
                 angle_max=None):
        self.ranges = list(ranges)
        self.angle_min = angle_min
        self.angle_increment = angle_increment
        self.angle_max = (angle_max if angle_max is not None
                          else angle_min + angle_increment * (len(self.ranges) - 1))
        self.range_min = range_min
        self.range_max = range_max


def scan_of(convention, ranges):
    return Scan(ranges, convention.angle_min, convention.increment, convention.range_min,
                convention.range_max)


ROOM = box(-1.0, -0.5, 2.0, 1.0)


@pytest.mark.parametrize('convention', CONVENTIONS, ids=lambda c: c.name)
def test_a_scan_of_a_room_is_usable_in_every_convention(convention):
    check = check_scan(scan_of(convention, cast(ROOM, (0.0, 0.0, 0.0), convention)))
    assert check.problem is None and check.view.valid.any()


def test_a_sweep_ending_one_beam_past_its_last_angle_is_usable():
    # LD08-style: angle_increment = span / count, angle_max the end of the sweep.
    msg = Scan([1.0] * 240, 0.0, 2.0 * math.pi / 240, 0.0, 8.0, angle_max=2.0 * math.pi)
    assert check_scan(msg).problem is None


@pytest.mark.parametrize('ranges, problem', [
    ([], 'it has 0 beams'),
    ([1.0], 'it has 1 beam'),
])
def test_too_few_beams(ranges, problem):
    assert check_scan(Scan(ranges, 0.0, 0.1, 0.1, 3.5)) == (None, problem)


def test_a_zero_increment():
    msg = Scan([1.0] * 360, 0.0, 0.0, 0.12, 3.5, angle_max=6.28)
    assert check_scan(msg) == (None, 'its angle_increment is 0')


def test_range_max_below_range_min():
    msg = scan_of(LDS01, [1.0] * 360)
    msg.range_min, msg.range_max = 3.5, 0.12
    assert check_scan(msg) == (None, 'its range_max (0.12) is not above its range_min (3.5)')


def test_not_finite_angles():
    msg = scan_of(LDS01, [1.0] * 360)
    msg.angle_increment = math.nan
    assert check_scan(msg).problem == 'its angles or range limits are not finite numbers'


def test_ranges_that_contradict_the_angles():
    msg = scan_of(STAGE, [1.0] * 180)
    msg.angle_max = math.pi
    assert check_scan(msg).problem == ('its 180 ranges do not match its angles '
                                       '(-3.14159 to 3.14159 by 0.0175019: 360 beams)')


@pytest.mark.parametrize('value, named', [
    (0.0, '360 0.0'), (math.nan, '360 NaN'), (-1.0, '360 negative'),
    (0.05, '360 below range_min'), (-math.inf, '360 negative, 360 -inf')])
def test_no_usable_reading_names_what_the_readings_are(value, named):
    check = check_scan(scan_of(LDS01, [value] * 360))
    assert check == (None, 'none of its 360 readings is usable (%s)' % named)


@pytest.mark.parametrize('no_return', [math.inf, 3.5, 40.0])
def test_no_returns_written_as_range_max_or_more_prove_free_space(no_return):
    check = check_scan(scan_of(LDS01, [no_return] * 360))
    assert check.problem is None
    assert check.view.free.all() and not check.view.valid.any()
    assert check.view.known_share_in_sector(0.0, math.radians(30.0)) == (61, 61)


def test_dropouts_prove_nothing_ahead():
    ranges = np.full(360, 1.0)
    ranges[:31] = 0.0
    ranges[-30:] = math.nan   # LDS-01: beam 0 ahead, so +-30 deg is beams 330..30
    view = check_scan(scan_of(LDS01, ranges)).view
    assert view.known_share_in_sector(0.0, math.radians(30.0)) == (0, 61)
    assert view.known_share_in_sector(0.0, math.radians(32.0)) == (4, 65)


def test_a_scan_with_a_beam_or_two_usable_out_of_hundreds_is_unusable():
    ranges = [math.nan] * 360
    ranges[29] = 3.0    # LDS-01: 29 deg left
    check = check_scan(scan_of(LDS01, ranges))
    assert check == (None, 'only 1 of its 360 readings is usable (359 NaN)')


def test_a_scan_that_sees_only_a_near_wall_in_a_large_hall_is_usable():
    ranges = [0.0] * 360     # LDS-01: nothing within its reach...
    ranges[80:100] = [0.5] * 20   # ...but a wall on the left
    assert check_scan(scan_of(LDS01, ranges)).problem is None


finite_or_not = st.floats(allow_nan=True, allow_infinity=True, width=32)


@settings(max_examples=300, deadline=None, database=None)
@given(ranges=st.lists(finite_or_not, max_size=400), angle_min=finite_or_not,
       angle_max=finite_or_not, increment=finite_or_not, range_min=finite_or_not,
       range_max=finite_or_not)
def test_any_scan_gets_a_view_or_a_reason_and_never_raises(ranges, angle_min, angle_max,
                                                           increment, range_min, range_max):
    check = check_scan(Scan(ranges, angle_min, increment, range_min, range_max, angle_max))
    assert (check.view is None) != (check.problem is None)
    if check.view is not None:
        assert check.view.known.any()
        assert np.isfinite(check.view.angles).all()
