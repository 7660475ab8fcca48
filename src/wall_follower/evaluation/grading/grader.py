"""`rosrun wall_follower grade PACKAGE LAUNCH_FILE [ARG:=VALUE ...]`: a course solution graded.

The solution's launch file (PACKAGE LAUNCH_FILE, or a launch file's path)
starts the course nodes only, as the course has students start the
simulation first: per case, the grader makes a world (world_generator,
from --seed and the case's number), starts a master of the case's own on a
free port, the simulator (launch/grade_case.launch, paused, in lockstep,
with the course robot's interface: scan in --laser, odom, cmd_vel) and the
grade_case node that scores the run from ground truth, then the solution's
launch file. When the case has ended, every process it started is ended
(evaluation.launching.ProcessGroup), in the case's own sandbox (grading/sandbox.py: its
namespaces end every process of it; the solution runs read-only and
unprivileged within). With --workspace the solution runs in the student's
own workspace's clean environment (grading/workspace.py), never in
grade's. Each case is one independent command (--list
prints them, --case K runs one), so a batch system can spread a class over
many machines; --collect DIR then builds the report from the finished
cases (--collect DIR1 DIR2 ..., the class page too: class_report.py).

What a case is depends on the task (--task): the course's (CourseTask
below: a generated room, grade_case.launch) or a line follower's
(line_task.LineTask: a generated line course and camera, line_case.launch);
CaseRunner runs either.

A launch file given by its path, in a directory that is no package's
root, is run with that directory as a package named like the directory
(made for the run in a temporary overlay), so that a solution kept outside
any catkin workspace can name its scripts pkg="<that directory's name>".

Before any case runs, every option and the solution itself are checked
(evaluation/grading/options.py): a mistake in how grade is called ends it at
once with exit status 2. A case whose own harness fails (its master, the
simulator or the grade_case node does not start, or its record cannot be
written) is the grader's error, not the solution's: its record holds
'grader_error', grading gives it no verdict, and grade exits with status 3.
"""
import json
import os
import shlex
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
from concurrent.futures import ThreadPoolExecutor

import rospkg

from wall_follower.control.motion import MAX_LINEAR
from wall_follower.evaluation.grading import class_report
from wall_follower.evaluation.grading import options as grade_options
from wall_follower.evaluation.grading import report as grade_report
from wall_follower.evaluation.grading import sandbox
from wall_follower.evaluation.grading.line_task import LineTask
from wall_follower.evaluation.grading.options import parser, room_of
from wall_follower.evaluation.grading.workspace import StudentWorkspace, WorkspaceError
from wall_follower.evaluation.launching import ProcessGroup, display_wrapper, free_port
from wall_follower.evaluation.worlds.generator import (GenerationError, Settings, free_space_of,
                                                       generate, world_name, write_world)

# Simulated seconds a case may last without a lap: a start, then two laps of the
# world's walls at the speed bound.
LAP_ALLOWANCE = (30.0, 2.0)
# Wall seconds a case's sandbox has, beyond --timeout, to start and to end.
SANDBOX_MARGIN = 60.0
_PACKAGE_XML = """<?xml version="1.0"?>
<package format="2">
  <name>{name}</name>
  <version>0.0.0</version>
  <description>A course solution under grading (made by wall_follower's grade).</description>
  <maintainer email="grade@localhost">grade</maintainer>
  <license>none</license>
  <buildtool_depend>catkin</buildtool_depend>
</package>
"""


