"""The grade's criteria on ground-truth tracks fed to the grade_case node's monitor.

A robot goes round room.world 0.28 m from its walls (counter-clockwise,
walls on its right, as a right-hand follower goes): a genuine lap, one
declared after 6 m (premature), and one never declared. The messages are
handed to the monitor's callbacks directly, as in test_course_monitor:
the built workspace's messages, no master.
"""
import json
import math
import os
import re
import threading
from types import SimpleNamespace

import numpy as np
import pytest
import rospy
from actionlib_msgs.msg import GoalID, GoalStatus
from geometry_msgs.msg import Point, Twist
from nav_msgs.msg import Odometry

from command_replay import stage_log
from wall_follower.evaluation.grading.commands import CommandLog
from wall_follower.evaluation.grading.criteria import find_wall_fits, grade_case, grades, shown
from wall_follower.evaluation.grading.service_calls import (CallWatch, PortWatch, peers_by_port,
                                                            reply_moment)
from wall_follower.evaluation.pictures.course_plot import plot_course, plt, points_label
from wall_follower.evaluation.scoring.course import CourseMap
from wall_follower.msg import (OdomRecordActionFeedback, OdomRecordActionGoal,
                               OdomRecordActionResult)
from wall_follower.nodes.evaluation import grade_case as grade_case_node
from wall_follower.nodes.evaluation.grade_case import FindWallWatch, SolutionSeen, case_record
from wall_follower.nodes.shared.case_graph import _json_safe
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


def run(declare_after=None, lap_rule=True, off=OFF, command_at=None):
    """A record of the track off metres from the walls, with the lap declared after
    declare_after metres (None: by the recorder's lap rule when lap_rule, else never);
    command_at: (time, field, value) of one command of its own."""
    monitor = CourseMonitor(CourseMap(ROOM))
    goal = OdomRecordActionGoal()
    goal.goal_id = GOAL_ID
    monitor._on_goal(goal)
    travelled, last, points, end = 0.0, None, [], None
    commands = CommandLog()
    poses = lap_track(off=off)
    for index, pose in enumerate(poses):
        stamp = index * STEP
        monitor._on_truth(truth(stamp, pose))
        command = Twist()
        command.linear.x = SPEED
        if command_at is not None and abs(stamp - command_at[0]) < STEP / 2:
            setattr(command.linear if command_at[1] == 'linear.x' else command.angular,
                    command_at[1][-1], command_at[2])
        monitor._on_command(command)
        commands.add(stamp, command.linear.x, command.angular.z)
        commands.applied(stamp + STEP, command.linear.x, command.angular.z)
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
                         0.0, (-1.0, -1.0, 1.0), SimpleNamespace(first=0.0, commands=commands),
                         end_time=len(poses) * STEP)
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


def test_following_says_where_the_grid_showed_the_laser_the_wall_in_the_band():
    case = run()
    case['figures']['time_in_band'] = 0.9
    case['out_of_band'] = [{'after': 12.0, 'seconds': 2.5, 'x': 0.5, 'y': -0.25,
                            'distance': 0.18, 'grid_distance': 0.2200013}]
    assert grade_case(case)['criteria']['following']['reason'].endswith(
        "at worst 0.18 m from the wall (0.22 m on Stage's grid, as a noise-free laser read it "
        "there)")


def test_a_stretch_out_of_band_keeps_what_the_grid_showed_a_laser_where_it_was_worst():
    worst = run(off=0.33)['out_of_band'][0]
    # room.world's walls lie on the grid's lines: Stage reads them a cell out, at most.
    assert worst['distance'] > 0.33
    assert worst['distance'] < worst['grid_distance'] <= worst['distance'] + 0.02


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


def json_round_trip(record):
    """The record as grade_case writes it and grade reads it back."""
    return json.loads(json.dumps(_json_safe(record)))


@pytest.mark.parametrize('field, value, text', [
    ('angular.z', -math.inf, '-inf'), ('linear.x', math.nan, 'nan')])
def test_a_non_finite_command_fails_safety_named_with_its_time(field, value, text):
    case = run(command_at=(12.3, field, value))
    graded = grade_case(json_round_trip(case))
    assert graded['criteria']['safety']['passed'] is False
    assert graded['criteria']['safety']['reason'] == 'commanded %s = %s at 12.3 s' % (
        field, text)
    # Kept, not dropped to null (nor to the largest finite command) in grades.json.
    key = 'max_angular' if field == 'angular.z' else 'max_linear'
    assert graded[key] == text.lstrip('-')
    assert json.loads(json.dumps(graded))[key] == text.lstrip('-')


