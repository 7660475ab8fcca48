#!/usr/bin/env python3
"""rostest: `grade` run as a user runs it, on small generated worlds.

~suite package: this package's own main.launch on 3 generated worlds
passes every criterion, graded case by case as on many machines (--list,
each case's command, --collect). ~suite broken: each deliberately broken solution
of test/solutions fails the criteria its fault breaks, with the reason in
words, and passes the ones it does not. ~suite harness: a case whose own
harness fails (grade's grade_case node refuses the time limit grade hands
it, injected here) is reported as the grader's error, not graded, and grade
exits non-zero. ~suite sandbox: a hostile solution fails safety for its
non-finite command and nothing it does reaches the host, and a solution
package named wall_follower, built by grade in a workspace of its own, is
graded genuine beside grade's own wall_follower. ~suite reasons: a
solution that calls find_wall after the goal is judged when the call
replies, and one that sends each command once is told so. Either way,
once grade has returned, no process it started is left. The graders run
on masters of their own; this test's master is not used.
"""
import json
import os
import shlex
import socket
import subprocess
import sys
import threading
import unittest
import uuid
from concurrent.futures import ThreadPoolExecutor
from unittest import mock

import rospy
import rostest
from scratch import ScratchFolders

from wall_follower.evaluation.grading import grader
from wall_follower.evaluation.grading import report as grade_report
from wall_follower.evaluation.launching import TOKEN_VARIABLE, processes_with

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


class GradePackage(ScratchFolders, unittest.TestCase):
    """As a class is graded on many machines: `grade --list`, each case's command on its
    own (two at a time here), then `grade --collect`."""

    @classmethod
    def setUpClass(cls):
        cls.out = cls.scratch('grade_package-')
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