class Solution(object):
    """How to start a solution: roslaunch's arguments, and the package path it needs."""

    def __init__(self, words):
        launch = [w for w in words if ':=' not in w]
        self.args = [w for w in words if ':=' in w]
        self.words = list(words)
        self.overlay = None
        if launch and launch[0].endswith('.launch'):
            if len(launch) > 1:
                raise ValueError('after the launch file %s come only ARG:=VALUE arguments, '
                                 'not %s' % (launch[0], ' '.join(launch[1:])))
            path = os.path.abspath(launch[0])
            if not os.path.isfile(path):
                raise ValueError('no launch file %s' % launch[0])
            self.launch = [path]
            if not os.path.isfile(os.path.join(os.path.dirname(path), 'package.xml')):
                self.overlay = os.path.dirname(path)
        elif len(launch) == 2:
            self.launch = launch
        elif len(launch) > 2:
            raise ValueError('after PACKAGE LAUNCH_FILE (%s %s) come only ARG:=VALUE arguments, '
                             'not %s' % (launch[0], launch[1], ' '.join(launch[2:])))
        else:
            raise ValueError('expected PACKAGE LAUNCH_FILE or a .launch path, then ARG:=VALUE '
                             'arguments; got %s' % (' '.join(words) or 'nothing'))

    def problems(self, base, preparation=None):
        """Why roslaunch could not start the solution in environment base (as the cases
        give it, see Preparation); [] when it can."""
        preparation = preparation or Preparation(sandbox.Containment(False, '.'))
        scratch = tempfile.mkdtemp(prefix='grade-check-')
        try:
            wrap, env = preparation.solution_launch(self, base, scratch, network=False)
            return grade_options.solution_problems(self.launch, self.args, env, wrap)
        finally:
            shutil.rmtree(scratch, ignore_errors=True)

    def command(self):
        return ['roslaunch', '--wait'] + self.launch + self.args

    def environment(self, base, scratch):
        """base, with the solution's directory made a package under scratch if it needs one."""
        if self.overlay is None:
            return dict(base)
        name = os.path.basename(self.overlay.rstrip('/'))
        package = os.path.join(scratch, 'overlay', name)
        if not os.path.isdir(package):
            os.makedirs(package)
            with open(os.path.join(package, 'package.xml'), 'w') as out:
                out.write(_PACKAGE_XML.format(name=name))
            for entry in os.listdir(self.overlay):
                os.symlink(os.path.join(self.overlay, entry), os.path.join(package, entry))
        paths = [os.path.join(scratch, 'overlay')] + [
            p for p in base.get('ROS_PACKAGE_PATH', '').split(':') if p]
        return dict(base, ROS_PACKAGE_PATH=':'.join(paths))


class Preparation(object):
    """What every case of one grading shares: its sandboxes (containment: a
    sandbox.Containment, enabled or not) and the student's workspace (a prepared
    workspace.StudentWorkspace, or None: the solution then runs in grade's environment)."""

    def __init__(self, containment, workspace=None):
        self.containment = containment
        self.workspace = workspace

    @property
    def sandboxed(self):
        return self.containment.enabled

    def harness_environment(self, base):
        """grade's own processes of a case: grade's environment, on the case's loopback."""
        return dict(base, **sandbox.LOOPBACK_ENVIRONMENT) if self.sandboxed else dict(base)

    def solution_launch(self, solution, base, scratch, network=True):
        """(wrap, env): how the solution's processes start, whose master is base's.

        env: the student's clean environment (with --workspace) or grade's
        (base), with ROS_MASTER_URI of base; in a sandbox, a private HOME
        and ROS_HOME in scratch. wrap: command -> the command in its sandbox.
        """
        private = os.path.join(scratch, 'solution')
        os.makedirs(private, exist_ok=True)
        if self.workspace is not None:
            env = dict(self.workspace.environment)
            if 'ROS_MASTER_URI' in base:
                env['ROS_MASTER_URI'] = base['ROS_MASTER_URI']
            env.update(HOME=private, ROS_HOME=os.path.join(private, '.ros'))
        else:
            env = dict(base)
        env = solution.environment(env, scratch)
        if not self.sandboxed:
            return list, env
        env.update(sandbox.LOOPBACK_ENVIRONMENT, HOME=private,
                   ROS_HOME=os.path.join(private, '.ros'))
        visible = sandbox.needed_paths(env) + [os.path.dirname(p) for p in solution.launch
                                               if os.path.isabs(p)]
        if solution.overlay:
            visible += [solution.overlay, os.path.join(scratch, 'overlay')]
        # The launch file's check runs grade's launch_check.py by its path.
        visible.append(os.path.dirname(os.path.abspath(grade_options.launch_check.__file__)))
        wrap = self.containment.wrap
        if self.workspace is not None:
            wrap = self.workspace.wrapper(wrap)
        return wrap(private, visible=visible, network=network), env


