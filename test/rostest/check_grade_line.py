#!/usr/bin/env python3
"""rostest: a class graded on the line task as a teacher would, through a batch system.

Two students: this package's own line follower (pursuit), graded case by case
as on many machines (`grade --task line ... --list`, the commands run by
GNU parallel two at a time, then `grade --collect`), and the lab's
follower_p.py (`controller:=pixel_p`) on the tight course, graded by
another grade at the same time. Small courses (--room 1.4 1.8) of seed 0:
a loop, a tight loop and an open line, each with a camera of its own.

The package's follower passes every criterion on every course; pixel_p
laps the tight loop but cuts its bends, and is told so in words and
numbers. `grade --collect` of the directory that holds both writes the
class page. Then the pages are opened in a real browser (headless
Chromium, report_browser.py): every case's row, its verdicts and its plot
are on the page as drawn, and the class page lists both students. Once
every grade has returned, no process any of them started is left. The
graders run on masters of their own; this test's master is not used.
"""
import json
import os
import subprocess
import sys
import unittest
import uuid

import rospy
import rostest

import report_browser as browser
from scratch import ScratchFolders
from wall_follower.evaluation.launching import marked_processes

SOLUTION = ['--task', 'line', 'wall_follower', 'line_following.launch']
SMALL = ['--worlds', '3', '--seed', '0', '--room', '1.4', '1.8', '--start-limit', '20',
         '--timeout', '300']
TIGHT = 1
PLOT_WIDTH = 280


def grade(words):
    return ['rosrun', 'wall_follower', 'grade'] + words


# Every process this test starts, and all they start (parallel, the graders, every case's
# processes), carries this mark in its environment: none may be left at the end. (Not the
# case token's variable: each grade gives its cases tokens of their own.)
MARK = ('WALL_FOLLOWER_GRADE_LINE_TEST', uuid.uuid4().hex)


def read_json(path):
    with open(path) as stream:
        return json.load(stream)


