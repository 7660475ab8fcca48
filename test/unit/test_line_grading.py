"""Grading a line follower from ground truth (grading/line_record.py, line_criteria.py).

Runs are synthetic (line_runs.py): the base's true poses laid along a course's
centreline (at a speed, with an offset of the test's choosing), and the
commands sent.
"""
import re

import numpy as np
import pytest

from line_runs import DT, LOOP, OPEN, commands, cutting, drive, record
from wall_follower.evaluation.grading import line_criteria
from wall_follower.evaluation.grading.line_criteria import against, grade_case, grades
from wall_follower.evaluation.grading.line_record import first_motion, still_from
from wall_follower.evaluation.scoring.line_track import centreline_of


def test_a_lap_on_the_line_passes_every_criterion():
    graded = grade_case(record(LOOP, drive(LOOP)))
    assert graded['reason'] == '', graded
    assert graded['completed'] and graded['closed']
    assert graded['rms_error'] < 0.002
    assert graded['mean_speed'] == pytest.approx(0.17, abs=0.005)
    assert graded['criteria']['stop'] == {'passed': True, 'reason': '', 'applies': False}


def test_a_base_that_cuts_the_bends_fails_tracking_and_is_told_where():
    graded = grade_case(record(LOOP, drive(LOOP, offset=cutting(0.045))))
    verdict = graded['criteria']['tracking']
    assert not verdict['passed']
    reason = verdict['reason']
    assert 'cm RMS from the line (1.50 at most)' in reason
    assert 'cm from it at worst (5.00 at most)' not in reason    # 4.5 cm is within 5
    assert 'inside a 0.35 m bend to the left' in reason, reason
    assert 'it cuts its bends (off the line on them, inside them 100 % of the time; ' in reason
    assert 'cm RMS on the bends, 0.0 on the straights)' in reason, reason
    # The lap itself was done: only tracking fails.
    assert [name for name, v in graded['criteria'].items() if not v['passed']] == ['tracking']


def test_a_base_wide_of_its_bends_is_told_so():
    reason = grade_case(record(LOOP, drive(LOOP, offset=cutting(-0.06))))['criteria'][
        'tracking']['reason']
    assert 'cm from it at worst (5.00 at most)' in reason
    assert 'outside a 0.35 m bend to the left' in reason and 'runs wide of its bends' in reason


def test_a_base_that_weaves_is_not_said_to_cut_or_run_wide():
    def weave(alongs):
        return 0.03 * np.sin(alongs * 12.0)
    reason = grade_case(record(LOOP, drive(LOOP, offset=weave)))['criteria']['tracking'][
        'reason']
    assert reason.startswith('the base kept 2.1'), reason
    assert 'cuts' not in reason and 'wide' not in reason


def test_no_lap_says_how_far_it_went_and_why_the_run_ended():
    poses = drive(LOOP, until=3.0)
    graded = grade_case(record(LOOP, poses, end_reason='the base stood still for 5 simulated s'))
    completion = graded['criteria']['completion']
    assert not completion['passed'] and not graded['completed']
    assert re.match(r'no lap: the base went 2\.(69|70) m of the %.2f m loop'
                    % centreline_of(LOOP).length, completion['reason']), completion
    assert completion['reason'].endswith('(the run ended: the base stood still for 5 '
                                         'simulated s)')
    assert graded['criteria']['speed']['reason'] == 'no lap to time'


def test_leaving_the_line_is_placed_on_the_course():
    # Into the first bend (1.0 to 1.55 m along), 0.3 m to the left of the line.
    def off(alongs):
        return np.where(alongs > 1.2, 0.3, 0.0)
    reason = grade_case(record(LOOP, drive(LOOP, offset=off, until=2.5)))['criteria'][
        'completion']['reason']
    assert re.search(r'; it left the line inside a 0\.35 m bend to the left at \(\d\.\d\d, '
                     r'0\.\d\d\), 5\.\d s in \(the run ended', reason), reason


def test_an_open_line_driven_to_its_end_passes_with_its_stop():
    graded = grade_case(record(OPEN, drive(OPEN, until=centreline_of(OPEN).length - 0.1)))
    assert graded['reason'] == '', graded
    assert graded['end_distance'] == pytest.approx(0.1, abs=0.01)
    assert graded['criteria']['stop']['applies']


