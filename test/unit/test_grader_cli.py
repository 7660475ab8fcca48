"""grade's command line without running a case: how a solution is started, --list,
--collect, and a case's processes ended however they hid."""
import json
import os
import subprocess

import pytest

from wall_follower.evaluation import grader
from wall_follower.evaluation.processes import ProcessGroup, marked_processes

SOLUTIONS = os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, 'solutions')


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
                                   ['/no/such/file.launch']])
def test_what_is_no_solution_is_refused(words):
    with pytest.raises(ValueError):
        grader.Solution(words)


def test_list_prints_one_command_per_case(capsys, tmp_path):
    out = str(tmp_path / 'grades')
    assert grader.main(['pkg', 'x.launch', 'rate:=2', '--worlds', '3', '--seed', '4',
                        '--laser', 'lds01', '--out', out, '--list']) == 0
    lines = capsys.readouterr().out.splitlines()
    assert len(lines) == 3
    for index, line in enumerate(lines):
        words = line.split()
        assert words[:6] == ['rosrun', 'wall_follower', 'grade', 'pkg', 'x.launch', 'rate:=2']
        options = grader.parser().parse_args(words[3:])
        got = (options.case, options.seed, options.laser, options.out)
        assert got == (index, 4, 'lds01', out)


def test_collect_builds_the_report_from_the_records(tmp_path, capsys):
    cases = tmp_path / 'cases'
    cases.mkdir()
    (cases / 'gen_s0_000.json').write_text(json.dumps(
        {'name': 'gen_s0_000', 'world': '/w/gen_s0_000.world', 'error': 'it crashed'}))
    (cases / 'gen_s0_001.json').write_text('{"not json')
    assert grader.main(['--collect', str(tmp_path)]) == 0
    grades = json.loads((tmp_path / 'grades.json').read_text())
    assert grades['summary'] == {'cases': 2, 'laps': 0, 'passed': 0}
    assert grades['cases'][0]['reason'] == 'it crashed'
    assert 'no record of this case' in grades['cases'][1]['reason']
    report = (tmp_path / 'report.html').read_text()
    assert report.count('<tr>') == 3 and 'it crashed' in report
    assert 'gen_s0_000' in capsys.readouterr().out


def test_collect_without_cases_fails(tmp_path):
    assert grader.main(['--collect', str(tmp_path)]) == 1


def test_a_case_ends_processes_that_left_its_session():
    group = ProcessGroup('%d-test' % os.getpid())
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
    group.stop(grace=0.5)
    assert marked_processes(group.token) == []
