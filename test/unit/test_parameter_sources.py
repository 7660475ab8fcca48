"""Every place a parameter's value is written agrees with its one declaration.

Each node's table in wall_follower.params is the single source of its
parameters' defaults. These tests hold to it everything else that names a
value: the modules dynamic_reconfigure generates from cfg/*.cfg, the
files in config/ (which may hold only what differs from the defaults),
the <param>s the launch files set (with their <arg> defaults) and the
README's tables of defaults. Changing any of them alone makes a test fail.
"""
import ast
import functools
import glob
import importlib
import logging
import os
import pickle
import re

import pytest
import rosgraph.names
import roslaunch.config
import yaml
from dynamic_reconfigure.encoding import extract_params

from wall_follower.params import ParameterError, checked, defaults, parameters
from wall_follower.params import driving
from wall_follower.params.arm import arm_controller
from wall_follower.params.arm import arm_plot
from wall_follower.params.arm import move_arm
from wall_follower.params.camera import camera_view
from wall_follower.params.camera import line_follower
from wall_follower.params.camera import line_mask
from wall_follower.params.course import odom_recorder
from wall_follower.params.course import wall_finder
from wall_follower.params.course import wall_following
from wall_follower.params.evaluation import course_report
from wall_follower.params.evaluation import find_trials
from wall_follower.params.evaluation import grade_case
from wall_follower.params.evaluation import line_case
from wall_follower.params.exercises import forward_stop
from wall_follower.params.exercises import range_ahead
from wall_follower.params.exercises import simple_move_square
from wall_follower.params.exercises import teleop_key
from wall_follower.params.exercises import wander
from wall_follower.params.mapping import map_saver
from wall_follower.params.mapping import slam
from wall_follower.params.mapping import world_map
from wall_follower.params.sim import stage_sim

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..')

#: node -> (its table, the name of its generated dynamic_reconfigure config, or None)
NODES = {
    'wall_following': (wall_following.TABLE, 'WallFollowing'),
    'wall_finder': (wall_finder.TABLE, 'WallFinder'),
    'odom_recorder': (odom_recorder.TABLE, 'OdomRecorder'),
    'stage_sim': (stage_sim.TABLE, None),
    'teleop_key': (teleop_key.TABLE, 'TeleopKey'),
    'simple_move_square': (simple_move_square.TABLE, 'SimpleMoveSquare'),
    'forward_stop': (forward_stop.TABLE, 'ForwardStop'),
    'range_ahead': (range_ahead.TABLE, 'RangeAhead'),
    'wander': (wander.TABLE, 'Wander'),
    'slam': (slam.TABLE, 'Slam'),
    'map_saver': (map_saver.TABLE, None),
    'course_report': (course_report.TABLE, None),
    'find_trials': (find_trials.TABLE, None),
    'arm_controller': (arm_controller.TABLE, None),
    'move_arm': (move_arm.TABLE, 'MoveArm'),
    'arm_plot': (arm_plot.TABLE, None),
    'grade_case': (grade_case.TABLE, None),
    'line_case': (line_case.TABLE, None),
    'line_follower': (line_follower.TABLE, 'LineFollower'),
    'line_mask': (line_mask.TABLE, 'LineMask'),
    'camera_view': (camera_view.TABLE, None),
    'world_map': (world_map.TABLE, None),
}
#: the executable of each node in launch files -> its node
EXECUTABLES = {'wall_following.py': 'wall_following', 'wall_finder.py': 'wall_finder',
               'odom_recorder.py': 'odom_recorder'}
EXECUTABLES.update((node, node) for node in NODES if node + '.py' not in EXECUTABLES)
#: the nodes that drive, whose tables take params.driving's sections
DRIVING = ('wall_following', 'wall_finder', 'teleop_key', 'simple_move_square', 'forward_stop',
           'wander')
DRIVING += ('line_follower',)
#: nodes set only by their launch files' arguments, which document them: no README table
WITHOUT_README_TABLE = {'course_report', 'find_trials', 'grade_case', 'line_case', 'world_map'}
TUNED_LIVE = sorted(node for node, (_, config) in NODES.items() if config is not None)


def config_file_values(node):
    """What config/<node>.yaml sets (nothing, when it holds only comments or is absent)."""
    path = os.path.join(ROOT, 'config', node + '.yaml')
    if not os.path.exists(path):
        return {}
    with open(path) as stream:
        return yaml.safe_load(stream) or {}


