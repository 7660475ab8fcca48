"""grade's command line without running a case: how a solution is started, every option and
the solution checked before any case runs, --list, --collect, a case whose own harness failed
reported as the grader's error, and a case's processes ended however they hid."""
import json
import os
import resource
import subprocess
import sys

import pytest

from wall_follower.evaluation.grading import report as grade_report

from wall_follower.evaluation.grading import grader
from wall_follower.evaluation.launching import marked_processes, ProcessGroup
from wall_follower.evaluation.worlds.generator import GenerationError

REPO = os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, os.pardir)
SOLUTIONS = os.path.join(REPO, 'test', 'solutions')
EARLY_LAP = os.path.join(SOLUTIONS, 'early_lap', 'solution.launch')
# A solution that loads: this package's own course.
GOOD = ['wall_follower', 'main.launch']


def test_a_package_and_launch_file_with_arguments():
    solution = grader.Solution(['my_course', 'main.launch', 'laser_x:=-0.032'])
    assert solution.command() == ['roslaunch', '--wait', 'my_course', 'main.launch',
                                  'laser_x:=-0.032']
    assert solution.overlay is None
    assert solution.environment({'A': '1'}, '/nowhere') == {'A': '1'}


def test_a_launch_file_outside_a_package_becomes_one(tmp_path):
    launch = os.path.join(SOLUTIONS, 'early_lap', 'solution.launch')
    solution = grader.Solution([launch])
    env = solution.environment({'ROS_PACKAGE_PATH': '/opt/a'}, str(tmp_path))
    overlay = env['ROS_PACKAGE_PATH'].split(':')[0]
    assert env['ROS_PACKAGE_PATH'].endswith(':/opt/a')
    package = os.path.join(overlay, 'early_lap')
    assert '<name>early_lap</name>' in open(os.path.join(package, 'package.xml')).read()
    assert os.access(os.path.join(package, 'six_metre_recorder.py'), os.X_OK)
    assert solution.command() == ['roslaunch', '--wait', os.path.abspath(launch)]


@pytest.mark.parametrize('words', [[], ['only_a_package'], ['a', 'b', 'c'],
                                   ['/no/such/file.launch'], [EARLY_LAP, 'stray']])
def test_what_is_no_solution_is_refused(words):
    with pytest.raises(ValueError):
        grader.Solution(words)


@pytest.fixture
def no_case_runs(monkeypatch):
    """grade with run_cases made to fail the test: a refusal must come before any case."""
    def run_cases(*_args):
        raise AssertionError('a case was started')
    monkeypatch.setattr(grader, 'run_cases', run_cases)


@pytest.fixture
def solution_loads(monkeypatch):
    """The solution taken as one that loads (its own check is tested apart)."""
    monkeypatch.setattr(grader.Solution, 'problems', lambda self, *args: [])


def refusal(capsys, words):
    """grade's exit status and what it wrote to stderr, for words."""
    status = grader.main(words)
    return status, capsys.readouterr().err


@pytest.mark.parametrize('options, named', [
    (['--worlds', '0'], '--worlds must be at least 1, not 0'),
    (['--jobs', '0'], '--jobs must be at least 1, not 0'),
    (['--timeout', '0'], '--timeout must be a positive number'),
    (['--timeout', '-5'], '--timeout must be a positive number'),
    (['--timeout', 'nan'], '--timeout must be a positive number'),
    (['--start-limit', '0'], '--start-limit must be within 1 .. 600'),
    (['--seed', str(2 ** 80)], '--seed must be within 0 .. 2147483647'),
    (['--seed', '-7'], '--seed must be within 0 .. '),
    (['--speedup', '-1'], '--speedup must be within 0 .. '),
    (['--case', '7', '--worlds', '1'], '--case 7 is not one of the cases of --worlds 1'),
    (['--case', '-1'], '--case -1 is not one of the cases'),
    (['--room', '3', '2'], '--room needs two positive sides [m], the shortest first'),
    (['--room', '0', '2'], '--room needs two positive sides'),
    (['--action-ns', 'record odom'], "--action-ns 'record odom' is not a legal ROS name"),
])
def test_a_bad_option_is_named_before_any_case(capsys, tmp_path, no_case_runs,
                                               solution_loads, options, named):
    status, err = refusal(capsys, GOOD + options + ['--out', str(tmp_path)])
    assert status == 2
    assert named in err
    assert not os.path.exists(os.path.join(str(tmp_path), 'cases'))


def test_every_bad_option_is_named_at_once(capsys, tmp_path, no_case_runs, solution_loads):
    status, err = refusal(capsys, GOOD + ['--worlds', '0', '--jobs', '0', '--timeout', '0',
                                          '--out', str(tmp_path)])
    assert status == 2 and len(err.splitlines()) == 3


