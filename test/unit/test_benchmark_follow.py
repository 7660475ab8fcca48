"""How `benchmark follow` turns several laps of one world and laser into its row, and times
a lap against its T*."""
import numpy as np
import pytest

from wall_follower.evaluation.benchmarks import follow_generated
from wall_follower.evaluation.benchmarks.follow import combined
from wall_follower.evaluation.scoring import driven_bound, lap_bound


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


def test_each_generated_lap_is_timed_against_its_loop_s_bound_found_once(monkeypatch):
    found = []

    def fastest_lap(world, start, margin):
        found.append((world, margin))
        return lap_bound.LapBound(50.0, 9.5, np.array([[0.0, -1.0], [1.0, -1.0]]),
                                  np.zeros(2), (-0.032, 0.0), 0.0)

    def drive(world, bound):
        return driven_bound.DrivenLap(51.0, 0.99, 0.03, 0.1, False, True)

    monkeypatch.setattr(driven_bound, 'fastest_lap', fastest_lap)
    monkeypatch.setattr(driven_bound, 'drive', drive)
    monkeypatch.setattr(follow_generated, 'grade_case',
                        lambda record: {'lap_genuine': record['genuine']})
    bounds = follow_generated.Bounds(0.02)

    def record(laser, start, lap_time, genuine=True):
        return {'world': '/out/%s/gen_s5_003.world' % laser, 'genuine': genuine,
                'figures': {'lap_start': start, 'lap_time': lap_time}}

    assert bounds.graded(record('stage', [0.1, -0.95, 0.0], 55.0))['lap_over_bound'] == \
        pytest.approx(1.1)
    # Another laser's copy of the world, a lap begun elsewhere on the same loop.
    assert bounds.graded(record('lds01', [0.9, -1.1, 0.0], 60.0))['lap_over_bound'] == \
        pytest.approx(1.2)
    assert bounds.graded(record('lds02', [0.5, -1.0, 0.0], 60.0, False))['lap_over_bound'] \
        is None
    assert found == [('/out/stage/gen_s5_003.world', 0.02)]
    # A lap round another loop (an island, say) has a bound of its own.
    bounds.graded(record('gazebo', [3.0, 2.0, 0.0], 20.0))
    assert len(found) == 2
