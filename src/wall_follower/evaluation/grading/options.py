"""grade's command line, checked whole before any case runs.

A mistake in how grade is called is grade's to report, at once, naming the
option or the word, with a non-zero exit: never a case that starts, fails
and is then graded as if the solution had failed. So before the first case:

- every number is within what the case's parts take: --seed and --speedup
  within the simulator's own parameter ranges (params/sim/stage_sim.py), since
  the case's simulator is given them; --start-limit within grade_case's
  (params/evaluation/grade_case.py); --worlds, --jobs at least 1; --timeout a positive
  number of seconds; --case one of the --worlds cases; --room two positive
  sides, the shortest first;
- --out is a directory grade can create and write in (each --collect DIR
  one that exists and can be written in);
- --laser and --action-ns are the course task's: with --task line they are
  refused, not ignored;
- --simulator stage has stage_ros installed and a display to run in;
- the solution resolves as roslaunch would resolve it: its package on
  ROS_PACKAGE_PATH, its launch file in that package, and the launch file
  loads (every include and $(find) found, every required argument given)
  with no ARG:=VALUE it does not declare (roslaunch ignores those
  silently: a misspelt argument would grade the solution on its default).

Loading the solution's launch file runs its substitutions ($(eval), a
param's command), so it is loaded in a child process, in the environment
(and the sandbox) the cases give the solution, never in grade's own process.
"""
import argparse
import math
import os
import subprocess
import sys
import tempfile
import uuid

import rosgraph.names

from wall_follower.evaluation.grading import launch_check
from wall_follower.evaluation.launching import ProcessGroup, display_wrapper, package_installed
from wall_follower.evaluation.worlds.generator import Settings
from wall_follower.evaluation.worlds.line_courses import DEFAULT_ROOM as LINE_ROOM
from wall_follower.params import parameters
from wall_follower.params.evaluation.grade_case import TABLE as CASE_TABLE
from wall_follower.params.sim.stage_sim import TABLE as SIMULATOR_TABLE
from wall_follower.sim.laser_profiles import PROFILES

DEFAULT_LASER = 'course720'
DEFAULT_ACTION_NS = 'record_odom'
# What grade grades: the course (find_wall, record_odom, the follower), or a line follower.
TASKS = ('course', 'line')
ROOMS = {'course': Settings().room, 'line': LINE_ROOM}
# Wall seconds the solution's launch file may take to load (a param's command runs then).
LOAD_LIMIT = 60.0
# How the child process marks a problem in its output (roslaunch may print there too).
PROBLEM = launch_check.PROBLEM


def _parameter(table, name):
    return next(p for p in parameters(table) if p.name == name)


# The case's simulator and grade_case node take these options as their parameters.
SEED = _parameter(SIMULATOR_TABLE, 'seed')
SPEEDUP = _parameter(SIMULATOR_TABLE, 'speedup')
START_LIMIT = _parameter(CASE_TABLE, 'start_limit')


