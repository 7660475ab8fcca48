"""What a grading hands back: the terminal table, DIR/grades.json and DIR/report.html.

Built from the case records in DIR/cases/ (one JSON each, written where the
case ran), so that cases run on many machines and copied into one DIR give
the same report as cases run here (`grade --collect DIR`).
"""
import glob
import html
import json
import os

from wall_follower.evaluation.tables import fmt, print_table as _print_rows
from wall_follower.evaluation.grading.criteria import CRITERIA, grades

# grade's exit status when a case could not be graded (its harness failed).
NOT_GRADED = 3
HEADER = ['world', 'lap', 'in band %', 'RMS cm', 'find_wall', 'contact', 'max v', 'max w',
          'reason']


def read_record(path):
    """A case record, or None when the case wrote none (or not a whole one)."""
    try:
        with open(path) as stream:
            return json.load(stream)
    except (IOError, OSError, ValueError):
        return None


def case_records(directory, names=None):
    """The records of DIR/cases/, in the order of names (all of them, sorted, without)."""
    cases = os.path.join(directory, 'cases')
    if names is None:
        paths = sorted(p for p in glob.glob(os.path.join(cases, '*.json')))
    else:
        paths = [os.path.join(cases, name + '.json') for name in names]
    records = []
    for path in paths:
        record = read_record(path)
        if record is None:
            name = os.path.splitext(os.path.basename(path))[0]
            record = {'name': name, 'world': name,
                      'grader_error': 'no record of this case in %s' % cases}
        records.append(record)
    return records


def _lap_word(grade):
    if grade['lap_genuine']:
        return 'genuine'
    return 'premature' if grade['premature'] else 'never'


def _rows(records, graded):
    rows = []
    for record, grade in zip(records, graded['cases']):
        in_band = grade['in_band']
        rows.append([record.get('name') or os.path.basename(str(grade['world'])),
                     _lap_word(grade),
                     fmt(100.0 * in_band if in_band is not None else None, '.1f'),
                     fmt(100.0 * grade['rms_error'] if grade['rms_error'] is not None else None,
                         '.2f'),
                     'ok' if grade['find_wall_ok'] else 'FAIL',
                     'yes' if grade['contact'] else 'no',
                     fmt(grade['max_linear'], '.3f'), fmt(grade['max_angular'], '.3f'),
                     grade['reason'] or '-'])
    return rows


def print_table(records):
    graded = grades(records)
    _print_rows(HEADER, _rows(records, graded))
    summary = graded['summary']
    print('\n%d cases: %d genuine laps, %d passed every criterion'
          % (summary['cases'], summary['laps'], summary['passed']))
    if summary['not_graded']:
        print('%d case(s) NOT GRADED: the grader itself failed (see the reason, and the '
              "case's log in cases/)" % summary['not_graded'])
    return graded


def write_html(path, records, graded):
    """report.html: one row per case, its verdicts and its path over the map."""
    out = ['<!DOCTYPE html>', '<html><head><meta charset="utf-8"><title>grades</title>',
           '<style>body{font-family:sans-serif} td,th{border:1px solid #999;padding:4px;'
           'vertical-align:top} table{border-collapse:collapse} .fail{color:#b00}'
           ' .pass{color:#070}</style></head><body>']
    summary = graded['summary']
    command = records[0].get('solution_command', '') if records else ''
    out.append('<h1>Grades: %s</h1>' % html.escape(command))
    out.append('<p>%d cases, %d genuine laps, %d passed every criterion.</p>'
               % (summary['cases'], summary['laps'], summary['passed']))
    out.append('<table><tr><th>case</th>%s<th>figures</th><th>path</th></tr>'
               % ''.join('<th>%s</th>' % c for c in CRITERIA))
    directory = os.path.dirname(os.path.abspath(path))
    for record, grade, row in zip(records, graded['cases'], _rows(records, graded)):
        cells = ['<td>%s<br><small>%s</small></td>' % (
            html.escape(row[0]), html.escape(str(grade['world'])))]
        for name in CRITERIA:
            verdict = grade['criteria'][name]
            cells.append('<td class="%s">%s<br><small>%s</small></td>' % (
                'pass' if verdict['passed'] else 'fail', 'pass' if verdict['passed'] else 'FAIL',
                html.escape(verdict['reason'])))
        cells.append('<td>lap: %s<br>in band: %s %%<br>RMS: %s cm<br>max v, w: %s, %s</td>'
                     % tuple(html.escape(c) for c in (row[1], row[2], row[3], row[6], row[7])))
        plot = record.get('plot')
        if plot and os.path.exists(plot):
            relative = os.path.relpath(plot, directory)
            cells.append('<td><a href="%s"><img src="%s" width="280"></a></td>'
                         % (html.escape(relative), html.escape(relative)))
        else:
            cells.append('<td>no plot</td>')
        out.append('<tr>%s</tr>' % ''.join(cells))
    out.append('</table></body></html>')
    with open(path, 'w') as stream:
        stream.write('\n'.join(out) + '\n')


def collect(directory, names=None):
    """Print the table and write grades.json and report.html of DIR's cases.

    Returns 0, 1 when DIR holds no case, NOT_GRADED when the grader failed a case.
    """
    records = case_records(directory, names)
    if not records:
        print('grade: no case records in %s' % os.path.join(directory, 'cases'))
        return 1
    graded = print_table(records)
    with open(os.path.join(directory, 'grades.json'), 'w') as stream:
        json.dump(graded, stream, indent=1)
    write_html(os.path.join(directory, 'report.html'), records, graded)
    print('%s and %s written' % (os.path.join(directory, 'grades.json'),
                                 os.path.join(directory, 'report.html')))
    return NOT_GRADED if graded['summary']['not_graded'] else 0
