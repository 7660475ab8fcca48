"""How far beyond the left turn's reach the wall ahead lies, tracked through one scan's errors."""
import pytest

from wall_follower.control.following.reach_track import GAIN, JUMP, ReachTrack

CELL = 0.02


def test_a_slack_the_plan_keeps_is_held_through_a_scan_that_reads_a_cell_off():
    # Flown as planned, the turn keeps the slack it began with; one scan
    # reads the wall a whole cell farther, as Stage's grid does. The
    # estimate moves by GAIN of that cell, not by all of it, and goes back.
    track = ReachTrack()
    measured = [-0.003] * 3 + [-0.003 + CELL] + [-0.003] * 6
    estimates = [track.update(slack, 0.0) for slack in measured]
    assert max(estimates) == pytest.approx(-0.003 + GAIN * CELL)
    assert estimates[-1] == pytest.approx(-0.003, abs=0.001)


def test_a_slack_that_changes_as_the_command_says_is_taken_as_it_is():
    # A turn flown tighter than planned (begun late) loses slack at every
    # scan by as much as its command says: measurements that agree with
    # that are the estimate.
    track = ReachTrack()
    measured = [0.01 - 0.004 * scan for scan in range(8)]
    track.update(measured[0], 0.0)
    for slack in measured[1:]:
        assert track.update(slack, -0.004) == pytest.approx(slack)


def test_a_measurement_far_from_the_prediction_starts_afresh():
    # Another wall across the way, or a robot that did not move as commanded.
    track = ReachTrack()
    track.update(0.0, 0.0)
    assert track.update(JUMP + 0.01, 0.0) == JUMP + 0.01
    assert track.update(JUMP + 0.01 - 0.005, 0.0) == pytest.approx(JUMP + 0.01 - GAIN * 0.005)


def test_no_wall_across_the_way_leaves_no_slack():
    track = ReachTrack()
    track.update(0.02, 0.0)
    assert track.update(None, 0.0) is None
    assert track.update(0.05, -0.01) == 0.05
