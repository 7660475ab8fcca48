"""CourseMonitor fed its messages directly, in the orders a fast simulator delivers them.

Needs the workspace's generated messages (the built workspace, as in CI),
but no ROS master: the monitor's subscribers are only created, and its
callbacks are called here.
"""
import os

import numpy as np
import pytest
import rospy
from actionlib_msgs.msg import GoalID
from geometry_msgs.msg import Point
from nav_msgs.msg import Odometry

from wall_follower.evaluation.scoring.course import CourseMap
from wall_follower.msg import OdomRecordActionGoal, OdomRecordActionResult
from wall_follower.nodes.shared.course_monitor import (BUILTIN, NEEDED_TOPICS, STAGEROS,
                                                       CourseMonitor, simulator_of)

ROOM = os.path.join(os.path.dirname(__file__), '..', '..', 'worlds', 'room.world')
SPEED = 0.19    # m/s along x, one ground truth per 0.1 s


def _truth(stamp, x=None):
    msg = Odometry()
    msg.header.stamp = rospy.Time.from_sec(stamp)
    msg.pose.pose.position.x = SPEED * stamp if x is None else x
    msg.pose.pose.orientation.w = 1.0
    return msg


def _goal(stamp):
    msg = OdomRecordActionGoal()
    msg.goal_id = GoalID(stamp=rospy.Time.from_sec(stamp), id='goal')
    return msg


def _result(stamp, first, last):
    """A result stamped `stamp` whose points are the true poses at `first` .. `last` s."""
    msg = OdomRecordActionResult()
    msg.header.stamp = rospy.Time.from_sec(stamp)
    msg.status.goal_id = GoalID(stamp=rospy.Time.from_sec(1.0), id='goal')
    msg.result.list_of_odoms = [Point(x=SPEED * t) for t in (first, (first + last) / 2.0, last)]
    return msg


@pytest.fixture
def monitor():
    watching = CourseMonitor(CourseMap(ROOM))
    yield watching
    watching.close()


def _hear(monitor, first, end, goal=1.0):
    """The goal at `goal` s (None: none), then ground truth along x, tenths first to end - 1."""
    if goal is not None:
        monitor._on_goal(_goal(goal))
    for tenth in range(first, end):
        monitor._on_truth(_truth(tenth / 10.0))


@pytest.mark.parametrize('result_first', (True, False), ids=('result first', 'truth first'))
def test_true_distance_runs_from_the_first_recorded_point_to_the_last(result_first, monitor):
    """The recorder takes its first point 0.2 s after the goal and answers 0.6 s after its
    last point (1.0 s later), and ground truth stamped after the answer may arrive first:
    the true distance is still that between the first and the last point."""
    _hear(monitor, 10, 27)
    late = [_truth(tenth / 10.0) for tenth in range(27, 35)]   # stamped after the result
    result = _result(2.6, 1.2, 2.2)
    if result_first:
        monitor._on_result(result)
    for msg in late:
        monitor._on_truth(msg)
    if not result_first:
        monitor._on_result(result)
    assert monitor.truth_at_result == pytest.approx(SPEED * 1.0)


def test_a_point_where_the_robot_passed_before_is_placed_at_its_later_pass(monitor):
    """Out along x and back: the last point lies where the first was taken, 1.6 s later."""
    def there(stamp):
        return SPEED * min(stamp, 4.0 - stamp)

    monitor._on_goal(_goal(1.0))
    for tenth in range(10, 31):
        monitor._on_truth(_truth(tenth / 10.0, there(tenth / 10.0)))
    result = _result(3.0, 1.2, 2.8)
    result.result.list_of_odoms = [Point(x=there(t)) for t in (1.2, 2.0, 2.8)]
    monitor._on_result(result)
    assert monitor.recorded_stamps == pytest.approx([1.2, 2.0, 2.8])
    assert monitor.truth_at_result == pytest.approx(SPEED * 1.6)


def test_a_point_taken_while_the_robot_stood_still_spans_the_stand_still(monitor):
    """Standing at the origin until 1.5 s, then along x: the first point, taken there, may
    have been taken at any time from the first truth (1.0 s) to the last still one (1.4 s)."""
    monitor._on_goal(_goal(1.0))
    for tenth in range(10, 31):
        monitor._on_truth(_truth(tenth / 10.0, SPEED * max(0.0, tenth / 10.0 - 1.4)))
    result = _result(3.0, 1.2, 2.8)
    result.result.list_of_odoms = [Point(x=SPEED * max(0.0, t - 1.4)) for t in (1.2, 2.2)]
    monitor._on_result(result)
    assert np.ravel(monitor.recorded_spans) == pytest.approx([1.0, 1.4, 2.2, 2.2])
    assert monitor.recorded_stamps == pytest.approx([1.0, 2.2])


