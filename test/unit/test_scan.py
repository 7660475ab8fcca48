"""ScanView: queries by angle in every laser convention, and what counts as a reading."""
import math

import numpy as np
import pytest

from laser_conventions import CONVENTIONS, REVERSED, box, cast, scan_view
from scan_queries import fit_wall, min_range, nearest, range_at
from wall_follower.control.sensing.scan import FRONT, LEFT, RIGHT, ScanView
from wall_follower.rotation import wrap_angle

ALL = CONVENTIONS + [REVERSED]

# A laser at the origin, heading +x, in a box whose four sides are at
# different distances: right 0.3, front 1.2, left 0.8, back 2.0.
ASYMMETRIC = box(-2.0, -0.3, 1.2, 0.8)


def view_of(ranges, convention=ALL[0]):
    return ScanView(ranges, convention.angle_min, convention.increment,
                    convention.range_min, convention.range_max)


@pytest.mark.parametrize('convention', ALL, ids=lambda c: c.name)
def test_each_direction_is_found_by_angle(convention):
    view = scan_view(ASYMMETRIC, (0.0, 0.0, 0.0), convention)
    assert range_at(view, RIGHT) == pytest.approx(0.3, abs=0.002)
    assert range_at(view, FRONT) == pytest.approx(1.2, abs=0.005)
    assert range_at(view, LEFT) == pytest.approx(0.8, abs=0.005)
    assert range_at(view, math.pi) == pytest.approx(2.0, abs=0.01)


@pytest.mark.parametrize('convention', ALL, ids=lambda c: c.name)
def test_turning_the_laser_turns_the_answers(convention):
    # Yaw +90 deg: the box's right side (y = -0.3) is now behind the laser.
    view = scan_view(ASYMMETRIC, (0.0, 0.0, math.pi / 2), convention)
    assert range_at(view, math.pi) == pytest.approx(0.3, abs=0.002)
    assert range_at(view, RIGHT) == pytest.approx(1.2, abs=0.005)


def test_angles_are_wrapped_into_minus_pi_pi():
    wrapped = wrap_angle(np.array([3.5 * math.pi, -3.5 * math.pi, 0.25]))
    assert wrapped == pytest.approx([-0.5 * math.pi, 0.5 * math.pi, 0.25])


@pytest.mark.parametrize('bad', [0.0, math.inf, math.nan, 0.05, 3.5, 40.0, -1.0],
                         ids=['zero', 'inf', 'nan', 'below_min', 'range_max', 'above_max',
                              'negative'])
def test_implausible_readings_are_not_walls(bad):
    ranges = np.full(360, 1.0)
    ranges[270] = bad  # LDS-01 layout: beam 270 points right
    view = ScanView(ranges, 0.0, 2.0 * math.pi / 360, 0.12, 3.5)
    assert not view.valid[270]
    assert range_at(view, RIGHT, half_width=math.radians(0.4)) == math.inf
    assert min_range(view, RIGHT, math.radians(10.0)) == 1.0


def test_a_window_of_dropouts_reads_inf():
    ranges = np.full(360, 0.0)
    view = ScanView(ranges, 0.0, 2.0 * math.pi / 360, 0.12, 3.5)
    assert range_at(view, FRONT) == math.inf
    assert fit_wall(view, RIGHT, math.radians(30.0)) is None
    assert nearest(view) is None
    assert view.points().shape == (0, 2)


def test_the_median_window_ignores_one_wild_beam():
    ranges = np.full(360, 0.5)
    ranges[0] = 0.13  # one spurious short reading straight ahead
    view = ScanView(ranges, 0.0, 2.0 * math.pi / 360, 0.12, 3.5)
    assert range_at(view, FRONT) == 0.5
    assert min_range(view, FRONT, math.radians(5.0)) == 0.13


@pytest.mark.parametrize('convention', ALL, ids=lambda c: c.name)
@pytest.mark.parametrize('yaw_deg', [-10.0, 0.0, 15.0])
def test_fit_wall_gives_distance_and_normal(convention, yaw_deg):
    wall = [((-3.0, -0.25), (3.0, -0.25))]
    view = scan_view(wall, (0.0, 0.0, math.radians(yaw_deg)), convention)
    distance, normal = fit_wall(view, RIGHT, math.radians(30.0))
    assert distance == pytest.approx(0.25, abs=1e-6)
    # The normal turns against the laser: yaw left puts the wall's normal further right.
    assert normal == pytest.approx(RIGHT - math.radians(yaw_deg), abs=1e-6)


def test_fit_wall_needs_enough_hits():
    ranges = np.zeros(360)
    ranges[268:272] = 0.25
    view = ScanView(ranges, 0.0, 2.0 * math.pi / 360, 0.12, 3.5)
    assert fit_wall(view, RIGHT, math.radians(30.0), min_points=5) is None
    assert fit_wall(view, RIGHT, math.radians(30.0), min_points=4) is not None


@pytest.mark.parametrize('convention', ALL, ids=lambda c: c.name)
def test_nearest_is_not_fooled_by_a_single_spurious_beam(convention):
    ranges = cast(box(-2.0, -0.6, 2.0, 2.0), (0.0, 0.0, 0.0), convention)
    front = int(np.argmin(np.abs(wrap_angle(
        convention.angle_min + convention.increment * np.arange(convention.count)))))
    ranges[front] = 0.2  # one beam says "something 0.2 m ahead"
    distance, angle = nearest(view_of(ranges, convention))
    assert distance == pytest.approx(0.6, abs=0.01)
    assert angle == pytest.approx(RIGHT, abs=math.radians(4.0))


def test_nearest_prefers_a_real_obstacle_over_nothing():
    post = box(0.9, -0.05, 1.0, 0.05)  # a 10 cm post 0.9 m ahead, in an open field
    view = scan_view(post, (0.0, 0.0, 0.0), CONVENTIONS[0])
    distance, angle = nearest(view)
    assert distance == pytest.approx(0.9, abs=0.01)
    assert angle == pytest.approx(0.0, abs=math.radians(4.0))
