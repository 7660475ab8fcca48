"""How `benchmark follow` turns several laps of one world and laser into its row."""
import pytest

from wall_follower.evaluation.benchmarks.follow import combined


def lap(ratio, band=0.98, clearance=0.12, contact=False, max_linear=0.19):
    return dict(time_in_band=band, rms_error=0.019, lap_time=90.0 * ratio / 1.2,
                path_length=14.0, lap_time_ratio=ratio, min_clearance=clearance,
                contact=contact, max_linear=max_linear, max_angular=0.49)


def test_a_row_is_the_mean_of_its_laps_with_the_worst_beside_it():
    row = combined([lap(1.19, band=0.97), lap(1.21, band=0.99, clearance=0.10)])
    assert row['laps'] == 2
    assert row['lap_time_ratio'] == pytest.approx(1.20)
    assert row['time_in_band'] == pytest.approx(0.98)
    assert row['worst_ratio'] == pytest.approx(1.21)
    assert row['min_clearance'] == pytest.approx(0.10)


def test_one_lap_in_contact_or_too_fast_marks_the_row():
    row = combined([lap(1.2), lap(1.2, contact=True, max_linear=0.2)])
    assert row['contact'] is True
    assert row['max_linear'] == pytest.approx(0.2)


def test_laps_that_wrote_nothing_are_left_out_and_none_at_all_is_no_row():
    assert combined([None, lap(1.18), {}])['laps'] == 1
    assert combined([None, None]) is None


def test_a_row_says_which_simulator_its_laps_ran_on():
    assert combined([dict(lap(1.2), simulator='stageros')])['simulator'] == 'stageros'
    assert combined([lap(1.2)])['simulator'] == '?'