def test_an_out_that_is_a_file_is_refused(capsys, tmp_path, no_case_runs, solution_loads):
    afile = tmp_path / 'grades'
    afile.write_text('')
    status, err = refusal(capsys, GOOD + ['--out', str(afile)])
    assert (status, err) == (2, 'grade: --out %s: %s is not a directory\n' % (afile, afile))


def test_an_out_that_cannot_be_made_is_refused(capsys, tmp_path, no_case_runs,
                                               solution_loads):
    afile = tmp_path / 'file'
    afile.write_text('')
    status, err = refusal(capsys, GOOD + ['--out', str(afile / 'grades')])
    assert status == 2 and err.startswith('grade: --out %s: ' % (afile / 'grades'))


@pytest.mark.parametrize('words, named', [
    (['no_such_package', 'main.launch'], 'no package no_such_package on ROS_PACKAGE_PATH'),
    (['wall_follower', 'no_such.launch'], 'no launch file no_such.launch in package '
     'wall_follower'),
    (GOOD + ['lazer_x:=0.1'], 'declares no argument lazer_x'),
    (GOOD + ['_x:=1'], 'roslaunch takes no argument _x:=1'),
    (['wall_follower', 'grade_case.launch'], "does not load: arg 'world' is not defined"),
    ([EARLY_LAP, 'stray'], 'come only ARG:=VALUE arguments, not stray'),
    (GOOD + ['stray'], 'come only ARG:=VALUE arguments, not stray'),
])
@pytest.mark.ros
def test_a_solution_roslaunch_cannot_start_is_named_before_any_case(capsys, tmp_path,
                                                                    no_case_runs, words, named):
    status, err = refusal(capsys, words + ['--out', str(tmp_path)])
    assert status == 2
    assert named in err


def test_a_refused_command_makes_no_out_directory(capsys, tmp_path, no_case_runs,
                                                  solution_loads):
    out = tmp_path / 'new' / 'grades'
    status, _ = refusal(capsys, GOOD + ['--jobs', '0', '--out', str(out)])
    assert status == 2 and os.listdir(str(tmp_path)) == []


@pytest.mark.ros
def test_solutions_that_load_pass_the_check():
    assert grader.Solution(GOOD + ['laser_x:=-0.032']).problems(os.environ) == []
    # Outside any package: its directory is made one, as in a case.
    assert grader.Solution([EARLY_LAP]).problems(os.environ) == []