def test_figures_are_printed_so_that_a_failing_one_never_reads_as_passing():
    assert shown(0.3036, 0.20, 0.30) == '0.304'
    assert shown(0.2996, 0.20, 0.30) == '0.30'
    assert shown(0.3503, 0.25, 0.35) == '0.3503'
    assert shown(10.4, None, 10.0, 0) == '10.4'
    case = run()
    case['figures']['time_in_band'] = 0.9
    case['out_of_band'] = [{'after': 1.0, 'seconds': 2.0, 'x': 0.0, 'y': 0.0,
                            'distance': 0.3036}]
    assert 'at worst 0.304 m from the wall' in grade_case(case)['criteria']['following'][
        'reason']


def test_find_wall_names_the_heading_too_when_it_is_off():
    case = run()
    case['figures'].update(found_distance=0.19, found_heading_error_deg=-21.7)
    reason = grade_case(case)['criteria']['find_wall']['reason']
    assert reason == ('the wall on the right was 0.19 m away (0.25-0.35 m expected) and the '
                      'heading was 22 deg off parallel to it (10 deg at most) when the lap '
                      'began (find_wall was never called, or never replied)')


def test_find_wall_names_the_heading_alone_against_the_wall():
    case = run()
    case['figures'].update(found_distance=0.28, found_heading_error_deg=60.2)
    assert grade_case(case)['criteria']['find_wall']['reason'].startswith(
        'the heading was 60 deg off parallel to the wall (10 deg at most) when the lap began')


def call(called, replied, moved=0.8, turned=90.0, distance=0.28, heading=2.0):
    return {'called': called, 'replied': replied, 'seconds': replied - called, 'moved': moved,
            'turned_deg': turned, 'distance': distance, 'heading_error_deg': heading,
            'calls': 1, 'all': [(called, replied)]}


def test_find_wall_is_judged_when_its_call_replied_even_after_the_goal():
    case = run()
    # The lap began where the robot stood (nothing beside it): find_wall came after.
    case['figures'].update(found_distance=0.28, found_heading_error_deg=2.0)
    case['moved_before_lap'] = False
    case['find_wall_call'] = call(5.0, 175.0)
    assert grade_case(case)['criteria']['find_wall'] == {'passed': True, 'reason': ''}


def test_a_find_wall_that_did_nothing_says_what_happened_in_numbers():
    case = run()
    case['find_wall_call'] = call(3.0, 173.0, moved=0.02, turned=3.0)
    reason = grade_case(case)['criteria']['find_wall']['reason']
    assert reason == ('find_wall did nothing: it replied at 173.0 s, and moved the robot '
                      '0.02 m in 170 s (turned 3 deg)')


def test_commands_sent_once_are_named_as_the_watchdog_stopping_them():
    case = run(lap_rule=False)
    case['commands'] = stage_log([(sent, sent * STEP, 0.10, 0.196) for sent in (10, 50, 90)],
                                 400).record()
    case['find_wall_call'] = call(0.5, 2.0, moved=0.02, turned=1.0)
    graded = grade_case(case)
    note = ("each command was sent once and stopped by the simulator's 0.2 s watchdog: "
            "publish cmd_vel continuously")
    assert note in graded['criteria']['lap']['reason']
    assert note in graded['criteria']['find_wall']['reason']


def test_commands_sent_continuously_get_no_watchdog_note(genuine):
    case = run(lap_rule=False)
    assert case['commands']['cut_by_watchdog'] == 0
    assert 'watchdog' not in grade_case(case)['reason']


def test_a_preempted_result_is_judged_for_what_it_holds_and_said_to_be_preempted():
    case = run()
    case['result_status'] = 'preempted'
    graded = grade_case(case)
    points = len(case['recorded_spans'])
    assert graded['criteria']['recording'] == {
        'passed': True, 'reason': "judged on the preempted goal's result (%d points)" % points}
    case['figures']['recorded_distance'] *= 1.2
    reason = grade_case(case)['criteria']['recording']['reason']
    assert reason.startswith("the preempted goal's result (%d points): the feedback said"
                             % points)


def test_the_plot_legend_says_what_the_points_are():
    assert points_label(362, 56.2) == '362 record_odom points over 56 s'
    assert points_label(1) == '1 record_odom point'


def test_a_robot_that_never_moved_has_its_start_in_the_plot(tmp_path, monkeypatch):
    labels = []
    real_legend = plt.Axes.legend

    def legend(axes, *args, **kwargs):
        labels.extend(line.get_label() for line in axes.get_lines())
        return real_legend(axes, *args, **kwargs)
    monkeypatch.setattr(plt.Axes, 'legend', legend)
    out = str(tmp_path / 'plot.png')
    plot_course(CourseMap(ROOM), [], None, out, start=(0.1, 0.2, 0.0))
    assert labels == ['start'] and os.path.getsize(out) > 0