@pytest.mark.parametrize('node', TUNED_LIVE)
def test_the_generated_config_is_the_table(node):
    table, config_name = NODES[node]
    config = importlib.import_module('wall_follower.cfg.%sConfig' % config_name)
    assert config.defaults == defaults(table)
    for p in parameters(table):
        assert config.type[p.name] == p.kind, p.name
        if p.minimum is not None:
            assert (config.min[p.name], config.max[p.name]) == (p.minimum, p.maximum), p.name
    # A parameter with choices is an enum of them, and only such a one.
    enums = dict((d['name'], [c['value'] for c in ast.literal_eval(d['edit_method'])['enum']])
                 for d in extract_params(config.config_description) if d['edit_method'])
    assert enums == dict((p.name, list(p.choices)) for p in parameters(table) if p.choices)


@pytest.mark.parametrize('node', sorted(NODES))
def test_a_config_file_holds_only_known_values_that_differ_from_the_defaults(node):
    table = NODES[node][0]
    values = config_file_values(node)
    checked(table, values)   # no unknown name, no wrong type, nothing out of range
    repeated = sorted(name for name, value in values.items() if value == defaults(table)[name])
    assert not repeated, 'config/%s.yaml repeats the default of %s' % (node, ', '.join(repeated))


@functools.lru_cache(maxsize=None)
def launch_parameters(path, args=()):
    """(node, parameter, value) of every parameter a launch file gives the package's nodes.

    roslaunch's own loader reads the file, with every <arg> at its default
    but those of args ('name:=value'), its includes and the config files its
    rosparam elements load. Each file is read once (up to 2 s for one that
    includes others), however many tests look at it.
    """
    logging.getLogger('roslaunch').setLevel(logging.WARNING)
    config = roslaunch.config.load_config_default([(path, list(args))], None, verbose=False)
    found = []
    for node in config.nodes:
        if node.package != 'wall_follower' or node.type not in EXECUTABLES:
            continue
        prefix = rosgraph.names.ns_join(node.namespace, node.name) + '/'
        values = {}
        for key, param in config.params.items():
            if key.startswith(prefix):
                _nest(values, key[len(prefix):].split('/'), param.value)
        found.extend((EXECUTABLES[node.type], name, value) for name, value in values.items())
    return tuple(found)


def _nest(values, path, value):
    """Put value at path in values, a dict of dicts: roslaunch hands a structure (find_trials'
    ~poses) over flattened, one parameter per leaf."""
    for name in path[:-1]:
        values = values.setdefault(name, {})
    values[path[-1]] = value


LAUNCH_FILES = sorted(glob.glob(os.path.join(ROOT, 'launch', '*.launch')))
#: The args a launch file cannot do without (declared with no default), and a value for
#: each: a parameter set to that value from it is the caller's, not a default to check.
REQUIRED_ARGS = {'grade_case.launch': {'world': '/tmp/generated.world'},
                 'line_case.launch': {'world': '/tmp/line_s0_000.world'}}
#: (launch file, its args): each file at its defaults, and with the args that add a node
LAUNCH_RUNS = [(path, tuple('%s:=%s' % item for item in sorted(
    REQUIRED_ARGS.get(os.path.basename(path), {}).items()))) for path in LAUNCH_FILES] + [
    (os.path.join(ROOT, 'launch', 'main.launch'), ('report:=true',))]


@pytest.mark.parametrize('path, args', LAUNCH_RUNS, ids=[
    ' '.join((os.path.basename(path),) + args) for path, args in LAUNCH_RUNS])
def test_a_launch_file_gives_the_defaults_or_the_config_files(path, args):
    required = REQUIRED_ARGS.get(os.path.basename(path), {})
    for node, name, value in launch_parameters(path, args):
        if required.get(name) == value:
            continue
        table = NODES[node][0]
        expected = dict(defaults(table), **config_file_values(node))
        assert name in expected, '%s: unknown parameter ~%s of %s' % (path, name, node)
        assert checked(table, {name: value})[name] == expected[name], (node, name)


def test_the_launch_files_set_the_nodes_parameters():
    """The test above looks at something: the launch files do set parameters."""
    found = set((node, name) for path, args in LAUNCH_RUNS
                for node, name, _ in launch_parameters(path, args))
    assert {('wall_following', 'laser_x'), ('wall_finder', 'laser_x'),
            ('stage_sim', 'speedup')} <= found
    assert {('forward_stop', 'forward_period'), ('simple_move_square', 'side')} <= found
    assert {('slam', 'scan_matching'), ('course_report', 'plot'),
            ('find_trials', 'poses')} <= found


