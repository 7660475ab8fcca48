"""What a grading hands back: the terminal table, DIR/grades.json and DIR/report.html.

Built from the case records in DIR/cases/ (one JSON each, written where the
case ran), so that cases run on many machines and copied into one DIR give
the same report as cases run here (`grade --collect DIR`). Each task reads
its records its own way (a Sheet: its criteria, its grades, its table's
columns): the course task's here, the line task's in line_sheet.py; a
record names its task (a record without one is the course's). report.html
has a row per case, its verdicts and its plot, and sorts and filters by
criterion in the page (page.py). Several students' directories collected
at once also get the class page (class_report.py).
"""
import glob
import json
import os

from wall_follower.evaluation.grading import page
from wall_follower.evaluation.grading.criteria import CRITERIA, grades
from wall_follower.evaluation.grading.line_sheet import LineSheet
from wall_follower.evaluation.tables import fmt, print_table as _print_rows

# grade's exit status when a case could not be graded (its harness failed).
NOT_GRADED = 3


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


def _percent(value, spec):
    return fmt(100.0 * value if value is not None else None, spec)


class CourseSheet(object):
    """How the course task's grades read: criteria.py's criteria, its table's columns."""

    task = 'course'
    criteria = CRITERIA
    header = ['world', 'lap', 'in band %', 'RMS cm', 'find_wall', 'contact', 'max v', 'max w',
              'reason']

    @staticmethod
    def grades(records):
        return grades(records)

    @staticmethod
    def row(record, grade):
        return [record.get('name') or os.path.basename(str(grade['world'])), _lap_word(grade),
                _percent(grade['in_band'], '.1f'), _percent(grade['rms_error'], '.2f'),
                'ok' if grade['find_wall_ok'] else 'FAIL', 'yes' if grade['contact'] else 'no',
                fmt(grade['max_linear'], '.3f'), fmt(grade['max_angular'], '.3f'),
                grade['reason'] or '-']

    @staticmethod
    def figures(grade):
        return [('lap', _lap_word(grade)), ('in band', _percent(grade['in_band'], '.1f') + ' %'),
                ('RMS', _percent(grade['rms_error'], '.2f') + ' cm'),
                ('max v, w', '%s, %s' % (fmt(grade['max_linear'], '.3f'),
                                         fmt(grade['max_angular'], '.3f')))]

    @staticmethod
    def summary(summary):
        return '%d cases: %d genuine laps, %d passed every criterion' % (
            summary['cases'], summary['laps'], summary['passed'])


SHEETS = {'course': CourseSheet, 'line': LineSheet}


def task_of(records):
    """The task of DIR's records; ValueError when they are of more than one."""
    tasks = sorted(set(record.get('task') or 'course' for record in records
                       if not record.get('grader_error') or record.get('task')))
    if len(tasks) > 1:
        raise ValueError('the cases are of different tasks (%s): grade each task into a '
                         'directory of its own' % ', '.join(tasks))
    return tasks[0] if tasks else 'course'


def sheet_of(records):
    return SHEETS[task_of(records)]


def print_table(records, sheet=None):
    sheet = sheet or sheet_of(records)
    graded = sheet.grades(records)
    _print_rows(sheet.header, [sheet.row(record, grade)
                               for record, grade in zip(records, graded['cases'])])
    summary = graded['summary']
    print('\n' + sheet.summary(summary))
    if summary['not_graded']:
        print('%d case(s) NOT GRADED: the grader itself failed (see the reason, and the '
              "case's log in cases/)" % summary['not_graded'])
    return graded


def _verdict_cell(name, verdict):
    if not verdict.get('applies', True):
        return 'na', '<td class="na" data-criterion="%s">n/a<br><small>%s</small></td>' % (
            name, page.escape(verdict['reason']))
    word = 'pass' if verdict['passed'] else 'fail'
    return word, '<td class="%s" data-criterion="%s">%s<br><small>%s</small></td>' % (
        word, name, 'pass' if verdict['passed'] else 'FAIL', page.escape(verdict['reason']))


def _row(order, record, grade, sheet, directory):
    name = record.get('name') or os.path.basename(str(grade['world']))
    verdicts = [_verdict_cell(c, grade['criteria'][c]) for c in sheet.criteria]
    cells = ['<td class="case">%s<br><small>%s</small></td>' % (
        page.escape(name), page.escape(str(grade['world'])))]
    cells += [cell for _, cell in verdicts]
    cells.append('<td class="figures">%s</td>' % '<br>'.join(
        '%s: %s' % (page.escape(label), page.escape(text)) for label, text in sheet.figures(grade)))
    plot = record.get('plot')
    if plot and os.path.exists(plot):
        relative = page.escape(os.path.relpath(plot, directory))
        cells.append('<td class="path"><a href="%s"><img class="plot" src="%s" width="280" '
                     'alt="%s"></a></td>' % (relative, relative, page.escape('path of ' + name)))
    else:
        cells.append('<td class="path">no plot</td>')
    values = [('case', name), ('order', order),
              ('failed', sum(1 for word, _ in verdicts if word == 'fail'))]
    values += [(c, word) for c, (word, _) in zip(sheet.criteria, verdicts)]
    return '<tr class="case"%s>%s</tr>' % (page.data_attributes(values), ''.join(cells))


def write_html(path, records, graded, sheet=None):
    """report.html: one row per case, its verdicts and its path over the map."""
    sheet = sheet or sheet_of(records)
    command = records[0].get('solution_command', '') if records else ''
    directory = os.path.dirname(os.path.abspath(path))
    heads = ['<th data-sort="case">case</th>'] + [
        '<th data-sort="%s" data-type="verdict">%s</th>' % (c, c) for c in sheet.criteria] + [
        '<th>figures</th>', '<th>path</th>']
    body = ['<h1>Grades (%s task): %s</h1>' % (sheet.task, page.escape(command)),
            '<p id="summary">%s.</p>' % page.escape(sheet.summary(graded['summary'])),
            page.filter_control(sheet.criteria, 'case'),
            '<table class="sortable" id="grades" data-task="%s"><thead><tr>%s</tr></thead>'
            '<tbody>' % (sheet.task, ''.join(heads))]
    body += [_row(order, record, grade, sheet, directory)
             for order, (record, grade) in enumerate(zip(records, graded['cases']))]
    body.append('</tbody></table>')
    with open(path, 'w') as stream:
        stream.write(page.document('grades: %s' % command, '\n'.join(body)))


def grade_directory(directory, names=None):
    """Print DIR's table and write its grades.json and report.html.

    Returns (status, grades.json's content or None, the sheet or None):
    status 0, 1 when DIR holds no case (or cases of two tasks),
    NOT_GRADED when the grader failed a case.
    """
    records = case_records(directory, names)
    if not records:
        print('grade: no case records in %s' % os.path.join(directory, 'cases'))
        return 1, None, None
    try:
        sheet = sheet_of(records)
    except ValueError as err:
        print('grade: %s: %s' % (directory, err))
        return 1, None, None
    graded = print_table(records, sheet)
    with open(os.path.join(directory, 'grades.json'), 'w') as stream:
        json.dump(graded, stream, indent=1)
    write_html(os.path.join(directory, 'report.html'), records, graded, sheet)
    print('%s and %s written' % (os.path.join(directory, 'grades.json'),
                                 os.path.join(directory, 'report.html')))
    return (NOT_GRADED if graded['summary']['not_graded'] else 0), graded, sheet


def collect(directory, names=None):
    """Print the table and write grades.json and report.html of DIR's cases; the status
    (see grade_directory)."""
    return grade_directory(directory, names)[0]
