"""find_trials refuses a start pose that is not [x, y, yaw_deg] before it runs any trial."""
import pytest

from wall_follower.nodes.evaluation.find_trials import RestWatch, is_pose


@pytest.mark.parametrize('start, ok', [
    ([0.0, 1.0, 90.0], True), ([1, -2, 0], True),
    ([0.0, 1.0], False), ([0.0, 1.0, 'ahead'], False), ([0.0, 1.0, True], False),
    ('0 1 90', False), ({'x': 0.0}, False),
])
def test_a_start_pose_is_three_numbers(start, ok):
    assert is_pose(start) is ok


def test_the_pose_is_judged_once_the_robot_stood_still_not_mid_turn():
    # The reply came while this process still had the finder's last turn to hear: poses
    # turning in place, then the same pose for SETTLE of simulated time.
    watch = RestWatch(settle=0.5)
    turning = [(10.0 + 0.1 * k, (1.0, 2.0, 0.3 * k)) for k in range(5)]
    still = [(10.5 + 0.1 * k, (1.0, 2.0, 1.5)) for k in range(6)]
    judged = [watch.look(stamp, pose) for stamp, pose in turning + still]
    assert judged[:-1] == [None] * (len(judged) - 1)
    assert judged[-1] == (1.0, 2.0, 1.5)


def test_rest_is_counted_from_the_last_change_and_nothing_before_the_first_pose():
    watch = RestWatch(settle=0.5)
    assert watch.look(None, None) is None
    assert watch.look(1.0, (0.0, 0.0, 0.0)) is None
    assert watch.look(1.4, (0.0, 0.0, 0.0)) is None
    assert watch.look(1.45, (0.0, 0.01, 0.0)) is None
    assert watch.look(1.9, (0.0, 0.01, 0.0)) is None
    assert watch.look(1.95, (0.0, 0.01, 0.0)) == (0.0, 0.01, 0.0)
