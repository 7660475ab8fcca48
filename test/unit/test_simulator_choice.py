"""The rule that picks the simulator, for every simulator x gui x stage_ros installed.

Real stageros is paced only in its window, so it is picked only with gui;
`auto` falls back to the built-in simulator, `stage` refuses. Checked twice:
the rule itself, and stage_sim's hand-over run as a process, with a fake
stage_ros package (a `stageros` that only says how it was called) on
ROS_PACKAGE_PATH or not.
"""
import os
import stat
import subprocess
import sys

import pytest

from wall_follower.sim.simulator_choice import BUILTIN, STAGE, choose_simulator

STAGE_SIM = os.path.join(os.path.dirname(__file__), '..', '..', 'scripts', 'stage_sim')
FAKE_STAGEROS_SAYS = 'fake stageros called with:'
MISSING_WORLD = '/nonexistent/simulator_choice.world'

# (simulator, gui, stage_ros installed) -> what runs; None = refused.
RULE = {
    ('builtin', False, False): BUILTIN,
    ('builtin', False, True): BUILTIN,
    ('builtin', True, False): BUILTIN,
    ('builtin', True, True): BUILTIN,
    ('auto', False, False): BUILTIN,
    ('auto', False, True): BUILTIN,
    ('auto', True, False): BUILTIN,
    ('auto', True, True): STAGE,
    ('stage', False, False): None,
    ('stage', False, True): None,
    ('stage', True, False): None,
    ('stage', True, True): STAGE,
}


@pytest.mark.parametrize('combination', sorted(RULE))
def test_rule(combination):
    choice = choose_simulator(*combination)
    assert choice.simulator == RULE[combination]
    assert bool(choice.error) == (RULE[combination] is None)


def test_refusals_say_why_and_what_to_do():
    headless = choose_simulator('stage', False, True).error
    assert 'gui:=true' in headless and 'cannot be paced' in headless
    missing = choose_simulator('stage', True, False).error
    assert 'stage_ros' in missing and 'not installed' in missing


def test_auto_says_why_it_passed_real_stage_over():
    assert 'gui:=true' in choose_simulator('auto', False, True).note


def test_unknown_simulator_is_refused():
    assert choose_simulator('gazebo', True, True).error


@pytest.fixture(scope='module')
def fake_stage_ros(tmp_path_factory):
    """A package path holding a stage_ros whose stageros prints its arguments."""
    root = tmp_path_factory.mktemp('packages')
    package = root / 'stage_ros'
    package.mkdir()
    (package / 'package.xml').write_text(
        '<?xml version="1.0"?>\n<package format="2"><name>stage_ros</name>'
        '<version>1.8.0</version><description>fake</description>'
        '<maintainer email="none@example.com">none</maintainer><license>BSD</license>'
        '</package>\n')
    stageros = package / 'stageros'
    stageros.write_text('#!/bin/sh\necho "%s $*"\n' % FAKE_STAGEROS_SAYS)
    stageros.chmod(stageros.stat().st_mode | stat.S_IXUSR)
    empty = root / 'empty'
    empty.mkdir()
    return {True: str(root), False: str(empty)}


def run_stage_sim(package_path, simulator, gui):
    """stage_sim's exit status and output, with only package_path to find packages in."""
    env = dict(os.environ, ROS_PACKAGE_PATH=package_path, CMAKE_PREFIX_PATH='')
    command = [sys.executable, STAGE_SIM, '--simulator', simulator]
    command += [] if gui else ['-g']
    command += [MISSING_WORLD, 'base_scan:=scan']
    done = subprocess.run(command, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                          universal_newlines=True, timeout=60)
    return done.returncode, done.stdout


@pytest.mark.ros
@pytest.mark.parametrize('combination', sorted(RULE))
def test_stage_sim_hands_over_by_the_rule(fake_stage_ros, combination):
    simulator, gui, installed = combination
    status, output = run_stage_sim(fake_stage_ros[installed], simulator, gui)
    expected = RULE[combination]
    if expected == STAGE:
        assert status == 0, output
        called = output.split(FAKE_STAGEROS_SAYS, 1)[1].split()
        # With its window (no -g), the world, and the remappings kept.
        assert called == [MISSING_WORLD, 'base_scan:=scan']
        return
    assert FAKE_STAGEROS_SAYS not in output
    assert status == 1
    if expected == BUILTIN:
        # The built-in simulator went on to read the world (which is missing here).
        assert MISSING_WORLD in output and 'needs' not in output, output
    else:
        assert 'simulator:=stage needs' in output, output
