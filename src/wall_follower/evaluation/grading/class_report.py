"""A class's page: every student's laps and passed cases, from their graded directories.

`grade --collect DIR1 DIR2 ... --out CLASS`: each DIR is one student's
(graded by `grade ... --out DIR`, on one machine or many), and is collected
as `grade --collect DIR` collects it (its table, grades.json, report.html);
then CLASS/class.json and CLASS/class.html list the students: their task,
cases, laps (the course task's genuine laps; the line task's courses
completed), cases that passed every criterion, cases not graded, and per
criterion the cases that passed it, each student linked to their report.
`grade --collect PARENT`, where PARENT holds no cases/ of its own but
student directories that do, is the same with every such directory, and
PARENT as CLASS. A student is named by their directory (its path below the
directories' common parent when two share a name).
"""
import json
import os
from collections import OrderedDict

from wall_follower.evaluation.grading import page, report
from wall_follower.evaluation.tables import print_table


def student_directories(parent):
    """The directories directly in parent that hold a cases/ directory, sorted."""
    try:
        names = sorted(os.listdir(parent))
    except OSError:
        return []
    return [os.path.join(parent, name) for name in names
            if os.path.isdir(os.path.join(parent, name, 'cases'))]


def student_names(directories):
    """A name for each student directory: its own, or its path below the common parent."""
    paths = [os.path.abspath(d) for d in directories]
    names = [os.path.basename(p.rstrip('/')) for p in paths]
    if len(set(names)) == len(names):
        return names
    common = os.path.commonpath(paths)
    return [os.path.relpath(p, common) for p in paths]


def student_entry(name, directory, out, graded, sheet):
    """class.json's entry of one student (graded None: no case to grade in the directory)."""
    entry = OrderedDict([('student', name), ('directory', os.path.abspath(directory)),
                         ('report', os.path.relpath(os.path.join(directory, 'report.html'), out))])
    if graded is None:
        entry['error'] = 'no case records (or cases of two tasks) in %s' % directory
        return entry
    cases = graded['cases']
    entry['task'] = sheet.task
    entry.update(graded['summary'])
    entry['criteria'] = OrderedDict(
        (name, sum(1 for case in cases if case['criteria'][name]['passed']
                   and case['criteria'][name].get('applies', True)))
        for name in sheet.criteria)
    entry['applicable'] = OrderedDict(
        (name, sum(1 for case in cases if case['criteria'][name].get('applies', True)))
        for name in sheet.criteria)
    return entry


def _criteria_of(entries):
    names = []
    for entry in entries:
        names += [name for name in entry.get('criteria', ()) if name not in names]
    return names


def _html_row(order, entry, criteria):
    cells = ['<td class="student"><a href="%s">%s</a></td>' % (
        page.escape(entry['report']), page.escape(entry['student']))]
    values = [('student', entry['student']), ('order', order)]
    if 'error' in entry:
        cells.append('<td colspan="%d" class="fail">%s</td>'
                     % (5 + len(criteria), page.escape(entry['error'])))
        values += [('failed', 1)] + [(name, 'fail') for name in criteria]
        return '<tr class="student"%s>%s</tr>' % (page.data_attributes(values), ''.join(cells))
    for key in ('cases', 'laps', 'passed', 'not_graded'):
        cells.append('<td class="%s">%d</td>' % (key, entry[key]))
        values.append((key, entry[key]))
    cells.insert(1, '<td class="task">%s</td>' % page.escape(entry['task']))
    failed = 0
    for name in criteria:
        applicable = entry['applicable'].get(name, 0)
        passed = entry['criteria'].get(name, 0)
        word = 'na' if not applicable else ('pass' if passed == applicable else 'fail')
        failed += word == 'fail'
        cells.append('<td class="%s">%s</td>' % (word, '%d/%d' % (passed, applicable)
                                                 if applicable else 'n/a'))
        values.append((name, word))
    values.append(('failed', failed))
    return '<tr class="student"%s>%s</tr>' % (page.data_attributes(values), ''.join(cells))


def write_class(out, entries):
    """CLASS/class.json and CLASS/class.html of the students' entries; their paths."""
    if not os.path.isdir(out):
        os.makedirs(out)
    criteria = _criteria_of(entries)
    summary = OrderedDict([('students', len(entries)),
                           ('cases', sum(e.get('cases', 0) for e in entries)),
                           ('laps', sum(e.get('laps', 0) for e in entries)),
                           ('passed', sum(e.get('passed', 0) for e in entries)),
                           ('not_graded', sum(e.get('not_graded', 0) for e in entries))])
    json_path, html_path = os.path.join(out, 'class.json'), os.path.join(out, 'class.html')
    with open(json_path, 'w') as stream:
        json.dump(OrderedDict([('summary', summary), ('students', entries)]), stream, indent=1)
    heads = ['<th data-sort="student">student</th>', '<th>task</th>'] + [
        '<th data-sort="%s" data-type="num">%s</th>' % (key, label) for key, label in (
            ('cases', 'cases'), ('laps', 'laps'), ('passed', 'passed'),
            ('not_graded', 'not graded'))] + [
        '<th data-sort="%s" data-type="verdict">%s</th>' % (c, c) for c in criteria]
    body = ['<h1>Class: %d students</h1>' % len(entries),
            '<p id="summary">%d cases, %d laps, %d passed every criterion, %d not graded. '
            'A criterion\'s cell: the cases that passed it, of those it applies to.</p>'
            % (summary['cases'], summary['laps'], summary['passed'], summary['not_graded']),
            page.filter_control(criteria, 'student'),
            '<table class="sortable" id="class"><thead><tr>%s</tr></thead><tbody>'
            % ''.join(heads)]
    body += [_html_row(order, entry, criteria) for order, entry in enumerate(entries)]
    body.append('</tbody></table>')
    with open(html_path, 'w') as stream:
        stream.write(page.document('class', '\n'.join(body)))
    return json_path, html_path


def print_class(entries):
    rows = [[e['student'], e.get('task', '-'), str(e.get('cases', '-')), str(e.get('laps', '-')),
             str(e.get('passed', '-')), str(e.get('not_graded', '-')), e.get('error', e['report'])]
            for e in entries]
    print_table(['student', 'task', 'cases', 'laps', 'passed', 'not graded', 'report'], rows)


def collect_all(directories, out):
    """`grade --collect DIR...`: one student's directory collected alone, or a class (see
    the module). Returns 0, 1 when a directory holds no case, NOT_GRADED when the grader
    failed a case."""
    if len(directories) == 1:
        students = student_directories(directories[0])
        if os.path.isdir(os.path.join(directories[0], 'cases')) or not students:
            return report.collect(directories[0])
        out = directories[0]
    else:
        students = list(directories)
    entries, statuses = [], []
    for name, directory in zip(student_names(students), students):
        print('\n== %s (%s)' % (name, directory))
        status, graded, sheet = report.grade_directory(directory)
        statuses.append(status)
        entries.append(student_entry(name, directory, out, graded, sheet))
    print('\n== the class')
    print_class(entries)
    paths = write_class(out, entries)
    print('%s and %s written' % paths)
    if report.NOT_GRADED in statuses:
        return report.NOT_GRADED
    return max(statuses) if statuses else 1
