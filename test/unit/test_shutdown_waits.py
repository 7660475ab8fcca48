"""The evaluation nodes tell a wait that rospy's shutdown ended from one that gave up.

A signal (Ctrl-C, roslaunch or grade ending a node) shuts rospy down; the
waits then end with rospy.ROSInterruptException, as rospy's own do, and
the node ends quietly: status 0, no error naming a wrong cause, no record
blaming the simulator or the solution. No master: rospy.is_shutdown() says
True as it does after a signal, rospy's own waits raise as they do then,
and each node's main runs on stand-ins up to its first wait.
"""
import os
from types import SimpleNamespace

import pytest
import rospy

from wall_follower.evaluation.scoring.course import CourseMap
from wall_follower.nodes.evaluation import course_report, find_trials, grade_case, line_case
from wall_follower.nodes.shared.case_graph import call_simulator, wait_for_simulator
from wall_follower.nodes.shared.course_monitor import CourseMonitor

ROOM = os.path.join(os.path.dirname(__file__), '..', '..', 'worlds', 'room.world')
LEVELS = ('info', 'warn', 'err')


def interrupted(*_args, **_kwargs):
    """What rospy's waits (wait_for_service, sleep, a service call) raise once shut down."""
    raise rospy.ROSInterruptException('rospy shutdown')


def parameters(values):
    """A NodeParameters stand-in whose snapshot is values."""
    return lambda _table: SimpleNamespace(snapshot=lambda: dict(values))


@pytest.fixture
def log(monkeypatch):
    """What the code logs, level -> lines (rospy's log needs no node)."""
    lines = dict((level, []) for level in LEVELS)
    for level in LEVELS:
        monkeypatch.setattr(rospy, 'log' + level,
                            lambda text, *args, level=level: lines[level].append(text % args))
    return lines


@pytest.fixture
def shut_down(monkeypatch, log):
    """rospy as a signal leaves it: shut down, its waits interrupted. Returns the log."""
    monkeypatch.setattr(rospy, 'is_shutdown', lambda: True)
    monkeypatch.setattr(rospy, 'wait_for_service', interrupted)
    return log


@pytest.fixture
def monitors():
    """CourseMonitor, every one made (by the test or a node's main) closed after the test."""
    made = []

    def monitor(*args, **kwargs):
        made.append(CourseMonitor(*args, **kwargs))
        return made[-1]
    yield monitor
    for each in made:
        each.close()


def assert_ended_quietly(status, log, record=None):
    assert status == 0
    assert log['err'] == [] and log['warn'] == []
    assert len(log['info']) <= 1
    assert record is None or not os.path.exists(record)


# The waits: a shutdown raises; a time-limit is still an answer.

def test_the_wait_for_the_simulator_raises_on_shutdown(shut_down):
    with pytest.raises(rospy.ROSInterruptException):
        wait_for_simulator(lambda: False)


def test_the_wait_for_the_simulator_still_gives_up_after_its_limit(log):
    assert wait_for_simulator(lambda: False, limit=0.0) is False


def test_a_simulator_service_wait_ended_by_shutdown_is_no_missing_service(shut_down):
    with pytest.raises(rospy.ROSInterruptException):
        call_simulator('unpause_physics', wait=10.0)
    assert shut_down['info'] == []


def test_the_monitor_raises_on_shutdown_while_it_waits_to_connect(shut_down, monitors):
    with pytest.raises(rospy.ROSInterruptException):
        monitors(CourseMap(ROOM)).start_world()


def test_the_monitor_still_gives_up_connecting_after_its_limit(log, monitors):
    assert monitors(CourseMap(ROOM)).start_world(limit=0.0) is False


def test_the_monitor_raises_on_shutdown_while_it_waits_for_unpause_physics(shut_down, monitors):
    monitor = monitors(CourseMap(ROOM))
    monitor.connected = lambda topics=None: True
    with pytest.raises(rospy.ROSInterruptException):
        monitor.start_world()
    assert shut_down['info'] == []


def test_the_monitor_raises_on_shutdown_while_it_waits_for_the_run(shut_down, monitors):
    with pytest.raises(rospy.ROSInterruptException):
        monitors(CourseMap(ROOM)).wait()