def test_a_stop_short_of_the_end_fails_with_its_distance():
    graded = grade_case(record(OPEN, drive(OPEN, until=1.5)))
    stop = graded['criteria']['stop']
    assert not stop['passed']
    assert re.match(r"it stopped 1\.\d\d m from the line's end \(0\.35 at most\), at \(",
                    stop['reason']), stop
    assert graded['criteria']['completion']['reason'].startswith(
        "the line's end was never reached: the base came 1.")


def test_no_stop_on_an_open_line_fails_stop():
    poses = drive(OPEN, until=centreline_of(OPEN).length - 0.1, still=2.0)
    graded = grade_case(record(OPEN, poses, end_reason='no stop within 80 simulated s'))
    assert graded['criteria']['stop']['reason'] == (
        'the base never stopped for good (the run ended: no stop within 80 simulated s)')


def test_a_slow_lap_fails_speed_with_the_courses_bound():
    reason = grade_case(record(LOOP, drive(LOOP, speed=0.12)))['criteria']['speed']['reason']
    assert reason.startswith('0.120 m/s along the line on average (0.150 at least; within the '
                             'limits the line allows 0.1'), reason


def test_a_non_finite_command_fails_safety_naming_it():
    log = commands()
    log.add(12.3, {'linear.x': 0.1, 'angular.z': float('-inf')})
    log.add(12.4, {'linear.x': float('nan'), 'angular.z': 0.0})
    graded = grade_case(record(LOOP, drive(LOOP), log))
    assert graded['criteria']['safety'] == {
        'passed': False, 'applies': True,
        'reason': 'commanded angular.z = -inf at 12.3 s (and 1 more non-finite values)'}
    assert graded['non_finite_commands'] == 2
    # What was finite still counts toward the largest command.
    assert graded['max_linear'] == pytest.approx(0.17)


def test_commands_over_the_limits_and_contact_fail_safety():
    log = commands({'linear.x': 0.25, 'angular.z': -0.6})
    graded = grade_case(record(LOOP, drive(LOOP), log,
                               contact={'time': 3.0, 'x': 1.0, 'y': 0.2}))
    assert graded['criteria']['safety']['reason'] == (
        'the robot touched a wall at (1.00, 0.20), 3.0 s in; commanded 0.25 m/s (limit 0.19); '
        'commanded 0.60 rad/s (limit 0.49)')


def test_a_base_that_never_moved_fails_completion_and_tracking():
    poses = np.array([(t * DT, 0.3, 0.0, 0.0) for t in range(400)])
    graded = grade_case(record(LOOP, poses))
    assert not graded['completed']
    assert graded['criteria']['tracking']['reason'] == 'nothing to judge: the base never moved'


@pytest.mark.parametrize('value, limit, scale, expected', [
    (0.01503, 0.015, 100.0, ('1.503', '1.500')),
    (0.0151, 0.015, 100.0, ('1.51', '1.50')),
    (0.1499999, 0.15, 1.0, ('0.1499', '0.1500')),
    (0.35000001, 0.35, 1.0, ('0.3501', '0.3500')),
    (0.35042, 0.35, 1.0, ('0.3504', '0.3500')),
])
def test_a_failing_figure_never_reads_as_its_limit(value, limit, scale, expected):
    assert against(value, limit, scale) == expected


def test_still_and_first_motion():
    poses = drive(OPEN, until=1.0, still=6.0)
    assert first_motion(poses) == 0
    stop = still_from(poses, 5.0)
    assert stop is not None and poses[stop, 1:3] == pytest.approx(poses[-1, 1:3])
    assert still_from(poses, 7.0) is None
    assert first_motion(np.array([(0.0, 1.0, 1.0, 0.0), (0.1, 1.0, 1.0, 0.0)])) is None


def test_grades_count_completed_courses_as_laps():
    cases = [record(LOOP, drive(LOOP)), record(OPEN, drive(OPEN, until=1.0)),
             {'task': 'line', 'grader_error': 'its master did not start'}]
    summary = grades(cases)['summary']
    assert summary == {'cases': 3, 'laps': 1, 'passed': 1, 'not_graded': 1}
    assert line_criteria.CRITERIA == ('completion', 'tracking', 'speed', 'stop', 'safety')
