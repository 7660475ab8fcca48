"""stageros' naming, watchdog and start-pose rules, as the simulator node applies them."""
import math

import pytest

from wall_follower.stage_interface import CommandWatchdog, parse_pose, robot_prefix


def test_a_lone_robot_has_unprefixed_names():
    assert robot_prefix(0, 1) == ''


def test_several_robots_are_named_like_stageros():
    assert [robot_prefix(i, 3) for i in range(3)] == ['robot_0/', 'robot_1/', 'robot_2/']


def drive_with_one_message(watchdog, steps, dt=0.1):
    """Steps moved after one command received just after the first update,
    checking the watchdog before every later update as the node does."""
    now = dt
    watchdog.command_received(now)
    moved = 0
    for _ in range(steps):
        if watchdog.expired(now):
            break
        now += dt
        moved += 1
    return moved


def test_a_single_command_drives_two_steps_with_the_default_timeout():
    assert drive_with_one_message(CommandWatchdog(0.2), steps=20) == 2


def test_the_watchdog_counts_in_simulated_steps_without_float_drift():
    watchdog = CommandWatchdog(0.2)
    watchdog.command_received(0.5)
    assert not watchdog.expired(0.6)
    assert watchdog.expired(0.1 * 7)   # 0.7000000000000001 - 0.5 and 0.7 - 0.5 alike
    assert watchdog.expired(0.7)


def test_a_disabled_watchdog_never_stops_a_commanded_robot():
    watchdog = CommandWatchdog(0.0)
    watchdog.command_received(0.1)
    assert not watchdog.expired(1000.0)


def test_a_robot_never_commanded_counts_as_stopped():
    assert CommandWatchdog(0.2).expired(0.1)


def test_reset_forgets_the_last_command():
    watchdog = CommandWatchdog(0.2)
    watchdog.command_received(1.0)
    watchdog.reset()
    assert watchdog.expired(1.0)


def test_pose_is_read_in_degrees():
    x, y, yaw = parse_pose('1.5 -0.25 90')
    assert (x, y) == (1.5, -0.25)
    assert yaw == pytest.approx(math.pi / 2)


def test_pose_accepts_commas_and_empty_means_none():
    assert parse_pose('1,2,0') == (1.0, 2.0, 0.0)
    assert parse_pose('  ') is None


@pytest.mark.parametrize('text', ['1 2', '1 2 3 4', 'a b c', '1 nan 0'])
def test_bad_poses_are_rejected_with_the_text_quoted(text):
    with pytest.raises(ValueError) as error:
        parse_pose(text)
    assert repr(text) in str(error.value)
