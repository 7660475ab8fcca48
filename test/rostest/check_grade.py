#!/usr/bin/env python3
"""rostest: `grade` run as a user runs it, on small generated worlds.

~suite package: this package's own main.launch on 3 generated worlds
passes every criterion, graded case by case as on many machines (--list,
each case's command, --collect). ~suite broken: each deliberately broken solution
of test/solutions fails the criteria its fault breaks, with the reason in
words, and passes the ones it does not. ~suite harness: a case whose own
harness fails (grade's grade_case node refuses the time limit grade hands
it, injected here) is reported as the grader's error, not graded, and grade
exits non-zero. Either way, once grade has returned, no process it started
is left. The graders run on masters of their own; this test's master is
not used.
"""
import json
import os
import shlex
import subprocess
import sys
import tempfile
import unittest
from concurrent.futures import ThreadPoolExecutor
from unittest import mock

import rospy
import rostest

from wall_follower.evaluation.grading import report as grade_report

from wall_follower.evaluation.grading import grader
from wall_follower.evaluation.launching import TOKEN_VARIABLE

SOLUTIONS = os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, 'solutions')
# Small worlds, and a short start limit: every case takes seconds, not minutes.
SMALL = ['--room', '1.8', '2.4', '--seed', '5', '--start-limit', '10', '--timeout', '200']
BROKEN = ('never_calls_find_wall', 'early_lap', 'into_wall', 'crash_at_start')
# Worlds of seed 1 (full size) that this package laps within every criterion; the
# worlds it does not are the benchmark's to show (benchmark follow --generated).
PACKAGE_CASES = (3, 5, 6)


def left_behind(pid):
    """Ids of processes still carrying a case token of the grade whose id is pid."""
    needle = ('%s=%d-' % (TOKEN_VARIABLE, pid)).encode()
    found = []
    for entry in os.listdir('/proc'):
        if entry.isdigit():
            try:
                with open('/proc/%s/environ' % entry, 'rb') as stream:
                    if needle in stream.read():
                        found.append(int(entry))
            except (IOError, OSError):
                pass
    return found


def grade(words, out):
    """Run grade with words into out; (its exit status, its pid, grades.json, its output)."""
    process = subprocess.Popen(['rosrun', 'wall_follower', 'grade'] + words + ['--out', out],
                               stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                               universal_newlines=True)
    output, _ = process.communicate()
    return process.returncode, process.pid, read_grades(out), output


def read_grades(out):
    try:
        with open(os.path.join(out, 'grades.json')) as stream:
            return json.load(stream)
    except (IOError, ValueError):
        return None


class GradePackage(unittest.TestCase):
    """As a class is graded on many machines: `grade --list`, each case's command on its
    own (two at a time here), then `grade --collect`."""

    @classmethod
    def setUpClass(cls):
        cls.out = tempfile.mkdtemp(prefix='grade_package-')
        listing = subprocess.check_output(
            ['rosrun', 'wall_follower', 'grade', 'wall_follower', 'main.launch', '--worlds',
             str(max(PACKAGE_CASES) + 1), '--seed', '1', '--out', cls.out, '--list'],
            universal_newlines=True).splitlines()
        commands = [listing[index] for index in PACKAGE_CASES]

        def run(command):
            process = subprocess.Popen(shlex.split(command), stdout=subprocess.PIPE,
                                       stderr=subprocess.STDOUT, universal_newlines=True)
            output, _ = process.communicate()
            return process.returncode, process.pid, output
        with ThreadPoolExecutor(max_workers=2) as pool:
            cls.runs = list(pool.map(run, commands))
        collect = subprocess.run(['rosrun', 'wall_follower', 'grade', '--collect', cls.out],
                                 stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                 universal_newlines=True)
        cls.status, cls.output = collect.returncode, collect.stdout
        cls.grades = read_grades(cls.out)

    def test_every_case_ran(self):
        for status, _, output in self.runs:
            self.assertEqual(status, 0, output)

    def test_every_criterion_passes(self):
        self.assertEqual(self.status, 0, self.output)
        self.assertEqual(self.grades['summary']['cases'], len(PACKAGE_CASES), self.output)
        self.assertEqual(self.grades['summary']['laps'], len(PACKAGE_CASES), self.output)
        for case in self.grades['cases']:
            self.assertEqual(case['reason'], '', case)
            self.assertTrue(all(v['passed'] for v in case['criteria'].values()), case)
            self.assertFalse(case['premature'] or case['contact'], case)
            self.assertGreaterEqual(case['in_band'], 0.97, case)

    def test_report_shows_every_case_with_its_path(self):
        with open(os.path.join(self.out, 'report.html')) as stream:
            report = stream.read()
        for case in self.grades['cases']:
            self.assertTrue(os.path.isfile(case['plot']), case)
            self.assertIn(os.path.relpath(case['plot'], self.out), report)

    def test_nothing_left_running(self):
        for _, pid, _ in self.runs:
            self.assertEqual(left_behind(pid), [])