def prepare(options):
    """The Preparation of a grading, checked: (preparation, problems in words).

    The sandbox is tried (unless --no-sandbox), then --workspace made
    ready: built when it is a package, its environment read.
    """
    scratch = tempfile.mkdtemp(prefix='grade-prepare-')
    try:
        enabled = not options.no_sandbox
        if enabled:
            problems = sandbox.sandbox_problems(scratch)
            if problems:
                return None, problems
        preparation = Preparation(sandbox.Containment(enabled, options.out))
        if options.workspace:
            workspace = StudentWorkspace(options.workspace, options.out)
            try:
                workspace.prepare(preparation.containment.wrap, scratch)
            except (WorkspaceError, OSError) as err:
                return None, [str(err)]
            preparation.workspace = workspace
        return preparation, []
    finally:
        shutil.rmtree(scratch, ignore_errors=True)


def case_paths(out, name):
    cases = os.path.join(out, 'cases')
    return {key: os.path.join(cases, name + suffix)
            for key, suffix in (('json', '.json'), ('plot', '.png'), ('log', '.log'),
                                ('solution_log', '.solution.log'))}


def lap_limit(world):
    """Simulated seconds a case in world may last without a lap (see LAP_ALLOWANCE)."""
    space = free_space_of(world)
    walls = len(space.wall_pixels()[0]) * space.pixel
    return LAP_ALLOWANCE[0] + LAP_ALLOWANCE[1] * walls / MAX_LINEAR


class CourseTask(object):
    """The course task's cases (find_wall, record_odom, the follower, in generated rooms), for
    CaseRunner; the line task's are line_task.LineTask's."""

    name = 'course'
    launch_file = 'grade_case.launch'
    default_room = Settings().room

    def __init__(self, seed, room, out, laser, action_ns):
        self.seed = seed
        self.room = tuple(room)
        self.out = out
        self.laser = laser
        self.action_ns = action_ns

    def generate(self, index):
        return generate(self.seed, index, Settings(room=self.room))

    def case_name(self, index):
        return world_name(self.seed, index)

    def write(self, world, index):
        """Write the case's world into OUT/worlds/; its path."""
        include = os.path.join(rospkg.RosPack().get_path('wall_follower'), 'worlds', 'burger.inc')
        return write_world(world, os.path.join(self.out, 'worlds'), include, self.seed, index)

    def case_args(self, world):
        """grade_case.launch's arguments of the task's own (beside the harness's common ones)."""
        return {'laser_profile': self.laser, 'action_ns': self.action_ns,
                'time_limit': '%.0f' % lap_limit(world)}

    def notes(self):
        """What a case record of the task notes of how it ran."""
        return {'laser': self.laser}


def task_of(options):
    """The task options name, on options' seed, room and --out."""
    if options.task == 'line':
        return LineTask(options.seed, room_of(options), options.out)
    return CourseTask(options.seed, room_of(options), options.out, options.laser,
                      options.action_ns)


