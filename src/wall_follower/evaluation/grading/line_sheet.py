"""How the line task's grades read (line_criteria.py): its table's columns and figures."""
import os

from wall_follower.evaluation.grading.line_criteria import CRITERIA, grades
from wall_follower.evaluation.tables import fmt


def _completion(grade):
    if grade['closed'] is None:
        return '-'
    if grade['closed']:
        return 'lap' if grade['completed'] else 'no lap'
    return 'end' if grade['completed'] else 'not reached'


def _cm(value):
    return fmt(100.0 * value if value is not None else None, '.2f')


class LineSheet(object):
    task = 'line'
    criteria = CRITERIA
    header = ['course', 'kind', 'lap/end', 'RMS cm', 'max cm', 'mean m/s', 'bound m/s',
              'stop m', 'max v', 'max w', 'reason']

    @staticmethod
    def grades(records):
        return grades(records)

    @staticmethod
    def row(record, grade):
        return [record.get('name') or os.path.basename(str(grade['world'])),
                grade['kind'] or '-', _completion(grade), _cm(grade['rms_error']),
                _cm(grade['max_error']), fmt(grade['mean_speed'], '.3f'),
                fmt(grade['speed_bound'], '.3f'), fmt(grade['end_distance'], '.3f'),
                fmt(grade['max_linear'], '.3f'), fmt(grade['max_angular'], '.3f'),
                grade['reason'] or '-']

    @staticmethod
    def figures(grade):
        return [('course', '%s, %s m' % (grade['kind'] or '-', fmt(grade['length'], '.2f'))),
                ('camera', grade['camera'] or '-'), ('lap/end', _completion(grade)),
                ('RMS, max', '%s, %s cm' % (_cm(grade['rms_error']), _cm(grade['max_error']))),
                ('mean', '%s m/s (bound %s)' % (fmt(grade['mean_speed'], '.3f'),
                                                fmt(grade['speed_bound'], '.3f'))),
                ('stop', '%s m from the end' % fmt(grade['end_distance'], '.3f')
                 if grade['end_distance'] is not None else '-'),
                ('max v, w', '%s, %s' % (fmt(grade['max_linear'], '.3f'),
                                         fmt(grade['max_angular'], '.3f')))]

    @staticmethod
    def summary(summary):
        return ('%d line courses: %d completed (a lap, or an open line\'s end), %d passed every '
                'criterion' % (summary['cases'], summary['laps'], summary['passed']))
