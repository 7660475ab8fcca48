"""report.html and the class page in a real browser (headless Chromium): every case's row,
its verdicts and its plot are on the page as drawn, and the page's own script sorts and
filters by criterion, links a view by its address, and says so when a plot is missing.

The grading here is synthetic (line_runs.py): three cases of the line task with their
plots, one passing everything, one cutting its bends (tracking fails), one stopping short
of an open line's end (completion, speed and stop fail). Each browser run takes seconds:
the tests ask few. The rostest grade_line.test
runs the same checks on a real grading (test/rostest/report_browser.py holds them).
"""
import importlib.util
import json
import os
import shutil

import pytest

from line_runs import LOOP, OPEN, cutting, drive, write_case
from wall_follower.evaluation.grading import class_report

ROSTEST = os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, 'rostest')
SPEC = importlib.util.spec_from_file_location('report_browser',
                                              os.path.join(ROSTEST, 'report_browser.py'))
browser = importlib.util.module_from_spec(SPEC)
SPEC.loader.exec_module(browser)

NAMES = ('line_s0_000', 'line_s0_001', 'line_s0_002')
# Another loop than LOOP, so that no two plots look alike.
WIDE_LOOP = dict(LOOP, path=[['straight', 1.6], ['arc', 0.35, 90.0], ['straight', 0.6],
                             ['arc', 0.35, 90.0]] * 2)
PLOT_WIDTH = 280


@pytest.fixture(scope='module')
def graded(tmp_path_factory):
    """A student's graded directory of three cases, and its grades.json."""
    directory = str(tmp_path_factory.mktemp('alice'))
    write_case(directory, NAMES[0], LOOP, drive(LOOP))
    write_case(directory, NAMES[1], WIDE_LOOP,
               drive(WIDE_LOOP, offset=cutting(0.045, WIDE_LOOP)))
    write_case(directory, NAMES[2], OPEN, drive(OPEN, until=1.5))
    assert class_report.collect_all([directory], directory) == 0
    with open(os.path.join(directory, 'grades.json')) as stream:
        return directory, json.load(stream)


def verdict_words(case):
    return {name: ('na' if not v['applies'] else 'pass' if v['passed'] else 'fail')
            for name, v in case['criteria'].items()}


def test_every_row_with_its_verdicts_and_plot_is_in_the_page(graded):
    directory, grades = graded
    page = browser.dom(os.path.join(directory, 'report.html'))
    assert [row['data']['case'] for row in page.rows] == list(NAMES)
    assert page.visible() == page.rows and page.shown == '3 of 3 shown'
    for row, case in zip(page.rows, grades['cases']):
        assert row['verdicts'] == verdict_words(case)
        assert row['images'] == [os.path.relpath(case['plot'], directory)]
    assert page.missing == []


def test_the_page_as_drawn_shows_every_verdict_and_every_plot(graded):
    directory, grades = graded
    shot = browser.screenshot(os.path.join(directory, 'report.html'))
    words = [w for case in grades['cases'] for w in verdict_words(case).values()]
    for word, colour in browser.COLOURS.items():
        assert len(browser.cells_of_colour(shot, colour)) == words.count(word), word
    tops = []
    for case in grades['cases']:
        score, (left, top) = browser.find_picture(shot, case['plot'], PLOT_WIDTH)
        assert score > 0.95, (case['plot'], score)
        tops.append(top)
    # One plot a row, in the rows' order.
    assert tops == sorted(tops) and len(set(tops)) == len(tops)


def test_the_page_sorts_and_filters_by_criterion_from_its_address(graded):
    directory, _ = graded
    page = browser.dom(os.path.join(directory, 'report.html'), 'sort=stop:asc&filter=fail:any')
    # Failing first, then not applicable, then passing; the original order among equals.
    assert [row['data']['case'] for row in page.rows] == [NAMES[2], NAMES[0], NAMES[1]]
    assert [row['data']['case'] for row in page.visible()] == [NAMES[2], NAMES[1]]
    assert page.shown == '2 of 3 shown'


def test_a_missing_plot_is_said_to_be_missing(graded, tmp_path):
    directory, grades = graded
    copy = str(tmp_path / 'copy')
    shutil.copytree(directory, copy)
    os.unlink(os.path.join(copy, 'cases', NAMES[1] + '.png'))
    page = browser.dom(os.path.join(copy, 'report.html'))
    assert page.missing == ['plot not found: cases/%s.png' % NAMES[1]]
    assert [len(row['images']) for row in page.rows] == [1, 0, 1]


def test_the_class_page_lists_every_student(graded, tmp_path):
    directory, _ = graded
    bob = str(tmp_path / 'bob')
    write_case(bob, NAMES[0], LOOP, drive(LOOP))
    out = str(tmp_path / 'class')
    assert class_report.collect_all([directory, bob], out) == 0
    page = browser.dom(os.path.join(out, 'class.html'), 'filter=fail:tracking')
    assert [(row['data']['student'], row['data']['laps'], row['data']['passed'])
            for row in page.rows] == [(os.path.basename(directory), '2', '1'), ('bob', '1', '1')]
    assert page.links == [os.path.relpath(os.path.join(d, 'report.html'), out)
                          for d in (directory, bob)]
    assert [row['data']['student'] for row in page.visible()] == [os.path.basename(directory)]