class CaseRunner(object):
    """Runs cases of one grading; stop_all() ends every case still running."""

    def __init__(self, solution, options, preparation):
        self.solution = solution
        self.options = options
        self.preparation = preparation
        self.task = task_of(options)
        # Real stageros runs paced only in its window (see sim/simulator_choice.py).
        self.wrapper = (display_wrapper() or []) if options.simulator == 'stage' else []
        self._running = set()
        self._lock = threading.Lock()
        self._stopping = False

    def run(self, index, world):
        """Run case index in world (generated); returns its record, None once stopping.

        The record holds 'grader_error' when the case's own harness failed,
        'error' when the case ran out of wall time before a record was written.
        """
        options = self.options
        paths = case_paths(options.out, world.name)
        group = ProcessGroup()
        with self._lock:
            if self._stopping:
                return None
            self._running.add(group)
        scratch = tempfile.mkdtemp(prefix='grade-')
        try:
            world_file = self._prepare(world, index, paths)
            port = free_port()
            base = dict(os.environ, ROS_MASTER_URI='http://localhost:%d' % port)
            ended, harness_failed = self._run_processes(group, base, port, world_file, paths,
                                                        self.task.case_args(world), scratch)
        except OSError as err:
            world_file = None
            ended, harness_failed = 'grade could not start it: %s' % err, True
        finally:
            group.stop()
            shutil.rmtree(scratch, ignore_errors=True)
            with self._lock:
                self._running.discard(group)
        record = grade_report.read_record(paths['json'])
        if record is None:
            record = {'grader_error' if harness_failed else 'error':
                      'the case wrote no record (%s; see %s)' % (ended, paths['log'])}
        record.update(self.task.notes(), name=world.name, task=self.task.name, world=world_file,
                      index=index, seed=options.seed,
                      solution_command=' '.join(self.solution.words),
                      plot=paths['plot'] if os.path.exists(paths['plot']) else None)
        try:
            with open(paths['json'], 'w') as stream:
                json.dump(record, stream, indent=1)
        except (IOError, OSError) as err:
            record['grader_error'] = 'its record could not be written to %s: %s' % (
                paths['json'], err)
        return record

    def _prepare(self, world, index, paths):
        """Write the case's world file, and clear what an earlier run of it left; its path."""
        world_file = self.task.write(world, index)
        os.makedirs(os.path.dirname(paths['json']), exist_ok=True)
        for stale in (paths['json'], paths['plot']):
            if os.path.exists(stale):
                os.unlink(stale)
        return world_file

    def _run_processes(self, group, base, port, world_file, paths, task_args, scratch):
        """Start the case's processes and wait for its end (sandbox.hold), in the case's
        sandbox unless there is none.

        Returns how it ended, in words, and whether the case's own harness
        (its master, simulator and case node: the task's launch file,
        grade_case.launch or line_case.launch) is what ended it: that launch
        ends by itself only once its case node has ended, which writes the
        record first unless the harness failed.
        """
        options = self.options
        case_args = dict(task_args, world=world_file, json=paths['json'], plot=paths['plot'],
                         simulator=options.simulator, seed=str(options.seed),
                         speedup=str(options.speedup), lockstep='true', paused='true',
                         start_limit=str(options.start_limit))
        grading = self.wrapper + ['roslaunch', '-p', str(port), 'wall_follower',
                                  self.task.launch_file] + [
            '%s:=%s' % item for item in sorted(case_args.items())]
        wrap, solution_env = self.preparation.solution_launch(self.solution, base, scratch)
        spec = {'harness': grading, 'harness_env': self.preparation.harness_environment(base),
                'port': port, 'solution': wrap(self.solution.command()),
                'solution_env': solution_env, 'timeout': options.timeout,
                'log': paths['log'], 'solution_log': paths['solution_log'],
                'token': group.token}
        for name in ('log', 'solution_log'):
            open(paths[name], 'w').close()
        if not self.preparation.sandboxed:
            return sandbox.hold(spec, group)
        return self._hold_in_sandbox(group, spec, scratch)

    def _hold_in_sandbox(self, group, spec, scratch):
        """sandbox.hold, as the first process of the case's own namespaces."""
        spec_file, outcome_file = (os.path.join(scratch, name)
                                   for name in ('case.json', 'outcome.json'))
        with open(spec_file, 'w') as stream:
            json.dump(spec, stream)
        command = sandbox.case_command([sys.executable, '-m', sandbox.__name__, 'hold',
                                        spec_file, outcome_file])
        with open(spec['log'], 'a') as log:
            process = group.start(command, spec['harness_env'], log)
            try:
                process.wait(timeout=spec['timeout'] + SANDBOX_MARGIN)
            except subprocess.TimeoutExpired:
                return 'it ran out of its %.0f wall seconds' % spec['timeout'], False
        outcome = grade_report.read_record(outcome_file)
        if outcome is None:
            return "the case's sandbox ended (exit %d) without saying how the case ended" % (
                process.returncode), True
        return outcome['ended'], outcome['harness_failed']

    def stop_all(self):
        with self._lock:
            self._stopping = True
            running = list(self._running)
        for group in running:
            group.stop()