@pytest.mark.parametrize('watch', [
    lambda: grade_case.watch(None, None, None, None, {'start_limit': 0.0, 'gone_limit': 0.0},
                             0.0, None),
    lambda: line_case.watch(None, None, None, {'start_limit': 0.0, 'gone_limit': 0.0}, 0.0),
    lambda: grade_case.keep_watching(SimpleNamespace(wait=lambda catch_up: None), 5.0),
], ids=['grade_case.watch', 'line_case.watch', 'grade_case.keep_watching'])
def test_a_case_run_watched_until_shutdown_has_not_ended(shut_down, monkeypatch, watch):
    """Not an end reason: the record would say the run ended 'shut down', and grading
    would fail the solution for a run the grader stopped."""
    monkeypatch.setattr(rospy, 'get_time', lambda: 0.0)
    with pytest.raises(rospy.ROSInterruptException):
        watch()


def test_find_trials_judges_no_pose_on_shutdown(shut_down):
    """Not the newest pose, with a warning that the robot never came to rest."""
    monitor = SimpleNamespace(latest=lambda: (1.0, (0.0, 0.0, 0.0)))
    with pytest.raises(rospy.ROSInterruptException):
        find_trials.at_rest(monitor, limit=5.0)
    assert shut_down['warn'] == []


# The nodes: a signal while they wait ends them quietly.

def test_grade_case_signalled_while_it_waits_for_the_simulator(shut_down, monkeypatch, tmp_path):
    """Before: 'no ground truth from the simulator', a grader_error record, status 1."""
    record = str(tmp_path / 'case.json')
    for name, stand_in in (
            ('init_node', lambda _name: None),
            ('NodeParameters', parameters({'world': ROOM, 'json': record, 'plot': '',
                                           'action_ns': 'record_odom'})),
            ('CourseMap', lambda _world: None),
            ('CourseMonitor', lambda *_args, **_kwargs: SimpleNamespace(
                connected=lambda topics: False)),
            ('RunClock', lambda: None),
            ('Graph', lambda _action_ns: None)):
        monkeypatch.setattr(grade_case, name, stand_in)
    assert_ended_quietly(grade_case.main(), shut_down, record)


def test_line_case_signalled_while_it_waits_for_the_simulator(shut_down, monkeypatch, tmp_path):
    record = str(tmp_path / 'case.json')
    for name, stand_in in (
            ('init_node', lambda _name: None),
            ('NodeParameters', parameters({'world': 'line.world', 'json': record,
                                           'plot': ''})),
            ('course_path', lambda world: world),
            ('read_course', lambda _path: {}),
            ('centreline_of', lambda _course, _path: None),
            ('Run', lambda: SimpleNamespace(connected=lambda: False)),
            ('Graph', lambda _action_ns: None)):
        monkeypatch.setattr(line_case, name, stand_in)
    assert_ended_quietly(line_case.main(), shut_down, record)


def test_course_report_signalled_while_it_waits_for_the_simulator(shut_down, monkeypatch,
                                                                  monitors, tmp_path):
    """Before: 'could not connect to the simulator ... and record_odom', status 1."""
    monkeypatch.setattr(course_report, 'init_node', lambda _name: None)
    monkeypatch.setattr(course_report, 'NodeParameters', parameters(
        {'world': os.path.abspath(ROOM), 'plot': str(tmp_path / 'course.png'), 'json': '',
         'follower': 'wall_following'}))
    monkeypatch.setattr(course_report, 'CourseMonitor', monitors)
    assert_ended_quietly(course_report.main(), shut_down, str(tmp_path / 'course.png'))


def test_find_trials_signalled_while_it_waits_for_find_wall(shut_down, monkeypatch):
    """Before: the error 'find_trials: rospy shutdown', status 1."""
    monkeypatch.setattr(find_trials, 'init_node', lambda _name: None)
    monkeypatch.setattr(find_trials, 'NodeParameters', parameters(
        {'world': os.path.abspath(ROOM), 'json': '', 'poses': {
            os.path.abspath(ROOM): [[0.0, 0.0, 0.0]]}}))
    assert_ended_quietly(find_trials.main(), shut_down)