class GradeLineClass(ScratchFolders, unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        cls.root = cls.scratch('grade_line-')
        cls.pursuit = os.path.join(cls.root, 'pursuit')
        cls.pixel_p = os.path.join(cls.root, 'pixel_p')
        env = dict(os.environ, **{MARK[0]: MARK[1]})
        listing = subprocess.check_output(grade(SOLUTION + SMALL + ['--out', cls.pursuit,
                                                                    '--list']),
                                          universal_newlines=True, env=env)
        cls.cases = listing.splitlines()
        cases_file = os.path.join(cls.root, 'cases.txt')
        with open(cases_file, 'w') as stream:
            stream.write(listing)
        # The other student's grade, at the same time: every case runs in lockstep on its
        # own master, so the load cannot change what either scores.
        other = subprocess.Popen(grade(SOLUTION + ['controller:=pixel_p'] + SMALL + [
            '--case', str(TIGHT), '--out', cls.pixel_p]), stdout=subprocess.PIPE,
            stderr=subprocess.STDOUT, universal_newlines=True, env=env)
        cls.joblog = os.path.join(cls.root, 'joblog')
        with open(cases_file) as commands:
            cls.parallel = subprocess.run(
                ['parallel', '--will-cite', '--jobs', '2', '--joblog', cls.joblog],
                stdin=commands, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                universal_newlines=True, env=env)
        cls.other_output, _ = other.communicate()
        cls.other = other
        collect = subprocess.run(grade(['--collect', cls.root]), stdout=subprocess.PIPE,
                                 stderr=subprocess.STDOUT, universal_newlines=True, env=env)
        cls.status, cls.output = collect.returncode, collect.stdout
        cls.grades = read_json(os.path.join(cls.pursuit, 'grades.json'))
        cls.pixel_grades = read_json(os.path.join(cls.pixel_p, 'grades.json'))

    def test_parallel_ran_every_listed_case(self):
        self.assertEqual(self.parallel.returncode, 0, self.parallel.stdout)
        with open(self.joblog) as stream:
            jobs = [line.split('\t') for line in stream.read().splitlines()[1:]]
        self.assertEqual(sorted(job[-1] for job in jobs), sorted(self.cases))
        # Exitval (the 7th column) of each job: every case graded.
        self.assertEqual([job[6] for job in jobs], ['0'] * len(self.cases), jobs)
        self.assertEqual(self.status, 0, self.output)

    def test_the_packages_line_follower_passes_every_course(self):
        self.assertEqual(self.grades['summary'],
                         {'cases': 3, 'laps': 3, 'passed': 3, 'not_graded': 0}, self.output)
        self.assertEqual([case['kind'] for case in self.grades['cases']],
                         ['loop', 'tight', 'open'])
        for case in self.grades['cases']:
            self.assertEqual(case['reason'], '', case)
            self.assertLessEqual(case['rms_error'], 0.015, case)
        self.assertLessEqual(self.grades['cases'][2]['end_distance'], 0.35)

    def test_pixel_p_cuts_the_tight_courses_bends_and_is_told_so(self):
        self.assertEqual(self.other.returncode, 0, self.other_output)
        (case,) = self.pixel_grades['cases']
        self.assertEqual(case['kind'], 'tight')
        failed = [name for name, verdict in case['criteria'].items() if not verdict['passed']]
        self.assertEqual(failed, ['tracking'], case)
        reason = case['criteria']['tracking']['reason']
        self.assertRegex(reason, r'^the base kept \d\.\d\d cm RMS from the line \(1\.50 at most\)')
        self.assertRegex(reason, r'inside a 0\.3\d m bend to the (left|right) at \(')
        self.assertIn('it cuts its bends', reason)

    def test_the_class_page_lists_both_students(self):
        graded = read_json(os.path.join(self.root, 'class.json'))
        self.assertEqual([(s['student'], s['laps'], s['passed']) for s in graded['students']],
                         [('pixel_p', 1, 0), ('pursuit', 3, 3)])
        page = browser.dom(os.path.join(self.root, 'class.html'))
        self.assertEqual([(row['data']['student'], row['data']['laps'], row['data']['passed'])
                          for row in page.rows], [('pixel_p', '1', '0'), ('pursuit', '3', '3')])
        self.assertEqual(page.links, [os.path.join('pixel_p', 'report.html'),
                                      os.path.join('pursuit', 'report.html')])

    def test_the_report_in_a_browser_shows_every_case_its_verdicts_and_plot(self):
        path = os.path.join(self.pursuit, 'report.html')
        page = browser.dom(path)
        self.assertEqual([row['data']['case'] for row in page.rows],
                         ['line_s0_000', 'line_s0_001', 'line_s0_002'])
        words = []
        for row, case in zip(page.rows, self.grades['cases']):
            expected = {name: 'na' if not v['applies'] else 'pass' if v['passed'] else 'fail'
                        for name, v in case['criteria'].items()}
            self.assertEqual(row['verdicts'], expected)
            self.assertEqual(row['images'], [os.path.relpath(case['plot'], self.pursuit)])
            words += expected.values()
        self.assertEqual(page.missing, [])
        shot = browser.screenshot(path)
        for word, colour in browser.COLOURS.items():
            self.assertEqual(len(browser.cells_of_colour(shot, colour)), words.count(word), word)
        tops = []
        for case in self.grades['cases']:
            score, (_, top) = browser.find_picture(shot, case['plot'], PLOT_WIDTH)
            self.assertGreater(score, 0.95, case['plot'])
            tops.append(top)
        self.assertEqual(tops, sorted(set(tops)))

    def test_nothing_left_running(self):
        self.assertEqual(marked_processes(MARK[1], MARK[0]), [])


if __name__ == '__main__':
    rospy.init_node('check_grade_line')
    rostest.rosrun('wall_follower', 'check_grade_line', GradeLineClass, sys.argv)