def readme_rows():
    """(nodes, parameter names, default texts, line) of every README table row with defaults.

    A row names its nodes in its first column and its parameters (`~name`)
    in its second; its third holds their defaults, comma-separated, in the
    same order.
    """
    rows = []
    with open(os.path.join(ROOT, 'README.md')) as stream:
        for line in stream:
            cells = [cell.strip() for cell in line.strip().strip('|').split('|')]
            if not line.startswith('|') or len(cells) < 4:
                continue
            nodes = re.findall(r'`(\w+)`', cells[0])
            names = re.findall(r'`~(\w+)`', cells[1])
            if nodes and names and all(node in NODES for node in nodes):
                rows.append((nodes, names, [text.strip() for text in cells[2].split(',')], line))
    return rows


SHOWN_DECIMALS = 4
"""A default that needs more decimals than this (an angle in radians) is shown to this many."""


def readme_value_matches(text, default):
    """True when a README default is the declared one, shown to every decimal it has."""
    if isinstance(default, bool):
        return text == str(default).lower()
    if isinstance(default, str):
        return text == '"%s"' % default
    shown = len(text.split('.')[1]) if '.' in text else 0
    needed = next((d for d in range(SHOWN_DECIMALS) if round(default, d) == default),
                  SHOWN_DECIMALS)
    return shown >= needed and round(float(text), shown) == round(default, shown)


def test_the_readme_tables_show_the_defaults():
    rows = readme_rows()
    assert set(NODES) - WITHOUT_README_TABLE == set(
        node for nodes, _, _, _ in rows for node in nodes)
    for nodes, names, texts, line in rows:
        assert len(names) == len(texts), line
        for node in nodes:
            declared = defaults(NODES[node][0])
            for name, text in zip(names, texts):
                assert name in declared, '%s has no ~%s: %s' % (node, name, line)
                assert readme_value_matches(text, declared[name]), line


def test_a_refusal_reads_the_same_after_crossing_to_another_process():
    with pytest.raises(ParameterError) as refused:
        checked(wall_following.TABLE, {'target_distance': 'far', 'target_distanse': 0.3})
    crossed = pickle.loads(pickle.dumps(refused.value))
    assert crossed.problems == refused.value.problems
    assert str(crossed) == str(refused.value)
    assert 'unknown parameter target_distanse' in str(crossed)


def test_a_wrong_type_or_a_misspelling_is_refused_by_name():
    with pytest.raises(ParameterError, match='target_distance must be a number'):
        checked(wall_following.TABLE, {'target_distance': 'far'})
    with pytest.raises(ParameterError, match='unknown parameter target_distanse'):
        checked(wall_following.TABLE, {'target_distanse': 0.3})
    with pytest.raises(ParameterError, match='find_wall must be true or false'):
        checked(wall_following.TABLE, {'find_wall': 1})
    with pytest.raises(ParameterError, match='max_linear must be at most'):
        checked(wall_following.TABLE, {'max_linear': 0.3})
    assert checked(wall_following.TABLE, {'wall_min_points': 7.0})['wall_min_points'] == 7
    with pytest.raises(ParameterError, match='poses must be a mapping'):
        checked(find_trials.TABLE, {'poses': [[0.0, 0.0, 0.0]]})


@pytest.mark.parametrize('node', DRIVING)
def test_a_driving_node_declares_the_loop_and_the_clamp_through_params_driving(node):
    """One declaration of the loop's and the clamp's parameters: only the input timeout's
    default (and a laser node's scan_timeout's meaning) and blind_turn's default, where a node
    has one, may differ from node to node; a node that drives by its camera has image_timeout
    instead, and no share of beams. A node whose behaviour judges its own way by the loop's
    rule (wall_finder) declares that rule as the shared section of its own."""
    table = NODES[node][0]
    sections = dict((section.name, section) for section in table)
    assert sections['limits'] is driving.LIMITS
    assert sections.get('view_ahead', driving.AHEAD) is driving.AHEAD
    declared = dict((p.name, p) for p in sections['drive_loop'].parameters)
    if 'image_timeout' in declared:
        expected = driving.camera_loop(declared['image_timeout'].default)
    else:
        blind_turn = declared['blind_turn'].default if 'blind_turn' in declared else None
        expected = driving.loop(declared['scan_timeout'].default,
                                declared['scan_timeout'].description, blind_turn,
                                ahead='view_ahead' not in sections)
    assert sections['drive_loop'] == expected
    loops = (driving.loop(1.0, blind_turn=0.0), driving.camera_loop(1.0), driving.LIMITS)
    shared = set(p.name for p in parameters(loops))
    elsewhere = [p.name for section in table for p in section.parameters
                 if section.name not in ('drive_loop', 'limits', 'view_ahead')]
    assert not shared & set(elsewhere)
