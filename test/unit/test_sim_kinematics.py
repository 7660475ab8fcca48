"""Stage's Euler step for a differential drive, against closed forms."""
import cmath
import math

import pytest

from wall_follower.sim.kinematics import clamp_velocity, diff_drive_step, normalize_angle

DT = 0.1


def _drive(pose, v, w, steps):
    for _ in range(steps):
        pose = diff_drive_step(pose, v, w, DT)
    return pose


def _euler_closed_form(pose, v, w, steps):
    """Sum of the Euler steps: x + i*y += v*dt * sum_k exp(i*(yaw0 + k*w*dt))."""
    x, y, yaw = pose
    turn = w * DT
    if turn == 0.0:
        total = steps * cmath.exp(1j * yaw)
    else:
        ratio = cmath.exp(1j * turn)
        total = cmath.exp(1j * yaw) * (1 - ratio ** steps) / (1 - ratio)
    end = complex(x, y) + v * DT * total
    return end.real, end.imag, normalize_angle(yaw + steps * turn)


def test_straight_line():
    pose = _drive((-0.5, -0.3, math.radians(30)), 0.19, 0.0, 30)
    assert pose == pytest.approx((-0.5 + 0.57 * math.cos(math.radians(30)),
                                  -0.3 + 0.57 * math.sin(math.radians(30)),
                                  math.radians(30)), abs=1e-12)


def test_arc_matches_the_closed_form_of_the_euler_steps():
    start = (-0.5, -0.3, math.radians(30))
    assert _drive(start, 0.15, 0.4, 50) == pytest.approx(
        _euler_closed_form(start, 0.15, 0.4, 50), abs=1e-12)


def test_arc_is_within_first_order_of_the_true_circle():
    start = (0.0, 0.0, 0.0)
    v, w, steps = 0.15, 0.4, 50
    radius = v / w
    yaw = w * steps * DT
    circle = (radius * math.sin(yaw), radius * (1 - math.cos(yaw)))
    x, y, _ = _drive(start, v, w, steps)
    # the heading lags by half a step on average: off by about v*dt/2 sideways
    assert math.hypot(x - circle[0], y - circle[1]) < v * DT


def test_arc_reproduces_stage_drive_ii_end_pose():
    x, y, yaw = _drive((-0.5, -0.3, math.radians(30)), 0.15, 0.4, 50)
    assert (x, y) == pytest.approx((-0.4576205, 0.3297209), abs=1e-7)
    assert yaw == pytest.approx(math.radians(30) + 2.0)


def test_spin_in_place_turns_exactly_w_dt_per_step():
    start = (0.3, -0.2, 0.0)
    pose = start
    for step in range(1, 41):
        pose = diff_drive_step(pose, 0.0, 0.49, DT)
        assert pose[:2] == start[:2]
        assert pose[2] == pytest.approx(normalize_angle(0.049 * step), abs=1e-12)


def test_heading_wraps_into_minus_pi_to_pi():
    pose = _drive((0.0, 0.0, 3.0), 0.0, 1.0, 3)
    assert -math.pi <= pose[2] <= math.pi
    assert pose[2] == pytest.approx(3.3 - 2 * math.pi)


def test_velocity_bounds_clamp_both_ways():
    bounds = (-0.5, 0.5, 0, 0, 0, 0, -math.pi / 2, math.pi / 2)
    assert clamp_velocity(0.22, 2.84, bounds) == (0.22, math.pi / 2)
    assert clamp_velocity(-0.9, -3.0, bounds) == (-0.5, -math.pi / 2)