def test_the_largest_command_keeps_a_nan():
    score = CourseMonitor(CourseMap(ROOM)).score
    for linear in (0.1, math.nan, 0.15):
        score.add_command(linear, 0.0)
    assert math.isnan(score.max_linear)


# /proc/net/tcp: a node's port 0x9C40 (40000) listening, a subscriber of its topic and a
# call in progress (the server's side, established, and the client's), a probe already
# closed by its client.
TCP_TABLE = '''  sl  local_address rem_address   st tx_queue rx_queue tr tm->when retrnsmt   uid
   0: 00000000:9C40 00000000:0000 0A 00000000:00000000 00:00000000 00000000     0
   1: 0100007F:9C40 0100007F:D430 01 00000000:00000000 00:00000000 00000000     0
   2: 0100007F:9C40 0100007F:D431 01 00000000:00000000 00:00000000 00000000     0
   3: 0100007F:D431 0100007F:9C40 01 00000000:00000000 00:00000000 00000000     0
   4: 0100007F:9C40 0100007F:D432 08 00000000:00000000 00:00000000 00000000     0
'''


def test_the_connections_to_a_services_port_are_told_by_their_peers():
    peers = peers_by_port(TCP_TABLE)
    assert peers[40000] == {'0100007F:D430', '0100007F:D431'}
    assert peers[0xD431] == {'0100007F:9C40'}
    assert 40001 not in peers


def test_a_call_that_ended_before_its_service_was_seen_is_kept():
    watch = PortWatch()
    for time, peers in ((0.0, {}), (1.0, {40000: {'call'}, 50000: {'x'}}), (5.0, {})):
        watch.look(peers, (time, (0.0, 0.0, 0.0)))
    assert [(c['start'], c['end']) for c in watch.of(40000).calls] == [(1.0, 5.0)]
    assert watch.of(None).judged() is None


def test_a_call_is_a_connection_that_came_and_went_and_the_first_that_lasted_is_judged():
    watch = CallWatch()
    topic = 'subscriber'
    for time, peers, pose in ((0.0, {topic}, 'a'), (1.0, {topic, 'probe'}, 'b'),
                              (1.0, {topic}, 'c'), (2.0, {topic, 'call'}, 'd'),
                              (9.0, {topic}, 'e'), (10.0, {topic, 'late'}, 'f')):
        watch.look(peers, (time, pose))
    calls = [(c['start'], c['end']) for c in watch.calls]
    assert calls == [(1.0, 1.0), (2.0, 9.0)]
    assert watch.judged()['end_pose'] == 'e'
    assert (watch.judged()['last_open'], watch.judged()['last_open_pose']) == (2.0, 'd')


def test_a_probe_whose_closing_poll_came_late_is_not_taken_for_the_call():
    # rospy.wait_for_service's probe was seen by one poll; the next came 0.1 s later (a
    # loaded machine), then the real call ran from 3.6 to 16.3.
    watch = CallWatch()
    for time, peers, pose in ((3.5, {'probe'}, 'a'), (3.6, {'call'}, 'b'), (9.0, {'call'}, 'c'),
                              (16.3, set(), 'd')):
        watch.look(peers, (time, pose))
    assert [(c['start'], c['end']) for c in watch.calls] == [(3.5, 3.6), (3.6, 16.3)]
    assert (watch.judged()['start'], watch.judged()['end_pose']) == (3.6, 'd')


def test_a_reply_seen_late_is_judged_where_the_robot_stood_before_it_drove_away():
    # Polled at 20.0 with the call open, the robot parallel to its wall; the next poll came
    # late, at 21.7, after the solution had turned 35 deg away from it.
    watch = CallWatch()
    for time, peers, pose in ((9.0, {'call'}, (0.0, 0.0, 1.0)), (20.0, {'call'}, (1.0, 0.0, 0.0)),
                              (21.7, set(), (1.2, 0.1, 0.6))):
        watch.look(peers, (time, pose))
    headings = {0.0: math.radians(2.0), 0.6: math.radians(35.0), 1.0: math.radians(60.0)}
    time, pose, aligned = reply_moment(watch.judged(),
                                       lambda pose: (0.28, headings[pose[2]]))
    assert (time, pose) == (20.0, (1.0, 0.0, 0.0))
    assert aligned == (0.28, math.radians(2.0))


def test_a_poll_stamps_what_it_saw_open_before_its_read_and_what_it_found_gone_after():
    watch = CallWatch()
    watch.look({'call'}, (2.0, 'a'), (2.1, 'b'))
    watch.look({'call'}, (3.0, 'c'), (4.2, 'd'))
    watch.look(set(), (4.3, 'e'), (5.0, 'f'))
    call, = watch.calls
    assert (call['start'], call['start_pose']) == (2.0, 'a')
    assert (call['last_open'], call['last_open_pose']) == (3.0, 'c')
    assert (call['end'], call['end_pose']) == (5.0, 'f')


