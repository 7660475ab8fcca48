"""How `benchmark find` turns a find_wall trial into its row."""
from wall_follower.evaluation.benchmarks.find import TARGET, trial_row
from wall_follower.params import defaults
from wall_follower.params.course.wall_finder import FINDER


def trial(distance, found=True):
    return dict(start=(0.5, -0.5, 30.0), found=found, time=11.0, distance=distance,
                heading_error_deg=-0.4, contact=False)


def test_the_distance_error_is_counted_from_where_the_finder_aims():
    assert TARGET == defaults(FINDER)['wall_distance']
    row = trial_row('room', trial(TARGET + 0.012))
    assert row == ['room', '0.50 -0.50 30', 'yes', '11.0', '1.20', '0.40', 'no']


def test_a_trial_that_found_no_wall_says_so():
    assert trial_row('arena', trial(float('nan'), found=False))[2] == 'NO'
