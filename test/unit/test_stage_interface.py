"""stageros' multi-robot names and the ~pose parameter, as the simulator node reads them."""
import math

import pytest

from wall_follower.sim.stage_interface import (parse_pose, quit_report, rate_in_quit_report,
                                               robot_prefix)


def test_a_lone_robot_has_unprefixed_names():
    assert robot_prefix(0, 1) == ''


def test_several_robots_are_named_like_stageros():
    assert [robot_prefix(i, 3) for i in range(3)] == ['robot_0/', 'robot_1/', 'robot_2/']


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


def test_the_quit_report_carries_the_real_time_multiple_back_to_the_benchmark():
    line = quit_report(5000.0, 0.5)
    assert line.startswith('quit_time 5000.0 s of simulated time reached after 0.50 wall s')
    logged = '[INFO] [1795348212.066946]: %s\n[INFO] [1795348212.1]: shutting down\n' % line
    assert rate_in_quit_report(logged) == 10000.0


def test_no_quit_report_reads_as_none():
    assert rate_in_quit_report('[INFO] [1.0]: world arena.world: 1 robot(s)\n') is None
