"""What the launch files start, read with roslaunch's own loader (no master).

main.launch is the course's command, typed on the real robot and next to a
simulation the user started first: with its default arguments it must start
the course nodes only and leave /use_sim_time alone; a simulator is opt-in
(sim:=true). Needs the package on ROS_PACKAGE_PATH (the built workspace).
"""
import os

import pytest
import roslaunch.config

from wall_follower.evaluation.benchmarks.follow import lap_args

LAUNCH = os.path.join(os.path.dirname(__file__), '..', '..', 'launch')
COURSE_NODES = {'wall_finder', 'odom_recorder', 'wall_following'}


def load(launch_file, *args):
    return roslaunch.config.load_config_default(
        [(os.path.join(LAUNCH, launch_file), list(args))], None)


def nodes_of(config):
    return {node.name: node for node in config.nodes}


def simulators_of(config):
    return [node for node in config.nodes if node.type in ('stage_sim', 'stageros')]


@pytest.mark.parametrize('args', [(), ('report:=true',), ('rviz:=true',),
                                  ('world:=room', 'simulator:=stage', 'gui:=true')])
def test_main_launch_starts_no_simulator_unless_asked(args):
    config = load('main.launch', *args)
    assert simulators_of(config) == []
    assert '/use_sim_time' not in config.params
    assert COURSE_NODES <= set(nodes_of(config))


def test_main_launch_starts_the_course_nodes_only_by_default():
    assert set(nodes_of(load('main.launch'))) == COURSE_NODES


def test_main_launch_with_sim_starts_the_simulation_in_simulated_time():
    config = load('main.launch', 'sim:=true')
    simulator, = simulators_of(config)
    assert simulator.name == 'simulator'
    assert simulator.args.split()[:3] == ['--simulator', 'auto', '-g']
    assert simulator.args.endswith('/worlds/arena.world')
    assert config.params['/use_sim_time'].value is True
    assert COURSE_NODES <= set(nodes_of(config))


def test_main_launch_rviz_without_sim_starts_rviz_only_beside_the_course():
    config = load('main.launch', 'rviz:=true')
    assert set(nodes_of(config)) == COURSE_NODES | {'rviz'}


@pytest.mark.parametrize('simulator', ['builtin', 'stage', 'auto'])
@pytest.mark.parametrize('gui', ['true', 'false'])
def test_simulation_launch_hands_the_choice_to_stage_sim(simulator, gui):
    """The launch passes simulator and gui through; stage_sim applies the rule
    (test_simulator_choice.py)."""
    config = load('simulation.launch', 'simulator:=' + simulator, 'gui:=' + gui)
    node, = simulators_of(config)
    assert (node.package, node.type, node.name) == ('wall_follower', 'stage_sim', 'simulator')
    args = node.args.split()
    assert args[:2] == ['--simulator', simulator]
    assert ('-g' in args) == (gui == 'false')
    assert config.params['/use_sim_time'].value is True


@pytest.mark.parametrize('simulator', ['builtin', 'stage'])
def test_follow_benchmark_asks_main_launch_for_its_simulator(simulator):
    """main.launch starts no simulator by itself: the benchmark must ask for one."""
    args = lap_args(simulator, 'room', 'stage', 0)
    config = load('main.launch', *['%s:=%s' % item for item in sorted(args.items())])
    node, = simulators_of(config)
    assert node.args.split()[:2] == ['--simulator', simulator]
    assert ('-g' in node.args.split()) == (simulator == 'builtin')