def parser():
    p = argparse.ArgumentParser(
        prog='grade', description='A course solution (or, with --task line, a line follower) '
        'graded on generated worlds, from ground truth.',
        epilog='examples: grade my_course main.launch; grade ~/sub/alice.launch --worlds 20 '
               '--jobs 2; grade my_course main.launch --list > cases.txt; '
               'grade --collect DIR')
    p.add_argument('solution', nargs='*',
                   help='PACKAGE LAUNCH_FILE, or the path of a launch file, then ARG:=VALUE')
    p.add_argument('--task', choices=TASKS, default='course',
                   help='course (default): find_wall, record_odom and the wall follower in '
                   'generated rooms; line: a line follower (experiment 5) on generated line '
                   'courses')
    p.add_argument('--worlds', type=int, default=10, help='generated worlds (default 10)')
    p.add_argument('--seed', type=int, default=0,
                   help='seed of the generated worlds, %s .. %s (default 0)'
                   % (_plain(SEED.minimum), _plain(SEED.maximum)))
    p.add_argument('--jobs', type=int, default=1, help='cases run at once (default 1)')
    p.add_argument('--laser', default=DEFAULT_LASER, choices=PROFILES,
                   help='laser profile of the scan (default %s, the course robot\'s)'
                   % DEFAULT_LASER)
    p.add_argument('--speedup', type=float, default=0.0,
                   help='simulated seconds per wall second at most; 0 (default): as fast as '
                   'the solution answers (lockstep); 1 for solutions that time with time.sleep')
    p.add_argument('--action-ns', default=DEFAULT_ACTION_NS,
                   help='namespace of the record_odom action (default %s)' % DEFAULT_ACTION_NS)
    p.add_argument('--timeout', type=float, default=900.0,
                   help='wall seconds a case may take (default 900)')
    p.add_argument('--start-limit', type=float, default=30.0,
                   help='wall seconds the solution has to start its nodes, %s .. %s '
                   '(default 30)' % (_plain(START_LIMIT.minimum), _plain(START_LIMIT.maximum)))
    p.add_argument('--simulator', choices=('builtin', 'stage'), default='builtin',
                   help='builtin (default) or stage: real stageros in its window')
    p.add_argument('--room', type=float, nargs=2, metavar=('SHORTEST', 'LONGEST'),
                   help='sides of the generated main rooms [m] (default %.1f %.1f); with --task '
                   'line, of the line courses\' loops (default %.1f %.1f)'
                   % (ROOMS['course'] + ROOMS['line']))
    p.add_argument('--out', default='grades', help='output directory (default ./grades)')
    p.add_argument('--list', action='store_true',
                   help='print one command per case, to run anywhere, then --collect')
    p.add_argument('--case', type=int, help='run only this case (0 .. worlds-1)')
    p.add_argument('--collect', metavar='DIR', nargs='+',
                   help='build DIR/grades.json and DIR/report.html from its finished cases; '
                   'several DIRs (students), or a DIR of students\' directories: each one\'s, '
                   'and the class page (--out, or that DIR)')
    _add_solution_options(p)
    return p


def _add_solution_options(p):
    """Where the solution comes from and how it is contained (grading/workspace.py,
    grading/sandbox.py)."""
    p.add_argument('--workspace', metavar='DIR',
                   help="the student's catkin workspace (its devel/ or install/ setup is "
                   "sourced for the solution only), or a package directory, built first into "
                   "a private workspace in --out")
    p.add_argument('--no-sandbox', action='store_true',
                   help='run the solution with grade\'s rights, in the host\'s namespaces '
                   '(where no sandbox can be had)')


def room_of(options):
    """The --room given, or the task's default."""
    return tuple(options.room) if options.room is not None else ROOMS[options.task]


def option_problems(options):
    """Sentences naming each option (all but the solution) grade cannot run with; [] if none."""
    if options.collect:
        found = []
        for directory in options.collect:
            found += _directory_problems('--collect', directory, may_create=False)
        if len(options.collect) > 1:
            found += _directory_problems('--out', options.out, may_create=True)
        if options.solution:
            found.append('--collect takes no solution (got %s)' % ' '.join(options.solution))
        return found
    found = _task_problems(options)
    found += _at_least('--worlds', options.worlds, 1)
    found += _at_least('--jobs', options.jobs, 1)
    found += _within('--seed', options.seed, SEED)
    found += _within('--speedup', options.speedup, SPEEDUP)
    found += _within('--start-limit', options.start_limit, START_LIMIT)
    if not (math.isfinite(options.timeout) and options.timeout > 0.0):
        found.append('--timeout must be a positive number of wall seconds, not %s'
                     % options.timeout)
    if options.case is not None:
        if options.list:
            found.append('--list prints every case and --case runs one: give one of them')
        elif not 0 <= options.case < max(options.worlds, 1):
            found.append('--case %d is not one of the cases of --worlds %d (0 .. %d)'
                         % (options.case, options.worlds, options.worlds - 1))
    shortest, longest = room_of(options)
    if not (math.isfinite(shortest) and math.isfinite(longest) and 0.0 < shortest <= longest):
        found.append('--room needs two positive sides [m], the shortest first, not %s %s'
                     % (shortest, longest))
    if not options.action_ns or not rosgraph.names.is_legal_name(options.action_ns):
        found.append('--action-ns %r is not a legal ROS name' % options.action_ns)
    if options.simulator == 'stage':
        found += _stage_problems()
    if not options.list:
        # A listed case runs elsewhere, and checks its own --out there.
        found += _directory_problems('--out', options.out, may_create=True)
    return found


