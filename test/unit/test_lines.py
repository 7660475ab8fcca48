"""Straight lines through hits: the Line type and the fits that make one."""
import math

import numpy as np
import pytest

from wall_follower.control.sensing.lines import Line, consensus_line, fit_line


def test_fit_line_through_chosen_points():
    points = np.array([[x, 0.4 - 0.5 * x] for x in np.linspace(-1.0, 1.0, 9)])
    distance, normal = fit_line(points)
    # The line y = 0.4 - x/2 passes 0.4 / sqrt(1.25) from the origin, normal up-right.
    assert distance == pytest.approx(0.4 / math.sqrt(1.25))
    assert normal == pytest.approx(math.atan2(1.0, 0.5))
    assert fit_line(points[:3], min_points=4) is None


def test_consensus_line_ignores_stray_hits_that_would_tilt_a_fit():
    wall = np.array([[0.69, y] for y in np.linspace(0.05, 0.13, 7)])
    stray = np.array([[0.82, 0.05]])
    distance, angle = consensus_line(np.vstack((stray, wall)), 0.025, 6)
    assert distance == pytest.approx(0.69) and angle == pytest.approx(0.0, abs=1e-9)


def test_offsets_are_signed_distances_beyond_the_line():
    # The wall 0.25 m to the right: its normal points right, from the laser to it.
    wall = Line(0.25, -math.pi / 2)
    points = np.array([[1.0, -0.25], [0.0, -0.35], [2.0, 0.0]])
    assert wall.offsets(points) == pytest.approx([0.0, 0.1, -0.25])
    assert wall.normal == pytest.approx([0.0, -1.0])
