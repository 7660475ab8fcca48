"""The grade of one course run, criterion by criterion, from ground-truth figures.

A case record (what nodes/evaluation/grade_case.py writes for one world) holds only
what the simulator's ground truth and the world map say, and what the
solution's record_odom action sent; nothing the solution says about its
own position counts. Each criterion passes or fails with its reason in
words:

- find_wall: when its call replied (seen from the service's own
  connection; where the lap began, the record_odom goal, if no call of it
  ended), the wall on the right is FIND_WALL_DISTANCE away and the
  heading within FIND_WALL_HEADING of parallel to it;
- lap: the action's result came (never: it did not), and not before the
  robot had truly come back to where the lap began (premature: declared
  at under LAP_SHARE of the true lap);
- following: at least MIN_IN_BAND of the lap in the band [0.20, 0.30] m;
- safety: no contact, no command above the robot's limits, and no
  non-finite command (inf or NaN: named, with when it was sent);
- recording: a point every second and feedback within FEEDBACK_ERROR of
  the true distance travelled (a preempted goal's result is judged for
  what it holds, and said to be preempted).

Every failing reason says what happened in numbers, printed with as many
decimals as it takes for a failing value never to read as a passing one
(0.3036 m out of 0.20-0.30 m reads 0.304, not 0.30).

A case whose own harness failed ('grader_error' in its record: grade's
master, simulator or grade_case node did not start, or its record could not
be written) is not graded: every criterion fails with the grader's reason,
and the summary counts it as not graded, so that it is never taken for the
solution's failure.
"""
import math
from collections import OrderedDict

from wall_follower.control.motion import MAX_ANGULAR, MAX_LINEAR
from wall_follower.evaluation.grading.commands import watchdog_note
from wall_follower.evaluation.scoring.course import taken_every

FIND_WALL_DISTANCE = (0.25, 0.35)
FIND_WALL_HEADING = math.radians(10.0)
LAP_SHARE = 0.9
MIN_IN_BAND = 0.97
FEEDBACK_ERROR = 0.05
SAMPLE_PERIOD = 1.0
# A point is taken at an odometry message (10 Hz in Stage) by a timer of its own:
# either can be a step late.
SAMPLE_TOLERANCE = 0.25
# Commands are floats sent over the wire: a hair over the limit is rounding.
LIMIT_TOLERANCE = 1e-3
CRITERIA = ('find_wall', 'lap', 'following', 'safety', 'recording')
# How far a robot must have gone during find_wall to have done anything [m, deg].
MOVED = (0.05, 10.0)
# The most decimals a figure is printed with.
MAX_DIGITS = 6


def _number(value):
    """value as a float, None for a missing or NaN figure ('inf' and '-inf' as such)."""
    if value is None:
        return None
    value = float(value)
    return None if value != value else value


def shown(value, low=None, high=None, digits=2):
    """value printed with digits decimals, or more where fewer would put it on the other
    side of low or high (a limit it passes or fails) than it is."""
    def inside(number):
        return (low is None or number >= low) and (high is None or number <= high)
    for places in range(digits, MAX_DIGITS + 1):
        text = '%.*f' % (places, value)
        if inside(float(text)) == inside(value):
            break
    return text


def _with_note(reason, case):
    note = watchdog_note(case.get('commands'))
    return '%s (%s)' % (reason, note) if note else reason


def _wall_beside(distance, heading):
    """What is wrong of the wall beside the robot, in numbers; [] when nothing is."""
    low, high = FIND_WALL_DISTANCE
    most = math.degrees(FIND_WALL_HEADING)
    wrong = []
    if not low <= distance <= high:
        wrong.append('the wall on the right was %s m away (%.2f-%.2f m expected)' % (
            shown(distance, low, high), low, high))
    if heading is None or abs(heading) > most:
        wrong.append('the heading was %s deg off parallel to %s (%.0f deg at most)' % (
            shown(abs(heading), None, most, 0) if heading is not None else 'an unknown number of',
            'it' if wrong else 'the wall', most))
    return wrong


def find_wall_fits(aligned):
    """Whether the wall beside the robot, aligned ((distance, heading error [rad]) or
    None), is where find_wall has to leave it."""
    return aligned is not None and not _wall_beside(aligned[0], math.degrees(aligned[1]))


