"""simple_move_square closed-loop on odometry, driven through Stage's kinematics.

Odometry lags the true pose by one step, as Stage's does; the corners are
where the robot stands still and turns, measured on the true poses.
"""
import math

import pytest

from wall_follower.control.motion import STOP
from wall_follower.exercises.move_square import CORNER, SIDE, SquareDriver
from wall_follower.rotation import wrap_angle
from wall_follower.sim.kinematics import diff_drive_step

STEP = 0.1


def drive(driver, start, limit=2000):
    """True poses, one per step, until the driver is done; and the poses at each corner."""
    truth = [start, start]
    driver.start(start)
    corners = []
    for _ in range(limit):
        command = driver.update(truth[-2])          # odometry: one step behind
        if driver.done:
            break
        if driver.state == CORNER and command.linear == 0.0:
            corners.append(truth[-1])
        truth.append(diff_drive_step(truth[-1], command.linear, command.angular, STEP))
    return truth, corners


@pytest.mark.parametrize('start', [(0.0, 0.0, 0.0), (1.3, -0.4, math.radians(137.0)),
                                   (-2.0, 0.7, math.radians(-71.0))])
@pytest.mark.parametrize('side, laps', [(0.5, 1), (0.8, 2)])
def test_the_corners_lie_on_the_true_square_and_the_heading_comes_back(start, side, laps):
    driver = SquareDriver(side=side, laps=laps)
    truth, corners = drive(driver, start)
    assert driver.done
    assert driver.update(truth[-1]) == STOP
    for k in range(4 * laps):
        ideal = driver.corner(k + 1)
        at_corner = [p for p in corners if math.hypot(p[0] - ideal[0], p[1] - ideal[1]) < 0.1]
        assert at_corner, 'never turned at corner %d' % (k + 1)
        worst = max(math.hypot(p[0] - ideal[0], p[1] - ideal[1]) for p in at_corner)
        assert worst < 0.03
    assert abs(math.degrees(wrap_angle(truth[-1][2] - start[2]))) < 3.0


def test_sides_at_the_linear_limit_and_corners_at_the_angular_limit():
    driver = SquareDriver()
    driver.start((0.0, 0.0, 0.0))
    assert driver.update((0.0, 0.0, 0.0)).linear == pytest.approx(0.19)
    assert driver.state == SIDE
    assert driver.update((0.5, 0.0, 0.0)).angular == pytest.approx(0.49)
    assert driver.state == CORNER


def test_bad_parameters_are_refused_by_name():
    with pytest.raises(ValueError, match='side'):
        SquareDriver(side=0.0)
    with pytest.raises(ValueError, match='unknown parameter speed'):
        SquareDriver(speed=1.0)


def test_a_new_side_moves_the_corners_of_the_square_laid_out():
    driver = SquareDriver()
    driver.start((1.0, 2.0, 0.0))
    driver.reconfigure(side=0.8)
    assert driver.corner(1) == pytest.approx((1.8, 2.0))
    assert driver.update((1.0, 2.0, 0.0)).linear == pytest.approx(0.19)
