"""The reading of the wall on the right along a planned left turn, through an ideal corner."""
import math

import numpy as np
import pytest

from wall_follower.control.following.left_turn import LeftTurn
from wall_follower.control.following.turn_reading import peak_reading
from wall_follower.control.sensing.lines import Line
from wall_follower.evaluation.scoring.course import RIGHT_SECTOR
from wall_follower.evaluation.scoring.geometry import cast_rays

WIDE = 0.19 / 0.49
LANDING = 0.225


def judged(edges, laser, heading):
    """The course's reading, by its own rays: the nearest within RIGHT_SECTOR of the right."""
    angles = heading - math.pi / 2 + np.linspace(-RIGHT_SECTOR, RIGHT_SECTOR, 601)
    return float(np.min(cast_rays(edges, laser[0], laser[1], angles)))


def corner(right, ahead, angle, into):
    """The wall on the right (right to the right of the origin, along x) and the wall ahead
    (ahead from the origin, at angle), as edges that meet, turned by into (rad) to the left:
    the origin then heads into the wall on the right."""
    sine, cosine = math.sin(angle), math.cos(angle)
    # The wall ahead passes (ahead sin, -ahead cos) along (cos, sin); where it meets y = -right:
    along = (-right + ahead * cosine) / sine
    meet = (ahead * sine + along * cosine, -right)
    far = (meet[0] + 5.0 * cosine, meet[1] + 5.0 * sine)
    edges = np.array([((-5.0, -right), meet), (meet, far)])
    turn = np.array([[math.cos(into), math.sin(into)], [-math.sin(into), math.cos(into)]])
    return edges @ turn


@pytest.mark.parametrize('laser_x', [0.0, -0.032, -0.064])
@pytest.mark.parametrize('angle_deg', [90.0, 60.0, 110.0])
@pytest.mark.parametrize('right', [0.22, 0.30])
@pytest.mark.parametrize('into_deg', [0.0, 8.0])
def test_a_pivot_reads_as_the_courses_own_rays_do(laser_x, angle_deg, right, into_deg):
    # A pivot leaves the rotation centre where it is, so the course's rays
    # can be cast from the laser's circle round it at every heading.
    pivot = LeftTurn(0.0, WIDE, 0.0, 0.0)
    angle, into = math.radians(angle_deg), math.radians(into_deg)
    edges = corner(right, LANDING, angle, into)
    headings = np.linspace(0.0, angle + into, 721)
    expected = max(judged(edges, (laser_x * math.cos(h), laser_x * math.sin(h)), h)
                   for h in headings)
    peak = peak_reading(pivot, Line(right, into), Line(LANDING, angle + into), LANDING, laser_x,
                        RIGHT_SECTOR)
    # Read every 2 degrees, the peak, where the nearer wall hands over, may fall between.
    assert expected - 2e-3 <= peak <= expected + 1e-6


def default_turn():
    return LeftTurn(0.09, WIDE, math.radians(30.0), math.radians(32.0))


def peak_from(turn, right, into=0.0, laser_x=-0.032):
    """The peak through a square corner, begun right from the wall on the right, heading into
    it by into (rad), where the turn is planned to start."""
    ahead = Line(turn.gap(math.pi / 2 + into) + LANDING, math.pi / 2 + into)
    return peak_reading(turn, Line(right, into), ahead, LANDING, laser_x, RIGHT_SECTOR)


def test_a_turn_begun_farther_from_the_wall_it_leaves_reads_farther_through_the_corner():
    peaks = [peak_from(default_turn().drifting_at_most(0.265 - right), right)
             for right in (0.22, 0.25, 0.28, 0.30)]
    assert all(later > earlier for earlier, later in zip(peaks, peaks[1:]))
    assert peaks[-1] > 0.31


def test_a_tighter_arc_reads_nearer_from_the_bands_far_edge():
    # The tight arc carries the robot off the wall it leaves before the wall
    # ahead is near enough to read: the tighter, the less.
    turn = default_turn().drifting_at_most(0.0)
    peaks = [peak_from(turn.tightened(scale), 0.28) for scale in (1.0, 0.5, 0.0)]
    assert peaks[0] > 0.30 > peaks[2]
    assert peaks[0] > peaks[1] > peaks[2]
