"""The grade's criteria on ground-truth tracks fed to the grade_case node's monitor.

A robot goes round room.world 0.28 m from its walls (counter-clockwise,
walls on its right, as a right-hand follower goes): a genuine lap, one
declared after 6 m (premature), and one never declared. The messages are
handed to the monitor's callbacks directly, as in test_course_monitor:
the built workspace's messages, no master.
"""
import math
import os
import re
from types import SimpleNamespace

import pytest
import rospy
from actionlib_msgs.msg import GoalID, GoalStatus
from geometry_msgs.msg import Point, Twist
from nav_msgs.msg import Odometry

from wall_follower.evaluation.grading.criteria import grade_case, grades
from wall_follower.evaluation.scoring.course import CourseMap
from wall_follower.msg import (OdomRecordActionFeedback, OdomRecordActionGoal,
                               OdomRecordActionResult)
from wall_follower.nodes.evaluation.grade_case import SolutionSeen, case_record
from wall_follower.nodes.shared.course_monitor import CourseMonitor

ROOM = os.path.join(os.path.dirname(__file__), '..', '..', 'worlds', 'room.world')
# room.world: free space x in [-1.5, 1.5], y in [-1.2, 1.2].
OFF = 0.28
STEP = 0.1          # s of ground truth
SPEED = 0.19        # m/s
TURN = 0.49         # rad/s at the corners
PARAMS = {'world': ROOM, 'plot': ''}


def lap_track(laps=1.3, off=OFF):
    """Ground-truth poses (x, y, yaw), one a STEP, round the room `laps` times, off metres
    from its walls, from (-0.5, -1.2 + off) heading +x."""
    poses = []
    x, y = -0.5, -1.2 + off
    yaw = 0.0
    corners = [(1.5 - off, -1.2 + off), (1.5 - off, 1.2 - off), (-1.5 + off, 1.2 - off),
               (-1.5 + off, -1.2 + off)]
    route = corners * 3
    travelled, limit = 0.0, laps * 2 * ((3.0 - 2 * off) + (2.4 - 2 * off))
    for cx, cy in route:
        heading = math.atan2(cy - y, cx - x)
        while abs(math.remainder(heading - yaw, 2 * math.pi)) > 1e-9:
            turn = math.remainder(heading - yaw, 2 * math.pi)
            yaw += max(-TURN * STEP, min(TURN * STEP, turn))
            poses.append((x, y, yaw))
        while math.hypot(cx - x, cy - y) > 1e-9:
            step = min(SPEED * STEP, math.hypot(cx - x, cy - y))
            x += step * math.cos(yaw)
            y += step * math.sin(yaw)
            travelled += step
            poses.append((x, y, yaw))
            if travelled >= limit:
                return poses
    return poses


def truth(stamp, pose):
    msg = Odometry()
    msg.header.stamp = rospy.Time.from_sec(stamp)
    msg.pose.pose.position.x, msg.pose.pose.position.y = pose[:2]
    msg.pose.pose.orientation.z = math.sin(pose[2] / 2.0)
    msg.pose.pose.orientation.w = math.cos(pose[2] / 2.0)
    return msg


GOAL_ID = GoalID(stamp=rospy.Time.from_sec(0.0), id='lap')


def run(declare_after=None, lap_rule=True, off=OFF):
    """A record of the track off metres from the walls, with the lap declared after
    declare_after metres (None: by the recorder's lap rule when lap_rule, else never)."""
    monitor = CourseMonitor(CourseMap(ROOM))
    goal = OdomRecordActionGoal()
    goal.goal_id = GOAL_ID
    monitor._on_goal(goal)
    travelled, last, points, end = 0.0, None, [], None
    poses = lap_track(off=off)
    for index, pose in enumerate(poses):
        stamp = index * STEP
        monitor._on_truth(truth(stamp, pose))
        command = Twist()
        command.linear.x = SPEED
        monitor._on_command(command)
        if last is not None:
            travelled += math.hypot(pose[0] - last[0], pose[1] - last[1])
        last = pose
        if index % 10 == 0 and end is None:
            points.append(Point(x=pose[0], y=pose[1], z=pose[2]))
            feedback = OdomRecordActionFeedback()
            feedback.status.goal_id = GOAL_ID
            feedback.feedback.current_total = travelled
            monitor._on_feedback(feedback)
        closing = (declare_after is not None and travelled >= declare_after) or (
            declare_after is None and lap_rule and monitor.score.lap.closed)
        if closing and end is None:
            points.append(Point(x=pose[0], y=pose[1], z=pose[2]))
            result = OdomRecordActionResult()
            result.header.stamp = rospy.Time.from_sec(stamp)
            result.status.goal_id = GOAL_ID
            result.status.status = GoalStatus.SUCCEEDED
            result.result.list_of_odoms = points
            monitor._on_result(result)
            end = index
        if end is not None and declare_after is not None:
            break       # a premature recorder's robot stops where it declared
    seen = SolutionSeen()
    seen.find_wall_service, seen.action_server = '/find_wall', True
    record = case_record(monitor, PARAMS, seen, 'result' if end is not None else 'no lap',
                         0.0, (-1.0, -1.0, 1.0), SimpleNamespace(first=0.0))
    monitor.close()
    return record