@pytest.mark.ros
def test_the_grade_command_refuses_an_unknown_package_at_once(tmp_path):
    """As run by a user: a non-zero exit naming the package, with no case started. The
    time bound is on the CPU time grade spends (wall time on a loaded machine is not its)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    process = subprocess.run([sys.executable, os.path.join(REPO, 'scripts', 'grade'),
                              'no_such_package', 'main.launch', '--out', str(tmp_path)],
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                             universal_newlines=True, timeout=60)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    spent = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    assert process.returncode == 2
    assert 'no package no_such_package' in process.stderr
    assert spent < 5.0
    assert os.listdir(str(tmp_path)) == []


def test_a_room_no_world_fits_is_refused_before_any_case(capsys, tmp_path, monkeypatch,
                                                         solution_loads):
    def generate(seed, index, settings):
        raise GenerationError('seed %d, world %d: no layout passed the checks' % (seed, index))
    monkeypatch.setattr(grader, 'generate', generate)
    monkeypatch.setattr(grader.CaseRunner, 'run', lambda *args: pytest.fail('a case ran'))
    status, err = refusal(capsys, GOOD + ['--room', '0.5', '0.6', '--out', str(tmp_path)])
    assert status == 2
    assert err == 'grade: --room 0.5 0.6: seed 0, world 0: no layout passed the checks\n'


@pytest.mark.ros
def test_list_prints_one_command_per_case(capsys, tmp_path):
    out = str(tmp_path / 'grades')
    assert grader.main(GOOD + ['laser_x:=-0.032', '--worlds', '12', '--seed', '4',
                               '--laser', 'lds01', '--out', out, '--list']) == 0
    lines = capsys.readouterr().out.splitlines()
    assert len(lines) == 12
    for index, line in enumerate(lines):
        words = line.split()
        assert words[:6] == ['rosrun', 'wall_follower', 'grade'] + GOOD + ['laser_x:=-0.032']
        options = grader.parser().parse_args(words[3:])
        got = (options.case, options.worlds, options.seed, options.laser, options.out)
        assert got == (index, 12, 4, 'lds01', out)
        assert grader.grade_options.option_problems(options) == []


def _harness(monkeypatch, ended):
    """Cases whose processes are not started: each ends as `ended` says, with no record."""
    monkeypatch.setattr(grader.CaseRunner, '_run_processes', lambda *args: ended)


def test_a_case_whose_harness_failed_is_the_graders_error(capsys, tmp_path, monkeypatch,
                                                          solution_loads):
    _harness(monkeypatch, ('its master did not start', True))
    out = str(tmp_path)
    assert grader.main(GOOD + ['--worlds', '1', '--out', out]) == grade_report.NOT_GRADED
    grades = json.loads((tmp_path / 'grades.json').read_text())
    assert grades['summary'] == {'cases': 1, 'laps': 0, 'passed': 0, 'not_graded': 1}
    (case,) = grades['cases']
    assert case['grader_error'].startswith('the case wrote no record (its master did not start')
    assert case['reason'].startswith('not graded: the grader failed (')
    assert 'NOT GRADED: the grader itself failed' in capsys.readouterr().out


def test_one_case_whose_harness_failed_exits_non_zero(tmp_path, monkeypatch, solution_loads):
    _harness(monkeypatch, ('its master did not start', True))
    assert grader.main(GOOD + ['--case', '1', '--out', str(tmp_path)]) == grade_report.NOT_GRADED


def test_a_case_out_of_wall_time_is_the_solutions(tmp_path, monkeypatch, solution_loads):
    _harness(monkeypatch, ('it ran out of its 900 wall seconds', False))
    assert grader.main(GOOD + ['--worlds', '1', '--out', str(tmp_path)]) == 0
    (case,) = json.loads((tmp_path / 'grades.json').read_text())['cases']
    assert case['grader_error'] is None
    assert 'it ran out of its 900 wall seconds' in case['reason']


def test_collect_builds_the_report_from_the_records(tmp_path, capsys):
    cases = tmp_path / 'cases'
    cases.mkdir()
    (cases / 'gen_s0_000.json').write_text(json.dumps(
        {'name': 'gen_s0_000', 'world': '/w/gen_s0_000.world', 'error': 'it crashed'}))
    (cases / 'gen_s0_001.json').write_text('{"not json')
    # A case with no whole record is not graded: the grader's failure, not the solution's.
    assert grader.main(['--collect', str(tmp_path)]) == grade_report.NOT_GRADED
    grades = json.loads((tmp_path / 'grades.json').read_text())
    assert grades['summary'] == {'cases': 2, 'laps': 0, 'passed': 0, 'not_graded': 1}
    assert grades['cases'][0]['reason'] == 'it crashed'
    assert grades['cases'][1]['reason'].startswith(
        'not graded: the grader failed (no record of this case')
    report = (tmp_path / 'report.html').read_text()
    assert report.count('<tr class="case"') == 2 and 'it crashed' in report
    assert 'gen_s0_000' in capsys.readouterr().out


def test_collect_of_no_directory_is_refused(capsys, tmp_path):
    status, err = refusal(capsys, ['--collect', str(tmp_path / 'none')])
    assert (status, err) == (2, 'grade: --collect %s: no such directory\n' % (tmp_path / 'none'))


def test_collect_without_cases_fails(tmp_path):
    assert grader.main(['--collect', str(tmp_path)]) == 1


def test_a_case_ends_processes_that_left_its_session():
    group = ProcessGroup('%d-test' % os.getpid(), grace=0.5)
    # A shell that starts a process in a session of its own (as roslaunch does
    # its nodes), which ignores SIGINT, and then waits for ever itself.
    script = 'setsid sh -c "trap \\"\\" INT; sleep 300" & sleep 300'
    with open(os.devnull, 'w') as log:
        group.start(['sh', '-c', script], dict(os.environ), log)
    deadline = 50
    while len(marked_processes(group.token)) < 4 and deadline:
        subprocess.call(['sleep', '0.1'])
        deadline -= 1
    assert len(marked_processes(group.token)) >= 3
    group.stop()
    assert marked_processes(group.token) == []


def test_without_a_sandbox_grade_refuses_unless_told(capsys, tmp_path, monkeypatch,
                                                     solution_loads):
    monkeypatch.setattr(grader.sandbox, 'sandbox_problems',
                        lambda scratch: ['no sandbox: bubblewrap cannot make one here (x)'])
    monkeypatch.setattr(grader, 'run_cases', lambda *args: [])
    status, err = refusal(capsys, GOOD + ['--case', '0', '--out', str(tmp_path)])
    assert status == 2 and 'no sandbox: bubblewrap cannot make one here' in err
    # Told: it grades (no case is run here), with no sandbox.
    ran = []
    monkeypatch.setattr(grader, 'run_cases', lambda *args: ran.append(args[3]) or [])
    monkeypatch.setattr(grader.grade_report, 'print_table',
                        lambda records: {'summary': {'not_graded': 0}})
    assert grader.main(GOOD + ['--case', '0', '--no-sandbox', '--out', str(tmp_path)]) == 0
    assert not ran[0].sandboxed
