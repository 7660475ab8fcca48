"""circles: the circle fit, and round_pillar's choice of what to circle: a round pillar
standing free on the right, not a small box's corner, nor a pillar beside a wall."""
import math

import numpy as np
import pytest

from wall_follower.control.following.follower import FollowerParams
from wall_follower.control.sensing.circles import arc_span, bulge, fit_circle, round_pillar
from wall_follower.evaluation.scoring.geometry import cast_rays

PARAMS = FollowerParams()
# Stage's grid: where a beam stops is known to about a cell.
CELL = 0.02


def polygon(corners):
    """Edges (N, 2, 2) of the closed polygon through corners."""
    corners = np.asarray(corners, dtype=float)
    return np.stack((corners, np.roll(corners, -1, axis=0)), axis=1)


def disc(center, radius, sides=48):
    """A round pillar's outline."""
    angles = np.linspace(0.0, 2.0 * math.pi, sides, endpoint=False)
    return polygon(np.column_stack((center[0] + radius * np.cos(angles),
                                    center[1] + radius * np.sin(angles))))


def box(center, length, breadth, turned=0.0):
    """A box's outline: length along x turned by turned (rad), breadth across."""
    c, s = math.cos(turned), math.sin(turned)
    half = np.array(((1, 1), (-1, 1), (-1, -1), (1, -1))) * (length / 2.0, breadth / 2.0)
    return polygon(np.asarray(center) + half.dot(((c, s), (-s, c))))


def right_hits(*outlines):
    """The hits on the right of a laser at the origin heading along x, one beam a degree,
    each put on Stage's grid."""
    angles = np.radians(np.arange(-180.0, 0.5, 1.0))
    ranges = cast_rays(np.concatenate(outlines), 0.0, 0.0, angles)
    seen = ranges < 3.5
    points = ranges[seen, None] * np.column_stack((np.cos(angles[seen]), np.sin(angles[seen])))
    return np.round(points / CELL) * CELL


def nearest(points):
    distances = np.hypot(points[:, 0], points[:, 1])
    at = int(np.argmin(distances))
    return distances[at], math.atan2(points[at, 1], points[at, 0])


def pillar_of(*outlines):
    points = right_hits(*outlines)
    return round_pillar(points, nearest(points), PARAMS)


def test_a_circle_through_points_on_an_arc_is_that_circle():
    angles = np.radians(np.linspace(30.0, 150.0, 25))
    points = np.column_stack((0.2 + 0.1 * np.cos(angles), -0.4 + 0.1 * np.sin(angles)))
    circle = fit_circle(points)
    assert circle.center == pytest.approx((0.2, -0.4))
    assert circle.radius == pytest.approx(0.1)
    assert circle.rms == pytest.approx(0.0, abs=1e-9)


@pytest.mark.parametrize('points', [
    np.column_stack((np.linspace(0.0, 1.0, 10), np.full(10, -0.25))),
    np.array(((0.0, -0.3), (0.1, -0.25))),
], ids=['on a straight line', 'too few'])
def test_no_circle_through_points_that_make_none(points):
    assert fit_circle(points) is None


def test_the_arc_points_span_is_measured_across_the_back_of_the_circle_too():
    # From 150 degrees round past 180 to -150: 60 degrees, not 300.
    angles = np.radians(np.concatenate((np.arange(150.0, 180.0, 5.0),
                                        np.arange(-180.0, -149.0, 5.0))))
    points = np.column_stack((np.cos(angles), np.sin(angles)))
    assert math.degrees(arc_span(points, (0.0, 0.0))) == pytest.approx(60.0)


def test_a_round_thing_does_not_bulge_off_its_circle_but_a_corners_two_legs_do():
    round_hits = right_hits(disc((0.0, -0.35), 0.1))
    corner_hits = right_hits(box((0.0, -0.325), 0.3, 0.15, math.radians(45.0)))
    assert abs(bulge(round_hits, fit_circle(round_hits))) < PARAMS.pillar_max_bulge
    assert abs(bulge(corner_hits, fit_circle(corner_hits))) > PARAMS.pillar_max_bulge


@pytest.mark.parametrize('radius', [0.06, 0.1, 0.15])
def test_a_round_pillar_on_the_right_is_found_round(radius):
    fit = pillar_of(disc((0.05, -0.25 - radius), radius))
    assert fit is not None and fit.round
    assert fit.circle.radius == pytest.approx(radius, abs=CELL)


@pytest.mark.parametrize('turned', [0.0, 30.0, 45.0, 60.0])
def test_the_corner_of_a_small_box_is_not_taken_for_a_round_pillar(turned):
    # The generator's smallest island: 0.3 m by 0.15 m.
    fit = pillar_of(box((0.0, -0.35), 0.3, 0.15, math.radians(turned)))
    assert fit is None or not fit.round


def test_a_pillar_beside_a_wall_is_not_circled():
    # The wall runs on past the pillar's window: circling would cut across it.
    assert pillar_of(disc((0.0, -0.35), 0.1),
                     polygon(((-2.0, -0.6), (2.0, -0.6), (2.0, -0.7), (-2.0, -0.7)))) is None


def test_a_round_thing_larger_than_a_pillar_is_not_one():
    assert pillar_of(disc((0.0, -0.75), 0.5)) is None


def test_nothing_near_is_no_pillar():
    assert round_pillar(np.zeros((0, 2)), None, PARAMS) is None
