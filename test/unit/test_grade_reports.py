"""What `grade --collect` writes: a student's report of the line task, and the class page
over several students' directories (grading/report.py, line_sheet.py, class_report.py)."""
import json
import os
import shutil

import pytest

from line_runs import LOOP, OPEN, cutting, drive, write_case
from wall_follower.evaluation.grading import grader
from wall_follower.evaluation.grading import report as grade_report


def student(root, name, cut=0.0, open_until=None):
    """A student's directory: a loop (cut: how far inside its bends the base runs) and an
    open line (driven to open_until m along, its end by default)."""
    directory = os.path.join(str(root), name)
    write_case(directory, 'line_s0_000', LOOP, drive(LOOP, offset=cutting(cut)))
    write_case(directory, 'line_s0_002', OPEN, drive(OPEN, until=open_until))
    return directory


def load(directory, name):
    with open(os.path.join(directory, name)) as stream:
        return json.load(stream)


@pytest.fixture(scope='module')
def class_dirs(tmp_path_factory):
    """Two students: alice passes everything, bob cuts the loop's bends and stops short of
    the open line's end."""
    root = tmp_path_factory.mktemp('class')
    return [student(root, 'alice'), student(root, 'bob', cut=0.045, open_until=1.5)]


def test_a_line_report_has_a_row_per_case_with_its_verdicts(tmp_path, capsys):
    alice = os.path.join(str(tmp_path), 'alice')
    write_case(alice, 'line_s0_000', LOOP, drive(LOOP, offset=cutting(0.045)))
    write_case(alice, 'line_s0_002', OPEN, drive(OPEN))
    assert grader.main(['--collect', alice]) == 0
    out = capsys.readouterr().out
    assert '| course' in out and '| lap/end' in out and 'cuts its bends' in out
    grades = load(alice, 'grades.json')
    assert grades['summary'] == {'cases': 2, 'laps': 2, 'passed': 1, 'not_graded': 0}
    with open(os.path.join(alice, 'report.html')) as stream:
        html = stream.read()
    assert html.count('<tr class="case"') == 2
    assert ('data-case="line_s0_000" data-order="0" data-failed="1" data-completion="pass" '
            'data-tracking="fail" data-speed="pass" data-stop="na" data-safety="pass"') in html
    assert 'data-case="line_s0_002" data-order="1" data-failed="0"' in html
    assert '<img class="plot" src="cases/line_s0_000.png"' in html
    assert '<select id="filter">' in html and '<option value="fail:tracking">' in html
    # Self-contained: nothing fetched from elsewhere.
    assert 'http://' not in html and 'https://' not in html and '<script src' not in html


def test_a_directory_of_two_tasks_is_refused(tmp_path, capsys):
    alice = os.path.join(str(tmp_path), 'alice')
    write_case(alice, 'line_s0_002', OPEN, drive(OPEN))
    with open(os.path.join(alice, 'cases', 'gen_s0_000.json'), 'w') as stream:
        json.dump({'name': 'gen_s0_000', 'world': 'w', 'error': 'it crashed'}, stream)
    assert grader.main(['--collect', alice]) == 1
    assert 'the cases are of different tasks (course, line)' in capsys.readouterr().out


def test_collecting_several_students_writes_the_class_page(tmp_path, class_dirs, capsys):
    out = str(tmp_path / 'class')
    assert grader.main(['--collect'] + class_dirs + ['--out', out]) == 0
    text = capsys.readouterr().out
    assert '== alice' in text and '== bob' in text and '== the class' in text
    graded = load(out, 'class.json')
    assert graded['summary'] == {'students': 2, 'cases': 4, 'laps': 3, 'passed': 2,
                                 'not_graded': 0}
    alice, bob = graded['students']
    assert (alice['student'], alice['laps'], alice['passed']) == ('alice', 2, 2)
    assert (bob['student'], bob['laps'], bob['passed']) == ('bob', 1, 0)
    assert bob['criteria'] == {'completion': 1, 'tracking': 1, 'speed': 1, 'stop': 0,
                               'safety': 2}
    assert bob['applicable']['stop'] == 1
    assert bob['report'] == os.path.relpath(os.path.join(class_dirs[1], 'report.html'), out)
    # Each student's own report is written too.
    assert load(class_dirs[1], 'grades.json')['summary']['passed'] == 0
    with open(os.path.join(out, 'class.html')) as stream:
        html = stream.read()
    assert html.count('<tr class="student"') == 2
    assert '<a href="%s">bob</a>' % bob['report'] in html
    assert 'data-student="bob" data-order="1" data-cases="2" data-laps="1" data-passed="0"' in html
    assert 'data-tracking="fail" data-speed="fail" data-stop="fail" data-safety="pass"' in html


def test_a_parent_of_student_directories_is_a_class(tmp_path, class_dirs):
    for directory in class_dirs:
        shutil.copytree(directory, str(tmp_path / os.path.basename(directory)))
    assert grader.main(['--collect', str(tmp_path)]) == 0
    graded = load(str(tmp_path), 'class.json')
    assert [s['student'] for s in graded['students']] == ['alice', 'bob']
    assert graded['students'][0]['report'] == os.path.join('alice', 'report.html')
    assert os.path.isfile(os.path.join(str(tmp_path), 'class.html'))


def test_a_student_without_cases_is_listed_and_fails_the_collect(tmp_path, class_dirs):
    empty = tmp_path / 'carol'
    empty.mkdir()
    out = str(tmp_path / 'class')
    assert grader.main(['--collect'] + class_dirs + [str(empty), '--out', out]) == 1
    carol = load(out, 'class.json')['students'][2]
    assert carol['student'] == 'carol' and carol['error'].startswith('no case records')


def test_students_of_one_name_are_told_apart_by_their_paths(tmp_path, class_dirs):
    dirs = [str(tmp_path / who / 'line') for who in ('alice', 'bob')]
    for source, target in zip(class_dirs, dirs):
        shutil.copytree(source, target)
    out = str(tmp_path / 'class')
    assert grader.main(['--collect'] + dirs + ['--out', out]) == 0
    assert [s['student'] for s in load(out, 'class.json')['students']] == [
        os.path.join('alice', 'line'), os.path.join('bob', 'line')]


def test_a_class_needs_an_out_it_can_write(tmp_path, class_dirs, capsys):
    blocker = tmp_path / 'file'
    blocker.write_text('')
    assert grader.main(['--collect'] + class_dirs + ['--out', str(blocker / 'class')]) == 2
    assert '--out' in capsys.readouterr().err


def test_one_student_collects_as_before(tmp_path, class_dirs):
    assert grader.main(['--collect', class_dirs[0]]) == 0
    assert not os.path.exists(os.path.join(class_dirs[0], 'class.json'))
    assert grade_report.read_record(os.path.join(class_dirs[0], 'grades.json'))['summary'][
        'cases'] == 2
