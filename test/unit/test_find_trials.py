"""find_trials refuses a start pose that is not [x, y, yaw_deg] before it runs any trial."""
import pytest

from wall_follower.nodes.evaluation.find_trials import is_pose


@pytest.mark.parametrize('start, ok', [
    ([0.0, 1.0, 90.0], True), ([1, -2, 0], True),
    ([0.0, 1.0], False), ([0.0, 1.0, 'ahead'], False), ([0.0, 1.0, True], False),
    ('0 1 90', False), ({'x': 0.0}, False),
])
def test_a_start_pose_is_three_numbers(start, ok):
    assert is_pose(start) is ok