class GradeBroken(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        root = tempfile.mkdtemp(prefix='grade_broken-')

        def run(name):
            launch = os.path.join(SOLUTIONS, name, 'solution.launch')
            return grade([launch, '--worlds', '1'] + SMALL, os.path.join(root, name))
        # All at once: two of them only wait (for a call, for a node), and each grade runs its
        # world in lockstep, so the others' load cannot change what it scores.
        with ThreadPoolExecutor(max_workers=len(BROKEN)) as pool:
            cls.runs = dict(zip(BROKEN, pool.map(run, BROKEN)))

    def case(self, name):
        status, _, grades, output = self.runs[name]
        self.assertEqual(status, 0, output)
        self.assertEqual(len(grades['cases']), 1, output)
        return grades['cases'][0]

    def test_never_calling_find_wall_fails_find_wall(self):
        case = self.case('never_calls_find_wall')
        self.assertFalse(case['find_wall_ok'], case)
        self.assertIn('never called', case['criteria']['find_wall']['reason'])
        self.assertFalse(case['contact'], case)

    def test_a_lap_declared_after_6_m_is_premature(self):
        case = self.case('early_lap')
        self.assertTrue(case['premature'], case)
        self.assertFalse(case['lap_genuine'], case)
        # 6 m by its own sum of points a second apart; a little more along the true path.
        self.assertRegex(case['criteria']['lap']['reason'], r'declared after 6\.[0-4] m')
        self.assertTrue(case['find_wall_ok'], case)
        self.assertFalse(case['contact'], case)

    def test_driving_into_the_wall_is_contact_and_no_lap(self):
        case = self.case('into_wall')
        self.assertTrue(case['contact'], case)
        self.assertIn('touched an obstacle', case['criteria']['safety']['reason'])
        self.assertFalse(case['lap_genuine'] or case['premature'], case)
        self.assertIsNone(case['in_band'], case)
        self.assertTrue(case['find_wall_ok'], case)

    def test_a_crash_at_start_fails_everything_and_says_why(self):
        case = self.case('crash_at_start')
        # Safe it is: it never moved.
        self.assertTrue(case['criteria'].pop('safety')['passed'], case)
        self.assertFalse(any(v['passed'] for v in case['criteria'].values()), case)
        self.assertIn('no find_wall service', case['reason'])
        self.assertIn('crashed or ended', case['reason'])

    def test_nothing_left_running(self):
        for name, (_, pid, _, _) in self.runs.items():
            self.assertEqual(left_behind(pid), [], name)


class GradeHarness(unittest.TestCase):
    """grade run in this process, so that its own harness can be broken: a time limit of 0,
    which grade_case refuses (it ends, and grade_case.launch with it, before any record)."""

    @classmethod
    def setUpClass(cls):
        cls.out = tempfile.mkdtemp(prefix='grade_harness-')
        with mock.patch.object(grader, 'lap_limit', return_value=0.0):
            cls.status = grader.main(['wall_follower', 'main.launch', '--worlds', '1'] + SMALL +
                                     ['--out', cls.out])
        cls.grades = read_grades(cls.out)

    def test_grade_exits_saying_it_failed(self):
        self.assertEqual(self.status, grade_report.NOT_GRADED)

    def test_the_case_is_the_graders_error_not_the_solutions(self):
        self.assertEqual(self.grades['summary']['not_graded'], 1, self.grades)
        (case,) = self.grades['cases']
        self.assertIn("grade's simulator or grade_case node ended", case['grader_error'])
        self.assertTrue(case['reason'].startswith('not graded: the grader failed ('), case)
        for verdict in case['criteria'].values():
            self.assertNotIn('crashed or ended', verdict['reason'])

    def test_nothing_left_running(self):
        self.assertEqual(left_behind(os.getpid()), [])


if __name__ == '__main__':
    rospy.init_node('check_grade')
    suite = rospy.get_param('~suite')
    rostest.rosrun('wall_follower', 'check_grade_' + suite,
                   {'package': GradePackage, 'broken': GradeBroken, 'harness': GradeHarness}[suite],
                   sys.argv)