class SlowTable(object):
    """connected_peers on a busy machine, scripted: each read gives the next of tables as
    it stood when the read began, and a second of simulated time passes before the
    poller runs again; the robot's pose is the time it was taken at."""

    def __init__(self, tables):
        self.time = 0.0
        self.tables = list(tables)
        self.read_all = threading.Event()

    def read(self):
        """The next table; once all have been read (and so all looked at), an empty one."""
        if not self.tables:
            self.read_all.set()
        table = self.tables.pop(0) if self.tables else {}
        self.time += 1.0
        return table

    def now(self):
        return self.time

    @property
    def pose(self):
        return ('at', self.time)


def test_a_call_seen_open_by_a_slow_read_is_not_taken_to_have_lasted_past_it(monkeypatch):
    # Open at the reads that began at 0 s and 1 s, gone by the one that began at 2 s: the
    # reply came between 1 and 2 s. A watch that stamped its reads when they came back
    # would put the call open until 2 s, and judge the robot where it had driven on to.
    port = 40000
    table = SlowTable([{port: {'call'}}, {port: {'call'}}, {}])
    monkeypatch.setattr(grade_case_node, 'connected_peers', table.read)
    monkeypatch.setattr(grade_case_node.rospy, 'get_time', table.now)
    watch = FindWallWatch(table)
    try:
        assert table.read_all.wait(10.0)
    finally:
        watch.stop()
    call, = watch.watch.of(port).calls
    assert (call['start'], call['last_open'], call['end']) == (0.0, 1.0, 3.0)
    assert (call['last_open_pose'], call['end_pose']) == (('at', 1.0), ('at', 3.0))


def test_a_reply_seen_late_is_judged_where_the_robot_stood_between_the_polls():
    # Seen open at 13.0 mid-turn, 30 deg off its wall; the closing poll came late, at
    # 14.8, when the solution's follower had already ridden 3 cm nearer the wall. The
    # true poses between the polls show it parallel at 0.26 m, where the reply came.
    call = {'last_open': 13.0, 'last_open_pose': 'turning', 'end': 14.8,
            'end_pose': 'following'}
    walls = {'turning': (0.27, math.radians(30.0)), 'aligning': (0.265, math.radians(12.0)),
             'in place': (0.263, math.radians(1.0)), 'dipping': (0.25, math.radians(-3.0)),
             'following': (0.23, math.radians(0.2))}
    between = [(14.0, 'in place'), (13.5, 'aligning'), (14.4, 'dipping')]
    moment = reply_moment(call, walls.get, between, find_wall_fits)
    assert moment == (14.0, 'in place', walls['in place'])
    # the polls alone judged it at the closing one, the most parallel, 0.23 m off
    assert reply_moment(call, walls.get, fits=find_wall_fits)[1] == 'following'
    # where no moment fits, the most nearly parallel is judged, as before
    assert reply_moment(call, walls.get, between[1:])[1] == 'following'


def test_the_monitor_keeps_every_true_pose_heard_before_the_lap_and_in_it():
    monitor = CourseMonitor(CourseMap(ROOM))
    poses = lap_track(laps=0.1)
    for index, pose in enumerate(poses[:5]):
        monitor._on_truth(truth(index * STEP, pose))
    goal = OdomRecordActionGoal()
    goal.goal_id = GoalID(stamp=rospy.Time.from_sec(0.25), id='lap')
    monitor._on_goal(goal)
    for index, pose in enumerate(poses[5:8], 5):
        monitor._on_truth(truth(index * STEP, pose))
    between = monitor.poses_between(0.15, 0.55)
    monitor.close()
    assert [round(stamp, 3) for stamp, _ in between] == [0.2, 0.3, 0.4, 0.5]
    assert np.allclose([pose for _, pose in between], poses[2:6])


def test_find_wall_fits_where_its_call_has_to_leave_the_robot():
    assert find_wall_fits((0.26, math.radians(9.0)))
    assert not find_wall_fits((0.24, 0.0))
    assert not find_wall_fits((0.36, 0.0))
    assert not find_wall_fits((0.3, math.radians(-11.0)))
    assert not find_wall_fits(None)


def test_a_reply_with_no_wall_at_either_bound_is_judged_at_the_first():
    call = {'last_open': 3.0, 'last_open_pose': 'a', 'end': 4.0, 'end_pose': 'b'}
    assert reply_moment(call, lambda pose: None) == (3.0, 'a', None)
    assert reply_moment(dict(call, last_open_pose=None), lambda pose: None) == (4.0, 'b', None)