def test_the_lap_is_scored_only_once_ground_truth_up_to_the_result_has_come(monitor):
    """The result (stamped 2.6 s) overtakes ground truth from 2.0 s on: until that truth
    has come the figures would miss the lap's end, with a shorter path in a longer lap."""
    _hear(monitor, 10, 20)
    monitor._on_result(_result(2.6, 1.2, 2.2))
    assert monitor.done.is_set() and not monitor.caught_up()
    early = monitor.summary()
    _hear(monitor, 20, 27, goal=None)
    monitor.wait()
    assert monitor.caught_up()
    figures = monitor.summary()
    assert figures['lap_time'] == pytest.approx(early['lap_time']) == pytest.approx(1.6)
    assert figures['path_length'] == pytest.approx(SPEED * 1.6)
    assert early['path_length'] < figures['path_length'] - 0.1


@pytest.mark.parametrize('first_heard', (1.0, 1.1))
def test_the_lap_time_runs_from_the_goal_whatever_truth_comes_first(first_heard, monitor):
    _hear(monitor, int(round(first_heard * 10)), 27)
    monitor._on_result(_result(2.6, 1.2, 2.2))
    assert monitor.summary()['lap_time'] == pytest.approx(1.6)


def test_a_first_point_taken_just_before_the_goal_is_placed_there(monitor):
    """Odometry is the pose before each step: the first point, from the odometry stamped
    1.1 s, is where the robot stood at 1.0 s, before the goal (1.05 s). It stood still
    until 1.1 s, so that point may have been taken at 1.0 s as well as at 1.1 s."""
    for tenth in range(5, 31):
        stamp = tenth / 10.0
        if stamp > 1.0:
            monitor._on_goal(_goal(1.05))
        monitor._on_truth(_truth(stamp, SPEED * max(0.0, stamp - 1.1)))
    result = _result(3.0, 1.2, 2.8)
    result.result.list_of_odoms = [Point(x=SPEED * max(0.0, t - 1.1)) for t in (1.0, 2.0)]
    monitor._on_result(result)
    assert np.ravel(monitor.recorded_spans) == pytest.approx([1.0, 1.1, 2.0, 2.0])


def test_truth_stamped_before_the_goal_but_heard_after_it_is_not_scored(monitor):
    """On a busy machine the goal (1.45 s) can overtake the truth of the last steps before
    it (1.3 and 1.4 s): those steps are not the lap's, and the first point, taken at the
    goal, is placed at the last of them."""
    _hear(monitor, 10, 13, goal=None)
    monitor._on_goal(_goal(1.45))
    _hear(monitor, 13, 27, goal=None)
    monitor._on_result(_result(2.6, 1.4, 2.2))
    figures = monitor.summary()
    assert figures['lap_start'][0] == pytest.approx(SPEED * 1.5)
    assert figures['path_length'] == pytest.approx(SPEED * 1.1)
    assert monitor.recorded_stamps == pytest.approx([1.4, 1.8, 2.2])
    assert [x for x, _ in monitor.full_trail()] == pytest.approx([SPEED * t / 10.0
                                                                  for t in range(10, 27)])


def test_a_result_stamped_between_two_steps_is_caught_up_by_the_next_one(monitor):
    _hear(monitor, 10, 27)
    monitor._on_result(_result(2.65, 1.2, 2.2))
    assert not monitor.caught_up()
    monitor._on_truth(_truth(2.7))
    assert monitor.caught_up()


def test_the_score_does_not_need_stalled_which_real_stageros_lacks():
    assert 'stalled' not in NEEDED_TOPICS
    assert 'base_pose_ground_truth' in NEEDED_TOPICS


@pytest.mark.parametrize('publications, simulator', [
    ([('/base_pose_ground_truth', ['/simulator']), ('/stalled', ['/simulator'])], BUILTIN),
    ([('/base_pose_ground_truth', ['/simulator']), ('/odom', ['/simulator'])], STAGEROS),
    ([('/base_pose_ground_truth', ['/stageros']), ('/stalled', ['/other'])], STAGEROS),
    ([('/odom', ['/robot'])], None),
])
def test_simulator_told_apart_by_what_it_publishes(publications, simulator):
    assert simulator_of(publications, '/base_pose_ground_truth', '/stalled') == simulator


def test_before_any_goal_the_trail_is_every_pose_heard(monitor):
    _hear(monitor, 0, 5, goal=None)
    assert not monitor.scoring
    assert [x for x, _ in monitor.full_trail()] == pytest.approx([SPEED * t / 10.0
                                                                  for t in range(5)])


def test_scoring_from_the_start_takes_each_pose_once_when_a_goal_comes():
    watching = CourseMonitor(CourseMap(ROOM), start_on_goal=False)
    try:
        _hear(watching, 0, 5, goal=None)
        watching._on_goal(_goal(0.25))
        _hear(watching, 5, 8, goal=None)
        assert [x for x, _ in watching.trail] == pytest.approx([SPEED * t / 10.0
                                                                for t in range(8)])
        assert watching.full_trail() == watching.trail
    finally:
        watching.close()
