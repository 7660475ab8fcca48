"""Which mapper slam.launch (and mapping.launch through it) starts, read with roslaunch's loader.

slam_methods:=builtin (the default) starts this package's `slam`;
slam_methods:=gmapping starts gmapping's slam_gmapping under the same name,
with config/slam_gmapping.yaml. Where gmapping is not installed, the launch
must fail while it is read, before any node starts, and say what to do:
roslaunch's own "cannot launch node" error would let the robot drive off
with no mapper. gmapping's presence is set by ROS_PACKAGE_PATH: a fake
gmapping package, or every real one taken off the path. Needs the package
built (require_package is run with rosrun).
"""
import os

import pytest
import rospkg
import roslaunch.config
from roslaunch.core import RLException

from wall_follower.evaluation.launching import free_port, launch_and_read, launch_command

LAUNCH = os.path.join(os.path.dirname(__file__), '..', '..', 'launch')
HOW_TO_GET_IT = ('sudo apt install ros-noetic-gmapping', 'tools/build-real-gmapping')
# Wall seconds for roslaunch to read the launch files and give up.
LAUNCH_BOUND = 30.0


def load(launch_file, *args):
    return roslaunch.config.load_config_default(
        [(os.path.join(LAUNCH, launch_file), list(args))], None)


def mappers_of(config):
    return [node for node in config.nodes if node.name == 'slam']


def package_path_without_gmapping():
    """ROS_PACKAGE_PATH with every entry that holds a gmapping package left out."""
    entries = [entry for entry in os.environ.get('ROS_PACKAGE_PATH', '').split(os.pathsep)
               if entry]
    return [entry for entry in entries if 'gmapping' not in rospkg.RosPack([entry]).list()]


@pytest.fixture
def gmapping_installed(tmp_path, monkeypatch):
    """A package path on which a (fake) gmapping package is found; its directory."""
    package = tmp_path / 'gmapping'
    package.mkdir()
    (package / 'package.xml').write_text(
        '<?xml version="1.0"?>\n<package format="2"><name>gmapping</name>'
        '<version>1.4.2</version><description>fake</description>'
        '<maintainer email="none@example.com">none</maintainer><license>BSD</license>'
        '</package>\n')
    monkeypatch.setenv('ROS_PACKAGE_PATH',
                       os.pathsep.join([str(tmp_path)] + package_path_without_gmapping()))
    return str(package)


@pytest.fixture
def gmapping_missing(monkeypatch):
    monkeypatch.setenv('ROS_PACKAGE_PATH', os.pathsep.join(package_path_without_gmapping()))


def test_the_builtin_mapper_is_the_default(gmapping_installed):
    for config in (load('slam.launch'), load('slam.launch', 'slam_methods:=builtin')):
        mapper, = mappers_of(config)
        assert (mapper.package, mapper.type) == ('wall_follower', 'slam')
        assert '/slam/gmapping_path' not in config.params


def test_gmapping_starts_slam_gmapping_with_its_parameters(gmapping_installed):
    config = load('slam.launch', 'slam_methods:=gmapping')
    mapper, = mappers_of(config)
    assert (mapper.package, mapper.type) == ('gmapping', 'slam_gmapping')
    params = {name: param.value for name, param in config.params.items()}
    assert params['/slam/gmapping_path'] == gmapping_installed
    # The frames of this package's robots, and the map published after the robot stops.
    assert params['/slam/base_frame'] == 'base_footprint'
    assert params['/slam/odom_frame'] == 'odom'
    assert params['/slam/temporalUpdate'] > 0
    # No parameter of the builtin mapper.
    assert '/slam/max_range' not in params and '/slam/scan_matching' not in params


def test_mapping_launch_passes_slam_methods_on(gmapping_installed):
    mapper, = mappers_of(load('mapping.launch', 'sim:=true', 'slam_methods:=gmapping'))
    assert mapper.type == 'slam_gmapping'
    mapper, = mappers_of(load('mapping.launch', 'sim:=true'))
    assert mapper.type == 'slam'


def test_missing_gmapping_fails_the_launch_saying_what_to_do(gmapping_missing, capfd):
    with pytest.raises(RLException) as error:
        load('slam.launch', 'slam_methods:=gmapping')
    assert 'require_package' in str(error.value)
    said = capfd.readouterr().err
    assert 'the ROS package gmapping is not installed' in said
    for way in HOW_TO_GET_IT:
        assert way in said


def test_missing_gmapping_stops_roslaunch_before_any_node_starts(gmapping_missing):
    """The whole course with a simulator, as typed: roslaunch ends by itself (it would run
    until stopped otherwise) with the error, and no master, simulator or robot node ran."""
    port = free_port()
    ended, output = launch_and_read(launch_command('mapping.launch', {
        'sim': 'true', 'slam_methods': 'gmapping'}, port), port, LAUNCH_BOUND)
    assert ended, output
    assert 'the ROS package gmapping is not installed' in output
    assert 'tools/build-real-gmapping' in output
    assert 'process[' not in output and 'started with pid' not in output