def judge_find_wall(case):
    """(passed, reason) of find_wall: from the pose when its call replied, else (never
    called) where the lap began, else where the robot ended."""
    solution = case.get('solution', {})
    if not solution.get('find_wall_service'):
        return False, 'no find_wall service was ever advertised'
    figures = case.get('figures', {})
    distance = _number(figures.get('found_distance'))
    heading = _number(figures.get('found_heading_error_deg'))
    call = case.get('find_wall_call')
    if call is not None:
        when = 'when find_wall replied (at %.1f s, after %.1f s)' % (call['replied'],
                                                                     call['seconds'])
        if call['moved'] <= MOVED[0] and call['turned_deg'] <= MOVED[1]:
            return False, _with_note(
                'find_wall did nothing: it replied at %.1f s, and moved the robot %s m in %.0f s '
                '(turned %.0f deg)' % (call['replied'], shown(call['moved'], None, MOVED[0]),
                                       call['seconds'], call['turned_deg']), case)
    else:
        never = 'find_wall was never called, or never replied'
        when = ('when the lap began (%s)' % never if case.get('goal_time') is not None else
                'at the end (%s, and no record_odom goal was sent)' % never)
        if not case.get('moved_before_lap', True):
            return False, _with_note('%s, and the robot had not moved %s'
                                     % (never, when.split(' (')[0]), case)
    if distance is None:
        return False, 'no wall within 30 deg of the right %s' % when
    wrong = _wall_beside(distance, heading)
    if wrong:
        return False, '%s %s' % (' and '.join(wrong), when)
    if case.get('goal_time') is None:
        return False, 'the wall was found, but no record_odom goal was ever sent'
    return True, ''


def lap_outcome(case):
    """'genuine', 'premature' or 'never', and the reason for the last two (or a late lap)."""
    if case.get('result_status') != 'succeeded':
        if case.get('result_status'):
            return 'never', 'record_odom ended its goal without a lap (%s)' % case['result_status']
        return 'never', 'no lap was declared (%s)' % (case.get('end_reason') or 'no reason known')
    declared = _number(case.get('declared_distance'))
    true_lap = _number(case.get('true_lap'))
    if true_lap is None:
        return 'premature', ('the lap was declared after %.1f m, but the robot never came back '
                             'to where it began' % (declared or 0.0))
    if declared is None or declared < LAP_SHARE * true_lap:
        return 'premature', 'the lap was declared after %.1f m of a %.1f m lap' % (
            declared or 0.0, true_lap)
    if declared > (2.0 - LAP_SHARE) * true_lap:
        return 'genuine', 'the lap was declared late: after %.1f m of a %.1f m lap' % (
            declared, true_lap)
    return 'genuine', ''


def judge_lap(case):
    outcome, reason = lap_outcome(case)
    if outcome == 'never':
        reason = _with_note(reason, case)
    return outcome == 'genuine' and not reason, reason


def judge_following(case):
    in_band = _number(case.get('figures', {}).get('time_in_band'))
    if case.get('result_status') != 'succeeded' or in_band is None:
        return False, 'no lap to judge the following on'
    if in_band < MIN_IN_BAND:
        reason = 'only %s %% of the lap within 0.20-0.30 m of the wall (%.0f %% needed)' % (
            shown(100.0 * in_band, 100.0 * MIN_IN_BAND, None, 1), 100.0 * MIN_IN_BAND)
        stretches = case.get('out_of_band') or []
        if stretches:
            worst = stretches[0]
            distance = _number(worst['distance'])
            where = ('no wall on the right' if distance is None or math.isinf(distance)
                     else 'at worst %s m from the wall%s' % (shown(distance, 0.20, 0.30),
                                                             _as_the_grid_shows(worst)))
            reason += ', the longest stretch out %.1f s from (%.2f, %.2f), %s' % (
                worst['seconds'], worst['x'], worst['y'], where)
        return False, reason
    return True, ''


def _as_the_grid_shows(stretch):
    """What a noise-free laser read on Stage's grid where a stretch out of band was worst, when
    the record has it (CourseMap.grid_right_wall_distance): where the laser put the wall in
    the band, the follower was misled, not mistaken."""
    grid = _number(stretch.get('grid_distance'))
    if grid is None or math.isinf(grid):
        return ''
    return ' (%s m on Stage\'s grid, as a noise-free laser read it there)' % shown(
        grid, 0.20, 0.30)


def judge_safety(case):
    """No contact, and every command finite and within the limits (judged on what was
    commanded, not on what the simulator made of it)."""
    figures = case.get('figures', {})
    reasons = []
    if figures.get('contact'):
        reasons.append('the robot touched an obstacle')
    bad = (case.get('commands') or {}).get('non_finite')
    if bad:
        reasons.append('commanded %s = %s at %.1f s' % (
            bad['field'], bad['value'], bad['time'] - (case.get('start_time') or 0.0)))
    for key, limit, unit in (('max_linear', MAX_LINEAR, 'm/s'),
                             ('max_angular', MAX_ANGULAR, 'rad/s')):
        value = _number(figures.get(key))
        if value is not None and math.isfinite(value) and value > limit + LIMIT_TOLERANCE:
            reasons.append('commanded %s %s (limit %.2f)' % (
                shown(value, None, limit + LIMIT_TOLERANCE), unit, limit))
        elif not bad and (value is None and figures.get(key) is not None
                          or value is not None and not math.isfinite(value)):
            reasons.append('commanded %s %s' % (figures.get(key), unit))
    return not reasons, '; '.join(reasons)


