"""`grade --task line` without running a simulation: its options, --list, what a case starts
and writes, and the README's batch lines, which must be the commands grade itself prints."""
import json
import os
import re
import shlex

import pytest

from test_grader_cli import no_case_runs, solution_loads  # noqa: F401 (fixtures)
from wall_follower.evaluation.grading import grader
from wall_follower.evaluation.grading import report as grade_report

REPO = os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, os.pardir)
LINE = ['--task', 'line', 'wall_follower', 'line_following.launch']


@pytest.mark.usefixtures('no_case_runs', 'solution_loads')
@pytest.mark.parametrize('options, named', [
    (['--laser', 'lds01'], '--laser is an option of --task course, not of --task line'),
    (['--action-ns', 'odom_ns'], '--action-ns is an option of --task course, not of --task line'),
])
def test_the_course_tasks_options_are_refused_for_the_line_task(capsys, tmp_path, options, named):
    assert grader.main(LINE + options + ['--out', str(tmp_path)]) == 2
    assert named in capsys.readouterr().err


@pytest.mark.usefixtures('solution_loads')
def test_a_room_no_line_course_fits_is_refused_before_any_case(capsys, tmp_path, monkeypatch):
    monkeypatch.setattr(grader.CaseRunner, 'run', lambda *args: pytest.fail('a case ran'))
    assert grader.main(LINE + ['--room', '0.5', '0.6', '--out', str(tmp_path)]) == 2
    assert capsys.readouterr().err.startswith(
        'grade: --room 0.5 0.6: seed 0, line course 0 (loop): no draw passed the checks')


@pytest.mark.ros
def test_list_prints_one_line_case_per_course(capsys, tmp_path):
    out = str(tmp_path / 'grades')
    assert grader.main(LINE + ['controller:=pixel_p', '--worlds', '4', '--seed', '3',
                               '--out', out, '--list']) == 0
    lines = capsys.readouterr().out.splitlines()
    assert len(lines) == 4
    for index, line in enumerate(lines):
        words = shlex.split(line)
        assert words[:8] == ['rosrun', 'wall_follower', 'grade', 'wall_follower',
                             'line_following.launch', 'controller:=pixel_p', '--task', 'line']
        assert '--laser' not in words and '--action-ns' not in words
        options = grader.parser().parse_args(words[3:])
        assert (options.task, options.case, options.worlds, options.seed, options.out) == (
            'line', index, 4, 3, out)
        assert grader.room_of(options) == (1.6, 3.0)
        assert grader.grade_options.option_problems(options) == []


@pytest.mark.usefixtures('solution_loads')
def test_a_line_case_runs_its_own_harness_on_the_course_it_wrote(tmp_path, monkeypatch):
    started = []

    def run_processes(self, group, base, port, world_file, paths, task_args, scratch):
        started.append((self.task.launch_file, world_file, task_args))
        return 'its master did not start', True
    monkeypatch.setattr(grader.CaseRunner, '_run_processes', run_processes)
    out = str(tmp_path)
    assert grader.main(LINE + ['--worlds', '3', '--case', '2', '--out', out]) == \
        grade_report.NOT_GRADED
    ((launch, world, args),) = started
    assert launch == 'line_case.launch'
    assert world == os.path.join(out, 'worlds', 'line_s0_002.world')
    for name in ('line_s0_002.course.yaml', 'line_s0_002_line.png', 'waffle.inc',
                 'burger.inc'):
        assert os.path.isfile(os.path.join(out, 'worlds', name)), name
    assert args['lockstep_timeout'] == '10' and float(args['time_limit']) > 30.0
    with open(os.path.join(out, 'cases', 'line_s0_002.json')) as stream:
        record = json.load(stream)
    assert record['task'] == 'line' and 'laser' not in record
    graded = grade_report.LineSheet.grades([record])
    assert graded['summary']['not_graded'] == 1


def _readme():
    with open(os.path.join(REPO, 'README.md')) as stream:
        return stream.read()


def test_the_readmes_slurm_line_runs_the_command_grade_lists(capsys):
    """The job array's command is --list's, with the case's number from Slurm."""
    (line,) = [line for line in _readme().splitlines() if line.startswith('sbatch --array=')]
    array, command = re.match(r"sbatch --array=0-(\d+) .*--wrap '(.*)'$", line).groups()
    words = shlex.split(command.replace('$SLURM_ARRAY_TASK_ID', '0'))
    assert words[:3] == ['rosrun', 'wall_follower', 'grade']
    options = grader.parser().parse_args(words[3:])
    assert int(array) == options.worlds - 1 and '--case $SLURM_ARRAY_TASK_ID ' in command
    assert grader.case_command(options.solution, options, 0) == ' '.join(
        shlex.quote(word) for word in words)