@pytest.fixture(scope='module')
def genuine():
    return grade_case(run())


def test_a_genuine_lap_passes_every_criterion(genuine):
    assert genuine['lap_genuine'] and not genuine['premature']
    assert genuine['reason'] == ''
    assert all(v['passed'] for v in genuine['criteria'].values())
    assert genuine['in_band'] == pytest.approx(1.0, abs=0.05)
    assert genuine['find_wall_ok'] and not genuine['contact']


def test_a_lap_declared_after_6_m_is_premature():
    graded = grade_case(run(declare_after=6.0))
    assert graded['premature'] and not graded['lap_genuine']
    assert 'declared after 6.0 m' in graded['criteria']['lap']['reason']
    assert graded['criteria']['find_wall']['passed']


def test_no_lap_is_never_and_has_no_band():
    graded = grade_case(run(lap_rule=False))
    assert not graded['lap_genuine'] and not graded['premature']
    assert graded['in_band'] is None
    assert 'no lap was declared (no lap)' in graded['reason']
    assert not graded['criteria']['following']['passed']
    assert not graded['criteria']['recording']['passed']


def test_commands_over_the_limits_fail_safety(genuine):
    case = run()
    case['figures']['max_angular'] = 0.6
    graded = grade_case(case)
    assert graded['criteria']['safety'] == {'passed': False,
                                            'reason': 'commanded 0.60 rad/s (limit 0.49)'}


def test_feedback_off_the_true_distance_fails_recording():
    case = run()
    case['figures']['recorded_distance'] *= 1.2
    reason = grade_case(case)['criteria']['recording']['reason']
    assert reason.startswith('the feedback said')


def test_a_robot_that_never_moved_fails_find_wall():
    case = run()
    case['moved_before_lap'] = False
    assert 'never called' in grade_case(case)['criteria']['find_wall']['reason']


def test_a_case_without_a_record_fails_with_its_error():
    graded = grades([{'world': 'w', 'error': 'it ran out of its 900 wall seconds'}])
    assert graded['summary'] == {'cases': 1, 'laps': 0, 'passed': 0, 'not_graded': 0}
    case = graded['cases'][0]
    assert case['reason'] == 'it ran out of its 900 wall seconds'
    assert case['in_band'] is None and not case['lap_genuine']


def test_a_case_the_grader_failed_is_not_graded():
    graded = grades([{'world': 'w', 'grader_error': 'its master did not start'}, run()])
    assert graded['summary'] == {'cases': 2, 'laps': 1, 'passed': 1, 'not_graded': 1}
    case = graded['cases'][0]
    assert case['grader_error'] == 'its master did not start'
    assert case['reason'] == 'not graded: the grader failed (its master did not start)'
    assert not any(verdict['passed'] for verdict in case['criteria'].values())
    assert graded['cases'][1]['grader_error'] is None


def test_grades_json_fields(genuine):
    for key in ('world', 'lap_genuine', 'premature', 'find_wall_ok', 'in_band', 'contact',
                'reason'):
        assert key in genuine


def test_following_points_at_the_longest_stretch_out_of_band():
    case = run()
    case['figures']['time_in_band'] = 0.9
    case['out_of_band'] = [{'after': 12.0, 'seconds': 2.5, 'x': 0.5, 'y': -0.25,
                            'distance': 0.16}]
    assert grade_case(case)['criteria']['following']['reason'] == (
        'only 90.0 % of the lap within 0.20-0.30 m of the wall (97 % needed), the longest '
        'stretch out 2.5 s from (0.50, -0.25), at worst 0.16 m from the wall')


def test_a_track_too_far_from_the_walls_fails_following_where_it_began():
    graded = grade_case(run(off=0.33))
    assert graded['in_band'] == pytest.approx(0.0, abs=0.05)
    reason = graded['criteria']['following']['reason']
    # One stretch, the whole lap: from where the lap began, (-0.5, -0.87), a step or two on.
    found = re.search(r'the longest stretch out ([0-9.]+) s from \(([-0-9.]+), ([-0-9.]+)\)',
                      reason)
    assert found, reason
    assert float(found.group(1)) > 50.0
    assert float(found.group(2)) == pytest.approx(-0.5, abs=0.05)
    assert float(found.group(3)) == pytest.approx(-0.87, abs=0.005)
