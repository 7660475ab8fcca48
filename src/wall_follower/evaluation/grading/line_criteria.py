"""The grade of one line-following run, criterion by criterion, from its ground-truth record.

A record (line_record.run_record, written by nodes/evaluation/line_case.py)
holds what the base truly did on the course's line. Each criterion passes
or fails with its reason in words and numbers:

- completion: a closed line lapped (the base's progress along the line
  reached its length); an open line's end reached (the base came within
  END_DISTANCE of it);
- tracking: the base's distance to the centreline, RMS at most MAX_RMS and
  at worst MAX_ERROR (the line_follow rostest's bounds), over the lap or up
  to the stop; a failure says where the worst was (on which bend, inside or
  outside it) and, where it is so, that the base cuts its bends (off the
  line on a bend, it is inside it at least SIDE_SHARE of the time) or runs
  wide of them (outside as often);
- speed: the mean speed along the line over the lap (or the drive to the
  stop) at least MIN_SPEED, from the base's first motion;
- stop (open lines only): stopped for good within END_DISTANCE of the
  line's end, and no motion for the run's `still` seconds after;
- safety: no contact, no command above 0.19 m/s or 0.49 rad/s, and every
  command a finite number.

A figure in a reason is printed with as many decimals as it takes for a
failing value not to read as the limit it failed. A case whose own harness
failed is not graded (as in criteria.py).
"""
import math
from collections import OrderedDict

from wall_follower.control.motion import MAX_ANGULAR, MAX_LINEAR
from wall_follower.evaluation.grading.criteria import graded_cases

MAX_RMS = 0.015
MAX_ERROR = 0.05
MIN_SPEED = 0.15
END_DISTANCE = 0.35
# Commands are floats sent over the wire: a hair over the limit is rounding.
LIMIT_TOLERANCE = 1e-3
# A base that is off the line on its bends at least this share of the time on one side
# of them cuts them (inside) or runs wide of them (outside).
SIDE_SHARE = 0.75
CRITERIA = ('completion', 'tracking', 'speed', 'stop', 'safety')


def against(value, limit, scale=1.0, decimals=2, most=4):
    """(value, limit) as text, scaled: with as many decimals (from `decimals` up to `most`)
    as it takes for the two to read as different; a value still too near its limit to
    tell is rounded away from it, so that it never reads as the limit itself."""
    for places in range(decimals, most + 1):
        shown, bound = round(value * scale, places), round(limit * scale, places)
        if shown != bound and (shown > bound) == (value > limit):
            return '%.*f' % (places, shown), '%.*f' % (places, bound)
    step = 10.0 ** -most
    away = math.ceil if value > limit else math.floor
    shown = away(value * scale / step) * step
    if value != limit and round(shown, most) == round(limit * scale, most):
        shown += step if value > limit else -step
    return '%.*f' % (most, shown), '%.*f' % (most, limit * scale)


def _where(place):
    """Where on the course a place lies, in words."""
    piece = place['piece']
    if piece['kind'] == 'bend':
        side = 'inside' if place.get('inside') else 'outside'
        where = '%s a %.2f m bend to the %s' % (side, piece['radius'], piece['turn'])
    else:
        where = 'beside a straight'
    return '%s at (%.2f, %.2f), %.1f s in' % (where, place['x'], place['y'], place['time'])


def _end_reason(case):
    return case.get('end_reason') or 'no reason known'


def judge_completion(case):
    if case.get('closed'):
        if case.get('lap'):
            return True, ''
        reason = 'no lap: the base went %.2f m of the %.2f m loop' % (
            case.get('driven') or 0.0, case.get('length') or 0.0)
    else:
        nearest = case.get('nearest_end')
        if nearest is not None and nearest <= END_DISTANCE:
            return True, ''
        reason = "the line's end was never reached" + (
            '' if nearest is None else ': the base came %s m from it at best' % against(
                nearest, END_DISTANCE)[0])
    left = (case.get('tracking') or {}).get('left_line')
    if left:
        reason += '; it left the line %s' % _where(left)
    return False, '%s (the run ended: %s)' % (reason, _end_reason(case))


def judge_tracking(case):
    figures = case.get('tracking')
    if not case.get('moved') or not figures:
        return False, 'nothing to judge: the base never moved'
    failed = []
    if figures['rms'] > MAX_RMS:
        failed.append('%s cm RMS from the line (%s at most)'
                      % against(figures['rms'], MAX_RMS, 100.0))
    if figures['max'] > MAX_ERROR:
        failed.append('%s cm from it at worst (%s at most)'
                      % against(figures['max'], MAX_ERROR, 100.0))
    if not failed:
        return True, ''
    worst = figures['worst']
    reason = 'the base kept %s; the worst, %.1f cm, %s' % (
        ' and '.join(failed), 100.0 * figures['max'], _where(worst))
    inside = figures.get('inside_bends')
    if inside is not None and max(inside, 1.0 - inside) >= SIDE_SHARE:
        bends, straights = figures.get('rms_bends'), figures.get('rms_straights')
        reason += ': it %s its bends (off the line on them, %s them %.0f %% of the time; ' \
            '%.1f cm RMS on the bends%s)' % (
                'cuts' if inside >= SIDE_SHARE else 'runs wide of',
                'inside' if inside >= SIDE_SHARE else 'outside',
                100.0 * max(inside, 1.0 - inside), 100.0 * (bends or 0.0),
                '' if straights is None else ', %.1f on the straights' % (100.0 * straights))
    return False, reason