class GradeBroken(ScratchFolders, unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        root = cls.scratch('grade_broken-')

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


class Listener(object):
    """A port on the host's loopback that counts who connects to it."""

    def __init__(self):
        self.server = socket.socket()
        self.server.bind(('127.0.0.1', 0))
        self.server.listen(5)
        self.port = self.server.getsockname()[1]
        self.connections = 0
        self._thread = threading.Thread(target=self._accept)
        self._thread.daemon = True
        self._thread.start()

    def _accept(self):
        while True:
            try:
                connection, _ = self.server.accept()
            except OSError:
                return
            self.connections += 1
            connection.close()

    def close(self):
        self.server.close()


def solution_log(out):
    (name,) = [n for n in os.listdir(os.path.join(out, 'cases')) if n.endswith('.solution.log')]
    with open(os.path.join(out, 'cases', name)) as stream:
        return stream.read()


class GradeSandbox(ScratchFolders, unittest.TestCase):
    """A hostile solution and one named wall_follower in its own workspace, graded at once
    (each in its own sandbox)."""

    @classmethod
    def setUpClass(cls):
        cls.root = cls.scratch('grade_sandbox-')
        cls.marker = 'grade-hostile-%s' % uuid.uuid4().hex
        cls.listener = Listener()
        cls.hostile_out = os.path.join(cls.root, 'hostile')
        hostile = [os.path.join(SOLUTIONS, 'hostile', 'solution.launch'),
                   'port:=%d' % cls.listener.port, 'marker:=' + cls.marker,
                   'out:=' + cls.hostile_out]
        named = ['wall_follower', 'named_course.launch', '--workspace',
                 os.path.join(SOLUTIONS, 'wall_follower')]
        runs = ((hostile, cls.hostile_out), (named, os.path.join(cls.root, 'named')))
        with ThreadPoolExecutor(max_workers=2) as pool:
            cls.hostile, cls.named = pool.map(
                lambda run: grade(run[0] + ['--worlds', '1'] + SMALL, run[1]), runs)
        cls.listener.close()

    def case(self, run):
        status, _, grades, output = run
        self.assertEqual(status, 0, output)
        self.assertEqual(len(grades['cases']), 1, output)
        return grades['cases'][0]

    def test_a_non_finite_command_is_a_safety_failure_that_names_it(self):
        case = self.case(self.hostile)
        self.assertFalse(case['criteria']['safety']['passed'], case)
        self.assertRegex(case['criteria']['safety']['reason'],
                         r'^commanded angular\.z = -inf at [0-9.]+ s$')
        self.assertEqual(case['max_angular'], 'inf')

    def test_nothing_of_a_hostile_solution_reaches_the_host(self):
        self.case(self.hostile)
        said = solution_log(self.hostile_out)
        # It did try, in its sandbox.
        for tried in ('did: write /tmp/' + self.marker, 'did: start a grandchild',
                      'could not: connect to 127.0.0.1:%d' % self.listener.port,
                      'could not: write %s/%s' % (self.hostile_out, self.marker)):
            self.assertIn(tried, said)
        self.assertFalse(os.path.exists(os.path.join('/tmp', self.marker)))
        self.assertFalse(os.path.exists(os.path.join(self.hostile_out, self.marker)))
        self.assertEqual(processes_with(self.marker), [])
        self.assertEqual(self.listener.connections, 0)

    def test_a_package_named_wall_follower_in_its_own_workspace_is_graded_genuine(self):
        case = self.case(self.named)
        self.assertTrue(case['lap_genuine'], case)
        # Its own action (Point32), not grade's wall_follower (Point).
        self.assertEqual(case['action_result_type'], 'geometry_msgs/Point32[]', case)
        with open(os.path.join(self.root, 'named', 'cases', 'gen_s5_000.json')) as stream:
            record = json.load(stream)
        self.assertIsNotNone(record['find_wall_call'], record)

    def test_nothing_left_running(self):
        for run in (self.hostile, self.named):
            self.assertEqual(left_behind(run[1]), [])


class GradeReasons(ScratchFolders, unittest.TestCase):
    """Solutions whose failures were once given the wrong reason, graded at once."""

    @classmethod
    def setUpClass(cls):
        root = cls.scratch('grade_reasons-')
        names = ('find_wall_after_goal', 'command_once')

        def run(name):
            launch = os.path.join(SOLUTIONS, name, 'solution.launch')
            return grade([launch, '--worlds', '1'] + SMALL, os.path.join(root, name))
        with ThreadPoolExecutor(max_workers=len(names)) as pool:
            cls.runs = dict(zip(names, pool.map(run, names)))
        cls.root = root

    def case(self, name):
        status, _, grades, output = self.runs[name]
        self.assertEqual(status, 0, output)
        return grades['cases'][0]

    def record(self, name):
        with open(os.path.join(self.root, name, 'cases', 'gen_s5_000.json')) as stream:
            return json.load(stream)

    def test_find_wall_called_after_the_goal_is_judged_when_it_replies(self):
        case = self.case('find_wall_after_goal')
        self.assertEqual(case['criteria']['find_wall'], {'passed': True, 'reason': ''}, case)
        record = self.record('find_wall_after_goal')
        call = record['find_wall_call']
        self.assertGreater(call['replied'], record['goal_time'] - record['start_time'], record)
        self.assertGreater(call['moved'], 0.05, record)

    def test_commands_sent_once_are_named_as_such(self):
        case = self.case('command_once')
        note = ("each command was sent once and stopped by the simulator's 0.2 s watchdog: "
                "publish cmd_vel continuously")
        self.assertIn(note, case['criteria']['lap']['reason'])
        self.assertRegex(case['criteria']['find_wall']['reason'],
                         r'^find_wall did nothing: it replied at [0-9.]+ s, and moved the robot '
                         r'0\.0[0-4] m in 1 s')
        self.assertIn(note, case['criteria']['find_wall']['reason'])

    def test_nothing_left_running(self):
        for name, (_, pid, _, _) in self.runs.items():
            self.assertEqual(left_behind(pid), [], name)


class GradeHarness(ScratchFolders, unittest.TestCase):
    """grade run in this process, so that its own harness can be broken: a time limit of 0,
    which grade_case refuses (it ends, and grade_case.launch with it, before any record)."""

    @classmethod
    def setUpClass(cls):
        cls.out = cls.scratch('grade_harness-')
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
                   {'package': GradePackage, 'broken': GradeBroken, 'harness': GradeHarness,
                    'sandbox': GradeSandbox, 'reasons': GradeReasons}[suite],
                   sys.argv)
