"""Any stamp a message can carry is judged against ROS time without an error (nodes.stamps)."""
import pytest
import rospy

from wall_follower.nodes.stamps import stamp_problem

NOW = rospy.Time(1000)


@pytest.mark.parametrize('stamp,words', [
    (rospy.Time(1000, 200000000), None),
    (rospy.Time(1001), 'stamped in the future'),
    (rospy.Time(4102444800), 'stamped in the future'),          # 2100-01-01
    (rospy.Time(2 ** 32 - 1, 2 ** 32 - 1), 'stamped in the future'),
    (rospy.Time(995), None),
    (rospy.Time(0, 1), 'stamped over 10 s before'),
])
def test_stamps_far_from_now_are_named(stamp, words):
    problem = stamp_problem(stamp, NOW, ahead=0.5, behind=10.0)
    assert problem is None if words is None else words in problem


def test_without_a_bound_behind_any_past_stamp_will_do():
    assert stamp_problem(rospy.Time(0, 1), NOW, ahead=0.5) is None
