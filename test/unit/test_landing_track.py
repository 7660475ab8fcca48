"""The wall a left turn lands on, tracked through a grid's whole-cell ranges."""
import math

import pytest

from wall_follower.control.following.landing_track import JUMP, TOLERANCE, LandingTrack
from wall_follower.control.motion import Command
from wall_follower.control.sensing.lines import Line

CELL, DT = 0.02, 0.1


def in_cells(distance, offset=0.007):
    """A range as Stage's grid reads it: the wall's distance down to a cell boundary."""
    return math.floor((distance - offset) / CELL) * CELL + offset


def test_a_wall_crept_up_on_is_tracked_without_the_grids_steps():
    # Creeping square at a wall at 4 mm a scan, the fit freezes for five
    # scans and then jumps a whole cell: its error spans a cell. The
    # track's error spans a quarter of one, and it comes nearer at every scan.
    track, creep = LandingTrack(), Command(0.04, 0.0)
    truths = [0.40 - creep.linear * DT * (i + 1) for i in range(60)]
    fits = [in_cells(truth) for truth in truths]
    estimates = [track.update(Line(fit, math.pi / 2), creep, DT).distance for fit in fits]
    fit_errors = [fit - truth for fit, truth in zip(fits, truths)]
    errors = [estimate - truth for estimate, truth in zip(estimates, truths)][5:]
    assert max(fit_errors) - min(fit_errors) >= 0.75 * CELL
    assert max(errors) - min(errors) < CELL / 4
    steps = [earlier - later for earlier, later in zip(estimates, estimates[1:])]
    assert 0.0 < min(steps) and max(steps) < CELL / 2


def test_the_approach_is_predicted_along_the_arc_flown():
    # Turning left at 0.49 rad/s on a 0.39 m arc, the wall still 60 degrees
    # round: a fit that agrees with the motion is taken as it is.
    track, turn = LandingTrack(), Command(0.19, 0.49)
    track.update(Line(0.30, math.radians(60.0)), turn, DT)
    angle = math.radians(60.0) - turn.angular * DT
    nearer = 0.19 * DT * math.sin(math.radians(60.0) - 0.5 * turn.angular * DT)
    assert track.update(Line(0.30 - nearer, angle), turn, DT).distance == pytest.approx(
        0.30 - nearer)


def test_the_estimate_keeps_within_tolerance_of_the_fit():
    # Held back by the drive loop, the robot did not move as commanded.
    track, commanded = LandingTrack(), Command(0.19, 0.0)
    track.update(Line(0.50, math.pi / 2), commanded, DT)
    for _ in range(5):
        estimate = track.update(Line(0.50, math.pi / 2), commanded, DT)
        assert 0.50 - TOLERANCE <= estimate.distance <= 0.50


@pytest.mark.parametrize('fitted', [Line(0.50 - 1.5 * JUMP, math.pi / 2),
                                    Line(0.50, math.radians(60.0))])
def test_another_wall_starts_the_track_afresh(fitted):
    track, still = LandingTrack(), Command(0.0, 0.0)
    track.update(Line(0.50, math.pi / 2), still, DT)
    assert track.update(fitted, still, DT) == fitted


def test_no_wall_ends_the_track():
    track, still = LandingTrack(), Command(0.0, 0.0)
    track.update(Line(0.50, math.pi / 2), still, DT)
    assert track.update(None, still, DT) is None
    assert track.update(Line(0.30, math.pi / 2), still, DT) == Line(0.30, math.pi / 2)