def judge_speed(case):
    completed, _ = judge_completion(case)
    mean = case.get('mean_speed')
    if not completed or mean is None:
        return False, 'no %s to time' % ('lap' if case.get('closed') else 'drive to the end')
    if mean < MIN_SPEED:
        shown, bound = against(mean, MIN_SPEED, decimals=3)
        return False, ('%s m/s along the line on average (%s at least; within the limits the '
                       'line allows %.3f)' % (shown, bound, case.get('speed_bound') or 0.0))
    return True, ''


def judge_stop(case):
    """(passed, reason, applies): a closed line has no end to stop at."""
    if case.get('closed'):
        return True, '', False
    stop = case.get('stop')
    if not stop:
        return False, 'the base never stopped for good (the run ended: %s)' % _end_reason(case), \
            True
    if stop['end_distance'] > END_DISTANCE:
        shown, bound = against(stop['end_distance'], END_DISTANCE)
        return False, "it stopped %s m from the line's end (%s at most), at (%.2f, %.2f)" % (
            shown, bound, stop['x'], stop['y']), True
    return True, '', True


def judge_safety(case):
    reasons = []
    contact = case.get('contact')
    if contact:
        reasons.append('the robot touched a wall at (%.2f, %.2f), %.1f s in' % (
            contact['x'], contact['y'], contact['time']))
    commands = case.get('commands') or {}
    for key, limit, unit in (('max_linear', MAX_LINEAR, 'm/s'),
                             ('max_angular', MAX_ANGULAR, 'rad/s')):
        value = commands.get(key) or 0.0
        if value > limit + LIMIT_TOLERANCE:
            reasons.append('commanded %s %s (limit %s)' % (against(value, limit)[0], unit,
                                                           against(value, limit)[1]))
    bad = commands.get('non_finite') or []
    if bad:
        first = bad[0]
        more = (commands.get('non_finite_count') or len(bad)) - 1
        reasons.append('commanded %s = %s at %.1f s%s' % (
            first['field'], first['value'], first['time'],
            ' (and %d more non-finite values)' % more if more else ''))
    return not reasons, '; '.join(reasons)


_JUDGES = OrderedDict([('completion', judge_completion), ('tracking', judge_tracking),
                       ('speed', judge_speed), ('safety', judge_safety)])


def _verdicts(case):
    criteria = OrderedDict()
    for name in CRITERIA:
        if name == 'stop':
            passed, reason, applies = judge_stop(case)
        else:
            (passed, reason), applies = _JUDGES[name](case), True
        criteria[name] = {'passed': bool(passed), 'reason': reason, 'applies': applies}
    return criteria


def grade_case(case):
    """A case's grade: grades.json's fields for it, with every criterion's verdict."""
    grader_error = case.get('grader_error')
    unjudged = 'not graded: the grader failed (%s)' % grader_error if grader_error else \
        case.get('error')
    if unjudged:
        criteria = OrderedDict((name, {'passed': False, 'reason': unjudged, 'applies': True})
                               for name in CRITERIA)
    else:
        criteria = _verdicts(case)
    reasons = []
    for verdict in criteria.values():
        if not verdict['passed'] and verdict['reason'] not in reasons:
            reasons.append(verdict['reason'])
    tracking = case.get('tracking') or {}
    commands = case.get('commands') or {}
    stop = case.get('stop') or {}
    return OrderedDict([
        ('world', case.get('world')),
        ('grader_error', grader_error),
        ('kind', case.get('kind')),
        ('camera', case.get('camera')),
        ('closed', case.get('closed')),
        ('completed', bool(not unjudged and criteria['completion']['passed'])),
        ('reason', '; '.join(reasons)),
        ('criteria', criteria),
        ('length', case.get('length')),
        ('driven', case.get('driven')),
        ('rms_error', tracking.get('rms')),
        ('max_error', tracking.get('max')),
        ('mean_speed', case.get('mean_speed')),
        ('speed_bound', case.get('speed_bound')),
        ('end_distance', stop.get('end_distance')),
        ('max_linear', commands.get('max_linear')),
        ('max_angular', commands.get('max_angular')),
        ('non_finite_commands', commands.get('non_finite_count')),
        ('plot', case.get('plot')),
    ])


def grades(cases):
    """grades.json: the summary and every case's grade, cases in the order given. `laps`
    counts the courses completed (a closed line lapped, an open line's end reached)."""
    return graded_cases([grade_case(case) for case in cases], 'completed')
