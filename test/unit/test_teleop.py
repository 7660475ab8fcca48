"""Teleop: ROBOTIS's keys and ramp, clamped to the package's limits."""
import pytest

from wall_follower.control.motion import Command
from wall_follower.exercises.teleop import QUIT, Teleop


def ticks(teleop, count):
    return [teleop.tick() for _ in range(count)]


def test_w_raises_the_target_by_a_step_and_the_command_ramps_half_a_step_per_tick():
    teleop = Teleop()
    assert teleop.press('w') and teleop.press('w')
    assert teleop.target.linear == pytest.approx(0.02)
    linear = [c.linear for c in ticks(teleop, 5)]
    assert linear == pytest.approx([0.005, 0.01, 0.015, 0.02, 0.02])


def test_targets_are_clamped_to_the_limits():
    teleop = Teleop()
    for _ in range(30):
        teleop.press('w')
        teleop.press('d')
    assert teleop.target == pytest.approx(Command(0.19, -0.49))
    assert ticks(teleop, 60)[-1] == pytest.approx(Command(0.19, -0.49))


def test_s_and_space_stop_at_once():
    for key in ('s', ' '):
        teleop = Teleop()
        teleop.press('x')
        teleop.press('a')
        ticks(teleop, 5)
        assert teleop.press(key)
        assert teleop.target == Command(0.0, 0.0)
        assert teleop.tick() == Command(0.0, 0.0)


def test_ctrl_c_quits_with_a_stopped_command_and_other_keys_do_nothing():
    teleop = Teleop()
    assert not teleop.press('q')
    assert teleop.target == Command(0.0, 0.0)
    teleop.press('w')
    teleop.tick()
    teleop.press(QUIT)
    assert teleop.quit and teleop.command == Command(0.0, 0.0)


def test_describe_names_the_target():
    teleop = Teleop()
    teleop.press('a')
    assert teleop.describe() == 'target: linear 0.00 m/s, angular 0.10 rad/s'


def test_new_steps_and_limits_apply_from_the_next_key_and_the_target_within_the_limits():
    teleop = Teleop()
    for _ in range(10):
        teleop.press('w')
    teleop.reconfigure(max_linear=0.05, linear_step=0.02)
    assert teleop.target.linear == pytest.approx(0.05)
    teleop.press('x')
    assert teleop.target.linear == pytest.approx(0.03)
