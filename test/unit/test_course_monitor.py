"""CourseMonitor fed its messages directly, in the orders a fast simulator delivers them.

Needs the workspace's generated messages (the built workspace, as in CI),
but no ROS master: the monitor's subscribers are only created, and its
callbacks are called here.
"""
import os

import pytest
import rospy
from actionlib_msgs.msg import GoalID
from geometry_msgs.msg import Point
from nav_msgs.msg import Odometry

from wall_follower.msg import OdomRecordActionGoal, OdomRecordActionResult
from wall_follower.nodes.course_monitor import CourseMonitor
from wall_follower.scoring import CourseMap

ROOM = os.path.join(os.path.dirname(__file__), '..', '..', 'worlds', 'room.world')
SPEED = 0.19    # m/s along x, one ground truth per 0.1 s


def _truth(stamp):
    msg = Odometry()
    msg.header.stamp = rospy.Time.from_sec(stamp)
    msg.pose.pose.position.x = SPEED * stamp
    msg.pose.pose.orientation.w = 1.0
    return msg


def _goal(stamp):
    msg = OdomRecordActionGoal()
    msg.goal_id = GoalID(stamp=rospy.Time.from_sec(stamp), id='goal')
    return msg


def _result(stamp):
    msg = OdomRecordActionResult()
    msg.header.stamp = rospy.Time.from_sec(stamp)
    msg.status.goal_id = GoalID(stamp=rospy.Time.from_sec(1.0), id='goal')
    msg.result.list_of_odoms = [Point(x=0.19), Point(x=0.38)]
    return msg


@pytest.mark.parametrize('result_first', (True, False), ids=('result first', 'truth first'))
def test_true_distance_at_the_result_counts_ground_truth_up_to_the_results_stamp(result_first):
    monitor = CourseMonitor(CourseMap(ROOM))
    try:
        monitor._on_goal(_goal(1.0))
        for tenth in range(10, 21):
            monitor._on_truth(_truth(tenth / 10.0))
        late = [_truth(tenth / 10.0) for tenth in range(21, 31)]   # stamped after the result
        if result_first:
            monitor._on_result(_result(2.0))
        for msg in late:
            monitor._on_truth(msg)
        if not result_first:
            monitor._on_result(_result(2.0))
        assert monitor.truth_at_result == pytest.approx(SPEED * 1.0)
    finally:
        monitor.close()