def _task_problems(options):
    """The course task's options given to another task."""
    if options.task == 'course':
        return []
    return ['%s is an option of --task course, not of --task %s' % (flag, options.task)
            for flag, given, default in (('--laser', options.laser, DEFAULT_LASER),
                                         ('--action-ns', options.action_ns, DEFAULT_ACTION_NS))
            if given != default]


def _at_least(flag, value, low):
    return [] if value >= low else ['%s must be at least %d, not %d' % (flag, low, value)]


def _within(flag, value, parameter):
    """The option that the case hands on as parameter, within that parameter's range."""
    if parameter.minimum <= value <= parameter.maximum:
        return []
    return ['%s must be within %s .. %s (the case\'s ~%s), not %s' % (
        flag, _plain(parameter.minimum), _plain(parameter.maximum), parameter.name, value)]


def _plain(number):
    return '%g' % number if isinstance(number, float) else str(number)


def _stage_problems():
    found = []
    if not package_installed('stage_ros'):
        found.append('--simulator stage needs the stage_ros package, which is not installed '
                     '(the built-in simulator is the default)')
    if display_wrapper() is None:
        found.append('--simulator stage needs a display: no DISPLAY and no xvfb-run')
    return found


def _directory_problems(flag, path, may_create):
    """[] when path is a directory grade can write in, or (may_create) one it can make; else
    why not. Tried, not guessed from permissions, and nothing is left behind: a command
    refused for another reason makes no directory."""
    path = os.path.abspath(path)
    existing = path
    while not os.path.exists(existing):
        if not may_create:
            return ['%s %s: no such directory' % (flag, path)]
        existing = os.path.dirname(existing)
    if not os.path.isdir(existing):
        return ['%s %s: %s is not a directory' % (flag, path, existing)]
    try:
        # What grade will write there: a file, or (not there yet) the directories down to it.
        with tempfile.TemporaryFile(dir=path) if existing == path else \
                tempfile.TemporaryDirectory(dir=existing):
            pass
    except OSError as err:
        return ['%s %s: cannot write there (%s)' % (flag, path, err.strerror or err)]
    return []


def solution_problems(launch, args, environment, wrap=list):
    """Sentences saying why roslaunch could not start the solution; [] when it can.

    launch: [PACKAGE, LAUNCH_FILE], or [the launch file's path]; args: its
    ARG:=VALUE words; environment: the one the cases give the solution;
    wrap: the command the launch file is loaded with, as the cases wrap the
    solution's (its sandbox). The package is looked for in the child too:
    a launch file is found through the process's own environment (catkin's
    workspaces), which must be the solution's.
    """
    group = ProcessGroup('%d-check-%s' % (os.getpid(), uuid.uuid4().hex), grace=1.0)
    # Run by its path: the solution's environment may hold a package of its own named
    # wall_follower.
    command = wrap([sys.executable, launch_check.__file__] + list(launch) + ['--']
                   + list(args))
    with tempfile.TemporaryFile(mode='w+') as output:
        process = group.start(command, environment, output)
        try:
            process.wait(timeout=LOAD_LIMIT)
        except subprocess.TimeoutExpired:
            return ['the launch file %s did not load within %.0f s'
                    % (' '.join(launch), LOAD_LIMIT)]
        finally:
            group.stop()
        output.seek(0)
        lines = [line.strip() for line in output.read().splitlines() if line.strip()]
    problems = [line[len(PROBLEM):] for line in lines if line.startswith(PROBLEM)]
    if process.returncode != 0 and not problems:
        problems = ['the launch file %s could not be checked (exit %d): %s' % (
            ' '.join(launch), process.returncode, ' / '.join(lines[-3:]))]
    return problems