def judge_recording(case):
    """The result's points and the feedback; a result that ended its goal without a lap
    (preempted, aborted) is judged for what it holds, and said to be so."""
    status = case.get('result_status')
    spans = case.get('recorded_spans')
    if status != 'succeeded':
        if spans is None:
            return False, 'no record_odom result to judge'
        passed, reason = _judge_points(case, spans)
        held = 'the %s goal\'s result (%d points)' % (status, len(spans))
        return passed, ('judged on %s' % held if passed else '%s: %s' % (held, reason))
    return _judge_points(case, spans or [])


def _judge_points(case, spans):
    if len(spans) < 2:
        return False, 'the result holds %d point(s)' % len(spans)
    # The last point closes the lap when it ends, off the once-a-second grid.
    if not taken_every(spans[:-1], SAMPLE_PERIOD, SAMPLE_TOLERANCE):
        gaps = [later[0] - earlier[0] for earlier, later in zip(spans[:-1], spans[1:-1])]
        return False, 'points not taken once a second (gaps %.2f-%.2f s)' % (min(gaps), max(gaps))
    feedback = _number(case.get('figures', {}).get('recorded_distance'))
    truth = _number(case.get('figures', {}).get('true_distance'))
    if feedback is None:
        return False, 'no feedback was sent'
    if not case.get('feedback_rising', True):
        return False, 'the feedback went down'
    if truth and abs(feedback - truth) > FEEDBACK_ERROR * truth:
        return False, 'the feedback said %.2f m, the robot truly went %.2f m (%s %% off, %.0f %% ' \
            'at most)' % (feedback, truth, shown(100.0 * abs(feedback - truth) / truth, None,
                                                 100.0 * FEEDBACK_ERROR, 1),
                          100.0 * FEEDBACK_ERROR)
    return True, ''


_JUDGES = OrderedDict([('find_wall', judge_find_wall), ('lap', judge_lap),
                       ('following', judge_following), ('safety', judge_safety),
                       ('recording', judge_recording)])


def grade_case(case):
    """A case's grade: grades.json's fields for it, with every criterion's verdict."""
    grader_error = case.get('grader_error')
    unjudged = 'not graded: the grader failed (%s)' % grader_error if grader_error else \
        case.get('error')
    if unjudged:
        criteria = OrderedDict((name, {'passed': False, 'reason': unjudged})
                               for name in CRITERIA)
        outcome = 'never'
    else:
        criteria = OrderedDict()
        for name, judge in _JUDGES.items():
            passed, reason = judge(case)
            criteria[name] = {'passed': bool(passed), 'reason': reason}
        outcome, _ = lap_outcome(case)
    figures = case.get('figures', {})
    in_band = _number(figures.get('time_in_band')) if outcome != 'never' else None
    reasons = []
    for name, verdict in criteria.items():
        if not verdict['passed'] and verdict['reason'] not in reasons:
            reasons.append(verdict['reason'])
    return OrderedDict([
        ('world', case.get('world')),
        ('grader_error', grader_error),
        ('lap_genuine', outcome == 'genuine'),
        ('premature', outcome == 'premature'),
        ('find_wall_ok', criteria['find_wall']['passed']),
        ('in_band', in_band),
        ('contact', bool(figures.get('contact'))),
        ('reason', '; '.join(reasons)),
        ('criteria', criteria),
        ('rms_error', _number(figures.get('rms_error')) if outcome != 'never' else None),
        ('lap_time_ratio', _number(figures.get('lap_time_ratio')) if outcome != 'never' else None),
        ('max_linear', _figure(figures.get('max_linear'))),
        ('max_angular', _figure(figures.get('max_angular'))),
        ('find_wall_distance', _number(figures.get('found_distance'))),
        ('find_wall_heading_deg', _number(figures.get('found_heading_error_deg'))),
        ('find_wall_time', _number(case.get('find_wall_time'))),
        ('action_result_type', case.get('solution', {}).get('result_point_type')),
        ('plot', case.get('plot')),
    ])


def _figure(value):
    """A figure as grades.json keeps it: a finite number, or 'inf', '-inf', 'nan' (JSON has
    no non-finite number), or None when missing."""
    if value is None:
        return None
    value = float(value)
    if math.isfinite(value):
        return value
    return 'nan' if value != value else ('inf' if value > 0 else '-inf')


def grades(cases):
    """grades.json: the summary and every case's grade, cases in the order given."""
    return graded_cases([grade_case(case) for case in cases], 'lap_genuine')


def graded_cases(graded, lap_key):
    """grades.json of graded cases (any task's): the summary, then the cases. `laps`
    counts the cases whose grade holds a true lap_key."""
    return OrderedDict([
        ('summary', OrderedDict([('cases', len(graded)),
                                 ('laps', sum(1 for g in graded if g[lap_key])),
                                 ('passed', sum(1 for g in graded if not g['reason'])),
                                 ('not_graded', sum(1 for g in graded if g['grader_error']))])),
        ('cases', graded),
    ])
