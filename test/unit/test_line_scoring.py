"""Scoring a line follower: progress round a lap, cross-track distance, the speed bound."""
import math

import numpy as np
import pytest

from wall_follower.evaluation.scoring.line import cross_track, progress, speed_bound
from wall_follower.evaluation.scoring.line_track import Centreline


def circle(radius, closed=True):
    angles = np.linspace(0.0, 2.0 * math.pi, 4001)
    return Centreline(np.column_stack((radius * np.cos(angles), radius * np.sin(angles))),
                      closed, 0.045)


def test_progress_counts_a_lap_across_the_start():
    line = circle(1.0)
    angles = np.linspace(-0.5, 2.0 * math.pi - 0.5, 200)
    driven = progress(line, np.column_stack((np.cos(angles), np.sin(angles))))
    assert driven[-1] == pytest.approx(2.0 * math.pi, abs=0.01)
    assert np.all(np.diff(driven) > 0.0)


def test_cross_track_of_a_parallel_circle():
    line = circle(1.0)
    angles = np.linspace(0.0, 6.0, 50)
    rms, worst = cross_track(line, 1.02 * np.column_stack((np.cos(angles), np.sin(angles))))
    assert rms == pytest.approx(0.02, abs=1e-4) and worst == pytest.approx(0.02, abs=1e-4)


def test_speed_bound_is_the_turn_rate_limit_on_a_tight_circle_and_the_speed_limit_on_a_wide():
    assert speed_bound(circle(0.2), 0.19, 0.49) == pytest.approx(0.098, rel=0.01)
    assert speed_bound(circle(1.0), 0.19, 0.49) == pytest.approx(0.19, rel=0.01)
