"""grade --workspace (evaluation/grading/workspace.py): the solution's environment is the
system's ROS and the student's workspace, read in the solution's sandbox, never grade's own;
a directory that is no workspace, or a workspace built on grade's, is refused before any
case."""
import os
import shutil
import tempfile

import pytest

from wall_follower.evaluation.grading import grader, sandbox
from wall_follower.evaluation.grading.workspace import (DEFAULT_PATH, StudentWorkspace,
                                                        WorkspaceError, own_prefixes,
                                                        packages_to_build)

SETUP = '''export ROS_PACKAGE_PATH="{ws}/src:$ROS_PACKAGE_PATH"
export CMAKE_PREFIX_PATH="{prefix}"
export STUDENT_WORKSPACE=sourced
'''


@pytest.fixture
def base():
    """A directory the sandbox's user (nobody, under root) can read."""
    directory = tempfile.mkdtemp(prefix='grade-workspace-test-')
    os.chmod(directory, 0o755)
    yield directory
    shutil.rmtree(directory, ignore_errors=True)


def workspace(base, prefix=None):
    """A built workspace in base whose devel/setup.bash exports what SETUP says."""
    ws = os.path.join(base, 'ws')
    os.makedirs(os.path.join(ws, 'devel'))
    os.makedirs(os.path.join(ws, 'src'))
    with open(os.path.join(ws, 'devel', 'setup.bash'), 'w') as stream:
        stream.write(SETUP.format(ws=ws, prefix=prefix or os.path.join(ws, 'devel')))
    for directory in (ws, os.path.join(ws, 'devel'), os.path.join(ws, 'src')):
        os.chmod(directory, 0o755)
    os.chmod(os.path.join(ws, 'devel', 'setup.bash'), 0o644)
    return ws


@pytest.mark.parametrize('sandboxed', [True, False])
def test_the_solution_environment_is_the_workspaces_never_grades(base, sandboxed):
    ws = workspace(base)
    out = os.path.join(base, 'out')
    os.makedirs(out)
    student = StudentWorkspace(ws, out)
    student.prepare(sandbox.Containment(sandboxed, out).wrap, base)
    env = student.environment
    assert env['STUDENT_WORKSPACE'] == 'sourced'
    assert env['ROS_PACKAGE_PATH'].split(':')[0] == os.path.join(ws, 'src')
    assert env['PATH'] == DEFAULT_PATH
    # Nothing of grade's own environment: its workspace (packages, Python), its master.
    grades = os.environ.get('ROS_PACKAGE_PATH', '').split(':')
    assert not set(grades) & set(env['ROS_PACKAGE_PATH'].split(':')) - {''}
    for prefix in own_prefixes():
        assert prefix not in env.get('PYTHONPATH', '')
    assert 'ROS_MASTER_URI' not in env


def test_a_workspace_built_on_grades_own_is_refused(base):
    own = sorted(own_prefixes())
    if not own:
        pytest.skip('grade runs from no workspace of its own here')
    ws = workspace(base, prefix=':'.join([os.path.join(base, 'ws', 'devel')] + own))
    out = os.path.join(base, 'out')
    os.makedirs(out)
    with pytest.raises(WorkspaceError, match="built on top of grade's own workspace"):
        StudentWorkspace(ws, out).prepare(sandbox.Containment(False, out).wrap, base)


def test_what_is_built_first(base):
    package = os.path.join(base, 'pkg')
    os.makedirs(package)
    open(os.path.join(package, 'package.xml'), 'w').close()
    assert packages_to_build(package) == [package]
    unbuilt = os.path.join(base, 'unbuilt')
    os.makedirs(os.path.join(unbuilt, 'src', 'a'))
    assert packages_to_build(unbuilt) == [os.path.join(unbuilt, 'src', 'a')]
    assert packages_to_build(workspace(base)) is None


def test_a_directory_that_is_no_workspace_is_refused_before_any_case(base, capsys,
                                                                     monkeypatch):
    monkeypatch.setattr(grader, 'run_cases', lambda *args: pytest.fail('a case ran'))
    status = grader.main(['wall_follower', 'main.launch', '--workspace', base, '--no-sandbox',
                          '--out', os.path.join(base, 'out')])
    assert status == 2
    assert 'is no catkin workspace' in capsys.readouterr().err


def test_a_listed_case_keeps_the_workspace_and_the_sandbox_choice():
    options = grader.parser().parse_args(['p', 'l.launch', '--no-sandbox'])
    line = grader.case_command(['p', 'l.launch'], options, 3, '/w/ws')
    assert line.endswith('--workspace /w/ws --no-sandbox')