def case_command(solution_words, options, index, workspace=None):
    """The command line of one case, for --list (workspace: the one the cases use)."""
    task = ['--laser', options.laser, '--action-ns', options.action_ns] \
        if options.task == 'course' else ['--task', options.task]
    room = room_of(options)
    words = ['rosrun', 'wall_follower', 'grade'] + list(solution_words) + task + [
        '--worlds', str(options.worlds), '--seed', str(options.seed), '--case', str(index),
        '--speedup', str(options.speedup),
        '--timeout', str(options.timeout), '--start-limit', str(options.start_limit),
        '--simulator', options.simulator,
        '--room', str(room[0]), str(room[1]), '--out', options.out]
    if workspace:
        words += ['--workspace', workspace]
    if options.no_sandbox:
        words.append('--no-sandbox')
    return ' '.join(shlex.quote(w) for w in words)


def _interrupt(_number, _frame):
    raise KeyboardInterrupt


def main(argv=None):
    """grade's command line; its exit status: 0 graded (whatever the grades), 2 a mistake in
    the command (nothing ran), 3 a case the grader itself failed to grade, 130 interrupted."""
    options = parser().parse_args(argv)
    problems = grade_options.option_problems(options)
    if options.collect:
        return _refused(problems) if problems else class_report.collect_all(options.collect,
                                                                            options.out)
    options.out = os.path.abspath(options.out)
    try:
        solution = Solution(options.solution)
    except ValueError as err:
        return _refused(problems + [str(err)])
    if problems:
        return _refused(problems)
    made = not os.path.isdir(options.out)
    # The sandboxes hide it, so it must be there first.
    os.makedirs(options.out, exist_ok=True)
    preparation, problems = prepare(options)
    if not problems:
        problems = solution.problems(os.environ, preparation)
    if problems:
        if made and not os.listdir(options.out):
            os.rmdir(options.out)
        return _refused(problems)
    if options.list:
        workspace = preparation.workspace.directory if preparation.workspace else None
        for index in range(options.worlds):
            print(case_command(options.solution, options, index, workspace))
        return 0
    indices = [options.case] if options.case is not None else list(range(options.worlds))
    try:
        records = run_cases(solution, options, indices, preparation)
    except GenerationError as err:
        return _refused(['--room %g %g: %s' % (tuple(room_of(options)) + (err,))])
    if records is None:
        sys.stderr.write('grade: interrupted; every case it started has ended\n')
        return 130
    if options.case is not None:
        graded = grade_report.print_table(records)
        return grade_report.NOT_GRADED if graded['summary']['not_graded'] else 0
    task = task_of(options)
    return grade_report.collect(options.out, [task.case_name(i) for i in indices])


def _refused(problems):
    for problem in problems:
        sys.stderr.write('grade: %s\n' % problem)
    return 2


def run_cases(solution, options, indices, preparation=None):
    """The records of cases indices, options.jobs at a time; None when interrupted.

    preparation: prepare()'s; by default, the sandbox where one can be had
    and the solution in grade's environment. Every case's world is
    generated first (GenerationError, before any case runs, when --room
    allows none). SIGINT or SIGTERM ends every case still running (and
    every process it started) before this returns.
    """
    if preparation is None:
        preparation = _default_preparation(options)
    runner = CaseRunner(solution, options, preparation)
    previous = signal.signal(signal.SIGTERM, _interrupt)
    pool = ThreadPoolExecutor(max_workers=max(1, options.jobs))
    try:
        worlds = [runner.task.generate(index) for index in indices]
        futures = [pool.submit(runner.run, index, world) for index, world in zip(indices, worlds)]
        return [future.result() for future in futures]
    except KeyboardInterrupt:
        runner.stop_all()
        return None
    finally:
        pool.shutdown(wait=True)
        signal.signal(signal.SIGTERM, previous)


def _default_preparation(options):
    """A sandbox where one can be had (said on stderr where not), grade's environment."""
    enabled = not getattr(options, 'no_sandbox', False)
    if enabled:
        scratch = tempfile.mkdtemp(prefix='grade-prepare-')
        try:
            problems = sandbox.sandbox_problems(scratch)
        finally:
            shutil.rmtree(scratch, ignore_errors=True)
        for problem in problems:
            sys.stderr.write('grade: %s: the cases run without one\n' % problem)
        enabled = not problems
    return Preparation(sandbox.Containment(enabled, options.out))
